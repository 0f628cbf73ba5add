//! Output of `tribofe slide --dynamics`: the files of `slide` (written by [`super::slide`])
//! plus summary.csv, fronts_t.csv, dyn_events.csv, cycle.svg (every instability's extent
//! against the drive force) and, on request, space-time pictures of the slip rate
//! (`spacetime_<event>.svg`, [`Spacetime`]).

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
/// zero fracture energy (tau = mu_d p) and with the thin-layer Griffith balance, and the
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

/// `v` to 4 significant digits (titles and labels).
fn sig4(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let d = v.abs().log10().floor() as i32;
    if (-3..4).contains(&d) {
        format!("{:.*}", (3 - d).max(0) as usize, v)
    } else {
        format!("{v:.3e}")
    }
}

/// Tick values in [a, b]: a step of 1, 2 or 5 times a power of ten giving 4 to 10 ticks,
/// An axis: its value range and where a value is drawn (pixels).
type Axis<'a> = ((f64, f64), &'a dyn Fn(f64) -> f64);

/// A plot's frame at [left, top, width, height], ticks on both axes and their labels.
fn frame(s: &mut String, [ml, mt, w, h]: [f64; 4], x: Axis, y: Axis, xlabel: &str, ylabel: &str) {
    let _ = writeln!(
        s,
        "<rect x=\"{ml}\" y=\"{mt}\" width=\"{w}\" height=\"{h}\" fill=\"none\" stroke=\"black\"/>"
    );
    let (xt, xd) = ticks(x.0 .0, x.0 .1);
    for v in xt {
        let px = x.1(v);
        let _ = writeln!(
            s,
            "<line x1=\"{px:.1}\" y1=\"{}\" x2=\"{px:.1}\" y2=\"{}\" stroke=\"black\"/><text x=\"{px:.1}\" y=\"{}\" text-anchor=\"middle\">{v:.xd$}</text>",
            mt + h,
            mt + h + 6.0,
            mt + h + 22.0
        );
    }
    let (yt, yd) = ticks(y.0 .0, y.0 .1);
    for v in yt {
        let py = y.1(v);
        let _ = writeln!(
            s,
            "<line x1=\"{}\" y1=\"{py:.1}\" x2=\"{ml}\" y2=\"{py:.1}\" stroke=\"black\"/><text x=\"{}\" y=\"{:.1}\" text-anchor=\"end\">{v:.yd$}</text>",
            ml - 6.0,
            ml - 9.0,
            py + 5.0
        );
    }
    let _ = writeln!(
        s,
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{xlabel}</text>",
        ml + w / 2.0,
        mt + h + 48.0
    );
    let _ = writeln!(
        s,
        "<text x=\"18\" y=\"{0}\" transform=\"rotate(-90 18 {0})\" text-anchor=\"middle\">{ylabel}</text>",
        mt + h / 2.0
    );
}

/// and the decimals that show the step.
fn ticks(a: f64, b: f64) -> (Vec<f64>, usize) {
    let span = (b - a).max(f64::MIN_POSITIVE);
    let p = 10f64.powf((span / 5.0).log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0].iter().map(|m| m * p).find(|s| span / s <= 10.0).unwrap_or(10.0 * p);
    let first = (a / step).ceil() as i64;
    let v = (first..).map(|k| k as f64 * step).take_while(|v| *v <= b + 1e-9 * span).collect();
    (v, (-step.log10().floor()).max(0.0) as usize)
}

/// `10^k` as SVG text (a superscript tspan).
fn decade(k: i32) -> String {
    format!("10<tspan dy=\"-7\" font-size=\"11\">{k}</tspan>")
}

/// The end of a space-time picture's time axis, s since the onset: 5 % past the last sample
/// with a node above the arrival rate (the whole event if none is).
pub fn spacetime_end(rec: &crate::dynamics::driven::EventRecord) -> f64 {
    let active = |k: usize| rec.rates[k].iter().any(|&v| f64::from(v) > rec.arrival_rate);
    let last = (0..rec.rates.len()).rev().find(|&k| active(k));
    last.map_or(rec.duration, |k| (1.05 * rec.t[k]).min(rec.duration)).max(f64::MIN_POSITIVE)
}

/// Decades shown by the space-time colour scale, below the event's peak rate.
pub const SPACETIME_DECADES: i32 = 4;

/// A space-time picture of one dynamic event: log10 |v_x| over x/L (across) and time since
/// the onset (down), as plain SVG. Cropped to the activity: x to the nodes the front reached
/// (2 t margin), time to the last sample with a node above the arrival rate (5 % margin,
/// so the ring-down is left out); the colour scale spans [`SPACETIME_DECADES`] decades
/// below the peak (white below); dashed lines run at c_s and c_R both ways from the first
/// node reached, at its arrival.
pub fn spacetime_svg(r: &DynamicResult, e: &DynEvent) -> String {
    let rec = &e.record;
    let c = &r.slide.condensed;
    let (nx, ns) = (c.n, rec.rates.len());
    let t_of = |k: usize| rec.t.get(k).copied().unwrap_or(rec.duration);
    let t_end = spacetime_end(rec);
    let rows_shown = (0..ns).filter(|&k| t_of(k) <= t_end).count().max(1);
    let reached: Vec<usize> =
        (0..nx).filter(|&i| rec.arrival.get(i).is_some_and(|a| a.is_finite())).collect();
    let margin = 2.0 * r.slide.scene.block.thickness;
    let (xa, xb) = match (reached.first(), reached.last()) {
        (Some(&i), Some(&j)) => ((c.x[i] - margin).max(c.x[0]), (c.x[j] + margin).min(c.x[nx - 1])),
        _ => (c.x[0], c.x[nx - 1]),
    };
    let cols: Vec<usize> = (0..nx).filter(|&i| c.x[i] >= xa && c.x[i] <= xb).collect();
    let peak = peak(e).max(f64::MIN_POSITIVE);
    let top = peak.log10().ceil() as i32;
    let bottom = top - SPACETIME_DECADES;
    let (w, h, ml, mt, mb, mr) = (720.0, 480.0, 80.0, 50.0, 60.0, 150.0);
    let px = |x: f64| ml + (x - xa) / (xb - xa).max(f64::MIN_POSITIVE) * w;
    let py = |t: f64| mt + t / t_end * h;
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" font-family=\"sans-serif\" font-size=\"14\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<defs><clipPath id=\"plot\"><rect x=\"{ml}\" y=\"{mt}\" width=\"{w}\" height=\"{h}\"/></clipPath></defs>\n",
        ml + w + mr,
        mt + h + mb
    );
    let k_onset = e.f_onset / (r.slide.options.law.mu_s() * r.slide.options.n_force);
    let _ = writeln!(
        s,
        "<text class=\"title\" x=\"{}\" y=\"24\" text-anchor=\"middle\" font-size=\"16\">event {} ({}), F = {} mu_s N: slip rate, peak {} m/s</text>",
        ml + w / 2.0,
        e.event,
        r.slide.run.events[e.event].kind,
        sig4(k_onset),
        sig4(peak)
    );
    // The heat map: at most 360 columns and 320 rows, the largest rate of each block.
    let (cx, ct) = (cols.len().div_ceil(360).max(1), rows_shown.div_ceil(320).max(1));
    let mut g = String::from("<g clip-path=\"url(#plot)\">\n");
    for j0 in (0..rows_shown).step_by(ct) {
        let j1 = (j0 + ct).min(rows_shown);
        let (ya, yb) = (py(if j0 == 0 { 0.0 } else { t_of(j0 - 1) }), py(t_of(j1 - 1)));
        for block in cols.chunks(cx) {
            let v = (j0..j1)
                .flat_map(|k| block.iter().map(move |&i| (k, i)))
                .fold(0.0f64, |m, (k, i)| m.max(f64::from(rec.rates[k][i])));
            if v <= 10f64.powi(bottom) {
                continue;
            }
            let (i0, i1) = (block[0], block[block.len() - 1]);
            let half = |i: usize, d: isize| {
                let k = (i as isize + d).clamp(0, nx as isize - 1) as usize;
                0.5 * (c.x[i] + c.x[k])
            };
            let (x0, x1) = (px(half(i0, -1)), px(half(i1, 1)));
            let f = (v.log10() - f64::from(bottom)) / f64::from(SPACETIME_DECADES);
            let _ = writeln!(
                g,
                "<rect x=\"{:.2}\" y=\"{:.2}\" width=\"{:.2}\" height=\"{:.2}\" fill=\"{}\"/>",
                x0,
                ya,
                (x1 - x0).max(0.3) + 0.3,
                (yb - ya).max(0.3) + 0.3,
                colour(f as f32)
            );
        }
    }
    // Guides at c_s and c_R from the first node reached.
    if let Some(&first) = reached.iter().min_by(|&&i, &&j| rec.arrival[i].total_cmp(&rec.arrival[j])) {
        let (x0, t0) = (c.x[first], rec.arrival[first]);
        for (name, v, dash) in [("c_s", r.speeds.c_s, "8 4"), ("c_R", r.speeds.c_r, "3 3")] {
            for side in [-1.0, 1.0] {
                let x1 = x0 + side * v * (t_end - t0);
                let _ = writeln!(
                    g,
                    "<line class=\"guide\" x1=\"{:.2}\" y1=\"{:.2}\" x2=\"{:.2}\" y2=\"{:.2}\" stroke=\"#1f4e9c\" stroke-width=\"1.5\" stroke-dasharray=\"{dash}\"/>",
                    px(x0),
                    py(t0),
                    px(x1),
                    py(t_end)
                );
            }
            // Labelled where the right-going line leaves the box.
            let (xe, te) = if x0 + v * (t_end - t0) <= xb {
                (x0 + v * (t_end - t0), t_end)
            } else {
                (xb, t0 + (xb - x0) / v)
            };
            let _ = writeln!(
                g,
                "<text x=\"{:.1}\" y=\"{:.1}\" fill=\"#1f4e9c\" text-anchor=\"end\">{name}</text>",
                px(xe) - 4.0,
                py(te) - 4.0
            );
        }
    }
    g.push_str("</g>\n");
    s.push_str(&g);
    frame(
        &mut s,
        [ml, mt, w, h],
        ((xa / c.l, xb / c.l), &|v| px(v * c.l)),
        ((0.0, t_end), &py),
        "position x / L (dimensionless)",
        "time since onset (s)",
    );
    // The colour bar: one band per tenth of a decade, a labelled tick at each decade.
    let (bx, bw) = (ml + w + 24.0, 22.0);
    let steps = 10 * SPACETIME_DECADES;
    for k in 0..steps {
        let f = (k as f64 + 0.5) / steps as f64;
        let _ = writeln!(
            s,
            "<rect x=\"{bx}\" y=\"{:.2}\" width=\"{bw}\" height=\"{:.2}\" fill=\"{}\"/>",
            mt + h * (1.0 - (k + 1) as f64 / steps as f64),
            h / steps as f64 + 0.3,
            colour(f as f32)
        );
    }
    let _ = writeln!(
        s,
        "<rect x=\"{bx}\" y=\"{mt}\" width=\"{bw}\" height=\"{h}\" fill=\"none\" stroke=\"black\"/>"
    );
    for k in 0..=SPACETIME_DECADES {
        let y = mt + h * (1.0 - f64::from(k) / f64::from(SPACETIME_DECADES));
        let _ = writeln!(
            s,
            "<line x1=\"{}\" y1=\"{y:.1}\" x2=\"{}\" y2=\"{y:.1}\" stroke=\"black\"/><text class=\"cbar-tick\" x=\"{}\" y=\"{:.1}\">{}</text>",
            bx + bw,
            bx + bw + 5.0,
            bx + bw + 8.0,
            y + 5.0,
            decade(bottom + k)
        );
    }
    let lx = bx + bw + 62.0;
    let _ = writeln!(
        s,
        "<text x=\"{lx}\" y=\"{0}\" transform=\"rotate(-90 {lx} {0})\" text-anchor=\"middle\">slip rate |v_x| (m/s)</text>",
        mt + h / 2.0
    );
    s.push_str("</svg>\n");
    s
}

/// White through yellow and red to black, for a value in [0, 1].
fn colour(v: f32) -> String {
    let v = v.clamp(0.0, 1.0);
    let (r, g, b) = if v < 0.33 {
        let f = v / 0.33;
        (255.0, 255.0, 255.0 * (1.0 - f))
    } else if v < 0.66 {
        let f = (v - 0.33) / 0.33;
        (255.0, 255.0 * (1.0 - f), 0.0)
    } else {
        let f = (v - 0.66) / 0.34;
        (255.0 * (1.0 - 0.7 * f), 0.0, 0.0)
    };
    format!("#{:02x}{:02x}{:02x}", r as u8, g as u8, b as u8)
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
/// space-time pictures `spacetime` asks for (`spacetime_<event>.svg`) into `dir`.
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
