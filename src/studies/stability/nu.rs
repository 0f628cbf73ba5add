//! The `nu` study: near-incompressibility: locking per element against a QUA9 reference.

use super::*;

#[derive(Debug, Clone)]
pub struct NuPoint {
    pub nu: f64,
    pub element: String,
    pub errors: ZoneErrors,
    /// Largest interior error (p or tau), units of N/L: the edge zones' error is dominated by
    /// the singular corners for every element, the interior's shows locking.
    pub err: f64,
    /// See `edge_far`.
    pub err_edge_far: f64,
    /// Max |second difference| of p or tau between neighbouring nodes t/2 .. 10 t from the
    /// ends, in excess of the reference's sampled at those nodes (units of N/L): checkerboard.
    pub oscillation: f64,
    /// p(0) at F/N = 0 over the closed-form thin-layer value (dimensionless; 1 = exact).
    pub p0_closed: f64,
    /// N / (L strain) over the confined modulus lambda + 2G (dimensionless).
    pub modulus_ratio: f64,
}

#[derive(Debug, Clone)]
pub struct NuStudy {
    pub points: Vec<NuPoint>,
    /// The references' own closed-form p(0) ratios, per nu.
    pub reference_p0: Vec<(f64, f64)>,
}

/// Closed-form p(0) and N/(L strain) ratios of a run's F/N = 0 case (the first).
fn closed_form(r: &CheckResult) -> Result<(f64, f64)> {
    let s = &r.scene;
    let mat = s.block.material()?;
    let c = &r.cases[0];
    let strain = c.plate_v.abs() / s.block.thickness;
    let pmean = c.n / s.block.length;
    let p0 = interpolate(&c.x_over_l, &c.p, 0.0) * pmean;
    let m = mat.lambda() + 2.0 * mat.shear_modulus();
    Ok((
        p0 / crate::analytical::thin_layer::bonded_layer_p0(&mat, strain, s.block.length, s.block.thickness),
        pmean / (m * strain),
    ))
}

fn oscillation(r: &CheckResult, reference: &CheckResult) -> f64 {
    let (c, rc) = (r.cases.last().unwrap(), reference.cases.last().unwrap());
    let tl = r.scene.block.thickness / r.scene.block.length;
    let x = &c.x_over_l;
    let mut worst = 0.0f64;
    for i in 1..x.len() - 1 {
        let d = 0.5 - x[i].abs();
        if d < 0.5 * tl || d > 10.0 * tl {
            continue;
        }
        let second = |v: &dyn Fn(usize) -> f64| v(i - 1) - 2.0 * v(i) + v(i + 1);
        for (own, rv) in [(&c.p, &rc.p), (&c.tau, &rc.tau)] {
            let a = second(&|k| own[k]);
            let b = second(&|k| interpolate(&rc.x_over_l, rv, x[k]));
            worst = worst.max((a.abs() - b.abs()).max(0.0));
        }
    }
    worst
}

pub fn nu(base: &Scene, o: &Options, refs: &mut References, progress: Progress) -> Result<NuStudy> {
    let mut points = Vec::new();
    let mut reference_p0 = Vec::new();
    for &nu in &o.nus {
        let rf = refs.get(nu, o, progress)?.clone();
        reference_p0.push((nu, closed_form(&rf)?.0));
        for e in &o.elements {
            let mut s = base.clone();
            s.block.poisson = nu;
            s.mesh.h = s.block.thickness / o.n_thick as f64;
            s.mesh.n_thick = Some(o.n_thick);
            s.mesh.element = e.clone();
            s.loading.fn_ratios = vec![0.0, o.fn_ratio];
            o.cancel.check()?;
            let (r, _) = check::run(&s, &SolverOptions::default())?;
            let errors = errors_against(&r, &rf);
            let (p0_closed, modulus_ratio) = closed_form(&r)?;
            o.done(progress, &format!("nu {nu} {e}"))?;
            points.push(NuPoint {
                nu,
                element: e.clone(),
                err: interior_max(&errors),
                err_edge_far: edge_far(&r, &rf),
                errors,
                oscillation: oscillation(&r, &rf),
                p0_closed,
                modulus_ratio,
            });
        }
    }
    Ok(NuStudy { points, reference_p0 })
}
