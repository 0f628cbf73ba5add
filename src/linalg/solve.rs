//! Sparse Cholesky (faer) on the reduced system: the symbolic analysis (fill-reducing
//! ordering + elimination structure) is done once per pattern and reused for any values;
//! all load cases are solved together; every solve is checked by its residual, refined
//! once or twice with the same factor if needed, and rejected if still not trustworthy.

use crate::error::{Error, Result};
use crate::linalg::pattern::Bisection;
use crate::linalg::pattern::Pattern;
use crate::linalg::substructure::{supernodal_flops, TwoDomain, TwoDomainFactor};
use crate::linalg::NonPositivePivot;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::{LltError, LltRegularization};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LltRef, SymbolicCholesky, SymbolicCholeskyRaw,
    SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};

/// Fill-reducing ordering handed to faer.
#[derive(Debug, Clone, Default, PartialEq)]
pub enum Ordering {
    /// [`Ordering::TwoDomain`] when the mesh is a grid with at least
    /// [`crate::fem::problem::TWO_DOMAINS_FROM`] unknowns, AMD otherwise; resolved by
    /// [`crate::fem::problem::solve`], which knows the mesh.
    #[default]
    Auto,
    /// faer's approximate minimum degree.
    Amd,
    /// Our geometric nested dissection ([`crate::fem::ordering`]) in one factorisation on grids,
    /// AMD otherwise; resolved like `Auto`.
    NestedDissection,
    /// Our own permutation: `perm[new] = old`.
    Custom(Vec<usize>),
    /// Nested dissection whose first cut is solved by substructuring: both halves factorised
    /// at once, one per thread ([`crate::linalg::substructure`]).
    TwoDomain(Bisection),
}

#[derive(Debug, Clone)]
pub struct SolverOptions {
    pub ordering: Ordering,
    /// Largest accepted componentwise backward error after refinement.
    pub residual_limit: f64,
    /// Largest accepted forward-error estimate, condition estimate x machine epsilon: the
    /// relative accuracy the solution can be expected to have.
    pub max_error_estimate: f64,
    /// Refinement steps tried (each one solve with the same factor) when the residual exceeds `refine_above`.
    pub max_refinement: usize,
    pub refine_above: f64,
    /// Threads for the supernodal factorisation (1 = sequential; faster on thin strips).
    pub threads: usize,
    /// Force the supernodal (true) or simplicial (false) factorisation; None = faer's choice.
    pub supernodal: Option<bool>,
}

impl Default for SolverOptions {
    fn default() -> Self {
        Self {
            ordering: Ordering::Auto,
            residual_limit: 1e-8,
            max_error_estimate: 1e-4,
            max_refinement: 2,
            refine_above: 1e-12,
            threads: 1,
            supernodal: None,
        }
    }
}

/// What a solve achieved, for reports and stability studies.
#[derive(Debug, Clone, Default)]
pub struct SolveReport {
    /// Componentwise backward error max_i |f - K x|_i / (|K||x| + |f|)_i per right-hand side, before refinement.
    pub residual_initial: Vec<f64>,
    /// The same after refinement.
    pub residual: Vec<f64>,
    pub refinement_steps: usize,
    /// Lower bound of the 1-norm condition number of the reduced matrix (log10 = digits lost).
    pub condition_estimate: f64,
}

/// Symbolic analysis of a pattern; reusable across values and right-hand sides.
pub struct Solver {
    backend: Backend,
    par: Par,
    pub options: SolverOptions,
}

impl Solver {
    pub fn analyse(pattern: &Pattern, options: SolverOptions) -> Result<Self> {
        let sym = SymbolicSparseColMatRef::new_checked(
            pattern.n,
            pattern.n,
            &pattern.col_ptr,
            None,
            &pattern.row_idx,
        );
        let threshold = match options.supernodal {
            None => SupernodalThreshold::AUTO,
            Some(true) => SupernodalThreshold::FORCE_SUPERNODAL,
            Some(false) => SupernodalThreshold::FORCE_SIMPLICIAL,
        };
        let params =
            CholeskySymbolicParams { supernodal_flop_ratio_threshold: threshold, ..Default::default() };
        let (fwd32, inv);
        let ordering = match &options.ordering {
            Ordering::TwoDomain(split) => {
                let backend = Backend::TwoDomain(TwoDomain::analyse(pattern, split)?);
                return Ok(Self { backend, par: Par::Seq, options });
            }
            Ordering::Auto | Ordering::Amd | Ordering::NestedDissection => SymmetricOrdering::Amd,
            Ordering::Custom(fwd) => {
                if fwd.len() != pattern.n {
                    return Err(Error::input(
                        "ordering",
                        format!("permutation has {} entries for {} unknowns", fwd.len(), pattern.n),
                    ));
                }
                // Checked and inverted in one pass, in the pattern's 32-bit indices.
                let (mut f, mut i) = (Vec::with_capacity(fwd.len()), vec![u32::MAX; fwd.len()]);
                for (new, &old) in fwd.iter().enumerate() {
                    if old >= fwd.len() || i[old] != u32::MAX {
                        return Err(Error::input("ordering", "not a permutation"));
                    }
                    i[old] = new as u32;
                    f.push(old as u32);
                }
                fwd32 = f;
                inv = i;
                SymmetricOrdering::Custom(faer::perm::PermRef::new_checked(&fwd32, &inv, pattern.n))
            }
        };
        let symbolic = factorize_symbolic_cholesky(sym, Side::Lower, ordering, params)
            .map_err(|e| Error::input("symbolic factorisation", format!("{e:?}")))?;
        let par = if options.threads > 1 { Par::rayon(options.threads) } else { Par::Seq };
        Ok(Self { backend: Backend::Direct(symbolic), par, options })
    }

    /// Non-zeros of the Cholesky factor L (of both halves and the separator for two domains).
    pub fn factor_nnz(&self) -> usize {
        match &self.backend {
            Backend::Direct(s) => s.len_val(),
            Backend::TwoDomain(t) => t.factor_nnz(),
        }
    }

    /// Flop count of the numeric factorisation, sum over the columns of L of (column count)^2
    /// (one multiply-add = 2 flops; exact up to lower-order terms).
    pub fn factor_flops(&self) -> f64 {
        let symbolic = match &self.backend {
            Backend::Direct(s) => s,
            Backend::TwoDomain(t) => return t.factor_flops(),
        };
        match symbolic.raw() {
            SymbolicCholeskyRaw::Simplicial(s) => {
                s.col_ptr().windows(2).map(|w| ((w[1] - w[0]) as f64).powi(2)).sum()
            }
            SymbolicCholeskyRaw::Supernodal(s) => supernodal_flops(s),
        }
    }

    pub fn is_supernodal(&self) -> bool {
        match &self.backend {
            Backend::Direct(s) => matches!(s.raw(), SymbolicCholeskyRaw::Supernodal(_)),
            Backend::TwoDomain(_) => true,
        }
    }

    /// Numeric factorisation. A non-positive pivot is mapped back to the unknown it belongs
    /// to (in the reduced numbering) so the caller can name the node.
    pub fn factorize(
        &self,
        pattern: &Pattern,
        values: &[f64],
    ) -> std::result::Result<Factor<'_>, NonPositivePivot> {
        let symbolic = match &self.backend {
            Backend::Direct(s) => s,
            Backend::TwoDomain(t) => {
                return Ok(Factor { solver: self, values: FactorValues::TwoDomain(t.factorize(values)?) })
            }
        };
        let sym = SymbolicSparseColMatRef::new_checked(
            pattern.n,
            pattern.n,
            &pattern.col_ptr,
            None,
            &pattern.row_idx,
        );
        let a = SparseColMatRef::new(sym, values);
        let mut l = vec![0.0; symbolic.len_val()];
        let mut mem =
            MemBuffer::new(symbolic.factorize_numeric_llt_scratch::<f64>(self.par, Default::default()));
        let res = symbolic.factorize_numeric_llt(
            &mut l,
            a,
            Side::Lower,
            LltRegularization::default(),
            self.par,
            MemStack::new(&mut mem),
            Default::default(),
        );
        match res {
            Ok(_) => Ok(Factor { solver: self, values: FactorValues::Direct(l) }),
            Err(LltError::NonPositivePivot { index }) => Err(NonPositivePivot {
                unknown: symbolic.perm().map_or(index, |p| p.arrays().0[index.min(pattern.n - 1)] as usize),
            }),
        }
    }
}

#[allow(clippy::large_enum_variant)] // one per solver: its size does not matter
enum Backend {
    /// One faer factorisation.
    Direct(SymbolicCholesky<u32>),
    TwoDomain(TwoDomain),
}

enum FactorValues {
    Direct(Vec<f64>),
    TwoDomain(TwoDomainFactor),
}

/// Numeric Cholesky factor.
pub struct Factor<'a> {
    solver: &'a Solver,
    values: FactorValues,
}

impl Drop for Factor<'_> {
    fn drop(&mut self) {
        if let (Backend::TwoDomain(t), FactorValues::TwoDomain(f)) = (&self.solver.backend, &mut self.values)
        {
            t.recycle(f);
        }
    }
}

impl Factor<'_> {
    /// Core-seconds the numeric factorisation spent in dense kernels; known for the
    /// two-domain solver only (faer's own factorisation does not report it).
    pub fn dense_seconds(&self) -> Option<f64> {
        match &self.values {
            FactorValues::TwoDomain(f) => Some(f.dense_seconds),
            FactorValues::Direct(_) => None,
        }
    }

    /// Solves in place for `k` right-hand sides stored column-major in `b` (n x k).
    pub fn solve_in_place(&self, b: &mut [f64], k: usize) {
        let (s, l) = match (&self.solver.backend, &self.values) {
            (Backend::Direct(s), FactorValues::Direct(l)) => (s, l),
            (Backend::TwoDomain(t), FactorValues::TwoDomain(f)) => return t.solve_in_place(f, b, k),
            _ => unreachable!("a factor comes from its own solver"),
        };
        let n = s.nrows();
        let llt = LltRef::<'_, u32, f64>::new(s, l);
        let mut mem = MemBuffer::new(s.solve_in_place_scratch::<f64>(k, self.solver.par));
        let rhs = MatMut::from_column_major_slice_mut(b, n, k);
        llt.solve_in_place_with_conj(Conj::No, rhs, self.solver.par, MemStack::new(&mut mem));
    }

    /// Solves K x = f for the k columns of `f`, checks each residual, refines if needed.
    /// Returns x and the report; errors when the residual stays above the limit or x is not finite.
    pub fn solve_checked(
        &self,
        pattern: &Pattern,
        values: &[f64],
        f: &[f64],
        k: usize,
        opts: &SolverOptions,
        hint: &str,
    ) -> Result<(Vec<f64>, SolveReport)> {
        let mut x = f.to_vec();
        self.solve_in_place(&mut x, k);
        self.check_and_refine(pattern, values, f, x, k, opts, hint)
    }

    /// Checks an already computed solution x of K x = f (k columns) by its componentwise
    /// (Oettli-Prager) backward error max_i |f - K x|_i / (|K| |x| + |f|)_i, which unlike
    /// ||r|| / ||f|| is not hidden by a few very stiff rows (a stiff plate); refines with the
    /// same factor while that helps; errors when it stays above the limit or x is not finite.
    #[allow(clippy::too_many_arguments)]
    pub fn check_and_refine(
        &self,
        pattern: &Pattern,
        values: &[f64],
        f: &[f64],
        mut x: Vec<f64>,
        k: usize,
        opts: &SolverOptions,
        hint: &str,
    ) -> Result<(Vec<f64>, SolveReport)> {
        let (mut r, rel0) = backward_errors(pattern, values, f, &x, k);
        let mut report = SolveReport { residual_initial: rel0.clone(), residual: rel0, ..Default::default() };
        while report.refinement_steps < opts.max_refinement
            && report.residual.iter().any(|&v| !(v <= opts.refine_above))
        {
            self.solve_in_place(&mut r, k);
            let trial: Vec<f64> = x.iter().zip(&r).map(|(a, b)| a + b).collect();
            let (r2, rel2) = backward_errors(pattern, values, f, &trial, k);
            report.refinement_steps += 1;
            if rel2.iter().zip(&report.residual).all(|(new, old)| new <= old) {
                x = trial;
                r = r2;
                report.residual = rel2;
            } else {
                break; // refinement no longer helps
            }
        }
        let worst = report.residual.iter().cloned().fold(0.0, f64::max);
        if !(worst <= opts.residual_limit) || x.iter().any(|v| !v.is_finite()) {
            let detail = format!(
                "componentwise backward error {worst:.2e} exceeds {:.1e} after {} refinement steps",
                opts.residual_limit, report.refinement_steps
            );
            return Err(Error::Untrustworthy { detail, hint: hint.to_string() });
        }
        Ok((x, report))
    }
}

/// Residual r = f - K x and the componentwise backward error of each of the k columns, one
/// fused pass over the stored lower triangle per column (columns in parallel).
fn backward_errors(
    pattern: &Pattern,
    values: &[f64],
    f: &[f64],
    x: &[f64],
    k: usize,
) -> (Vec<f64>, Vec<f64>) {
    use rayon::prelude::*;
    let n = pattern.n;
    let cols: Vec<(Vec<f64>, f64)> = (0..k)
        .into_par_iter()
        .map(|c| {
            let (xc, fc) = (&x[c * n..(c + 1) * n], &f[c * n..(c + 1) * n]);
            let (mut kx, mut akx) = (vec![0.0; n], vec![0.0; n]);
            for j in 0..n {
                for p in pattern.col(j) {
                    let (i, v) = (pattern.row_idx[p] as usize, values[p]);
                    kx[i] += v * xc[j];
                    akx[i] += v.abs() * xc[j].abs();
                    if i != j {
                        kx[j] += v * xc[i];
                        akx[j] += v.abs() * xc[i].abs();
                    }
                }
            }
            let mut worst = 0.0f64;
            for i in 0..n {
                kx[i] = fc[i] - kx[i];
                let den = akx[i] + fc[i].abs();
                let e = if den > 0.0 {
                    kx[i].abs() / den
                } else if kx[i] == 0.0 {
                    0.0
                } else {
                    f64::INFINITY
                };
                worst = worst.max(e);
            }
            (kx, worst)
        })
        .collect();
    let rel = cols.iter().map(|c| c.1).collect();
    (cols.into_iter().flat_map(|c| c.0).collect(), rel)
}
