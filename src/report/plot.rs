//! The report layer's shared chart pieces: the typeface, the palette, [`render`] (every
//! figure is drawn through it), the one legend box ([`Legend`]) and the axis guards (an empty
//! or infinite range sends plotters' tick search into an endless loop).

use crate::{Error, Result};
use plotters::chart::DualCoordChartContext;
use plotters::prelude::*;

/// The typeface of every figure.
pub(crate) const FONT: &str = "sans-serif";

/// The series colours of every figure, in order: Tableau 10's first eight (told apart by
/// most readers, colour-blind ones included, unlike pure red and green), then navy and maroon.
pub(crate) const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(23, 190, 207),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(0, 0, 128),
    RGBColor(128, 0, 0),
];
/// The palette's blue, red and green, named: they replace plotters' pure colours of the same
/// names wherever a figure imports them.
pub(crate) const BLUE: RGBColor = PALETTE[0];
pub(crate) const RED: RGBColor = PALETTE[1];
pub(crate) const GREEN: RGBColor = PALETTE[2];

/// The drawing area handed to a figure's closure.
pub(crate) type Area<'a> = DrawingArea<SVGBackend<'a>, plotters::coord::Shift>;

/// What a figure's drawing closure returns: plotters' errors, named after the figure by
/// [`render`].
pub(crate) type Drawn<T = ()> = std::result::Result<T, Box<dyn std::error::Error>>;

fn plot_err(figure: &str) -> impl Fn(Box<dyn std::error::Error>) -> Error + '_ {
    move |e| Error::plot(figure, e)
}

/// Runs a plotting closure on an in-memory SVG of the given size (pixels), on white.
pub(crate) fn render(figure: &str, size: (u32, u32), draw: impl FnOnce(&Area) -> Drawn) -> Result<String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(|e| plot_err(figure)(e.into()))?;
        draw(&root).map_err(plot_err(figure))?;
        root.present().map_err(|e| plot_err(figure)(e.into()))?;
    }
    Ok(svg)
}

/// The legend box of every figure: the chart's series labels at a given corner, on white at
/// 90 % opacity, in a black frame, 14 pt. For plain and dual-coordinate charts alike (a
/// secondary axis's series are labelled on the primary chart).
pub(crate) trait Legend {
    fn legend_box(&mut self, pos: SeriesLabelPosition) -> Drawn;
}

impl<'a, 'b: 'a, CT: CoordTranslate> Legend for ChartContext<'a, SVGBackend<'b>, CT> {
    fn legend_box(&mut self, pos: SeriesLabelPosition) -> Drawn {
        self.configure_series_labels()
            .position(pos)
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .label_font((FONT, 14))
            .draw()?;
        Ok(())
    }
}

impl<'a, 'b: 'a, CT1: CoordTranslate, CT2: CoordTranslate> Legend
    for DualCoordChartContext<'a, SVGBackend<'b>, CT1, CT2>
{
    fn legend_box(&mut self, pos: SeriesLabelPosition) -> Drawn {
        (**self).legend_box(pos)
    }
}

/// An axis range for a log scale over the finite positive values, padded by 2x each way
/// (1e-6..1 when there is none).
pub(crate) fn log_range(v: impl Iterator<Item = f64>) -> std::ops::Range<f64> {
    let (lo, hi) = v
        .filter(|x| *x > 0.0 && x.is_finite())
        .fold((f64::INFINITY, 0.0f64), |(a, b), x| (a.min(x), b.max(x)));
    if lo.is_finite() {
        (lo / 2.0)..(hi * 2.0)
    } else {
        1e-6..1.0
    }
}

/// A linear axis range over the finite values, padded by 8 % of their span (at least 1e-3);
/// 0..1 when there is none.
pub(crate) fn padded_range(v: impl Iterator<Item = f64>) -> std::ops::Range<f64> {
    let (lo, hi) = v
        .filter(|x| x.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
    if !(lo.is_finite() && hi.is_finite()) {
        return 0.0..1.0;
    }
    let pad = 0.08 * (hi - lo).max(1e-3);
    (lo - pad)..(hi + pad)
}

/// Viridis, linearly interpolated between five anchors; `c` in [0, 1].
pub(crate) fn viridis(c: f64) -> RGBColor {
    const A: [(f64, f64, f64); 5] =
        [(68., 1., 84.), (59., 82., 139.), (33., 145., 140.), (94., 201., 98.), (253., 231., 37.)];
    let t = c.clamp(0.0, 1.0) * 4.0;
    let k = (t.floor() as usize).min(3);
    let u = t - k as f64;
    let mix = |a: f64, b: f64| (a + (b - a) * u).round() as u8;
    RGBColor(mix(A[k].0, A[k + 1].0), mix(A[k].1, A[k + 1].1), mix(A[k].2, A[k + 1].2))
}

/// The colour of a count `n` on a map whose largest count is `n_max`: viridis, logarithmic in
/// 1 + n (counts run from 0 to thousands).
pub(crate) fn n_colour(n: usize, n_max: usize) -> RGBColor {
    viridis(if n_max == 0 { 0.0 } else { (n as f64).ln_1p() / (n_max as f64).ln_1p() })
}

/// The shared colour key of the n maps ([`n_colour`]) down the `key` area; returns the y
/// below it, for further entries.
pub(crate) fn n_key(key: &Area, n_max: usize) -> Drawn<i32> {
    key.draw(&Text::new("n (log colour scale)", (0, 40), (FONT, 14)))?;
    let mut shown: Vec<usize> =
        [0, 1, 2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 10000, 20000, 50000]
            .into_iter()
            .filter(|&v| v < n_max)
            .collect();
    shown.push(n_max);
    let mut y = 60;
    for &v in &shown {
        key.draw(&Rectangle::new([(10, y), (36, y + 20)], n_colour(v, n_max).filled()))?;
        let label = if v == n_max { format!("{v} (max)") } else { v.to_string() };
        key.draw(&Text::new(label, (44, y + 4), (FONT, 13)))?;
        y += 25;
    }
    Ok(y)
}
