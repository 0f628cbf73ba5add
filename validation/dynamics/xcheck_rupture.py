#!/usr/bin/env python3
"""Independent explicit elastodynamic cross-check of the "rupture" scene (issue 33).

Plane-strain block x in [-0.1, 0.1] m, y in [0, 0.1] m on a rigid flat, regular QUA4 mesh
(bilinear, full 2x2 Gauss), row-sum lumped mass, central differences, no damping. The
body is a perturbation about a uniform background (sigma0, tau0) as in SEM2DPACK: it starts
at rest, top and sides are traction-free, base nodes keep u_y = 0 and slide in x with
slip-weakening friction, imposed node by node with the stick-trial rule of the shared spec
(validation/dynamics/README.md). numpy + scipy only; written from the spec alone,
independently of the Rust solver it checks.

Outputs in --out: arrival.csv (x_m,t_arrival_s) and summary.csv (force_drop_n_per_m,
min_sigma_pa, steps, dt_s, front_speed_m_per_s).

Examples:
  python3 xcheck_rupture.py --out /tmp/xc                 # default scene, S = 2
  python3 xcheck_rupture.py --S 1.0 --t-end 0.12 --out /tmp/xc_s1
"""
from __future__ import annotations

import argparse
import math
import os
import sys
import time

import numpy as np
import scipy.sparse as sp

# Material and friction of the spec.
E_PA, NU, RHO = 2000.0, 0.4, 1000.0
SIGMA0, MU_S, MU_D, DC = 2.5, 0.648, 0.583, 7.7e-7
LX, LY = 0.2, 0.1  # block x in [-LX/2, LX/2], y in [0, LY]
PATCH_HALF, PATCH_FACTOR = 0.01, 1.005
FRONT_X = (0.03, 0.08)  # x window of the front-speed fit
# Positions are compared with a tolerance of 1e-6 h, so that a node at exactly x = 0.01 or
# 0.03 (i h in binary floating point) is inside the closed interval the spec states.
XTOL = 1e-6


def lame(E=E_PA, nu=NU):
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    G = E / (2 * (1 + nu))
    return lam, G


def wave_speeds(E=E_PA, nu=NU, rho=RHO):
    lam, G = lame(E, nu)
    return math.sqrt((lam + 2 * G) / rho), math.sqrt(G / rho)


def rayleigh_speed(nu=NU):
    """c_R / c_s from the Rayleigh equation (plane strain), by bisection."""
    k2 = (1 - 2 * nu) / (2 * (1 - nu))  # (c_s / c_p)^2

    def f(x):  # x = (c / c_s)^2
        return (2 - x) ** 2 - 4 * math.sqrt(1 - x) * math.sqrt(1 - k2 * x)

    lo, hi = 0.5, 1.0 - 1e-15
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if f(lo) * f(mid) <= 0:
            hi = mid
        else:
            lo = mid
    return math.sqrt(0.5 * (lo + hi))


def plane_strain_D(E=E_PA, nu=NU):
    lam, G = lame(E, nu)
    return np.array([[lam + 2 * G, lam, 0.0], [lam, lam + 2 * G, 0.0], [0.0, 0.0, G]])


def quad4_stiffness(hx, hy, D):
    """8x8 stiffness of an hx x hy bilinear rectangle, 2x2 Gauss, unit thickness.

    Local nodes (-,-), (+,-), (+,+), (-,+); dofs (ux0, uy0, ux1, uy1, ...)."""
    xi_n = np.array([-1.0, 1.0, 1.0, -1.0])
    eta_n = np.array([-1.0, -1.0, 1.0, 1.0])
    g = 1.0 / math.sqrt(3.0)
    Ke = np.zeros((8, 8))
    for xi in (-g, g):
        for eta in (-g, g):
            dN_dxi = 0.25 * xi_n * (1 + eta_n * eta)
            dN_deta = 0.25 * eta_n * (1 + xi_n * xi)
            dN_dx = dN_dxi * 2.0 / hx
            dN_dy = dN_deta * 2.0 / hy
            B = np.zeros((3, 8))
            B[0, 0::2] = dN_dx
            B[1, 1::2] = dN_dy
            B[2, 0::2] = dN_dy
            B[2, 1::2] = dN_dx
            Ke += B.T @ D @ B * (hx * hy / 4.0)  # weights 1, detJ = hx hy / 4
    return Ke


class Mesh:
    """Regular nx x ny QUA4 grid of [x0, x0 + nx hx] x [0, ny hy]; node (i, j) = j (nx+1) + i."""

    def __init__(self, nx, ny, hx, hy, x0):
        self.nx, self.ny, self.hx, self.hy = nx, ny, hx, hy
        self.nn = (nx + 1) * (ny + 1)
        self.ndof = 2 * self.nn
        i = np.arange(nx + 1)
        j = np.arange(ny + 1)
        # x from the integer offset, so that the centre node is at exactly 0 when x0 = -nx hx / 2
        self.x = x0 + np.tile(i, ny + 1) * hx
        self.y = np.repeat(j, nx + 1) * hy
        ei, ej = np.meshgrid(np.arange(nx), np.arange(ny))
        n0 = (ej * (nx + 1) + ei).ravel()
        self.conn = np.stack([n0, n0 + 1, n0 + nx + 2, n0 + nx + 1], axis=1)
        self.base = np.arange(nx + 1)  # nodes on y = 0, left to right
        self.top = ny * (nx + 1) + np.arange(nx + 1)

    def node(self, i, j):
        return j * (self.nx + 1) + i


def centred_block(h, lx=LX, ly=LY):
    nx, ny = int(round(lx / h)), int(round(ly / h))
    if nx < 2 or ny < 1 or abs(nx * h - lx) > 1e-9 * lx or abs(ny * h - ly) > 1e-9 * ly:
        raise ValueError(f"--h {h}: must divide {lx} m and {ly} m into whole elements")
    # x_i = (i - nx/2) h, symmetric about 0 (nx even) without accumulated round-off
    m = Mesh(nx, ny, h, h, 0.0)
    m.x = (np.tile(np.arange(nx + 1), ny + 1) - nx / 2.0) * h
    return m


def assemble(mesh, D, rho):
    """Global stiffness K (CSR, ndof x ndof) and row-sum lumped mass per dof."""
    Ke = quad4_stiffness(mesh.hx, mesh.hy, D)
    dofs = np.empty((mesh.conn.shape[0], 8), dtype=np.int64)
    dofs[:, 0::2] = 2 * mesh.conn
    dofs[:, 1::2] = 2 * mesh.conn + 1
    rows = np.repeat(dofs, 8, axis=1).ravel()
    cols = np.tile(dofs, (1, 8)).ravel()
    data = np.tile(Ke.ravel(), mesh.conn.shape[0])
    K = sp.coo_matrix((data, (rows, cols)), shape=(mesh.ndof, mesh.ndof)).tocsr()
    K.sum_duplicates()
    # Row-sum of the consistent bilinear mass: each node of an element gets a quarter of it.
    m_node = np.bincount(mesh.conn.ravel(), minlength=mesh.nn) * (rho * mesh.hx * mesh.hy / 4.0)
    m = np.repeat(m_node, 2)
    return K, m


def tributary_widths(mesh):
    w = np.full(mesh.nx + 1, mesh.hx)
    w[0] = w[-1] = mesh.hx / 2.0
    return w


def background_tau(x, S, sigma0=SIGMA0, mu_s=MU_S, mu_d=MU_D, patch=PATCH_HALF, h=1.0):
    """tau0 from S = (mu_s sigma0 - tau0)/(tau0 - mu_d sigma0); 1.005 mu_s sigma0 in |x| <= patch."""
    tau = np.full(x.shape, (mu_s + S * mu_d) / (1.0 + S) * sigma0)
    tau[np.abs(x) <= patch + XTOL * h] = PATCH_FACTOR * mu_s * sigma0
    return tau


def simulate(mesh, K, m, dt, steps, tau0, w, sigma0=SIGMA0, mu_s=MU_S, mu_d=MU_D, dc=DC,
             track_energy=False, snapshots=(), u0=None, v0=None, sigma_fixed=False,
             base_y_free=False):
    """Central differences with the spec's base rule. Returns a dict of histories.

    Base nodes: dofs 2 i (x, frictional) and 2 i + 1 (y, u_y = 0). All other dofs are free.
    Friction is evaluated at steps n = 0 .. steps (the last one only to give T at t_end).
    u0, v0 (u^0, v^{-1/2}) default to rest. Two switches leave the spec, for the checks in
    test_xcheck.py and the README only: sigma_fixed (strength mu(d) sigma0, no normal coupling)
    and base_y_free (base nodes free in y: the symmetric-fault half-space of Andrews).
    """
    bx = 2 * mesh.base
    by = bx + 1
    mb = m[bx]
    minv = 1.0 / m
    u = np.zeros(mesh.ndof) if u0 is None else np.array(u0, dtype=float)
    v = np.zeros(mesh.ndof) if v0 is None else np.array(v0, dtype=float)  # v^{n-1/2}
    if not base_y_free:
        u[by] = 0.0
        v[by] = 0.0
    d = np.zeros(bx.size)
    d_hist = np.empty((steps + 1, bx.size))
    slipping_hist = np.zeros(steps + 1, dtype=np.int64)
    fd_hist = np.empty(steps + 1)
    min_sigma = math.inf
    T = None
    fext = np.zeros(mesh.ndof)
    if track_energy:
        # Exact discrete balance of central differences (see README):
        # C^{n+1/2} = 1/2 v^{n+1/2} M v^{n+1/2} + 1/2 u^{n+1} K u^n, and
        # C^{n+1/2} - C^{n-1/2} = F^n . (u^{n+1} - u^{n-1}) / 2, F^n the external force.
        W = D = 0.0
        en = {k: [] for k in ("C", "W", "D", "W_half", "D_half", "kin", "strain", "corr_bound")}
    snaps = {}
    for n in range(steps + 1):
        f = -(K @ u)
        tstar = tau0 + (mb * v[bx] / dt + f[bx]) / w
        sigma = np.full(bx.size, sigma0) if (sigma_fixed or base_y_free) else sigma0 - f[by] / w
        min_sigma = min(min_sigma, float(sigma.min()))
        mu = mu_s - (mu_s - mu_d) * np.minimum(d / dc, 1.0)
        strength = mu * sigma
        T = np.where(np.abs(tstar) <= strength, tstar, strength * np.sign(tstar))
        d_hist[n] = d
        fd_hist[n] = float(np.dot(tau0 - T, w))
        slipping_hist[n] = int(np.count_nonzero(np.abs(tstar) > strength))
        if n in snapshots:
            snaps[n] = {"d": d.copy(), "T": T.copy(), "vx": v[bx].copy(), "sigma": sigma.copy()}
        if n == steps:
            break
        fext[bx] = (tau0 - T) * w
        v_old = v
        v = v + dt * (f + fext) * minv
        if not base_y_free:
            v[by] = 0.0
        u_new = u + dt * v
        if track_energy:
            # u^{n+1} - u^{n-1} = dt (v^{n+1/2} + v^{n-1/2})
            du = 0.5 * dt * (v[bx] + v_old[bx])
            dW = float(np.dot(tau0 * w, du))
            dD = float(np.dot(T * w, du))
            C = 0.5 * float(np.dot(v * m, v)) + 0.5 * float(np.dot(u_new, K @ u))
            vmid = 0.5 * (v + v_old)
            en["kin"].append(0.5 * float(np.dot(vmid * m, vmid)))
            en["strain"].append(0.5 * float(np.dot(u, -f)))
            # E_phys^n - (C^{n-1/2} + C^{n+1/2})/2 = dt^2/8 r M^-1 r + dt^2/4 (Ku) M^-1 r,
            # r = F - K u (derivation in README); its Cauchy-Schwarz bound:
            r = f + fext
            kun = -f
            if not base_y_free:
                r[by] = 0.0  # constrained dofs carry no motion
                kun[by] = 0.0
            nr = math.sqrt(float(np.dot(r * minv, r)))
            nk = math.sqrt(float(np.dot(kun * minv, kun)))
            en["corr_bound"].append(dt * dt / 8.0 * (nr * nr + 2.0 * nk * nr))
            en["W"].append(W + 0.5 * dW)  # work to time n (trapezoid, as in the exact balance)
            en["D"].append(D + 0.5 * dD)
            W += dW
            D += dD
            en["W_half"].append(W)  # work to time n + 1/2, the partner of C^{n+1/2}
            en["D_half"].append(D)
            en["C"].append(C)
        u = u_new
        d = d + dt * np.abs(v[bx])
    out = {"d_hist": d_hist, "T": T, "min_sigma": min_sigma, "u": u, "v": v,
           "slipping": slipping_hist, "snapshots": snaps, "fd_hist": fd_hist}
    if track_energy:
        out["energy"] = {k: np.array(val) for k, val in en.items()}
    return out


def arrival_times(d_hist, dt, thr):
    """First time each node's d reaches thr, linear between the two steps; nan if never."""
    reached = d_hist >= thr
    any_ = reached.any(axis=0)
    k = np.argmax(reached, axis=0)  # first step with d >= thr
    t = np.full(d_hist.shape[1], np.nan)
    for i in np.nonzero(any_)[0]:
        n = k[i]
        if n == 0:
            t[i] = 0.0
            continue
        d0, d1 = d_hist[n - 1, i], d_hist[n, i]
        t[i] = (n - 1 + (thr - d0) / (d1 - d0)) * dt
    return t


def front_speed(x, t, lo=FRONT_X[0], hi=FRONT_X[1], h=1e-3):
    sel = (x >= lo - XTOL * h) & (x <= hi + XTOL * h) & np.isfinite(t)
    if np.count_nonzero(sel) < 2:
        return math.nan, int(np.count_nonzero(sel))
    slope = np.polyfit(t[sel], x[sel], 1)[0]
    return float(slope), int(np.count_nonzero(sel))


def cohesive_zone_estimate(dc=DC, sigma0=SIGMA0, mu_s=MU_S, mu_d=MU_D):
    _, G = lame()
    return 9 * math.pi / 32 * G * dc / ((1 - NU) * (mu_s - mu_d) * sigma0)


def measured_cohesive_zone(x, d_hist, dc, h, lo=FRONT_X[0], hi=FRONT_X[1]):
    """Process-zone length of the x > 0 front: at each step whose tip (rightmost node with
    d >= Dc/100) lies in [lo, hi], the distance from the rightmost node with d >= Dc (weakening
    complete) to the tip. Returns (mean, min, max, count), nan when no step qualifies."""
    right = x >= 0
    vals = []
    for d in d_hist:
        tip = np.nonzero(right & (d >= dc / 100.0))[0]
        full = np.nonzero(right & (d >= dc))[0]
        if tip.size == 0 or full.size == 0:
            continue
        xt = x[tip.max()]
        if lo - XTOL * h <= xt <= hi + XTOL * h:
            vals.append(xt - x[full.max()])
    if not vals:
        return math.nan, math.nan, math.nan, 0
    v = np.array(vals)
    return float(v.mean()), float(v.min()), float(v.max()), v.size


def run(h, S, dc, t_end, sigma0=SIGMA0, track_energy=False, snapshots=(), courant=0.5, **kw):
    c_p, c_s = wave_speeds()
    mesh = centred_block(h)
    K, m = assemble(mesh, plane_strain_D(), RHO)
    dt = courant * h / c_p  # the spec: 0.5 h / c_p
    steps = int(round(t_end / dt))
    w = tributary_widths(mesh)
    xb = mesh.x[mesh.base]
    tau0 = background_tau(xb, S, sigma0=sigma0, h=h)
    t0 = time.perf_counter()
    res = simulate(mesh, K, m, dt, steps, tau0, w, sigma0=sigma0, dc=dc,
                   track_energy=track_energy, snapshots=snapshots, **kw)
    res["wall_s"] = time.perf_counter() - t0
    t_arr = arrival_times(res["d_hist"], dt, dc / 100.0)
    res.update(mesh=mesh, K=K, m=m, dt=dt, steps=steps, w=w, xb=xb, tau0=tau0, t_arr=t_arr,
               c_p=c_p, c_s=c_s)
    res["force_drop"] = float(np.sum((tau0 - res["T"]) * w))
    res["force_drop_hist"] = res.pop("fd_hist")
    res["front_speed"], res["front_npts"] = front_speed(xb, t_arr, h=h)
    return res


def write_outputs(res, out):
    os.makedirs(out, exist_ok=True)
    xb, t_arr = res["xb"], res["t_arr"]
    sel = (xb >= 0) & np.isfinite(t_arr)
    with open(os.path.join(out, "arrival.csv"), "w") as fh:
        fh.write("x_m,t_arrival_s\n")
        for x, t in zip(xb[sel], t_arr[sel]):
            fh.write(f"{x:.17g},{t:.17g}\n")
    fs = res["front_speed"]
    with open(os.path.join(out, "summary.csv"), "w") as fh:
        fh.write("force_drop_n_per_m,min_sigma_pa,steps,dt_s,front_speed_m_per_s\n")
        fh.write(f"{res['force_drop']:.17g},{res['min_sigma']:.17g},{res['steps']},"
                 f"{res['dt']:.17g},{fs:.17g}\n")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--h", type=float, default=1e-3, help="element size, m (default 1e-3)")
    ap.add_argument("--S", type=float, default=2.0, help="strength ratio outside the patch")
    ap.add_argument("--dc", type=float, default=DC, help="slip-weakening distance D_c, m")
    ap.add_argument("--t-end", type=float, default=0.1, help="end time, s (default 0.1)")
    ap.add_argument("--out", required=True, help="output folder (created)")
    ap.add_argument("--quiet", action="store_true")
    ap.add_argument("--symmetric-fault", action="store_true",
                    help="leave the spec: base nodes free in y, strength mu(d) sigma0 (the "
                    "symmetric-fault half-space of Andrews), for reference runs only")
    ap.add_argument("--courant", type=float, default=0.5,
                    help="dt = COURANT h / c_p; the spec's 0.5 is the default, others leave it")
    ap.add_argument("--sigma-fixed", action="store_true",
                    help="leave the spec: keep u_y = 0 on the base but use mu(d) sigma0 as the "
                    "strength (no normal-stress coupling), for reference runs only")
    a = ap.parse_args(argv)
    for name, val in (("--h", a.h), ("--dc", a.dc), ("--t-end", a.t_end)):
        if not (math.isfinite(val) and val > 0):
            ap.error(f"{name} {val}: must be a positive number")
    if not (math.isfinite(a.S) and a.S > 0):
        ap.error(f"--S {a.S}: must be positive (tau0 between mu_d sigma0 and mu_s sigma0)")
    if a.symmetric_fault and a.sigma_fixed:
        ap.error("--symmetric-fault and --sigma-fixed: choose one")
    if not (math.isfinite(a.courant) and 0 < a.courant <= 0.5):
        ap.error(f"--courant {a.courant}: must be in (0, 0.5] (0.5 is the spec's)")
    try:
        res = run(a.h, a.S, a.dc, a.t_end, base_y_free=a.symmetric_fault,
                  sigma_fixed=a.sigma_fixed, courant=a.courant)
    except ValueError as e:
        ap.error(str(e))
    write_outputs(res, a.out)
    if not math.isfinite(res["front_speed"]):
        print(f"warning: fewer than 2 arrivals in {FRONT_X[0]} <= x <= {FRONT_X[1]} m; "
              "front_speed_m_per_s written as nan", file=sys.stderr)
    if a.quiet:
        return 0
    c_p, c_s = res["c_p"], res["c_s"]
    c_r = rayleigh_speed() * c_s
    xb, t_arr = res["xb"], res["t_arr"]
    reached = (xb >= 0) & np.isfinite(t_arr)
    tip = xb[reached].max() if reached.any() else math.nan
    fs = res["front_speed"]
    lam0 = cohesive_zone_estimate(dc=a.dc)
    variant = (" [NOT the spec: symmetric-fault base]" if a.symmetric_fault else
               " [NOT the spec: strength mu(d) sigma0]" if a.sigma_fixed else "")
    if a.courant != 0.5:
        variant += f" [NOT the spec: dt = {a.courant:g} h/c_p]"
    print(f"rupture xcheck{variant}: h = {a.h:g} m ({res['mesh'].ndof} dofs), S = {a.S:g}, "
          f"D_c = {a.dc:g} m, dt = {res['dt']:.6e} s, steps = {res['steps']}, "
          f"{res['wall_s']:.2f} s wall")
    print(f"  c_p = {c_p:.5f}, c_s = {c_s:.5f}, c_R = {c_r:.5f} m/s")
    print(f"  front speed (x in [0.03, 0.08] m, {res['front_npts']} nodes) = {fs:.5f} m/s "
          f"= {fs / c_s:.4f} c_s = {fs / c_r:.4f} c_R; tip at t_end x = {tip:.4f} m")
    last = res["force_drop_hist"][-10:]
    print(f"  force drop at t_end = {res['force_drop']:.9e} N/m (last 10 steps: "
          f"{last.min():.4e} .. {last.max():.4e}); min sigma = {res['min_sigma']:.6f} Pa")
    cz = measured_cohesive_zone(xb, res["d_hist"], a.dc, a.h)
    print(f"  cohesive zone estimate (9 pi/32) G Dc/((1-nu)(tau_s-tau_d)) = {lam0:.4e} m "
          f"= {lam0 / a.h:.2f} h; measured (tip to d = D_c, tip in [0.03, 0.08] m, "
          f"{cz[3]} steps) mean {cz[0]:.4e} m, range {cz[1]:.4e} .. {cz[2]:.4e} m")
    print(f"  wrote {os.path.join(a.out, 'arrival.csv')} ({int(reached.sum())} rows), "
          f"{os.path.join(a.out, 'summary.csv')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
