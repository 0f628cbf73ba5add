//! The paper's assumption 5 ("the friction force relaxation happens only after the front
//! arrested") measured as the model uses it: the arrest is set by the pre-event field. Per
//! instability, (1) how much p and tau change ahead of the moving tip while it runs, in
//! units of the local strength drop, and (2) where the pre-event field says the front
//! stops, with zero fracture energy (tau = mu_d p, the paper's rule), with the thin-layer
//! Griffith balance and with the Griffith balance on the whole body's G ([`super::fracture`]),
//! beside where it stopped (docs/dynamics-findings.md, "Assumption 5").

use super::fracture::{HeldStiffness, Release};
use crate::dynamics::driven::EventRecord;
use crate::error::Result;
use crate::law::Law;

/// The stated distance ahead of the tip, in block thicknesses t: the stress concentration
/// of a front in a thin layer decays over a few t (shear lag), so beyond it the field the
/// arrest reads is the pre-event one if assumption 5 holds.
pub const AHEAD_THICKNESSES: f64 = 2.5;

/// One instability's assumption-5 measures (positions in m, changes dimensionless).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Assumption5 {
    /// +1: the front ran toward +x (the tip's side of the nucleation node), -1 toward -x.
    pub direction: f64,
    /// Where the tip stopped (the end of the slipped run farther from the nucleation node).
    pub arrest: f64,
    /// Predicted from the pre-event field, walking from the nucleating patch's edge
    /// ([`patch_edge`]): zero fracture energy (the first node where tau < mu_d p) and the
    /// thin-layer Griffith balance ([`predicted_arrest`]), and the Griffith balance with G
    /// from the whole body's static response ([`super::fracture`]; NaN without a held
    /// stiffness).
    pub predicted_mu_d: f64,
    pub predicted_griffith: f64,
    pub predicted_fracture: f64,
    /// Largest |p - p_pre| / p_pre and |tau - tau_pre| / ((mu_s - mu_d) p_pre) over the
    /// contact nodes ahead of the tip, over the samples from nucleation to arrest: anywhere
    /// ahead (the tip's own stress concentration included), and from
    /// [`AHEAD_THICKNESSES`] t ahead on.
    pub dp_ahead: f64,
    pub dtau_ahead: f64,
    pub dp_far: f64,
    pub dtau_far: f64,
}

/// Where a front started at node `start` and running in `direction` (+1 or -1) stops on
/// the field p, tau (stresses, Pa): the first contact node (p > 0; open nodes are passed
/// over) at which the released energy per unit advance `released(i)` (J/m^2, called once per
/// contact node reached, in walking order) falls below the fracture energy of linear slip
/// weakening, or where the front has nothing left to release:
///
/// ```text
/// G(i)  <  (mu_s - mu_d) p D_c / 2,   or tau < mu_d p.
/// ```
///
/// `d_c` = 0 gives the zero-fracture-energy rule (tau < mu_d p). None of them: the last node
/// in that direction. Returns the node index. G is [`thin_layer_release`] for the thin-layer
/// Griffith rule and [`super::fracture::Release::advance`] for the whole body's.
pub fn predicted_arrest(
    (p, tau): (&[f64], &[f64]),
    start: usize,
    direction: i32,
    (mu_s, mu_d): (f64, f64),
    d_c: f64,
    mut released: impl FnMut(usize) -> Result<f64>,
) -> Result<usize> {
    let n = p.len();
    let mut i = start;
    loop {
        if p[i] > 0.0 {
            let gamma = (mu_s - mu_d) * p[i] * d_c / 2.0;
            if tau[i] < mu_d * p[i] || released(i)? < gamma {
                return Ok(i);
            }
        }
        match (direction > 0, i) {
            (true, k) if k + 1 < n => i += 1,
            (false, k) if k > 0 => i -= 1,
            _ => return Ok(i),
        }
    }
}

/// The long front's release in a layer of thickness t under a held rigid top (fixed grips;
/// G_s the shear modulus), J/m^2: t (tau - mu_d p)^2 / (2 G_s) (docs/dynamics-equations.md,
/// "The thin-layer energy release"). Against the fracture energy it is
/// tau - mu_d p < (mu_s - mu_d) p sqrt(kappa(x)), kappa = G_s D_c / ((mu_s - mu_d) p t),
/// validation/dynamics/paper/regime.py's rule.
pub fn thin_layer_release(p: f64, tau: f64, mu_d: f64, shear_modulus: f64, thickness: f64) -> f64 {
    let excess = tau - mu_d * p;
    thickness * excess * excess / (2.0 * shear_modulus)
}

/// The first node beyond the run of nodes with slip memory `d` above `threshold` that
/// contains `c`, walking in `direction` (`c` itself if it is not in such a run; the last
/// node if the run reaches the end).
pub fn patch_edge(d: &[f64], c: usize, direction: i32, threshold: f64) -> usize {
    let mut i = c;
    while d[i] > threshold {
        match (direction > 0, i) {
            (true, k) if k + 1 < d.len() => i += 1,
            (false, k) if k > 0 => i -= 1,
            _ => break,
        }
    }
    i
}

/// The measures of one held-drive event (None: it never nucleated, or the record holds no
/// pre-event field). `x`, `w`: the base nodes' positions and tributary widths (m); `held`:
/// the interface's stiffness for the fracture prediction (None: that one is NaN).
pub fn measure(
    rec: &EventRecord,
    (x, w): (&[f64], &[f64]),
    law: &Law,
    (shear_modulus, thickness): (f64, f64),
    held: Option<&HeldStiffness>,
) -> Option<Assumption5> {
    let Law::SlipWeakening { mu_s, mu_d, dc } = *law else { return None };
    let c = rec.nucleation?;
    let n = x.len();
    if rec.p_pre.len() != n || rec.d_pre.len() != n || mu_s <= mu_d {
        return None;
    }
    let arrest = *rec.tip.iter().rev().find(|v| v.is_finite())?;
    let direction = if arrest >= x[c] { 1 } else { -1 };
    // tau > 0 in the direction of the net friction force (the drive's shear).
    let s = if rec.t_pre.iter().sum::<f64>() < 0.0 { -1.0 } else { 1.0 };
    let p: Vec<f64> = (0..n).map(|i| rec.p_pre[i] / w[i]).collect();
    let tau: Vec<f64> = (0..n).map(|i| s * rec.t_pre[i] / w[i]).collect();
    // The front starts at the nucleating patch's edge on the tip's side: the patch (slip
    // memory past the threshold at the onset) is the crack already there, weakened below
    // what the balance asks of fresh interface.
    let start = patch_edge(&rec.d_pre, c, direction, rec.threshold);
    let walk = |d_c, released: &mut dyn FnMut(usize) -> Result<f64>| {
        predicted_arrest((&p, &tau), start, direction, (mu_s, mu_d), d_c, released).map(|i| x[i])
    };
    let mut thin = |i: usize| Ok(thin_layer_release(p[i], tau[i], mu_d, shear_modulus, thickness));
    let predicted_mu_d = walk(0.0, &mut thin).ok()?;
    let predicted_griffith = walk(dc, &mut thin).ok()?;
    // The whole body's release: the patch slipped from the start, grown toward the tip.
    let patch: Vec<usize> = if rec.d_pre[c] > rec.threshold {
        let (lo, hi) = crate::numeric::run_around(c, n, |i| rec.d_pre[i] > rec.threshold);
        (lo..=hi).collect()
    } else {
        vec![]
    };
    let predicted_fracture = held
        .and_then(|k| {
            let mut r = Release::new(k, (&p, &tau, w), mu_d, &patch).ok()?;
            walk(dc, &mut |i| r.advance(i)).ok()
        })
        .unwrap_or(f64::NAN);
    let drop = mu_s - mu_d;
    let far = AHEAD_THICKNESSES * thickness;
    // Positions are whole node spacings apart: 1e-9 of an element is round-off.
    let eps = 1e-9 * (x[n - 1] - x[0]) / n as f64;
    let [mut dp_ahead, mut dtau_ahead, mut dp_far, mut dtau_far] = [0.0f64; 4];
    for (j, (ps, ts)) in rec.p_samples.iter().zip(&rec.t_samples).enumerate() {
        let tip = rec.tip[j];
        if !tip.is_finite() {
            continue;
        }
        // Ahead: beyond the tip, on its side of the nucleation node at this sample.
        let side = if tip > x[c] {
            1.0
        } else if tip < x[c] {
            -1.0
        } else {
            direction as f64
        };
        for i in 0..n {
            let (p0, dist) = (rec.p_pre[i], side * (x[i] - tip));
            if p0 <= 0.0 || dist <= eps {
                continue;
            }
            let dp = (ps[i] as f64 - p0).abs() / p0;
            let dtau = (ts[i] as f64 - rec.t_pre[i]).abs() / (drop * p0);
            dp_ahead = dp_ahead.max(dp);
            dtau_ahead = dtau_ahead.max(dtau);
            if dist >= far - eps {
                dp_far = dp_far.max(dp);
                dtau_far = dtau_far.max(dtau);
            }
        }
    }
    Some(Assumption5 {
        direction: direction as f64,
        arrest,
        predicted_mu_d,
        predicted_griffith,
        predicted_fracture,
        dp_ahead,
        dtau_ahead,
        dp_far,
        dtau_far,
    })
}
