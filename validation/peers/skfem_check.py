#!/usr/bin/env python3
"""Independent scikit-fem solution of the tribofe check problem.

Plane-strain block [-L/2, L/2] x [0, t], regular QUA4 mesh (ElementQuad1,
intorder=2 = full 2x2 Gauss), bottom nodes clamped, top nodes tied exactly to a
rigid plate (U, V, theta) at (0, H) by a sparse T matrix, K_r = T^T K T (no
penalty). Unit cases A (U=0, V=-1e-4 m) and B (U=1e-4 m, V=0) are solved with
one factorisation and combined into F/N = 0, 0.41, 0.82 (see peerlib).

Examples:
  python3 skfem_check.py                       # paper's mesh h = 1 mm (400 x 2)
  python3 skfem_check.py --tribofe-out /tmp/t  # also compare with tribofe's CSVs
  python3 skfem_check.py --ny 16 --solver cholmod --out /tmp/s16 --quiet
"""
from __future__ import annotations

import argparse
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import peerlib as pl  # noqa: E402

import numpy as np  # noqa: E402
import scipy  # noqa: E402
import scipy.sparse as sp  # noqa: E402


def versions(solver):
    import skfem
    v = (f"python {sys.version.split()[0]}, numpy {np.__version__}, "
         f"scipy {scipy.__version__}, scikit-fem {skfem.__version__}")
    if solver == "cholmod":
        import sksparse
        v += f", scikit-sparse {sksparse.__version__} (CHOLMOD)"
    return v


def factorize(A, solver):
    """Return a solve(b) callable; the factorisation is done once."""
    if solver == "cholmod":
        try:
            from sksparse.cholmod import cholesky
        except ImportError as e:
            pl.die(f"--solver cholmod needs scikit-sparse (run install.sh): {e}")
        fac = cholesky(A.tocsc())
        return fac
    from scipy.sparse.linalg import splu
    # Same default ordering as scipy.sparse.linalg.spsolve (COLAMD).
    lu = splu(A.tocsc(), permc_spec="COLAMD")
    return lu.solve


def solve_unit_cases(ny: int, solver: str, log=print):
    """Assemble, condense, solve cases A and B; return peerlib's 'unit' dict."""
    from skfem import Basis, ElementQuad1, ElementVector, MeshQuad, asm
    from skfem.models.elasticity import lame_parameters, linear_elasticity

    h, nx = pl.mesh_size(ny)
    t0 = time.perf_counter()
    # Node coordinates (i - nx/2) h, j h: the centre node is exactly x = 0.
    xs = (np.arange(nx + 1) - nx / 2) * h
    ys = h * np.arange(ny + 1)
    mesh = MeshQuad.init_tensor(xs, ys)
    basis = Basis(mesh, ElementVector(ElementQuad1()), intorder=2)
    assert basis.X.shape[1] == 4, "expected 2x2 Gauss points per quad"
    # lame_parameters returns the 3D lambda, which is the plane-strain one.
    K = asm(linear_elasticity(*lame_parameters(pl.E, pl.NU)), basis).tocsr()
    ndof = K.shape[0]
    t1 = time.perf_counter()

    px, py = mesh.p
    tol = 1e-9 * h
    bottom = np.nonzero(np.abs(py) < tol)[0]
    top = np.nonzero(np.abs(py - pl.T) < tol)[0]
    bottom = bottom[np.argsort(px[bottom])]
    dofs = basis.nodal_dofs  # (2, nnodes): row 0 = u, row 1 = v

    # T maps reduced unknowns q = [dofs of non-top nodes..., U, V, theta] to u.
    is_top = np.zeros(ndof, bool)
    is_top[dofs[:, top].ravel()] = True
    keep = np.nonzero(~is_top)[0]
    m = keep.size + 3
    iU, iV, iTh = keep.size, keep.size + 1, keep.size + 2
    ut, vt = dofs[0, top], dofs[1, top]
    rows = np.concatenate([keep, ut, ut, vt, vt])
    cols = np.concatenate([np.arange(keep.size), np.full(top.size, iU),
                           np.full(top.size, iTh), np.full(top.size, iV),
                           np.full(top.size, iTh)])
    # u = U + theta (H - t), v = V + theta x (small rotation about (0, H)).
    vals = np.concatenate([np.ones(keep.size), np.ones(top.size),
                           np.full(top.size, pl.H - pl.T), np.ones(top.size),
                           px[top]])
    Tm = sp.csr_matrix((vals, (rows, cols)), shape=(ndof, m))
    Kr = (Tm.T @ K @ Tm).tocsr()

    # Reduced index of each full dof that survives (for the bottom dofs).
    red = -np.ones(ndof, int)
    red[keep] = np.arange(keep.size)
    presc = np.concatenate([red[dofs[:, bottom].ravel()], [iU, iV]])
    free = np.setdiff1d(np.arange(m), presc)
    Kff = Kr[free][:, free]
    KfUV = Kr[free][:, [iU, iV]]
    t2 = time.perf_counter()

    solve = factorize(Kff, solver)
    t3 = time.perf_counter()
    qp = np.array([[0.0, pl.DISP], [-pl.DISP, 0.0]])  # columns: case A, case B
    qf = solve(np.asarray(-(KfUV @ qp)))
    t4 = time.perf_counter()

    unit = {"xb": px[bottom], "ndof": ndof, "nx": nx, "ny": ny}
    for k, case in enumerate("AB"):
        q = np.zeros(m)
        q[free] = qf[:, k]
        q[[iU, iV]] = qp[:, k]
        R = K @ (Tm @ q)          # f = 0: no body or surface loads
        Rr = Kr @ q
        unit[case] = {"Rx": R[dofs[0, bottom]], "Ry": R[dofs[1, bottom]],
                      "N": -Rr[iV], "F": Rr[iU], "theta": q[iTh]}
    t5 = time.perf_counter()
    log(f"mesh {nx} x {ny} (h = {h*1e3:g} mm), {ndof} DOFs, free {free.size}, "
        f"solver {solver}")
    log(f"timings [s]: assemble {t1-t0:.2f}, condense {t2-t1:.2f}, "
        f"factorise {t3-t2:.2f}, solve {t4-t3:.2f}, reactions {t5-t4:.2f}")
    return unit


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    g = ap.add_mutually_exclusive_group()
    g.add_argument("--ny", type=int, help="elements through t (default 2: h = 1 mm)")
    g.add_argument("--h", type=float, help="element size [m] (alternative to --ny)")
    ap.add_argument("--solver", choices=["splu", "cholmod"], default="splu",
                    help="SciPy SuperLU (default) or CHOLMOD via scikit-sparse")
    ap.add_argument("--out", help="directory for profile_FN*.csv and summary.csv "
                    "(default validation/peers/results/skfem_ny<ny>)")
    ap.add_argument("--tribofe-out", help="tribofe --out directory to compare with")
    ap.add_argument("--fail-above", type=float, default=None,
                    help="with --tribofe-out: exit 1 if a profile differs by more than this (units of N/L)")
    ap.add_argument("--quiet", action="store_true", help="no summary table")
    a = ap.parse_args(argv)

    ny = pl.ny_from_h(a.h) if a.h is not None else (a.ny or 2)
    out = a.out or os.path.join(HERE, "results", f"skfem_ny{ny}")
    print(f"skfem_check: {versions(a.solver)}")

    unit = solve_unit_cases(ny, a.solver)
    prof = pl.profiles(unit)
    rows = pl.summary(prof)
    pl.write_profiles(prof, out)
    pl.write_csv_atomic(os.path.join(out, "summary.csv"), pl.SUMMARY_COLS, rows)
    print(f"theta: case A {unit['A']['theta']:.6e}, case B {unit['B']['theta']:.6e} rad; "
          f"N_A = {unit['A']['N']:.6g} N/m, F_B = {unit['B']['F']:.6g} N/m")
    if not a.quiet:
        pl.print_summary(rows, f"scikit-fem, nx x ny = {unit['nx']} x {ny}")
    print(f"wrote {out}/profile_FN*.csv, summary.csv")

    if a.tribofe_out:
        if not os.path.isdir(a.tribofe_out):
            pl.die(f"--tribofe-out {a.tribofe_out} is not a directory")
        cmp_rows = pl.compare_profiles(prof, a.tribofe_out, "tribofe",
                                       os.path.join(a.tribofe_out, "summary.csv"))
        pl.print_compare(cmp_rows, "scikit-fem")
        path = os.path.join(HERE, "results", f"skfem_vs_tribofe_ny{ny}.csv")
        pl.write_csv_atomic(path, pl.COMPARE_COLS, cmp_rows)
        print(f"wrote {path}")
        worst = max(max(c["max_dp"], c["max_dtau"]) for c in cmp_rows)
        if a.fail_above is not None and not worst <= a.fail_above:
            pl.die(f"tribofe and scikit-fem differ by {worst:.3e} N/L > {a.fail_above:g}")
        if a.fail_above is not None:
            print(f"OK: tribofe and scikit-fem agree to {worst:.3e} N/L (<= {a.fail_above:g})")


if __name__ == "__main__":
    main()
