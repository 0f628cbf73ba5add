//! Physics is input, resolution is checked: the dynamic run's default D_c comes from a
//! stated stability number and never from the mesh; the mesh is then chosen (or a given one
//! checked) so that the cohesive zone spans at least [`MIN_ZONE_ELEMENTS`] elements.

use crate::error::{Error, Result};
use crate::law::Law;
use crate::scene::Scene;

pub use crate::dynamics::rupture::MIN_ZONE_ELEMENTS;

/// A base node is reached by a dynamic front when its |v_x| first exceeds this fraction of
/// [`arrival_rate`]'s scale (fronts_t.csv): 1 %, below the slowest instabilities' peaks (7 %
/// of the scale on the paper's scene, whose stress drop is a fraction of the strength drop)
/// and far above a node at rest (0 exactly in the held drive; 1e-9 to 1e-7 m/s at an
/// event's end).
pub const ARRIVAL_FRACTION: f64 = 0.01;

/// The front-arrival threshold, m/s: [`ARRIVAL_FRACTION`] of dtau / (rho c_s), the particle
/// velocity of a shear wave carrying the strength drop dtau = (mu_s - mu_d) N/L at the mean
/// pressure (mu_s N/L without a drop); the scale is 1.92e-4 m/s on the paper's scene (the
/// threshold 1.92e-6 m/s), whose fronts slip at up to 3.7e-4 m/s. Set by the law, the load
/// and the material, never by the mesh.
pub fn arrival_rate(f: &Law, n_over_l: f64, density: f64, c_s: f64) -> f64 {
    ARRIVAL_FRACTION * rate_scale(f.mu_s(), f.mu_d(), n_over_l, density, c_s)
}

/// dtau / (rho c_s), m/s: the particle velocity of a shear wave carrying the strength drop
/// dtau = (mu_s - mu_d) N/L (mu_s N/L without a drop): the law's own slip-rate scale.
fn rate_scale(mu_s: f64, mu_d: f64, n_over_l: f64, density: f64, c_s: f64) -> f64 {
    let drop = if mu_s > mu_d { mu_s - mu_d } else { mu_s };
    drop * n_over_l / (density * c_s)
}

/// The constant-velocity drive's event threshold under a weakening law, m/s: the front
/// arrival rate at the mean pressure (1.92e-6 m/s on the paper's scene and the short one),
/// so a node is in an event exactly when a front has reached it. It is set by the law, the
/// load and the material, never by V or the mesh, so the V -> 0 limit is the held mode's;
/// the weakest instability seen, the held mode's first on the short scene (L = 0.1 m),
/// peaks at 2.1 times it.
pub fn event_rate(scene: &Scene, mu_s: f64, mu_d: f64, n_force: f64) -> Result<f64> {
    let b = &scene.block;
    let c_s = super::shear_speed(scene)?;
    Ok(ARRIVAL_FRACTION * rate_scale(mu_s, mu_d, n_force / b.length, b.density, c_s))
}

/// The convergence study's D_c on the paper's scene (validation/dynamics/converge): there
/// the thin-layer stability number is [`default_kappa`] = 0.509 and the paper's precursors
/// exist; F_1, x_1, the front envelope and the peak converge as h halves at this D_c.
pub const PAPER_DC: f64 = 2.3107e-7;

/// G D_c / ((mu_s - mu_d) (N/L) t) without D_c, m^-1: the thin-layer stability number per
/// metre of D_c. A point of the layer is held by the layer's shear stiffness G/t and weakens
/// at (mu_s - mu_d) p / D_c; the first exceeding the second (kappa > ~1) slips stably.
fn kappa_per_dc(scene: &Scene, mu_s: f64, mu_d: f64, n_force: f64) -> f64 {
    let b = &scene.block;
    let g = b.young / (2.0 * (1.0 + b.poisson));
    g / ((mu_s - mu_d) * (n_force / b.length) * b.thickness)
}

/// The thin-layer stability number kappa = G D_c / ((mu_s - mu_d) (N/L) t), dimensionless.
pub fn kappa(scene: &Scene, mu_s: f64, mu_d: f64, dc: f64, n_force: f64) -> f64 {
    kappa_per_dc(scene, mu_s, mu_d, n_force) * dc
}

/// The paper's scene and law ((r, g) = (0.9, 0.35), N = 1 N/m): what [`PAPER_DC`] refers to.
fn paper() -> Result<(Scene, f64, f64)> {
    let s = Scene::default();
    let (mu_s, mu_d) = crate::studies::slide::coefficients_from_rg(
        &s,
        crate::precursors::PAPER_R,
        crate::precursors::PAPER_G,
    )?;
    Ok((s, mu_s, mu_d))
}

/// kappa of [`PAPER_DC`] on the paper's scene (0.5093): the default stability number.
pub fn default_kappa() -> Result<f64> {
    let (s, mu_s, mu_d) = paper()?;
    Ok(kappa(&s, mu_s, mu_d, PAPER_DC, 1.0))
}

/// The default D_c, m: the one giving every scene the paper scene's [`default_kappa`], so
/// exactly [`PAPER_DC`] there. It depends on the block, the law and N, never on the mesh.
pub fn default_dc(scene: &Scene, mu_s: f64, mu_d: f64, n_force: f64) -> Result<f64> {
    crate::studies::slide::check_n_force(scene, n_force)?;
    if !(mu_s > mu_d) {
        return Err(Error::input(
            "--mu-s/--mu-d",
            format!("mu_s = {mu_s} must exceed mu_d = {mu_d} to weaken"),
        ));
    }
    let (s, ms, md) = paper()?;
    // A ratio of the same expression, so the paper's scene gets PAPER_DC to the last bit.
    Ok(PAPER_DC * (kappa_per_dc(&s, ms, md, 1.0) / kappa_per_dc(scene, mu_s, mu_d, n_force)))
}

/// Lambda_0 = (9 pi / 32) G D_c / ((1 - nu) (mu_s - mu_d) N/L), m, at the mean pressure.
pub fn lambda0(scene: &Scene, mu_s: f64, mu_d: f64, dc: f64, n_force: f64) -> Result<f64> {
    crate::studies::slide::check_n_force(scene, n_force)?;
    let b = &scene.block;
    let g = b.young / (2.0 * (1.0 + b.poisson));
    Ok(Law::SlipWeakening { mu_s, mu_d, dc }.cohesive_zone(g, b.plane_strain_nu(), n_force / b.length))
}

/// The smallest D_c whose cohesive zone spans [`MIN_ZONE_ELEMENTS`] elements of the scene's
/// h, m: what a given mesh can resolve (named in refusals; not a default).
pub fn smallest_resolved_dc(scene: &Scene, mu_s: f64, mu_d: f64, n_force: f64) -> Result<f64> {
    Ok(MIN_ZONE_ELEMENTS * scene.mesh.h / lambda0(scene, mu_s, mu_d, 1.0, n_force)?)
}

/// The largest element size t/k (k = 1, 2, ...: a whole number of elements through the
/// thickness) at which Lambda_0 spans at least [`MIN_ZONE_ELEMENTS`] elements, m.
pub fn resolving_h(thickness: f64, lambda0: f64) -> f64 {
    let mut k = ((MIN_ZONE_ELEMENTS * thickness / lambda0).ceil() as usize).max(1);
    while lambda0 * k as f64 / thickness < MIN_ZONE_ELEMENTS {
        k += 1;
    }
    thickness / k as f64
}

/// Refuses a mesh that does not resolve the cohesive zone, naming the element size that would
/// and the D_c this mesh resolves. `h_name` is the size as the user gave it (`--h`).
pub fn check_resolved(
    scene: &Scene,
    mu_s: f64,
    mu_d: f64,
    dc: f64,
    n_force: f64,
    h_name: &str,
) -> Result<()> {
    let l0 = lambda0(scene, mu_s, mu_d, dc, n_force)?;
    let h = scene.mesh.h;
    if l0 < MIN_ZONE_ELEMENTS * h {
        return Err(Error::input(
            h_name,
            format!(
                "{h} m: the cohesive zone Lambda_0 = {l0:.3e} m (D_c = {dc:.4e} m) spans {:.2} elements, fewer than {MIN_ZONE_ELEMENTS}, so the fronts would be set by the mesh: use {h_name} {:.4e} (or leave it out to have it chosen), or --dc >= {:.3e} m",
                l0 / h,
                resolving_h(scene.block.thickness, l0),
                smallest_resolved_dc(scene, mu_s, mu_d, n_force)?
            ),
        ));
    }
    Ok(())
}

/// Refuses a mesh that cannot resolve rate-and-state's process zone L_b = G L / ((1 - nu) b
/// sigma) at the mean pressure ([`Law::process_zone`]) with [`MIN_ZONE_ELEMENTS`] elements,
/// naming the h and the L that would (a rate-strengthening law, b = 0, has none to resolve).
pub fn check_rate_state_resolved(scene: &Scene, r: &crate::law::RateState, n_force: f64) -> Result<()> {
    crate::studies::slide::check_n_force(scene, n_force)?;
    let b = &scene.block;
    let g = b.young / (2.0 * (1.0 + b.poisson));
    let lb = Law::RateState(*r).process_zone(g, b.plane_strain_nu(), n_force / b.length);
    let h = scene.mesh.h;
    if lb < MIN_ZONE_ELEMENTS * h {
        return Err(Error::input(
            "--h",
            format!(
                "{h} m: rate-and-state's process zone L_b = G L / ((1 - nu) b sigma) = {lb:.3e} m at the mean pressure spans {:.2} elements, fewer than {MIN_ZONE_ELEMENTS}, so the fronts would be set by the mesh: use --h <= {:.4e} m, or --l-rs >= {:.3e} m",
                lb / h,
                lb / MIN_ZONE_ELEMENTS,
                r.l * MIN_ZONE_ELEMENTS * h / lb
            ),
        ));
    }
    Ok(())
}

/// What [`resolve`] chose, with the lines that say so (printed by the command, returned to
/// Python).
#[derive(Debug, Clone)]
pub struct Resolved {
    /// The slip-weakening law with its D_c.
    pub law: crate::law::Law,
    /// kappa and the regime it suggests.
    pub kappa: f64,
    pub notes: Vec<String>,
}

/// Physics is input, resolution is checked, for `slide --dynamics --law slip-weakening` from
/// any front end: D_c from [`default_dc`] when `choice.dc` is None; then, when `h_given` is
/// false (no `--h`, no `[mesh] h`, no `h=`) and the scene is generated, the element size is
/// refined to [`resolving_h`] if the scene's does not resolve Lambda_0. A given size is
/// checked later by [`check_resolved`] (in the run's own checks). `names`: D_c and h as the
/// front end's user types them (`["--dc", "--h"]`, `["dc=", "h="]`), for the notes.
pub fn resolve(
    scene: &mut Scene,
    choice: &crate::studies::slide::LawChoice,
    n_force: f64,
    h_given: bool,
    names: [&str; 2],
) -> Result<Resolved> {
    let probe = crate::studies::slide::LawChoice { dc: Some(1.0), ..choice.clone() }.law(scene)?;
    let (mu_s, mu_d) = (probe.mu_s(), probe.mu_d());
    let mut notes = Vec::new();
    let dc = match choice.dc {
        Some(dc) => dc,
        None => {
            let dc = default_dc(scene, mu_s, mu_d, n_force)?;
            notes.push(format!(
                "{} not given: D_c = {dc:.5e} m, the D_c giving the thin-layer stability number kappa = {:.4} of the paper's scene at D_c = {PAPER_DC:e} m (whatever the mesh)",
                names[0],
                default_kappa()?
            ));
            dc
        }
    };
    let law = crate::studies::slide::LawChoice { dc: Some(dc), ..choice.clone() }.law(scene)?;
    if scene.mesh.file.is_none() && !h_given {
        let l0 = lambda0(scene, mu_s, mu_d, dc, n_force)?;
        let h = resolving_h(scene.block.thickness, l0);
        if h < scene.mesh.h {
            scene.mesh.h = h;
            scene.validate()?;
        }
        notes.push(format!(
            "{} not given: h = {:.4e} m (t/{}), so that the cohesive zone Lambda_0 = {l0:.4e} m spans {:.2} elements (at least {MIN_ZONE_ELEMENTS}; 6 or more move the peak force by under 0.01 mu_s N and the count of front advances by several, validation/dynamics/converge)",
            names[1],
            scene.mesh.h,
            (scene.block.thickness / scene.mesh.h).round(),
            l0 / scene.mesh.h,
        ));
    }
    let kappa = kappa(scene, mu_s, mu_d, dc, n_force);
    notes.push(format!("kappa = {kappa:.4}: {}", regime(kappa)));
    Ok(Resolved { law, kappa, notes })
}

/// The regime the thin-layer balance expects, a heuristic said as such.
pub fn regime(kappa: f64) -> &'static str {
    if kappa < 1.0 {
        "kappa < ~1: a weakened trailing zone can go unstable, precursors are possible (heuristic from the thin-layer balance)"
    } else {
        "kappa > ~1: the interface weakens stably, expect no precursors (heuristic from the thin-layer balance)"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_is_the_papers_dc_there_and_never_follows_the_mesh() {
        let (s, ms, md) = paper().unwrap();
        assert_eq!(default_dc(&s, ms, md, 1.0).unwrap(), PAPER_DC);
        let mut fine = s.clone();
        fine.mesh.h = 1.25e-4;
        assert_eq!(default_dc(&fine, ms, md, 1.0).unwrap(), PAPER_DC);
        // kappa by hand: G = 2e3/2.8, (mu_s - mu_d) = 0.35 * 0.4 / 0.24 * (1/0.9 - 1), N/L = 2.5.
        let dmu = 0.35 * 0.4 / 0.24 * (1.0 / 0.9 - 1.0);
        let k = 2e3 / 2.8 * PAPER_DC / (dmu * 2.5 * 0.002);
        assert!((default_kappa().unwrap() - k).abs() < 1e-12 * k, "{k}");
        // A thicker block keeps kappa: D_c scales with t.
        let mut thick = s.clone();
        thick.block.thickness = 0.004;
        assert!((default_dc(&thick, ms, md, 1.0).unwrap() / PAPER_DC - 2.0).abs() < 1e-14);
    }

    #[test]
    fn the_resolving_size_is_a_whole_fraction_of_t() {
        // The paper's D_c spans 3.00001 elements of t/4 = 0.5 mm.
        let (s, ms, md) = paper().unwrap();
        let l0 = lambda0(&s, ms, md, PAPER_DC, 1.0).unwrap();
        assert!((l0 / 5e-4 - 3.0).abs() < 1e-4, "{l0}");
        assert_eq!(resolving_h(0.002, l0), 0.0005);
        assert_eq!(resolving_h(0.002, 0.1), 0.002);
        assert!(check_resolved(&s, ms, md, PAPER_DC, 1.0, "--h")
            .unwrap_err()
            .to_string()
            .contains("--h 5.0000e-4"));
    }
}
