//! The event solver's operator without the dense condensed S (issue 32): the block's
//! interior DOFs stay unknowns, so each solve is a sparse system over the interior DOFs, the
//! interface DOFs and the plate's three DOFs. Ordered by node x, the first two groups form a
//! band a few node rows wide (a thin layer has few rows); the plate couples to every node
//! tied to it and borders the band. Each solve factors the band afresh (banded LU with partial
//! pivoting, [`crate::linalg::banded`]) and eliminates the 3 x 3 border: O(n b^2) per solve
//! instead of the dense path's O(n^2) per state change and its O(n^3) condensation.
//!
//! Conventions are those of [`crate::interface::condense`] at the drive height H: boundary
//! DOFs u_0..u_{n-1}, v_0..v_{n-1} (interface nodes by x), then U_H, V, theta; f = S b the
//! forces on the block and plate at those DOFs. A constrained DOF's equation is "b_d = given"
//! (its row an identity row, scaled like a stiffness row); a free interface u-row of a
//! slipping node is f_u + c f_v + k (u - u_k) = 0; other free rows f_d = external force.
//!
//! About 670 lines: the assembly in band order, its symmetry and rigid-motion checks, the
//! bordered factor and solve and the residual products share one storage layout; the reuse of
//! one factor across events is in `banded/reuse.rs`.

use crate::error::{Error, Result};
use crate::fem::constraints::Target;
use crate::interface::condense::boundary_model;
use crate::linalg::banded::{dot, Banded};
use crate::scene::Scene;

/// The block + rigid plate stiffness over (interior, interface) DOFs in band order, bordered by
/// the plate's (U_H, V, theta).
#[derive(Debug, Clone)]
pub struct BandedOperator {
    /// Interface nodes.
    pub n: usize,
    /// Band unknowns (interior + 2 n interface DOFs).
    pub m: usize,
    pub kl: usize,
    pub ku: usize,
    /// Symmetric stiffness over the m + 3 unknowns, CSR (column m + p: plate DOF p).
    ptr: Vec<usize>,
    col: Vec<usize>,
    val: Vec<f64>,
    /// Band position of each interface node's u and v.
    pu: Vec<usize>,
    pv: Vec<usize>,
    /// Scale of identity rows (mean interface diagonal): keeps pivoting and residuals sane.
    scale: f64,
    /// Interface node positions along x (sorted), m, and tributary widths, m.
    pub x: Vec<f64>,
    pub w: Vec<f64>,
    /// Largest |K_ij - K_ji| / max |K| and largest |K r| / (max |K| |r|) over the three rigid
    /// motions (the checks the dense condensation reports for S).
    pub asymmetry: f64,
    pub rigid_residual: f64,
}

impl crate::interface::condense::Condensed {
    /// The interface of a run on the banded operator: positions, widths and the stiffness
    /// checks, without a dense S (the operator solves on the block instead).
    pub fn of_banded(scene: &Scene, op: &BandedOperator) -> Self {
        let b = &scene.block;
        Self {
            n: op.n,
            x: op.x.clone(),
            w: op.w.clone(),
            l: b.length,
            t: b.thickness,
            e_star: b.e_star(),
            s: vec![],
            asymmetry: op.asymmetry,
            rigid_residual: op.rigid_residual,
            border: crate::interface::events::TOP_PLATE.to_vec(),
        }
    }
}

/// What one solve needs, per boundary DOF d in 0..2n + 3 (see the module's conventions).
pub struct Rows<'a> {
    pub free: &'a [bool],
    /// Constrained values b = b0 + lambda b1 (entries of free DOFs are ignored).
    pub b0: &'a [f64],
    pub b1: &'a [f64],
    /// Per node: slip coefficient c of its u-row (0: none), Newton spring k and its centre.
    pub coef: &'a [f64],
    pub spring: &'a [f64],
    pub spring_u: &'a [f64],
    /// External force on V (DOF 2n + 1), affine in lambda, N/m.
    pub fk: (f64, f64),
    /// Extra constant right-hand sides of the free equations, per DOF (empty: none): columns
    /// of the free system's inverse for slip weakening's stability test.
    pub load: &'a [f64],
}

/// b = b0 + lambda b1 and f = f0 + lambda f1 over the 2n + 3 boundary DOFs.
#[derive(Debug, Clone)]
pub struct Solution {
    pub b0: Vec<f64>,
    pub b1: Vec<f64>,
    pub f0: Vec<f64>,
    pub f1: Vec<f64>,
}

impl BandedOperator {
    pub fn dim(&self) -> usize {
        2 * self.n + 3
    }

    /// Builds the operator of `scene`'s block and rigid plate with the drive at height `h`
    /// (m above the interface; the scene's own loading height is ignored).
    pub fn new(scene: &Scene, h: f64) -> Result<BandedOperator> {
        let (sm, bdofs) = boundary_model(scene)?;
        let model = sm.model();
        let n = sm.interface.len();
        let nb = bdofs.len();
        let red = sm.constraints.reduce()?;
        let t = scene.block.thickness;
        // Fixed slot -> boundary index.
        let mut slot_b = vec![usize::MAX; red.n_fixed()];
        for (b, &d) in bdofs.iter().enumerate() {
            slot_b[sm.constraints.fixed_slot(d).expect("boundary DOFs are prescribed")] = b;
        }
        let nfull = red.n_full;
        let nn = sm.mesh.n_nodes();
        // Band order: nodes by (x, y); per node u then v; a DOF is in the band if it is a
        // free unknown or an interface DOF (nodes tied to the plate are neither).
        let mut free_of = vec![usize::MAX; nfull];
        for (k, &d) in red.free_to_full.iter().enumerate() {
            if d >= 2 * nn {
                return Err(Error::input("scene", "the banded operator supports node DOFs only as unknowns"));
            }
            free_of[d] = k;
        }
        let mut bnd_of = vec![usize::MAX; nfull];
        for (b, &d) in bdofs.iter().enumerate().take(2 * n) {
            bnd_of[d] = b;
        }
        let mut order: Vec<usize> = (0..nn).collect();
        let xy = &sm.mesh.nodes;
        order.sort_by(|&a, &b| xy[a][0].total_cmp(&xy[b][0]).then(xy[a][1].total_cmp(&xy[b][1])));
        let mut pos_free = vec![usize::MAX; red.n_free()];
        let mut pos_bnd = vec![usize::MAX; nb];
        // Position -> (node, component) for the rigid-motion check.
        let mut at: Vec<(usize, usize)> = Vec::new();
        for &k in &order {
            for c in 0..2 {
                let d = 2 * k + c;
                if free_of[d] != usize::MAX {
                    pos_free[free_of[d]] = at.len();
                } else if bnd_of[d] != usize::MAX {
                    pos_bnd[bnd_of[d]] = at.len();
                } else {
                    continue;
                }
                at.push((k, c));
            }
        }
        let m = at.len();
        if m != red.n_free() + 2 * n {
            return Err(Error::input("scene", "the interface DOFs are not all in the band"));
        }
        for (p, b) in (2 * n..nb).enumerate() {
            pos_bnd[b] = m + p;
        }
        let idx = |t: Target| match t {
            Target::Free(k) => pos_free[k],
            Target::Fixed(j) => pos_bnd[slot_b[j]],
        };
        // U0 = U_H + (h - t) theta: K in the (U_H, V, theta) basis is T^T K T.
        let (iu0, ith) = (m, m + 2);
        let ch = h - t;
        let expand = |r: usize| -> [(usize, f64); 2] {
            if r == iu0 {
                [(iu0, 1.0), (ith, ch)]
            } else {
                [(r, 1.0), (usize::MAX, 0.0)]
            }
        };
        let mut trip: Vec<(usize, usize, f64)> = Vec::new();
        let mut ke = vec![0.0; crate::fem::element::stiffness::MAX_DOFS.pow(2)];
        for e in 0..sm.mesh.n_elements() {
            model.element_stiffness(e, &mut ke)?;
            let nodes = sm.mesh.element_nodes(e);
            let ne = 2 * nodes.len();
            for a in 0..ne {
                let da = 2 * nodes[a / 2] + a % 2;
                for b in 0..ne {
                    let kab = ke[a * ne + b];
                    if kab == 0.0 {
                        continue;
                    }
                    let db = 2 * nodes[b / 2] + b % 2;
                    for &(ta, ca) in red.terms(da) {
                        for &(tb, cb) in red.terms(db) {
                            for (r, cr) in expand(idx(ta)) {
                                if r == usize::MAX {
                                    continue;
                                }
                                for (c, cc) in expand(idx(tb)) {
                                    if c != usize::MAX {
                                        trip.push((r, c, ca * cb * cr * cc * kab));
                                    }
                                }
                            }
                        }
                    }
                }
            }
        }
        trip.sort_unstable_by_key(|&(r, c, _)| (r, c));
        let nu = m + 3;
        let (mut ptr, mut col, mut val) = (vec![0usize; nu + 1], Vec::new(), Vec::<f64>::new());
        let mut k = 0;
        while k < trip.len() {
            let (r, c, mut v) = trip[k];
            k += 1;
            while k < trip.len() && trip[k].0 == r && trip[k].1 == c {
                v += trip[k].2;
                k += 1;
            }
            col.push(c);
            val.push(v);
            ptr[r + 1] += 1;
        }
        for r in 0..nu {
            ptr[r + 1] += ptr[r];
        }
        let pu: Vec<usize> = (0..n).map(|i| pos_bnd[i]).collect();
        let pv: Vec<usize> = (0..n).map(|i| pos_bnd[n + i]).collect();
        // Band widths, with a slip row's v-row entries moved onto its u-row.
        let (mut kl, mut ku) = (0usize, 0usize);
        let mut widen = |r: usize, c: usize| {
            if c < m {
                if c < r {
                    kl = kl.max(r - c);
                } else {
                    ku = ku.max(c - r);
                }
            }
        };
        for r in 0..m {
            for &c in &col[ptr[r]..ptr[r + 1]] {
                widen(r, c);
            }
        }
        for i in 0..n {
            for &c in &col[ptr[pv[i]]..ptr[pv[i] + 1]] {
                widen(pu[i], c);
            }
        }
        // The band's storage (a, L, U: m (4 kl + 2 ku + 2) doubles), held twice (the factor and
        // a workspace): refused before it is allocated, as the dense condensation is.
        crate::scene::limits::check_bytes(
            2.0 * 8.0 * m as f64 * (4 * kl + 2 * ku + 2) as f64,
            "--thickness / --h (block.thickness, mesh.h)",
            &format!("the banded operator's band ({m} unknowns, half-bandwidths {kl}, {ku})"),
            "make the block thinner or h larger (the band grows with the nodes through the thickness)",
        )?;
        let diag = |r: usize| (ptr[r]..ptr[r + 1]).find(|&k| col[k] == r).map_or(0.0, |k| val[k]);
        let scale = (0..n).map(|i| diag(pu[i]).abs() + diag(pv[i]).abs()).sum::<f64>() / (2 * n) as f64;
        if !(scale > 0.0 && scale.is_finite()) {
            return Err(Error::input("scene", "the interface DOFs have no stiffness"));
        }
        // Checks: symmetry and the three rigid motions (translations, rotation about the
        // origin: u = -y, v = x; the plate's U_H = -h, theta = 1).
        let kmax = val.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        let mut asymmetry = 0.0f64;
        let entry =
            |r: usize, c: usize| col[ptr[r]..ptr[r + 1]].binary_search(&c).map_or(0.0, |k| val[ptr[r] + k]);
        for r in 0..nu {
            for k in ptr[r]..ptr[r + 1] {
                asymmetry = asymmetry.max((val[k] - entry(col[k], r)).abs() / kmax);
            }
        }
        let mut rigid_residual = 0.0f64;
        for mode in 0..3 {
            let mut z = vec![0.0; nu];
            for (p, &(k, c)) in at.iter().enumerate() {
                let [x, y] = sm.mesh.nodes[k];
                z[p] = match (mode, c) {
                    (0, 0) | (1, 1) => 1.0,
                    (2, 0) => -y,
                    (2, 1) => x,
                    _ => 0.0,
                };
            }
            match mode {
                0 => z[m] = 1.0,
                1 => z[m + 1] = 1.0,
                _ => (z[m], z[m + 2]) = (-h, 1.0),
            }
            let zn = z.iter().fold(0.0f64, |s, v| s.max(v.abs()));
            for r in 0..nu {
                let v: f64 = (ptr[r]..ptr[r + 1]).map(|k| val[k] * z[col[k]]).sum();
                rigid_residual = rigid_residual.max(v.abs() / (kmax * zn));
            }
        }
        if !(asymmetry < 1e-9 && rigid_residual < 1e-9) {
            return Err(Error::Untrustworthy {
                detail: format!(
                    "the block's stiffness is not symmetric ({asymmetry:.1e}) or does not annihilate the rigid motions ({rigid_residual:.1e}) to 1e-9"
                ),
                hint: "check the mesh and the material values".into(),
            });
        }
        let x = sm.interface.iter().map(|&k| sm.mesh.nodes[k][0]).collect();
        let w = sm.tributary_widths();
        Ok(BandedOperator { n, m, kl, ku, ptr, col, val, pu, pv, scale, x, w, asymmetry, rigid_residual })
    }

    /// K x and sum_j |K_rj x_j| for two vectors over all m + 3 rows, into `out` = (K x0, its
    /// sizes, K x1, its sizes).
    pub(crate) fn product2(&self, x0: &[f64], x1: &[f64], out: [&mut [f64]; 4]) {
        let [kx0, ka0, kx1, ka1] = out;
        for r in 0..self.m + 3 {
            let (c, v) = self.row(r);
            let (mut s0, mut a0, mut s1, mut a1) = (0.0, 0.0, 0.0, 0.0);
            for (&c, &v) in c.iter().zip(v) {
                let (t0, t1) = (v * x0[c], v * x1[c]);
                (s0, a0, s1, a1) = (s0 + t0, a0 + t0.abs(), s1 + t1, a1 + t1.abs());
            }
            (kx0[r], ka0[r], kx1[r], ka1[r]) = (s0, a0, s1, a1);
        }
    }

    /// A workspace for [`Self::solve`] (the band's storage, reused between solves).
    pub fn workspace(&self) -> Banded {
        Banded::zeros(self.m, self.kl, self.ku)
    }

    fn pos(&self, d: usize) -> usize {
        let n = self.n;
        if d < n {
            self.pu[d]
        } else if d < 2 * n {
            self.pv[d - n]
        } else {
            self.m + d - 2 * n
        }
    }

    fn row(&self, r: usize) -> (&[usize], &[f64]) {
        (&self.col[self.ptr[r]..self.ptr[r + 1]], &self.val[self.ptr[r]..self.ptr[r + 1]])
    }

    /// Band row -> boundary DOF (usize::MAX: an interior row).
    fn bnd(&self) -> Vec<usize> {
        let mut bnd = vec![usize::MAX; self.m];
        for d in 0..2 * self.n {
            bnd[self.pos(d)] = d;
        }
        bnd
    }

    fn check_sizes(&self, rows: &Rows) -> Result<()> {
        let (n, nb) = (self.n, self.dim());
        if rows.free.len() != nb || rows.b0.len() != nb || rows.b1.len() != nb || rows.coef.len() != n {
            return Err(Error::input("banded operator", "state sizes do not match the interface"));
        }
        Ok(())
    }

    /// Assembles the free system of `rows` into `lu` (band) and the border, factors it, and
    /// returns the factor with the right-hand sides: band (lambda^0, lambda^1; m each) and border.
    pub(crate) fn factor(&self, rows: &Rows, mut lu: Banded) -> Result<(Factored, Vec<f64>, [[f64; 3]; 2])> {
        self.check_sizes(rows)?;
        let (n, m) = (self.n, self.m);
        if (lu.m, lu.kl, lu.ku) != (m, self.kl, self.ku) {
            lu = self.workspace();
        }
        let bnd = self.bnd();
        lu.clear();
        // Right-hand sides: the 3 border columns, then lambda^0, lambda^1 (m each).
        let mut rhs = vec![0.0; 5 * m];
        let put = |lu: &mut Banded, rhs: &mut [f64], r: usize, cols: &[usize], vals: &[f64], w: f64| {
            for (&c, &v) in cols.iter().zip(vals) {
                if c < m {
                    lu.add(r, c, w * v);
                } else {
                    rhs[(c - m) * m + r] += w * v;
                }
            }
        };
        for r in 0..m {
            let d = bnd[r];
            if d == usize::MAX {
                let (c, v) = self.row(r);
                put(&mut lu, &mut rhs, r, c, v, 1.0);
                continue;
            }
            if !rows.free[d] {
                lu.add(r, r, self.scale);
                rhs[3 * m + r] = self.scale * rows.b0[d];
                rhs[4 * m + r] = self.scale * rows.b1[d];
                continue;
            }
            let (c, v) = self.row(r);
            put(&mut lu, &mut rhs, r, c, v, 1.0);
            if let Some(&e) = rows.load.get(d) {
                rhs[3 * m + r] += e;
            }
            if d < n {
                let cf = rows.coef[d];
                if cf != 0.0 {
                    let (c, v) = self.row(self.pv[d]);
                    put(&mut lu, &mut rhs, r, c, v, cf);
                }
                if rows.spring[d] != 0.0 {
                    lu.add(r, r, rows.spring[d]);
                    rhs[3 * m + r] += rows.spring[d] * rows.spring_u[d];
                }
            }
        }
        // Border rows (C | D) and their right-hand sides.
        let mut crow = vec![0.0; 3 * m];
        let mut dmat = [[0.0f64; 3]; 3];
        let srhs = self.border_rhs(rows);
        for p in 0..3 {
            let d = 2 * n + p;
            if !rows.free[d] {
                dmat[p][p] = self.scale;
                continue;
            }
            let (c, v) = self.row(m + p);
            for (&c, &v) in c.iter().zip(v) {
                if c < m {
                    crow[p * m + c] += v;
                } else {
                    dmat[p][c - m] += v;
                }
            }
        }
        lu.factor()?;
        // A^{-1} B (the border columns) and the Schur complement S = D - C A^{-1} B.
        rhs.truncate(5 * m);
        let rband = rhs.split_off(3 * m);
        let mut ab = rhs;
        lu.solve_in_place(&mut ab, 3);
        let mut s = dmat;
        for (p, sp) in s.iter_mut().enumerate() {
            for (q, v) in sp.iter_mut().enumerate() {
                *v -= dot(&crow[p * m..(p + 1) * m], &ab[q * m..(q + 1) * m]);
            }
        }
        Ok((Factored { lu, ab, crow, s }, rband, srhs))
    }

    /// Right-hand sides of the three border rows (lambda^0, lambda^1).
    fn border_rhs(&self, rows: &Rows) -> [[f64; 3]; 2] {
        let mut srhs = [[0.0f64; 3]; 2];
        for p in 0..3 {
            let d = 2 * self.n + p;
            if !rows.free[d] {
                srhs[0][p] = self.scale * rows.b0[d];
                srhs[1][p] = self.scale * rows.b1[d];
                continue;
            }
            if p == 1 {
                srhs[0][p] = rows.fk.0;
                srhs[1][p] = rows.fk.1;
            }
            if let Some(&e) = rows.load.get(d) {
                srhs[0][p] += e;
            }
        }
        srhs
    }

    /// The affine solution of one state set (factored afresh in the workspace `lu`).
    pub fn solve(&self, rows: &Rows, lu: &mut Banded) -> Result<Solution> {
        let m = self.m;
        let (f, rband, srhs) = self.factor(rows, std::mem::replace(lu, Banded::zeros(0, 0, 0)))?;
        let bnd = self.bnd();
        let mut full = [vec![0.0; m + 3], vec![0.0; m + 3]];
        for k in 0..2 {
            let mut z = rband[k * m..(k + 1) * m].to_vec();
            f.apply(&mut z, srhs[k], &mut full[k])?;
            // One step of iterative refinement: residuals of the band rows and the border rows
            // (the dense path's equilibrium to ~1e-12 of N/n at 3,201 nodes needs it).
            let mut res: Vec<f64> =
                (0..m).map(|r| rband[k * m + r] - self.lhs(r, &bnd, rows, &full[k])).collect();
            let t = [0, 1, 2].map(|p| srhs[k][p] - self.lhs(m + p, &bnd, rows, &full[k]));
            f.apply(&mut res, t, &mut full[k])?;
            if full[k].iter().any(|v| !v.is_finite()) {
                return Err(singular());
            }
        }
        *lu = f.lu;
        Ok(self.finish(rows, &mut full, None))
    }

    /// Sets the constrained values exactly as given (the identity rows return them to
    /// round-off) and reads b and f = S b at the boundary DOFs off the full solutions; `kx`:
    /// K times those (pinned) solutions where already known.
    fn finish(&self, rows: &Rows, full: &mut [Vec<f64>; 2], kx: Option<[&[f64]; 2]>) -> Solution {
        let nb = self.dim();
        for d in (0..nb).filter(|&d| !rows.free[d]) {
            let p = self.pos(d);
            full[0][p] = rows.b0[d];
            full[1][p] = rows.b1[d];
        }
        let mut out = Solution { b0: vec![0.0; nb], b1: vec![0.0; nb], f0: vec![0.0; nb], f1: vec![0.0; nb] };
        for d in 0..nb {
            let p = self.pos(d);
            let (c, v) = self.row(p);
            out.b0[d] = full[0][p];
            out.b1[d] = full[1][p];
            let f = |k: usize| match kx {
                Some(kx) => kx[k][p],
                _ => c.iter().zip(v).map(|(&c, &v)| v * full[k][c]).sum(),
            };
            out.f0[d] = f(0);
            out.f1[d] = f(1);
        }
        out
    }
}

/// The condensed stiffness S of the dense path, column by column, without forming it: the
/// block factored once with every boundary DOF held (identity rows), one banded solve a
/// column (O(m (kl + ku))). For the fracture-mechanics energy release
/// ([`crate::studies::dynamic_slide::fracture`]), which needs S on the slipped DOFs only.
pub struct HeldColumns<'a> {
    op: &'a BandedOperator,
    // Boxed: the factor's header is large beside a dense stiffness's reference.
    f: Box<Factored>,
}

impl BandedOperator {
    /// The factor of the block with the interface and the plate held.
    pub fn held_columns(&self) -> Result<HeldColumns<'_>> {
        let (n, nb) = (self.n, self.dim());
        let (free, zb, zn) = (vec![false; nb], vec![0.0; nb], vec![0.0; n]);
        let rows = Rows {
            free: &free,
            b0: &zb,
            b1: &zb,
            coef: &zn,
            spring: &zn,
            spring_u: &zn,
            fk: (0.0, 0.0),
            load: &[],
        };
        let (f, _, _) = self.factor(&rows, self.workspace())?;
        Ok(HeldColumns { op: self, f: Box::new(f) })
    }
}

impl HeldColumns<'_> {
    /// S e_d over the 2n interface DOFs (N/m per m): the forces on the block at the interface
    /// DOFs when interface DOF `d` (< 2n) moves by 1 m and every other boundary DOF is held.
    pub fn column(&self, d: usize) -> Result<Vec<f64>> {
        let op = self.op;
        let (m, nb) = (op.m, op.dim());
        if d >= 2 * op.n {
            return Err(Error::input(
                "held column",
                format!("DOF {d} is not an interface DOF (< {})", 2 * op.n),
            ));
        }
        let mut z = vec![0.0; m];
        z[op.pos(d)] = op.scale;
        let mut full = vec![0.0; m + 3];
        self.f.apply(&mut z, [0.0; 3], &mut full)?;
        // The held values exactly (the identity rows return them to round-off).
        for e in 0..nb {
            full[op.pos(e)] = if e == d { 1.0 } else { 0.0 };
        }
        Ok((0..2 * op.n)
            .map(|e| {
                let (c, v) = op.row(op.pos(e));
                c.iter().zip(v).map(|(&c, &v)| v * full[c]).sum()
            })
            .collect())
    }
}

fn singular() -> Error {
    Error::Singular {
        detail: "the interface leaves the block free to move (every node open, or N <= 0)".into(),
        node: None,
        component: None,
    }
}

/// The factored bordered system [A B; C D] of one state set: A's banded LU, A^{-1} B, C and
/// the border's Schur complement S = D - C A^{-1} B.
pub(crate) struct Factored {
    lu: Banded,
    ab: Vec<f64>,
    crow: Vec<f64>,
    s: [[f64; 3]; 3],
}

impl Factored {
    /// The band's storage, for the next factorisation.
    pub(crate) fn into_band(self) -> Banded {
        self.lu
    }

    /// Sign of the bordered system's determinant, det A det S.
    pub(crate) fn det_sign(&self) -> f64 {
        let s = &self.s;
        let d3 = s[0][0] * (s[1][1] * s[2][2] - s[1][2] * s[2][1])
            - s[0][1] * (s[1][0] * s[2][2] - s[1][2] * s[2][0])
            + s[0][2] * (s[1][0] * s[2][1] - s[1][1] * s[2][0]);
        self.lu.det_sign() * d3.signum()
    }

    /// Adds to `full` (m + 3) the solution for a band right-hand side z (solved in place) and a
    /// border one t: y = S^{-1} (t - C A^{-1} z), x = A^{-1} z - A^{-1} B y.
    pub(crate) fn apply(&self, z: &mut [f64], t: [f64; 3], full: &mut [f64]) -> Result<()> {
        let m = self.lu.m;
        self.lu.solve_in_place(z, 1);
        let c = &self.crow;
        let tt = [0, 1, 2].map(|p| t[p] - dot(&c[p * m..(p + 1) * m], z));
        let y = solve3(self.s, tt).ok_or_else(singular)?;
        let ab = &self.ab;
        for r in 0..m {
            full[r] += z[r] - (0..3).map(|q| ab[q * m + r] * y[q]).sum::<f64>();
        }
        for q in 0..3 {
            full[m + q] += y[q];
        }
        Ok(())
    }
}

impl BandedOperator {
    /// Left-hand side of equation `r` (band row, or m + p for the plate's DOF p) at `full`.
    fn lhs(&self, r: usize, bnd: &[usize], rows: &Rows, full: &[f64]) -> f64 {
        let dotk = |r: usize| -> f64 {
            let (c, v) = self.row(r);
            c.iter().zip(v).map(|(&c, &v)| v * full[c]).sum()
        };
        let d = if r < self.m { bnd[r] } else { 2 * self.n + r - self.m };
        if d == usize::MAX {
            return dotk(r);
        }
        if !rows.free[d] {
            return self.scale * full[r];
        }
        let mut v = dotk(r);
        if d < self.n {
            if rows.coef[d] != 0.0 {
                v += rows.coef[d] * dotk(self.pv[d]);
            }
            v += rows.spring[d] * full[r];
        }
        v
    }
}

/// 3 x 3 solve by Gaussian elimination with partial pivoting; None if singular.
fn solve3(mut a: [[f64; 3]; 3], mut b: [f64; 3]) -> Option<[f64; 3]> {
    let big = a.iter().flatten().fold(0.0f64, |s, v| s.max(v.abs()));
    for i in 0..3 {
        let p = (i..3).max_by(|&x, &y| a[x][i].abs().total_cmp(&a[y][i].abs()))?;
        if !(a[p][i].abs() > 1e-13 * big) {
            return None;
        }
        a.swap(i, p);
        b.swap(i, p);
        for r in i + 1..3 {
            let q = a[r][i] / a[i][i];
            for c in i..3 {
                a[r][c] -= q * a[i][c];
            }
            b[r] -= q * b[i];
        }
    }
    let mut x = [0.0; 3];
    for i in (0..3).rev() {
        x[i] = (b[i] - (i + 1..3).map(|c| a[i][c] * x[c]).sum::<f64>()) / a[i][i];
    }
    Some(x)
}

mod reuse;
pub(crate) use reuse::Solving;
pub use reuse::{RANK_CAP, REFINE};
