//! The energy release rate of a growing slipped region from the whole elastic body's static
//! response, not the thin-layer formula (issue 49): fixed grips (the plate's U_H, V, theta
//! held), the pre-event field, and on the slipped nodes the shear traction dropping from its
//! pre-event tau to the residual mu_d p with p frozen (the paper's assumption: the normal DOFs
//! of contact nodes stay held), every other contact node stuck. The released energy is
//!
//! ```text
//! W(l) = 1/2 df_s^T K_ss^{-1} df_s   (J/m),   df_i = (tau_i - mu_d p_i) w_i   (N/m),
//! ```
//!
//! K_ss the condensed stiffness S on the slipped tangential DOFs (and the open nodes' both
//! DOFs, traction-free before and after) with every other boundary DOF held, and the energy
//! release rate at a node added is G = (W after - W before) / w_node (J/m^2; the advance is
//! the node's tributary width, so the slipped length is the sum of the widths).
//!
//! K_ss grows by bordering: adding DOF j to a set of m solves L y = S_sj (O(m^2)), appends the
//! row (y, sqrt(S_jj - y.y)) to the Cholesky factor L and z_j = (df_j - y.z) / L_jj to
//! z = L^{-1} df, so W = |z|^2 / 2 grows by z_j^2 / 2. A walk over m nodes (patch included)
//! costs O(m^3 / 3) flops and m columns of S: read from the dense S, or one solve each on the
//! banded operator's held factor ([`HeldColumns`], O(band) each). At the paper's 801 nodes a
//! typical walk (tens of nodes) is ~1e7 flops, against ~1e8-1e9 for an event's explicit steps;
//! only a walk across the whole interface (~5e8) is comparable to an event.

use crate::error::{Error, Result};
use crate::interface::banded::HeldColumns;
use crate::interface::condense::Condensed;

/// The interface's static stiffness with the plate and every other boundary DOF held: the
/// dense condensed S, or columns solved on the banded operator.
pub enum HeldStiffness<'a> {
    Dense(&'a Condensed),
    Banded(HeldColumns<'a>),
}

impl HeldStiffness<'_> {
    /// S e_d over the 2n interface DOFs (u_0..u_{n-1}, v_0..v_{n-1}), N/m per m.
    pub fn column(&self, d: usize) -> Result<Vec<f64>> {
        match self {
            HeldStiffness::Dense(c) => {
                let nd = c.dim();
                if c.s.len() != nd * nd || d >= 2 * c.n {
                    return Err(Error::input(
                        "held stiffness",
                        "the dense S is not formed (a banded run: use its held columns) or the DOF is not an interface DOF",
                    ));
                }
                Ok((0..2 * c.n).map(|i| c.s[i * nd + d]).collect())
            }
            HeldStiffness::Banded(b) => b.column(d),
        }
    }
}

/// W(l) of a slipped region grown one node at a time (the module's bordered Cholesky).
pub struct Release<'k, 'a> {
    k: &'k HeldStiffness<'a>,
    /// Pre-event force drops (tau - mu_d p) w per node, N/m, and tributary widths, m.
    df: Vec<f64>,
    w: Vec<f64>,
    /// Free boundary DOFs so far, the rows of L, z = L^{-1} df_s.
    dofs: Vec<usize>,
    l: Vec<Vec<f64>>,
    z: Vec<f64>,
    /// W, J/m.
    pub energy: f64,
}

impl<'k, 'a> Release<'k, 'a> {
    /// The region at its start: the open nodes (p <= 0: both DOFs free, no drop) and the
    /// nodes of `patch` (slipped from the start). `p`, `tau`: pre-event pressure and shear, Pa
    /// (tau > 0 along the drive); `w`: tributary widths, m; `mu_d` the residual coefficient.
    pub fn new(
        k: &'k HeldStiffness<'a>,
        (p, tau, w): (&[f64], &[f64], &[f64]),
        mu_d: f64,
        patch: &[usize],
    ) -> Result<Self> {
        let n = p.len();
        if tau.len() != n || w.len() != n {
            return Err(Error::input("energy release", "p, tau and w differ in length"));
        }
        let df = (0..n).map(|i| if p[i] > 0.0 { (tau[i] - mu_d * p[i]) * w[i] } else { 0.0 }).collect();
        let mut r = Release { k, df, w: w.to_vec(), dofs: vec![], l: vec![], z: vec![], energy: 0.0 };
        for i in (0..n).filter(|&i| p[i] <= 0.0) {
            r.free(i, 0.0)?;
            r.free(n + i, 0.0)?;
        }
        for &i in patch {
            r.free(i, r.df[i])?;
        }
        Ok(r)
    }

    /// Frees node `i`'s tangential DOF with its drop; returns G there, J/m^2 (0 for a node
    /// already free: an open or patch node adds no compliance).
    pub fn advance(&mut self, i: usize) -> Result<f64> {
        let before = self.energy;
        self.free(i, self.df[i])?;
        Ok((self.energy - before) / self.w[i])
    }

    /// Borders L with DOF `d` carrying the force drop `f` (N/m).
    fn free(&mut self, d: usize, f: f64) -> Result<()> {
        if self.dofs.contains(&d) {
            return Ok(());
        }
        let col = self.k.column(d)?;
        let m = self.dofs.len();
        let mut y = vec![0.0; m];
        for a in 0..m {
            let s: f64 = (0..a).map(|b| self.l[a][b] * y[b]).sum();
            y[a] = (col[self.dofs[a]] - s) / self.l[a][a];
        }
        let pivot = col[d] - y.iter().map(|v| v * v).sum::<f64>();
        // K_ss is a principal block of S with the plate held: positive definite, so a pivot
        // at round-off of the diagonal means the columns are not S's.
        if !(pivot > 1e-12 * col[d].abs()) {
            return Err(Error::Untrustworthy {
                detail: format!("the slipped DOFs' stiffness is not positive definite at DOF {d} (pivot {pivot:.3e} of {:.3e})", col[d]),
                hint: "check the mesh and the material values".into(),
            });
        }
        let ljj = pivot.sqrt();
        let zj = (f - y.iter().zip(&self.z).map(|(a, b)| a * b).sum::<f64>()) / ljj;
        y.push(ljj);
        self.l.push(y);
        self.z.push(zj);
        self.dofs.push(d);
        self.energy += 0.5 * zj * zj;
        Ok(())
    }
}

/// The energy release rate G (J/m^2) at each node of `grow`, added in order to the slipped
/// region that starts as `patch` (plus the open nodes), under the module's assumptions: fixed
/// grips, p frozen, the slipped shear at mu_d p. `p`, `tau`: the pre-event field, Pa (tau > 0
/// along the drive); `w`: tributary widths, m. A node of `grow` already free gives 0.
pub fn energy_release(
    k: &HeldStiffness,
    field: (&[f64], &[f64], &[f64]),
    mu_d: f64,
    patch: &[usize],
    grow: &[usize],
) -> Result<Vec<f64>> {
    let mut r = Release::new(k, field, mu_d, patch)?;
    grow.iter().map(|&i| r.advance(i)).collect()
}
