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
    /// The slip rate of row k at node i, m/s.
    pub rate: &'a dyn Fn(usize, usize) -> f64,
    pub peak: f64,
    /// Where and when the first node was reached: the guides' origin.
    pub origin: Option<(f64, f64)>,
    /// c_s and c_R, m/s.
    pub speeds: [f64; 2],
    pub rate_label: &'a str,
}

/// The picture: at most 360 columns and 320 rows (the largest rate of each block), the
/// colour scale [`SPACETIME_DECADES`] decades below the peak (white below).
pub(crate) fn heat_map(m: &HeatMap) -> String {
    let (x, nx) = (m.x, m.x.len());
    let (t_of, t_end, rows_shown) = (m.t, m.t_end, m.rows);
    let (xa, xb) = m.x_range;
    let cols: Vec<usize> = (0..nx).filter(|&i| x[i] >= xa && x[i] <= xb).collect();
    let top = m.peak.log10().ceil() as i32;
    let bottom = top - SPACETIME_DECADES;
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
    // The heat map: at most 360 columns and 320 rows, the largest rate of each block.
    let (cx, ct) = (cols.len().div_ceil(360).max(1), rows_shown.div_ceil(320).max(1));
    let mut g = String::from("<g clip-path=\"url(#plot)\">\n");
    for j0 in (0..rows_shown).step_by(ct) {
        let j1 = (j0 + ct).min(rows_shown);
        let (ya, yb) = (py(if j0 == 0 { 0.0 } else { t_of(j0 - 1) }), py(t_of(j1 - 1)));
        // Cells of one colour band (a tenth of a decade, as the colour bar) side by side are
        // one rectangle: the picture is as read, at a tenth of the size.
        let mut run: Option<(f64, f64, i32)> = None;
        let flush = |g: &mut String, run: &mut Option<(f64, f64, i32)>| {
            if let Some((x0, x1, q)) = run.take() {
                let f = (f64::from(q) + 0.5) / f64::from(10 * SPACETIME_DECADES);
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
            let v = (j0..j1)
                .flat_map(|k| block.iter().map(move |&i| (k, i)))
                .fold(0.0f64, |acc, (k, i)| acc.max((m.rate)(k, i)));
            if v <= 10f64.powi(bottom) {
                flush(&mut g, &mut run);
                continue;
            }
            let (i0, i1) = (block[0], block[block.len() - 1]);
            let half = |i: usize, d: isize| {
                let k = (i as isize + d).clamp(0, nx as isize - 1) as usize;
                0.5 * (x[i] + x[k])
            };
            let (x0, x1) = (px(half(i0, -1)), px(half(i1, 1)));
            let f = (v.log10() - f64::from(bottom)) / f64::from(SPACETIME_DECADES);
            let q =
                ((f * f64::from(10 * SPACETIME_DECADES)).floor() as i32).clamp(0, 10 * SPACETIME_DECADES - 1);
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
    let unit = m.x_unit.0;
    frame(
        &mut s,
        [ml, mt, w, h],
        ((xa / unit, xb / unit), &|v| px(v * unit)),
        ((0.0, t_end), &py),
        m.x_unit.1,
        m.t_label,
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
        "<text x=\"{lx}\" y=\"{0}\" transform=\"rotate(-90 {lx} {0})\" text-anchor=\"middle\">{1}</text>",
        mt + h / 2.0,
        m.rate_label
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

/// What [`linear_map`] draws: a field over position (across) and time (down) on a linear
/// colour scale from `range.0` (white) to `range.1` (dark red).
pub(crate) struct LinearMap<'a> {
    pub title: String,
    pub x: &'a [f64],
    pub x_range: (f64, f64),
    pub x_unit: (f64, &'a str),
    pub t: &'a dyn Fn(usize) -> f64,
    pub rows: usize,
    pub t_end: f64,
    pub t_label: &'a str,
    pub value: &'a dyn Fn(usize, usize) -> f64,
    pub range: (f64, f64),
    pub label: &'a str,
}

/// The picture: one cell per node and row (20 colour bands), a colour bar with ticks.
pub(crate) fn linear_map(m: &LinearMap) -> String {
    const BANDS: usize = 20;
    let (x, nx) = (m.x, m.x.len());
    let (xa, xb) = m.x_range;
    let (lo, hi) = m.range;
    let span = (hi - lo).max(f64::MIN_POSITIVE);
    let (w, h, ml, mt, mb, mr) = (720.0, 480.0, 80.0, 50.0, 60.0, 150.0);
    let px = |x: f64| ml + (x - xa) / (xb - xa).max(f64::MIN_POSITIVE) * w;
    let py = |t: f64| mt + t / m.t_end * h;
    let band = |v: f64| (((v - lo) / span * BANDS as f64).floor() as i64).clamp(0, BANDS as i64 - 1) as usize;
    let fill = |q: usize| colour(((q as f64 + 0.5) / BANDS as f64) as f32);
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
    let mut g = String::from("<g clip-path=\"url(#plot)\">\n");
    let half = |i: usize, d: isize| 0.5 * (x[i] + x[(i as isize + d).clamp(0, nx as isize - 1) as usize]);
    for k in 0..m.rows {
        let (ya, yb) = (py(if k == 0 { 0.0 } else { (m.t)(k - 1) }), py((m.t)(k)));
        // Neighbours of one band are one rectangle.
        let mut run: Option<(f64, f64, usize)> = None;
        let flush = |g: &mut String, run: Option<(f64, f64, usize)>| {
            if let Some((x0, x1, q)) = run {
                let _ = writeln!(
                    g,
                    "<rect x=\"{x0:.2}\" y=\"{ya:.2}\" width=\"{:.2}\" height=\"{:.2}\" fill=\"{}\"/>",
                    (x1 - x0).max(0.3) + 0.3,
                    (yb - ya).max(0.3) + 0.3,
                    fill(q)
                );
            }
        };
        for i in (0..nx).filter(|&i| x[i] >= xa && x[i] <= xb) {
            let (q, x0, x1) = (band((m.value)(k, i)), px(half(i, -1)), px(half(i, 1)));
            match &mut run {
                Some((_, end, q0)) if *q0 == q => *end = x1,
                _ => {
                    flush(&mut g, run.take());
                    run = Some((x0, x1, q));
                }
            }
        }
        flush(&mut g, run);
    }
    g.push_str("</g>\n");
    s.push_str(&g);
    let unit = m.x_unit.0;
    frame(
        &mut s,
        [ml, mt, w, h],
        ((xa / unit, xb / unit), &|v| px(v * unit)),
        ((0.0, m.t_end), &py),
        m.x_unit.1,
        m.t_label,
    );
    let (bx, bw) = (ml + w + 24.0, 22.0);
    for q in 0..BANDS {
        let _ = writeln!(
            s,
            "<rect x=\"{bx}\" y=\"{:.2}\" width=\"{bw}\" height=\"{:.2}\" fill=\"{}\"/>",
            mt + h * (1.0 - (q + 1) as f64 / BANDS as f64),
            h / BANDS as f64 + 0.3,
            fill(q)
        );
    }
    let _ = writeln!(
        s,
        "<rect x=\"{bx}\" y=\"{mt}\" width=\"{bw}\" height=\"{h}\" fill=\"none\" stroke=\"black\"/>"
    );
    let (vt, vd) = ticks(lo, hi);
    for v in vt {
        let y = mt + h * (1.0 - (v - lo) / span);
        let _ = writeln!(
            s,
            "<line x1=\"{}\" y1=\"{y:.1}\" x2=\"{}\" y2=\"{y:.1}\" stroke=\"black\"/><text class=\"cbar-tick\" x=\"{}\" y=\"{:.1}\">{v:.vd$}</text>",
            bx + bw,
            bx + bw + 5.0,
            bx + bw + 8.0,
            y + 5.0
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
