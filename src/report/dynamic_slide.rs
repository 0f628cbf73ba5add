//! Output of `tribofe slide --dynamics`: the files of `slide` (written by [`super::slide`])
//! plus summary.csv, fronts_t.csv, dyn_events.csv, cycle.svg (every instability's extent
//! against the drive force) and, on request, space-time pictures of the slip rate
//! (`spacetime_<event>.svg`, [`Spacetime`]).

pub use super::spacetime::SPACETIME_DECADES;
use super::spacetime::{frame, heat_map, sig4, HeatMap, Scale};
use super::table::{Column, Table};
use super::{finite, write_atomic};
use crate::error::Result;
use crate::studies::dynamic_slide::assumption5::Assumption5;
use crate::studies::dynamic_slide::{DynEvent, DynamicResult};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

fn num(what: &str, v: f64) -> Result<String> {
    Ok(format!("{:.9e}", finite(what, v)?))
}

/// fronts_t.csv: one row per base node a dynamic event's front reached
/// ([`crate::studies::dynamic_slide::fronts`]): the first node reached (`side` 0), then each
/// side outward (-1 toward -x, +1 toward +x) to the end of the run of reached nodes.
/// `arrival_s`: the node's own arrival, the first explicit step at which its |v_x| exceeded
/// the arrival rate ([`crate::studies::dynamic_slide::physics::arrival_rate`]: 0.1 of
/// (mu_s - mu_d) (N/L) / (rho c_s), whatever the mesh), s since the onset; `front_time_s`:
/// when the front reached it (the largest arrival between it and the first node), so
/// (front_time_s, x_over_L) is the front's position in time; `front_speed_m_per_s`: the
/// least-squares slope of distance against front time over 1 t either side (the window kept
/// 2 t wide at the run's ends; empty when its nodes were reached at once), and over c_s
/// (dimensionless); `flag`: why the speed may exceed c_p, named wherever it applies:
/// `preslip` (the window holds a node slipped before the event, the nucleating zone that
/// moves at once), `join` (a node that arrived before the front reached it: a patch of its
/// own that the front joins), or, with neither, `above_c_p` (no wave from behind brought the
/// load: the rigid plate or the threshold running ahead of a growing front,
/// [`crate::studies::dynamic_slide::fronts::Cause::AboveCp`]); empty otherwise.
pub fn fronts_csv(r: &DynamicResult) -> Result<String> {
    fronts_table(r).csv()
}

/// fronts_t.csv's table ([`fronts_csv`]): an empty speed (NaN) for the first node or a window
/// reached at once (a jump; flagged).
pub fn fronts_table(r: &DynamicResult) -> Table {
    use crate::studies::dynamic_slide::fronts::arrivals;
    let (c, t) = (&r.slide.condensed, r.slide.scene.block.thickness);
    let (mut event, mut side, mut x, mut own, mut front, mut speed, mut cause) =
        (vec![], vec![], vec![], vec![], vec![], vec![], vec![]);
    for e in &r.events {
        for a in arrivals(&e.record, &c.x, t, r.speeds.c_p) {
            event.push(e.event as i64);
            side.push(i64::from(a.side));
            x.push(c.x[a.node] / c.l);
            own.push(a.own);
            front.push(a.front);
            speed.push(a.speed);
            cause.push(a.cause.name().to_string());
        }
    }
    let over_c_s = speed.iter().map(|v| v / r.speeds.c_s).collect();
    let columns = vec![
        Column::int("event", "-", event),
        Column::int("side", "-", side),
        Column::float("x_over_L", "1", x),
        Column::float("arrival_s", "s", own),
        Column::float("front_time_s", "s", front),
        Column::maybe("front_speed_m_per_s", "m/s", speed),
        Column::maybe("front_speed_over_c_s", "1", over_c_s),
        Column::text("flag", "-", cause),
    ];
    Table { columns, digits: 10 }
}

/// dyn_events.csv: one row per dynamic event. The assumption-5 columns (held drive only,
/// empty otherwise; [`crate::studies::dynamic_slide::assumption5`]): the dynamic arrest
/// (x/L of the tip's final place) beside the arrests predicted from the pre-event field with
/// zero fracture energy (tau = mu_d p), with the thin-layer Griffith balance and with the
/// Griffith balance on the whole body's G(l) (fixed grips, p frozen;
/// [`crate::studies::dynamic_slide::fracture`]), and the
/// largest changes of p (over p_pre) and tau (over the strength drop (mu_s - mu_d) p_pre)
/// ahead of the running tip, anywhere ahead and from 2.5 t ahead on.
/// `force_drop_at_arrest_over_event_drop`: (F_onset - F(t_arrest)) / (F_onset - F_after), not
/// a share (above 1: the force undershoots its final value at the arrest).
pub fn events_csv(r: &DynamicResult) -> Result<String> {
    events_table(r).csv()
}

/// dyn_events.csv's table ([`events_csv`]): the columns with their units and types, the one
/// definition the CSV and the Python package's `dyn_events` are both made from.
pub fn events_table(r: &DynamicResult) -> Table {
    let res = &r.slide;
    let (k, c) = (res.options.law.mu_s() * res.options.n_force, &res.condensed);
    let ev = |f: &dyn Fn(&DynEvent) -> f64| r.events.iter().map(f).collect::<Vec<f64>>();
    let region = |e: &DynEvent, end: usize| {
        res.run.events[e.event].region.map_or(f64::NAN, |(a, b)| c.x[[a, b][end]] / c.l)
    };
    // The assumption-5 columns: held drive only, and only for an instability.
    let a5 = |f: &dyn Fn(&Assumption5) -> f64| {
        ev(&|e| e.assumption5.filter(|_| e.record.weakened).as_ref().map_or(f64::NAN, f))
    };
    let residual = |e: &DynEvent| {
        let en = &e.record.energy;
        en.residual / (en.friction + en.damping).max(f64::MIN_POSITIVE)
    };
    let columns = vec![
        Column::int("event", "-", r.events.iter().map(|e| e.event as i64).collect()),
        Column::text(
            "kind",
            "-",
            r.events.iter().map(|e| res.run.events[e.event].kind.to_string()).collect(),
        ),
        Column::int("instability", "-", r.events.iter().map(|e| i64::from(e.record.weakened)).collect()),
        Column::float("X_m", "m", ev(&|e| e.x)),
        Column::float("F_onset_over_mu_s_N", "1", ev(&|e| e.f_onset / k)),
        Column::float("F_after_over_mu_s_N", "1", ev(&|e| e.f_after / k)),
        Column::float("duration_s", "s", ev(&|e| e.record.duration)),
        Column::int("steps", "-", r.events.iter().map(|e| e.record.steps as i64).collect()),
        Column::maybe("region_first_over_L", "1", ev(&|e| region(e, 0))),
        Column::maybe("region_last_over_L", "1", ev(&|e| region(e, 1))),
        Column::maybe("t_arrest_s", "s", ev(&|e| e.t_arrest.unwrap_or(f64::NAN))),
        Column::maybe("arrest_over_L", "1", a5(&|a| a.arrest / c.l)),
        Column::maybe("predicted_arrest_mu_d_over_L", "1", a5(&|a| a.predicted_mu_d / c.l)),
        Column::maybe("predicted_arrest_griffith_over_L", "1", a5(&|a| a.predicted_griffith / c.l)),
        Column::maybe("predicted_arrest_fracture_over_L", "1", a5(&|a| a.predicted_fracture / c.l)),
        Column::maybe("dp_ahead_over_p_pre", "1", a5(&|a| a.dp_ahead)),
        Column::maybe("dtau_ahead_over_strength_drop", "1", a5(&|a| a.dtau_ahead)),
        Column::maybe("dp_ahead_2_5t_over_p_pre", "1", a5(&|a| a.dp_far)),
        Column::maybe("dtau_ahead_2_5t_over_strength_drop", "1", a5(&|a| a.dtau_far)),
        Column::maybe(
            "force_drop_at_arrest_over_event_drop",
            "1",
            ev(&|e| e.force_drop_at_arrest.unwrap_or(f64::NAN)),
        ),
        Column::float("peak_slip_rate_m_per_s", "m/s", ev(&peak)),
        Column::float("f_gap_over_mu_s_N", "1", ev(&|e| e.f_gap)),
        Column::float("u_gap_over_max_slip", "1", ev(&|e| e.u_gap)),
        Column::float("energy_residual_over_dissipated", "1", ev(&residual)),
        Column::float("F_pre_over_mu_s_N", "1", ev(&|e| e.f_pre / k)),
    ];
    Table { columns, digits: 10 }
}

fn peak(e: &DynEvent) -> f64 {
    e.record.peak_rate.iter().cloned().fold(0.0, f64::max)
}

/// Which per-event space-time pictures `write` draws (`--spacetime`): none (the default),
/// every instability, or the events.csv rows given.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub enum Spacetime {
    #[default]
    None,
    All,
    Events(Vec<usize>),
}

impl std::str::FromStr for Spacetime {
    type Err = crate::error::Error;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "none" => Ok(Spacetime::None),
            "all" => Ok(Spacetime::All),
            list => list
                .split(',')
                .map(|k| k.trim().parse::<usize>())
                .collect::<std::result::Result<Vec<_>, _>>()
                .map(Spacetime::Events)
                .map_err(|_| {
                    crate::error::Error::input(
                        "--spacetime",
                        format!("'{s}': give all, none or event rows (events.csv's `event`) as N,M,..."),
                    )
                }),
        }
    }
}

impl Spacetime {
    /// The dynamic events to draw.
    pub fn picks<'a>(&self, r: &'a DynamicResult) -> Vec<&'a DynEvent> {
        match self {
            Spacetime::None => vec![],
            Spacetime::All => r.events.iter().filter(|e| e.record.weakened).collect(),
            Spacetime::Events(k) => r.events.iter().filter(|e| k.contains(&e.event)).collect(),
        }
    }

    /// The rows asked for that are no dynamic event of the run.
    pub fn missing(&self, r: &DynamicResult) -> Vec<usize> {
        match self {
            Spacetime::Events(k) => {
                k.iter().copied().filter(|k| !r.events.iter().any(|e| e.event == *k)).collect()
            }
            _ => vec![],
        }
    }
}

/// The end of a space-time picture's time axis, s since the onset: 5 % past the last sample
/// with a node above the arrival rate (the whole event if none is).
pub fn spacetime_end(rec: &crate::dynamics::driven::EventRecord) -> f64 {
    let active = |k: usize| rec.rates[k].iter().any(|&v| f64::from(v) > rec.arrival_rate);
    let last = (0..rec.rates.len()).rev().find(|&k| active(k));
    last.map_or(rec.duration, |k| (1.05 * rec.t[k]).min(rec.duration)).max(f64::MIN_POSITIVE)
}

/// The base nodes an event's front reached, and the x range its pictures show: those nodes
/// with a margin of 2 t each side (the whole interface when it reached none).
fn reached_span(r: &DynamicResult, e: &DynEvent) -> (Vec<usize>, (f64, f64)) {
    let (c, rec) = (&r.slide.condensed, &e.record);
    let reached: Vec<usize> =
        (0..c.n).filter(|&i| rec.arrival.get(i).is_some_and(|a| a.is_finite())).collect();
    let margin = 2.0 * r.slide.scene.block.thickness;
    let span = match (reached.first(), reached.last()) {
        (Some(&i), Some(&j)) => ((c.x[i] - margin).max(c.x[0]), (c.x[j] + margin).min(c.x[c.n - 1])),
        _ => (c.x[0], c.x[c.n - 1]),
    };
    (reached, span)
}

/// A space-time picture of one dynamic event: log10 |v_x| over x/L (across) and time since
/// the onset (down), as plain SVG. Cropped to the activity: x to the nodes the front reached
/// (2 t margin), time to the last sample with a node above the arrival rate (5 % margin,
/// so the ring-down is left out); the colour scale spans [`SPACETIME_DECADES`] decades
/// below the peak (white below); dashed lines run at c_s and c_R both ways from the first
/// node reached, at its arrival.
pub fn spacetime_svg(r: &DynamicResult, e: &DynEvent) -> String {
    let rec = &e.record;
    let c = &r.slide.condensed;
    let ns = rec.rates.len();
    let t_of = |k: usize| rec.t.get(k).copied().unwrap_or(rec.duration);
    let t_end = spacetime_end(rec);
    let rows_shown = (0..ns).filter(|&k| t_of(k) <= t_end).count().max(1);
    let (reached, (xa, xb)) = reached_span(r, e);
    let peak = peak(e).max(f64::MIN_POSITIVE);
    let k_onset = e.f_onset / (r.slide.options.law.mu_s() * r.slide.options.n_force);
    let first = reached.iter().min_by(|&&i, &&j| rec.arrival[i].total_cmp(&rec.arrival[j]));
    heat_map(&HeatMap {
        title: format!(
            "event {} ({}), F = {} mu_s N: slip rate, peak {} m/s",
            e.event,
            r.slide.run.events[e.event].kind,
            sig4(k_onset),
            sig4(peak)
        ),
        x: &c.x,
        x_range: (xa, xb),
        x_unit: (c.l, "position x / L (dimensionless)"),
        t: &t_of,
        rows: rows_shown,
        t_end,
        t_label: "time since onset (s)",
        value: &|k, i| f64::from(rec.rates[k][i]),
        scale: Scale::Log { peak },
        origin: first.map(|&i| (c.x[i], rec.arrival[i])),
        speeds: [r.speeds.c_s, r.speeds.c_r],
        label: "slip rate |v_x| (m/s)",
    })
}

/// The contact-area picture of one dynamic event (`contact_area_<event>.svg`), as the
/// experiments image it (Rubinstein et al., PRL 2007: A(x, t)/A(x, t_0)): the proxy
/// A(x)/A_0 = p(x)/p_mean ([`crate::studies::slide::contact_area_over_a0`]) at each sample over
/// its value at the onset, over x/L (across) and time since the onset (down), from the base's
/// contact forces sampled up to the front's arrest (the samples the event keeps); the same x
/// crop as [`spacetime_svg`]. Nodes out of contact at the onset are left blank. None when the
/// event kept no samples.
pub fn contact_area_svg(r: &DynamicResult, e: &DynEvent) -> Option<String> {
    let rec = &e.record;
    let c = &r.slide.condensed;
    let rows = rec.p_samples.len().min(rec.t.len());
    if rows == 0 || c.n == 0 {
        return None;
    }
    let proxy = |p: &Vec<f32>| {
        let p: Vec<f64> = p.iter().map(|&v| f64::from(v)).collect();
        crate::studies::slide::contact_area_over_a0(&p, &c.w, c.l)
    };
    let onset = proxy(&rec.p_samples[0]);
    let area: Vec<Vec<f64>> = rec.p_samples[..rows]
        .iter()
        .map(|p| {
            proxy(p).iter().zip(&onset).map(|(a, a0)| if *a0 > 0.0 { a / a0 } else { f64::NAN }).collect()
        })
        .collect();
    let (_, (xa, xb)) = reached_span(r, e);
    let shown = |i: usize| c.x[i] >= xa && c.x[i] <= xb;
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for row in &area {
        for &v in row.iter().enumerate().filter(|(i, v)| shown(*i) && v.is_finite()).map(|(_, v)| v) {
            lo = lo.min(v);
            hi = hi.max(v);
        }
    }
    if !(lo.is_finite() && hi.is_finite()) {
        return None;
    }
    if hi - lo < 1e-6 {
        (lo, hi) = (lo - 0.05, hi + 0.05);
    }
    let t_of = |k: usize| rec.t[k];
    let k_onset = e.f_onset / (r.slide.options.law.mu_s() * r.slide.options.n_force);
    Some(heat_map(&HeatMap {
        title: format!(
            "event {} ({}), F = {} mu_s N: contact area A(x,t)/A(x,onset), A/A0 = p/p_mean, to the arrest",
            e.event,
            r.slide.run.events[e.event].kind,
            sig4(k_onset)
        ),
        x: &c.x,
        x_range: (xa, xb),
        x_unit: (c.l, "position x / L (dimensionless)"),
        t: &t_of,
        rows,
        t_end: rec.t[rows - 1].max(f64::MIN_POSITIVE),
        t_label: "time since onset (s)",
        value: &|k, i| area[k][i],
        scale: Scale::Linear { range: (lo, hi) },
        origin: None,
        speeds: [0.0; 2],
        label: "A(x,t)/A(x,onset) (dimensionless)",
    }))
}

/// cycle.svg: the run's instabilities as experiments image precursors (Rubinstein et al.,
/// PRL 98, 226103, 2007): each one's slipped extent (x/L, across) at the drive force of its
/// onset (F/(mu_s N), up), one bar each, with its nucleation node as a dot; the cycle's end
/// (a crossing or whole slip) in dark red and the largest onset force marked.
pub fn cycle_svg(r: &DynamicResult) -> String {
    let res = &r.slide;
    let c = &res.condensed;
    let k = res.options.law.mu_s() * res.options.n_force;
    let inst: Vec<(&DynEvent, (usize, usize), bool)> = r
        .events
        .iter()
        .filter(|e| e.record.weakened)
        .filter_map(|e| {
            let ev = &res.run.events[e.event];
            ev.region.map(|g| (e, g, ev.ends_cycle()))
        })
        .collect();
    let (w, h, ml, mt, mb, mr) = (760.0, 520.0, 80.0, 50.0, 80.0, 30.0);
    let (f0, f1) = inst.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |m, i| {
        (m.0.min(i.0.f_onset / k), m.1.max(i.0.f_onset / k))
    });
    let (f0, f1) = if f0 < f1 {
        let pad = 0.05 * (f1 - f0);
        (f0 - pad, f1 + pad)
    } else if f0.is_finite() {
        (f0 - 0.05, f0 + 0.05)
    } else {
        (0.0, 1.0)
    };
    let (xa, xb) = (c.x[0] / c.l, c.x[c.n - 1] / c.l);
    let px = |x: f64| ml + (x - xa) / (xb - xa) * w;
    let py = |f: f64| mt + (1.0 - (f - f0) / (f1 - f0)) * h;
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" font-family=\"sans-serif\" font-size=\"14\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n",
        ml + w + mr,
        mt + h + mb
    );
    let ends = inst.iter().filter(|i| i.2).count();
    let _ = writeln!(
        s,
        "<text class=\"title\" x=\"{}\" y=\"24\" text-anchor=\"middle\" font-size=\"16\">{} instabilities: slipped extent at the onset force ({} cycle end{})</text>",
        ml + w / 2.0,
        inst.len(),
        ends,
        if ends == 1 { "" } else { "s" }
    );
    let bar = (0.8 * h / inst.len().max(1) as f64).clamp(1.5, 5.0);
    let peak = inst.iter().map(|i| i.0.f_onset).fold(f64::NEG_INFINITY, f64::max);
    for &(e, (a, b), end) in &inst {
        let y = py(e.f_onset / k);
        let (x0, x1) = (px(c.x[a] / c.l), px(c.x[b] / c.l));
        let colour = if end {
            "#8b0000"
        } else if a == 0 {
            "#1f4e9c"
        } else {
            "#e08a00"
        };
        let _ = writeln!(
            s,
            "<rect class=\"instability\" x=\"{x0:.2}\" y=\"{:.2}\" width=\"{:.2}\" height=\"{bar:.2}\" fill=\"{colour}\"><title>event {}: F = {} mu_s N, x/L {} to {}</title></rect>",
            y - bar / 2.0,
            (x1 - x0).max(1.5),
            e.event,
            sig4(e.f_onset / k),
            sig4(c.x[a] / c.l),
            sig4(c.x[b] / c.l)
        );
        if let Some(n) = e.record.nucleation {
            let _ = writeln!(
                s,
                "<circle cx=\"{:.2}\" cy=\"{y:.2}\" r=\"{:.1}\" fill=\"black\"/>",
                px(c.x[n] / c.l),
                bar.max(2.0) / 2.0 + 0.5
            );
        }
        if end || e.f_onset == peak {
            let what = match (end, e.f_onset == peak) {
                (true, true) => "cycle end, largest onset",
                (true, false) => "cycle end",
                _ => "largest onset",
            };
            // Right of the bar, or left of it where the text would leave the frame; a white
            // halo keeps it legible over other bars.
            let (x, anchor) =
                if x1 + 6.0 + 230.0 <= ml + w { (x1 + 6.0, "start") } else { (x0 - 6.0, "end") };
            let _ = writeln!(
                s,
                "<text class=\"mark\" x=\"{x:.1}\" y=\"{:.1}\" font-size=\"13\" text-anchor=\"{anchor}\" paint-order=\"stroke\" stroke=\"white\" stroke-width=\"3\">{what}: F = {} mu_s N</text>",
                y - bar / 2.0 - 3.0,
                sig4(e.f_onset / k)
            );
        }
    }
    frame(
        &mut s,
        [ml, mt, w, h],
        ((xa, xb), &px),
        ((f0, f1), &py),
        "slipped extent x / L (dimensionless)",
        "drive force at the onset F / (mu_s N) (dimensionless)",
    );
    let _ = writeln!(
        s,
        "<text class=\"key\" x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-size=\"12\">dot: nucleation node; bars: blue from the trailing edge, orange inside, dark red the cycle's end</text>",
        ml + w / 2.0,
        mt + h + mb - 6.0
    );
    s.push_str("</svg>\n");
    s
}

/// summary.csv: the run's one row ([`crate::studies::dynamic_slide::summary::COLUMNS`]);
/// an empty cell where a quantity does not exist in the run (no crossing reached...).
pub fn summary_csv(r: &DynamicResult) -> Result<String> {
    summary_table(r).csv()
}

/// summary.csv's table ([`summary_csv`]): one row; every column a number that may not exist
/// (the counts and flags too, as the CSV has always printed them).
pub fn summary_table(r: &DynamicResult) -> Table {
    use crate::studies::dynamic_slide::summary;
    let columns = summary::COLUMNS
        .iter()
        .zip(summary::values(r))
        .map(|(&(name, _), v)| Column::maybe(name, summary_unit(name), vec![v]))
        .collect();
    Table { columns, digits: 10 }
}

/// A summary column's unit, read off its name (SI suffix, `over`: a ratio, else a count or flag).
fn summary_unit(name: &str) -> &'static str {
    match name {
        "kappa" | "damping_ratio_thickness_mode" => "1",
        n if n.contains("over") => "1",
        n if n.ends_with("_m") => "m",
        n if n.ends_with("_s") => "s",
        _ => "-",
    }
}

/// Writes slide's files, summary.csv, fronts_t.csv, dyn_events.csv, cycle.svg and the
/// space-time pictures `spacetime` asks for (`spacetime_<event>.svg`, each with its
/// contact-area picture `contact_area_<event>.svg`) into `dir`.
pub fn write(
    r: &DynamicResult,
    dir: &Path,
    header: &str,
    states: bool,
    spacetime: &Spacetime,
) -> Result<Vec<PathBuf>> {
    let mut out = super::slide::write(&r.slide, dir, header, states)?;
    let mut files = vec![
        ("summary.csv".to_string(), summary_csv(r)?),
        ("fronts_t.csv".to_string(), fronts_csv(r)?),
        ("dyn_events.csv".to_string(), events_csv(r)?),
        ("cycle.svg".to_string(), cycle_svg(r)),
    ];
    for e in spacetime.picks(r) {
        files.push((format!("spacetime_{:06}.svg", e.event), spacetime_svg(r, e)));
        if let Some(svg) = contact_area_svg(r, e) {
            files.push((format!("contact_area_{:06}.svg", e.event), svg));
        }
    }
    for (name, text) in files {
        let p = dir.join(name);
        write_atomic(&p, text.as_bytes())?;
        out.push(p);
    }
    Ok(out)
}

/// refinement.csv: one row per judged quantity, its value on each mesh (columns named by h in
/// m), the spread, the change between the two finest meshes, the tolerance and the verdict
/// ([`crate::studies::dynamic_slide::refine`]); an empty cell where a mesh lacks the quantity.
pub fn refinement_csv(r: &crate::studies::dynamic_slide::refine::Refinement) -> Result<String> {
    use crate::studies::dynamic_slide::refine::tolerance;
    let cell = |what: &str, v: f64| if v.is_finite() { num(what, v) } else { Ok(String::new()) };
    let mut s = String::from("quantity");
    for h in &r.h {
        write!(s, ",value_at_h_{h:e}_m").unwrap();
    }
    s.push_str(",spread,change_between_two_finest,tolerance,converged\n");
    for v in r.verdicts() {
        s.push_str(v.name);
        for &x in &v.values {
            write!(s, ",{}", cell(v.name, x)?).unwrap();
        }
        let verdict = match v.converged {
            Some(true) => "yes",
            Some(false) => "no",
            None => "",
        };
        writeln!(
            s,
            ",{},{},{},{verdict}",
            cell("spread", v.spread)?,
            cell("change", v.last_change)?,
            num("tolerance", tolerance(v.name))?
        )
        .unwrap();
    }
    Ok(s)
}
