//! The `shape` study: elongated and distorted elements.

use super::*;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShapeCase {
    /// Square elements at the ends, growing to `aspect` x h in the smooth interior.
    Graded,
    /// Uniformly elongated elements everywhere, ends included.
    Uniform,
    /// Square structured mesh with interior nodes moved at random (`aspect` = amplitude / h).
    Distorted,
    /// The unstructured quad-dominant Gmsh mesh of the block (`meshes/`), QUA4-family
    /// elements only (the file holds QUA4 and TRI3).
    Unstructured,
}

impl ShapeCase {
    pub fn name(self) -> &'static str {
        match self {
            ShapeCase::Graded => "graded",
            ShapeCase::Uniform => "uniform",
            ShapeCase::Distorted => "distorted",
            ShapeCase::Unstructured => "unstructured",
        }
    }
}

#[derive(Debug, Clone)]
pub struct ShapePoint {
    pub case: ShapeCase,
    pub element: String,
    /// Largest element aspect ratio (length / height), or the distortion amplitude / h.
    pub param: f64,
    pub n_elements: usize,
    pub errors: ZoneErrors,
    /// Largest interior error and edge error t .. 10 t from the ends (p or tau), units of N/L.
    pub err: f64,
    pub err_edge_far: f64,
    /// Smallest Jacobian determinant over elements relative to the undistorted one (distorted only).
    pub min_jacobian_rel: f64,
}

pub fn shape(
    base: &Scene,
    o: &Options,
    refs: &mut References,
    progress: Progress,
) -> Result<Vec<ShapePoint>> {
    let rf = refs.get(base.block.poisson, o, progress)?.clone();
    let t = base.block.thickness;
    let h = t / o.n_thick as f64;
    let mut out = Vec::new();
    for e in &o.elements {
        let mut s = base.clone();
        s.mesh.element = e.clone();
        s.mesh.h = h;
        s.mesh.n_thick = Some(o.n_thick);
        s.loading.fn_ratios = vec![o.fn_ratio];
        for &a in &o.aspects {
            for case in [ShapeCase::Graded, ShapeCase::Uniform] {
                let mut v = s.clone();
                match case {
                    ShapeCase::Graded => {
                        v.mesh.grading = Some(o.grading_ratio);
                        v.mesh.h_max = Some(a * h);
                    }
                    _ => {
                        v.mesh.h = a * h;
                        v.mesh.n_thick = Some(o.n_thick);
                    }
                }
                o.cancel.check()?;
                let (r, _) = check::run(&v, &SolverOptions::default())?;
                let errors = errors_against(&r, &rf);
                o.done(progress, &format!("shape {} {e} 1:{a}", case.name()))?;
                out.push(ShapePoint {
                    case,
                    element: e.clone(),
                    param: a,
                    n_elements: r.n_elements,
                    err: interior_max(&errors),
                    err_edge_far: edge_far(&r, &rf),
                    errors,
                    min_jacobian_rel: 1.0,
                });
            }
        }
        for &amp in &o.distortions {
            let mut sm = s.build()?;
            let j0 = (0..sm.mesh.n_elements()).map(|k| sm.mesh.min_jacobian(k)).fold(f64::INFINITY, f64::min);
            sm.mesh.distort(amp * h, o.seed)?;
            let j1 = (0..sm.mesh.n_elements()).map(|k| sm.mesh.min_jacobian(k)).fold(f64::INFINITY, f64::min);
            o.cancel.check()?;
            let (r, _) = check::run_model(&s, sm, 0.0, &SolverOptions::default(), None)?;
            let errors = errors_against(&r, &rf);
            o.done(progress, &format!("shape distorted {e} {amp}"))?;
            out.push(ShapePoint {
                case: ShapeCase::Distorted,
                element: e.clone(),
                param: amp,
                n_elements: r.n_elements,
                err: interior_max(&errors),
                err_edge_far: edge_far(&r, &rf),
                errors,
                min_jacobian_rel: j1 / j0,
            });
        }
        let qua4_family = s.element()?.kind == crate::fem::element::ElementKind::Qua4;
        if let (Some(path), true) = (o.unstructured_mesh.as_ref().filter(|p| p.exists()), qua4_family) {
            let mut v = s.clone();
            v.mesh.file = Some(path.clone());
            let sm = v.build()?;
            let quality =
                (0..sm.mesh.n_elements()).map(|k| sm.mesh.jacobian_quality(k)).fold(f64::INFINITY, f64::min);
            o.cancel.check()?;
            let (r, _) = check::run_model(&v, sm, 0.0, &SolverOptions::default(), None)?;
            let errors = errors_against(&r, &rf);
            o.done(progress, &format!("shape unstructured {e}"))?;
            out.push(ShapePoint {
                case: ShapeCase::Unstructured,
                element: e.clone(),
                param: 0.0,
                n_elements: r.n_elements,
                err: interior_max(&errors),
                err_edge_far: edge_far(&r, &rf),
                errors,
                min_jacobian_rel: quality,
            });
        }
    }
    Ok(out)
}
