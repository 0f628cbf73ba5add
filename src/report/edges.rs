//! Output of `tribofe edges`: preslip.csv and preslip.svg (pre-slip extent under N alone
//! against refinement), opening.csv (the trailing end under the drive against the first
//! precursor). Undefined figures are empty cells, never NaN.

use crate::error::Result;
use crate::report::finite;
#[cfg(feature = "plots")]
use crate::report::plot::{render, Legend, PALETTE};
use crate::studies::edges::{Opening, Preslip};
#[cfg(feature = "plots")]
use plotters::prelude::*;
use std::fmt::Write as _;

fn cell(what: &str, v: Option<f64>) -> Result<String> {
    v.map_or(Ok(String::new()), |v| Ok(format!("{:.12e}", finite(what, v)?)))
}

pub fn preslip_csv(rows: &[Preslip]) -> Result<String> {
    let mut s = String::from("mu,t_over_h,interface_nodes,left_extent_over_t,right_extent_over_t\n");
    for r in rows {
        let c = |v| cell("pre-slip extent", Some(v));
        writeln!(s, "{},{},{},{},{}", r.mu, r.t_over_h, r.nodes, c(r.extent_t[0])?, c(r.extent_t[1])?)
            .unwrap();
    }
    Ok(s)
}

pub fn opening_csv(rows: &[Opening]) -> Result<String> {
    let mut s = String::from(
        "t_over_L,t_over_h,H_over_L,g,F1_model_over_mu_s_N,F_open_over_mu_s_N,open_length_over_t,F1_fe_over_mu_s_N,max_open_length_over_t,opens_before_first_precursor,open_nodes,max_open_nodes,end_element_over_t\n",
    );
    for r in rows {
        writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{},{},{},{}",
            r.t_over_l,
            r.t_over_h,
            r.h_over_l,
            cell("g", Some(r.g))?,
            cell("F_1", Some(r.f1_model))?,
            cell("F_open", r.f_open)?,
            cell("open length", r.open_length_t)?,
            cell("F_1 FE", r.f1_fe)?,
            cell("open length", Some(r.max_open_t))?,
            r.opens_first(),
            r.open_nodes.map_or(String::new(), |n| n.to_string()),
            r.max_open_nodes,
            cell("end element", Some(r.end_element_t))?
        )
        .unwrap();
    }
    Ok(s)
}

#[cfg(feature = "plots")]
/// Pre-slip extent (both ends) against t/h, one line per mu, log x.
pub fn preslip_svg(rows: &[Preslip]) -> Result<String> {
    let mut mus: Vec<f64> = rows.iter().map(|r| r.mu).collect();
    mus.sort_by(f64::total_cmp);
    mus.dedup();
    let kmax = rows.iter().map(|r| r.t_over_h).fold(2.0, f64::max);
    let ymax = rows.iter().flat_map(|r| r.extent_t).fold(0.5, f64::max) * 1.15;
    render("preslip.svg", (720, 480), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption("Pre-slip under N alone: extent from each end vs refinement", ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(55)
            .build_cartesian_2d((1.0..kmax * 1.3).log_scale(), 0.0..ymax)?;
        chart
            .configure_mesh()
            .x_desc("elements through the thickness t/h")
            .y_desc("pre-slip extent / t")
            .draw()?;
        for (i, &mu) in mus.iter().enumerate() {
            let color = PALETTE[i % PALETTE.len()];
            let pts = |end: usize| -> Vec<(f64, f64)> {
                rows.iter().filter(|r| r.mu == mu).map(|r| (r.t_over_h, r.extent_t[end])).collect()
            };
            chart
                .draw_series(LineSeries::new(pts(0), color.stroke_width(2)))?
                .label(format!("mu = {mu} (left end; dashed: right)"))
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2)));
            chart.draw_series(pts(0).into_iter().map(|p| Circle::new(p, 4, color.filled())))?;
            chart.draw_series(DashedLineSeries::new(pts(1), 6, 4, color.stroke_width(1)))?;
        }
        chart.legend_box(SeriesLabelPosition::MiddleRight)?;
        Ok(())
    })
}
