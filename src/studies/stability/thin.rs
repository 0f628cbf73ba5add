//! The `thin` study: t/L -> 0 at a fixed number of elements through the thickness.

use super::*;

#[derive(Debug, Clone)]
pub struct ThinPoint {
    pub t_over_l: f64,
    pub nx: usize,
    pub dofs: usize,
    /// Graded along x because the uniform mesh was over the DOF budget.
    pub graded: bool,
    pub condition: f64,
    pub backward_error: f64,
    /// nnz(L) / nnz(K).
    pub fill: f64,
    pub time: f64,
    /// Least-squares slope of p/(N/L) over |x| < L/4, and its relative error from 12 (F/N)(H/L).
    pub slope: f64,
    pub slope_rel_err: f64,
    /// Max |tau/(N/L) - F/N| over |x| < L/4.
    pub tau_dev: f64,
    /// Edge widths in units of t: p left/right, tau left/right.
    pub widths: [Option<f64>; 4],
}

pub fn thin(base: &Scene, o: &Options, progress: Progress) -> Result<Vec<ThinPoint>> {
    let l = base.block.length;
    let mut out = Vec::new();
    for &tl in &o.thin_ratios {
        let mut s = base.clone();
        s.block.thickness = tl * l;
        s.mesh.h = s.block.thickness / o.thin_n_thick as f64;
        s.mesh.element = "qua4".into();
        s.loading.fn_ratios = vec![o.fn_ratio];
        let nx = (l / s.mesh.h).round() as usize;
        let graded = 2 * (nx + 1) * (o.thin_n_thick + 1) > o.max_dofs;
        if graded {
            // Square elements over 20 t at the ends, growing by 10 % to at most 10 t.
            s.mesh.grading = Some(1.1);
            s.mesh.h_max = Some(10.0 * s.block.thickness);
        }
        o.cancel.check()?;
        let clock = Instant::now();
        let (r, _) = check::run(&s, &SolverOptions::default())?;
        let time = clock.elapsed().as_secs_f64();
        let c = &r.cases[0];
        let mid: Vec<usize> = (0..c.x_over_l.len()).filter(|&i| c.x_over_l[i].abs() < 0.25).collect();
        let slope =
            crate::numeric::line_fit(mid.iter().map(|&i| (c.x_over_l[i], c.p[i]))).map_or(f64::NAN, |l| l.1);
        let model = c.metrics.slope_model;
        let mt = &c.metrics;
        o.done(progress, &format!("thin t/L {tl:.0e}"))?;
        out.push(ThinPoint {
            t_over_l: tl,
            nx: c.x_over_l.len() - 1,
            dofs: 2 * r.n_nodes,
            graded,
            condition: r.stats.report.condition_estimate,
            backward_error: r.stats.report.residual.iter().cloned().fold(0.0, f64::max),
            fill: r.stats.factor_nnz as f64 / r.stats.matrix_nnz as f64,
            time,
            slope,
            slope_rel_err: (slope - model).abs() / model.abs(),
            tau_dev: mid.iter().map(|&i| (c.tau[i] - c.fn_ratio).abs()).fold(0.0, f64::max),
            widths: [mt.edge_p_t[0], mt.edge_p_t[1], mt.edge_tau_t[0], mt.edge_tau_t[1]],
        });
    }
    Ok(out)
}
