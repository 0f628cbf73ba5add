//! The space-time picture of every dynamic command: log10 of the slip rate over position
//! (across) and time (down), as plain SVG, with dashed guides at the shear and Rayleigh
//! speeds from the first node reached; and the frame, ticks and colours it shares with the
//! other hand-written pictures.

use std::fmt::Write as _;

/// Decades shown by the space-time colour scale, below the peak rate.
pub const SPACETIME_DECADES: i32 = 4;

/// What [`heat_map`] draws.
pub(crate) struct HeatMap<'a> {
    pub title: String,
    /// Node positions (m), increasing; the columns shown are those in `x_range`.
    pub x: &'a [f64],
    pub x_range: (f64, f64),
    /// The axis shows x / unit, with this label.
    pub x_unit: (f64, &'a str),
    /// The time of row k (s), rows 0..rows shown down to `t_end`.
    pub t: &'a dyn Fn(usize) -> f64,
    pub rows: usize,
    pub t_end: f64,
    pub t_label: &'a str,
    /// The value of row k at node i (the slip rate, m/s, on a log scale).
    pub value: &'a dyn Fn(usize, usize) -> f64,
    pub scale: Scale,
    /// Where and when the first node was reached: the origin of the guides at c_s and c_R
    /// (`speeds`, m/s); none, no guides.
    pub origin: Option<(f64, f64)>,
    pub speeds: [f64; 2],
    pub label: &'a str,
}

/// How [`heat_map`] colours a value.
pub(crate) enum Scale {
    /// log10 over [`SPACETIME_DECADES`] decades below the peak, ten bands a decade, white
    /// below; a block of cells shows its largest value (the slip rate's fronts stay sharp).
    Log { peak: f64 },
    /// Linear over (low, high), twenty bands; a block shows its mean.
    Linear { range: (f64, f64) },
}

impl Scale {
    fn bands(&self) -> usize {
        match self {
            Scale::Log { .. } => 10 * SPACETIME_DECADES as usize,
            Scale::Linear { .. } => 20,
        }
    }

    /// The lowest decade shown (log scale).
    fn bottom(peak: f64) -> i32 {
        peak.log10().ceil() as i32 - SPACETIME_DECADES
    }

    /// The colour band of a block's values, none (white) below a log scale's floor or where a
    /// linear scale's block holds no number (a quantity undefined there).
    fn band(&self, values: impl Iterator<Item = f64>) -> Option<usize> {
        match *self {
            Scale::Log { peak } => {
                let bottom = Self::bottom(peak);
                let v = values.fold(0.0f64, f64::max);
                if v <= 10f64.powi(bottom) {
                    return None;
                }
                let f = (v.log10() - f64::from(bottom)) / f64::from(SPACETIME_DECADES);
                Some(
                    ((f * f64::from(10 * SPACETIME_DECADES)).floor() as i32)
                        .clamp(0, 10 * SPACETIME_DECADES - 1) as usize,
                )
            }
            Scale::Linear { range: (lo, hi) } => {
                let (sum, count) =
                    values.filter(|v| v.is_finite()).fold((0.0, 0usize), |(s, c), v| (s + v, c + 1));
                if count == 0 {
                    return None;
                }
                let v = sum / count as f64;
                let span = (hi - lo).max(f64::MIN_POSITIVE);
                Some((((v - lo) / span * 20.0).floor() as i64).clamp(0, 19) as usize)
            }
        }
    }
}

/// The picture: at most 360 columns and 320 rows (blocks of cells shown as [`Scale`] says),
/// a colour bar with ticks.
pub(crate) fn heat_map(m: &HeatMap) -> String {
    let (x, nx) = (m.x, m.x.len());
    let (t_of, t_end, rows_shown) = (m.t, m.t_end, m.rows);
    let (xa, xb) = m.x_range;
    let cols: Vec<usize> = (0..nx).filter(|&i| x[i] >= xa && x[i] <= xb).collect();
    let bands = m.scale.bands();
    let (w, h, ml, mt, mb, mr) = (720.0, 480.0, 80.0, 50.0, 60.0, 150.0);
    let px = |x: f64| ml + (x - xa) / (xb - xa).max(f64::MIN_POSITIVE) * w;
    let py = |t: f64| mt + t / t_end * h;
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" font-family=\"sans-serif\" font-size=\"14\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<defs><clipPath id=\"plot\"><rect x=\"{ml}\" y=\"{mt}\" width=\"{w}\" height=\"{h}\"/></clipPath></defs>\n",
        ml + w + mr,
        mt + h + mb
    );
    let _ = writeln!(
        s,
        "<text class=\"title\" x=\"{}\" y=\"24\" text-anchor=\"middle\" font-size=\"16\">{}</text>",
        ml + w / 2.0,
        m.title
    );
    // The heat map: at most 360 columns and 320 rows.
    let (cx, ct) = (cols.len().div_ceil(360).max(1), rows_shown.div_ceil(320).max(1));
    let mut g = String::from("<g clip-path=\"url(#plot)\">\n");
    for j0 in (0..rows_shown).step_by(ct) {
        let j1 = (j0 + ct).min(rows_shown);
        let (ya, yb) = (py(if j0 == 0 { 0.0 } else { t_of(j0 - 1) }), py(t_of(j1 - 1)));
        // Cells of one colour band (as the colour bar) side by side are one rectangle: the
        // picture is as read, at a tenth of the size.
        let mut run: Option<(f64, f64, usize)> = None;
        let flush = |g: &mut String, run: &mut Option<(f64, f64, usize)>| {
            if let Some((x0, x1, q)) = run.take() {
                let f = (q as f64 + 0.5) / bands as f64;
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
        };
        for block in cols.chunks(cx) {
            let values = (j0..j1).flat_map(|k| block.iter().map(move |&i| (m.value)(k, i)));
            let Some(q) = m.scale.band(values) else {
                flush(&mut g, &mut run);
                continue;
            };
            let (i0, i1) = (block[0], block[block.len() - 1]);
            let half = |i: usize, d: isize| {
                let k = (i as isize + d).clamp(0, nx as isize - 1) as usize;
                0.5 * (x[i] + x[k])
            };
            let (x0, x1) = (px(half(i0, -1)), px(half(i1, 1)));
            match &mut run {
                Some((_, end, q0)) if *q0 == q => *end = x1,
                _ => {
                    flush(&mut g, &mut run);
                    run = Some((x0, x1, q));
                }
            }
        }
        flush(&mut g, &mut run);
    }
    // Guides at c_s and c_R from the first node reached.
    if let Some((x0, t0)) = m.origin {
        for (name, v, dash) in [("c_s", m.speeds[0], "8 4"), ("c_R", m.speeds[1], "3 3")] {
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
            // Labelled on the side with more room, at a different fraction of each line's
            // length inside the box: c_s and c_R differ by under 10 %, so labels at the lines'
            // exits would overlap.
            let side = if xb - x0 >= x0 - xa { 1.0 } else { -1.0 };
            let edge = if side > 0.0 { xb } else { xa };
            let (xe, te) = if (x0 + side * v * (t_end - t0) - edge) * side <= 0.0 {
                (x0 + side * v * (t_end - t0), t_end)
            } else {
                (edge, t0 + (edge - x0).abs() / v)
            };
            let f = if name == "c_s" { 0.92 } else { 0.6 };
            let (anchor, nudge) = if side > 0.0 { ("start", 4.0) } else { ("end", -4.0) };
            let _ = writeln!(
                g,
                "<text x=\"{:.1}\" y=\"{:.1}\" fill=\"#1f4e9c\" text-anchor=\"{anchor}\">{name}</text>",
                px(x0 + f * (xe - x0)) + nudge,
                py(t0 + f * (te - t0)) - 4.0
            );
        }
    }
    g.push_str("</g>\n");
    s.push_str(&g);
    let unit = m.x_unit.0;
    frame(
        &mut s,
        [ml, mt, w, h],
        ((xa / unit, xb / unit), &|v| px(v * unit)),
        ((0.0, t_end), &py),
        m.x_unit.1,
        m.t_label,
    );
    // The colour bar: one rectangle per band; a labelled tick at each decade (log) or at
    // round values (linear).
    let (bx, bw) = (ml + w + 24.0, 22.0);
    let steps = bands;
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
    let ticks: Vec<(f64, String)> = match m.scale {
        Scale::Log { peak } => {
            let bottom = Scale::bottom(peak);
            (0..=SPACETIME_DECADES)
                .map(|k| (f64::from(k) / f64::from(SPACETIME_DECADES), decade(bottom + k)))
                .collect()
        }
        Scale::Linear { range: (lo, hi) } => {
            let (vt, vd) = ticks(lo, hi);
            let span = (hi - lo).max(f64::MIN_POSITIVE);
            vt.into_iter().map(|v| ((v - lo) / span, format!("{v:.vd$}"))).collect()
        }
    };
    for (f, text) in ticks {
        let y = mt + h * (1.0 - f);
        let _ = writeln!(
            s,
            "<line x1=\"{}\" y1=\"{y:.1}\" x2=\"{}\" y2=\"{y:.1}\" stroke=\"black\"/><text class=\"cbar-tick\" x=\"{}\" y=\"{:.1}\">{text}</text>",
            bx + bw,
            bx + bw + 5.0,
            bx + bw + 8.0,
            y + 5.0,
        );
    }
    let lx = bx + bw + 62.0;
    let _ = writeln!(
        s,
        "<text x=\"{lx}\" y=\"{0}\" transform=\"rotate(-90 {lx} {0})\" text-anchor=\"middle\">{1}</text>",
        mt + h / 2.0,
        m.label
    );
    s.push_str("</svg>\n");
    s
}

/// `v` to 4 significant digits (titles and labels).
pub(crate) fn sig4(v: f64) -> String {
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
pub(crate) type Axis<'a> = ((f64, f64), &'a dyn Fn(f64) -> f64);

/// A plot's frame at [left, top, width, height], ticks on both axes and their labels.
pub(crate) fn frame(s: &mut String, [ml, mt, w, h]: [f64; 4], x: Axis, y: Axis, xlabel: &str, ylabel: &str) {
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

/// White through yellow and red to black, for a value in [0, 1].
pub(crate) fn colour(v: f32) -> String {
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
