//! The `corners` study: singular end nodes vs converging integrated quantities.

use super::*;

#[derive(Debug, Clone)]
pub struct CornerStudy {
    pub study: convergence::Study,
    /// p(+L/2) per mesh (coarse to fine) and the ratios of successive increments.
    pub p_end: Vec<f64>,
    pub increment_ratios: Vec<f64>,
    /// Mean of the last two increment ratios, and the exponent it implies: lambda = 1 - log2(factor).
    pub factor: f64,
    pub lambda_measured: f64,
    /// Williams' exponent of the clamped-free right-angle corner (plane strain) and 2^(1 - lambda).
    pub lambda_williams: f64,
    pub factor_williams: f64,
    pub nu: f64,
}

pub fn corners(base: &Scene, o: &Options, progress: Progress) -> Result<CornerStudy> {
    let so = StudyOptions {
        elements: vec!["qua4".into()],
        families: vec![Family::Uniform],
        n_thick: o.corner_n_thick.clone(),
        fn_ratio: o.fn_ratio,
        parallel: false,
        cancel: o.cancel.clone(),
        ..Default::default()
    };
    let each = |t: &crate::Tick<'_, convergence::Run>| {
        if let Some(r) = t.item {
            progress.message(&format!("corners qua4 t/{}", r.n_thick))
        }
    };
    let study = convergence::study(base, &so, Progress::new(&each))?;
    // Two successive increments make one ratio: at least three meshes.
    if study.runs.len() < 3 {
        return Err(Error::input(
            "--corner-max",
            format!(
                "the corner study needs at least three meshes (t/1, t/2, t/4) within the size limit; got {}{}",
                study.runs.len(),
                if study.skipped.is_empty() { String::new() } else { format!(", skipped: {}", study.skipped.join("; ")) }
            ),
        ));
    }
    let p_end: Vec<f64> = study.runs.iter().map(|r| r.p_end[1]).collect();
    let increment_ratios: Vec<f64> = p_end.windows(3).map(|w| (w[2] - w[1]) / (w[1] - w[0])).collect();
    let tail = &increment_ratios[increment_ratios.len().saturating_sub(2)..];
    let factor = tail.iter().sum::<f64>() / tail.len().max(1) as f64;
    let lw = crate::analytical::williams::clamped_free_exponent(
        std::f64::consts::FRAC_PI_2,
        base.block.plane_strain_nu(),
    )?
    .re;
    Ok(CornerStudy {
        study,
        p_end,
        increment_ratios,
        factor,
        lambda_measured: 1.0 - factor.log2(),
        lambda_williams: lw,
        factor_williams: 2f64.powf(1.0 - lw),
        nu: base.block.poisson,
    })
}
