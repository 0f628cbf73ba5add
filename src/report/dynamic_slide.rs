//! Output of `tribofe slide --dynamics`: the files of `slide` (written by [`super::slide`])
//! plus fronts_t.csv, dyn_events.csv and a space-time diagram of the slip rate along the
//! interface for each instability (`spacetime_<event>.svg`, x against time).

use super::{finite, write_atomic};
use crate::error::Result;
use crate::studies::dynamic_slide::assumption5::Assumption5;
use crate::studies::dynamic_slide::{DynEvent, DynamicResult};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

fn num(what: &str, v: f64) -> Result<String> {
    Ok(format!("{:.9e}", finite(what, v)?))
}

fn opt(what: &str, v: Option<f64>) -> Result<String> {
    v.map_or(Ok(String::new()), |v| num(what, v))
}

/// fronts_t.csv: event, time since onset, tip x/L, tip speed (central difference of the
/// samples, m/s); rows only once the event has nucleated.
pub fn fronts_csv(r: &DynamicResult) -> Result<String> {
    let l = r.slide.condensed.l;
    let mut s = String::from("event,time_s,tip_x_over_L,tip_speed_m_per_s\n");
    for e in &r.events {
        let rec = &e.record;
        let k: Vec<usize> = (0..rec.t.len()).filter(|&k| rec.tip[k].is_finite()).collect();
        for (j, &i) in k.iter().enumerate() {
            let (a, b) = (k[j.saturating_sub(1)], k[(j + 1).min(k.len() - 1)]);
            let speed = if rec.t[b] > rec.t[a] {
                (rec.tip[b] - rec.tip[a]).abs() / (rec.t[b] - rec.t[a])
            } else {
                0.0
            };
            writeln!(
                s,
                "{},{},{},{}",
                e.event,
                num("t", rec.t[i])?,
                num("tip", rec.tip[i] / l)?,
                num("speed", speed)?
            )
            .unwrap();
        }
    }
    Ok(s)
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
    let res = &r.slide;
    let (k, c) = (res.options.law.mu_s() * res.options.n_force, &res.condensed);
    let mut s = String::from(
        "event,kind,instability,X_m,F_onset_over_mu_s_N,F_after_over_mu_s_N,duration_s,steps,region_first_over_L,region_last_over_L,t_arrest_s,arrest_over_L,predicted_arrest_mu_d_over_L,predicted_arrest_griffith_over_L,dp_ahead_over_p_pre,dtau_ahead_over_strength_drop,dp_ahead_2_5t_over_p_pre,dtau_ahead_2_5t_over_strength_drop,force_drop_at_arrest_over_event_drop,peak_slip_rate_m_per_s,f_gap_over_mu_s_N,u_gap_over_max_slip,energy_residual_over_dissipated\n",
    );
    for e in &r.events {
        let ev = &res.run.events[e.event];
        let (a, b) = ev.region.map_or((f64::NAN, f64::NAN), |(a, b)| (c.x[a] / c.l, c.x[b] / c.l));
        let en = &e.record.energy;
        let diss = (en.friction + en.damping).max(f64::MIN_POSITIVE);
        let a5 = e.assumption5.filter(|_| e.record.weakened);
        let a5v = |f: &dyn Fn(&Assumption5) -> f64| a5.as_ref().map(f);
        writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
            e.event,
            ev.kind,
            u8::from(e.record.weakened),
            num("X", e.x)?,
            num("F", e.f_onset / k)?,
            num("F", e.f_after / k)?,
            num("duration", e.record.duration)?,
            e.record.steps,
            if a.is_finite() { num("x", a)? } else { String::new() },
            if b.is_finite() { num("x", b)? } else { String::new() },
            opt("t_arrest", e.t_arrest)?,
            opt("arrest", a5v(&|a| a.arrest / c.l))?,
            opt("predicted arrest", a5v(&|a| a.predicted_mu_d / c.l))?,
            opt("predicted arrest", a5v(&|a| a.predicted_griffith / c.l))?,
            opt("dp ahead", a5v(&|a| a.dp_ahead))?,
            opt("dtau ahead", a5v(&|a| a.dtau_ahead))?,
            opt("dp ahead", a5v(&|a| a.dp_far))?,
            opt("dtau ahead", a5v(&|a| a.dtau_far))?,
            opt("drop", e.force_drop_at_arrest)?,
            num("rate", peak(e))?,
            num("gap", e.f_gap)?,
            num("gap", e.u_gap)?,
            num("residual", en.residual / diss)?
        )
        .unwrap();
    }
    Ok(s)
}

fn peak(e: &DynEvent) -> f64 {
    e.record.peak_rate.iter().cloned().fold(0.0, f64::max)
}

/// A heat map of |slip rate| over x/L (horizontal) and time (vertical, down), as plain SVG.
pub fn spacetime_svg(r: &DynamicResult, e: &DynEvent) -> String {
    let rec = &e.record;
    let c = &r.slide.condensed;
    let (w, h, ml, mt, mb) = (800.0, 500.0, 70.0, 40.0, 50.0);
    let nt = rec.rates.len().max(1);
    let nx = c.n;
    // At most 400 columns and 300 rows (the largest rate of each block of cells).
    let (cx, ct) = (nx.div_ceil(400), nt.div_ceil(300));
    let vmax = peak(e).max(f64::MIN_POSITIVE) as f32;
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" font-family=\"sans-serif\" font-size=\"13\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n",
        w + ml + 120.0,
        h + mt + mb
    );
    let _ = writeln!(
        s,
        "<text x=\"{}\" y=\"22\" text-anchor=\"middle\">event {} ({}): slip rate |v_x| along the interface, max {:.3e} m/s, {:.4} s</text>",
        ml + w / 2.0,
        e.event,
        r.slide.run.events[e.event].kind,
        vmax,
        rec.duration
    );
    let (cols, rows) = (nx.div_ceil(cx), nt.div_ceil(ct));
    let (dw, dh) = (w / cols as f64, h / rows as f64);
    for j in 0..rows {
        for i in 0..cols {
            let mut v = 0.0f32;
            for tk in j * ct..((j + 1) * ct).min(rec.rates.len()) {
                for xk in i * cx..((i + 1) * cx).min(nx) {
                    v = v.max(rec.rates[tk][xk]);
                }
            }
            if v <= 0.0 {
                continue;
            }
            let _ = writeln!(
                s,
                "<rect x=\"{:.2}\" y=\"{:.2}\" width=\"{:.2}\" height=\"{:.2}\" fill=\"{}\"/>",
                ml + i as f64 * dw,
                mt + j as f64 * dh,
                dw + 0.3,
                dh + 0.3,
                colour(v / vmax)
            );
        }
    }
    let _ = writeln!(
        s,
        "<rect x=\"{ml}\" y=\"{mt}\" width=\"{w}\" height=\"{h}\" fill=\"none\" stroke=\"black\"/>"
    );
    for k in 0..=4 {
        let f = k as f64 / 4.0;
        let x = c.x[0] + f * (c.x[nx - 1] - c.x[0]);
        let _ = writeln!(
            s,
            "<text x=\"{:.1}\" y=\"{}\" text-anchor=\"middle\">{:.2}</text>",
            ml + f * w,
            mt + h + 18.0,
            x / c.l
        );
        let _ = writeln!(
            s,
            "<text x=\"{}\" y=\"{:.1}\" text-anchor=\"end\">{:.3}</text>",
            ml - 6.0,
            mt + f * h + 4.0,
            f * rec.duration
        );
    }
    let _ = writeln!(
        s,
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">position x / L (dimensionless)</text>",
        ml + w / 2.0,
        mt + h + 40.0
    );
    let _ = writeln!(
        s,
        "<text x=\"16\" y=\"{}\" transform=\"rotate(-90 16 {})\" text-anchor=\"middle\">time since onset (s)</text>",
        mt + h / 2.0,
        mt + h / 2.0
    );
    for k in 0..=10 {
        let f = k as f32 / 10.0;
        let _ = writeln!(
            s,
            "<rect x=\"{}\" y=\"{:.1}\" width=\"20\" height=\"{:.1}\" fill=\"{}\"/>",
            ml + w + 20.0,
            mt + (1.0 - f as f64) * (h - h / 11.0),
            h / 11.0,
            colour(f)
        );
    }
    let _ = writeln!(s, "<text x=\"{}\" y=\"{}\">{:.2e} m/s</text>", ml + w + 45.0, mt + 12.0, vmax);
    let _ = writeln!(s, "<text x=\"{}\" y=\"{}\">0</text>", ml + w + 45.0, mt + h);
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

/// summary.csv: the run's one row ([`crate::studies::dynamic_slide::summary::COLUMNS`]);
/// an empty cell where a quantity does not exist in the run (no crossing reached...).
pub fn summary_csv(r: &DynamicResult) -> Result<String> {
    use crate::studies::dynamic_slide::summary;
    let cols = summary::COLUMNS;
    let mut s = cols.iter().map(|c| c.0).collect::<Vec<_>>().join(",");
    s.push('\n');
    let row: Vec<String> = summary::values(r)
        .iter()
        .zip(cols)
        .map(|(&v, c)| if v.is_finite() { num(c.0, v) } else { Ok(String::new()) })
        .collect::<Result<_>>()?;
    s.push_str(&row.join(","));
    s.push('\n');
    Ok(s)
}

/// Writes slide's files, summary.csv, fronts_t.csv, dyn_events.csv and one `spacetime_<event>.svg` per
/// instability into `dir`.
pub fn write(r: &DynamicResult, dir: &Path, header: &str, states: bool) -> Result<Vec<PathBuf>> {
    let mut out = super::slide::write(&r.slide, dir, header, states)?;
    let mut files = vec![
        ("summary.csv".to_string(), summary_csv(r)?),
        ("fronts_t.csv".to_string(), fronts_csv(r)?),
        ("dyn_events.csv".to_string(), events_csv(r)?),
    ];
    for e in r.events.iter().filter(|e| e.record.weakened) {
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
