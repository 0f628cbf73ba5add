"""Shared definitions and post-processing for the tribofe peer checks.

Every peer (scikit-fem, CalculiX) only has to deliver, for the two unit cases
A (U=0, V=-1e-4 m) and B (U=1e-4 m, V=0), the bottom-node x coordinates, the
bottom-node reaction forces (Rx, Ry) and the plate reactions (N, F). All the
rest (load-case combination, tractions, model comparison, summary, file
output) is done here once, so the peers are compared on identical post-
processing. SI units throughout (m, Pa, N per metre of width).
"""
from __future__ import annotations

import csv
import math
import os
import sys
import tempfile

import numpy as np

# --- The paper's problem (Scheibert & Dysthe, EPL 2010, text before fig. 2) ---
L = 0.4          # m, block length
T = 0.002        # m, block thickness
E = 2.0e3        # Pa
NU = 0.4
H = 0.04         # m, height of the plate reference point (0, H)
DISP = 1.0e-4    # m, magnitude of the unit-case prescribed displacements
RATIOS = (0.0, 0.41, 0.82)
EDGE_TOL = 0.05  # relative deviation from the model that defines an edge zone

PROFILE_HEADER = ["x_over_L", "p_over_pmean", "tau_over_pmean",
                  "p_model", "tau_model"]


def die(msg: str, code: int = 2):
    """Fail with a one-line message instead of a traceback."""
    print(f"error: {msg}", file=sys.stderr)
    sys.exit(code)


def rust_fmt(r: float) -> str:
    """Format a ratio the way Rust's `{}` prints an f64 (0.0 -> '0')."""
    if r == int(r):
        return str(int(r))
    return repr(float(r))


def mesh_size(ny: int):
    """Square elements: h = t/ny, nx = L/h (must be an integer)."""
    if ny < 1:
        die(f"ny must be >= 1, got {ny}")
    h = T / ny
    nx = L / h
    if abs(nx - round(nx)) > 1e-9:
        die(f"L/h = {nx} is not an integer for ny = {ny}")
    return h, int(round(nx))


def ny_from_h(h: float) -> int:
    ny = T / h
    if h <= 0 or abs(ny - round(ny)) > 1e-9:
        die(f"t/h = {ny} is not a positive integer for h = {h} m")
    return int(round(ny))


def tributary_lengths(xb: np.ndarray) -> np.ndarray:
    """Half of each adjacent bottom edge (end nodes get half an element)."""
    d = np.diff(xb)
    w = np.zeros_like(xb)
    w[:-1] += 0.5 * d
    w[1:] += 0.5 * d
    return w


def model(xl: np.ndarray, ratio: float):
    """The paper's model: p/(N/L) = 1 + 12 (F/N)(H/L)(x/L), tau/(N/L) = F/N."""
    return 1.0 + 12.0 * ratio * (H / L) * xl, np.full_like(xl, ratio)


def combine(unit: dict, ratio: float):
    """Weights (a, b) of a*A + b*B with N = N_A and F/N = ratio exactly."""
    M = np.array([[unit["A"]["N"], unit["B"]["N"]],
                  [unit["A"]["F"], unit["B"]["F"]]])
    NA = unit["A"]["N"]
    return np.linalg.solve(M, np.array([NA, ratio * NA]))


def profiles(unit: dict):
    """Combine the unit cases into the requested F/N ratios.

    unit = {"xb": bottom x (sorted), "A": {"Rx","Ry","N","F"}, "B": {...}}.
    Returns {ratio: dict(xl, p, tau, p_model, tau_model, N, F, checks)}.
    """
    xb = np.asarray(unit["xb"])
    if np.any(np.diff(xb) <= 0):
        die("bottom nodes are not sorted by x")
    w = tributary_lengths(xb)
    out = {}
    for r in RATIOS:
        a, b = combine(unit, r)
        Rx = a * unit["A"]["Rx"] + b * unit["B"]["Rx"]
        Ry = a * unit["A"]["Ry"] + b * unit["B"]["Ry"]
        N = a * unit["A"]["N"] + b * unit["B"]["N"]
        F = a * unit["A"]["F"] + b * unit["B"]["F"]
        scale = N / L
        p = Ry / w / scale
        tau = -Rx / w / scale
        xl = xb / L
        pm, tm = model(xl, r)
        # Global equilibrium of the block: interface forces (-F, N), moment F H.
        checks = {
            "sumRy_minus_N_rel": (Ry.sum() - N) / N,
            "sumRx_plus_F_rel": (Rx.sum() + F) / N,
            "moment_minus_FH_rel": (np.dot(xb, Ry) - F * H) / (N * H),
        }
        out[r] = dict(xl=xl, p=p, tau=tau, p_model=pm, tau_model=tm,
                      N=N, F=F, a=a, b=b, checks=checks)
    return out


def edge_width(xl, dev, ref, end):
    """Distance (in units of t) from an end within which |dev| > tol*|ref|.

    Uses the innermost violating node of that half of the strip (robust to
    sign changes of the deviation inside the zone); the width runs to the
    next node inward, so it is quantised in steps of h. A zero model value
    (tau for F/N = 0) falls back to an absolute threshold of tol (in N/L).
    """
    ref = np.where(np.abs(ref) > 0, np.abs(ref), 1.0)
    bad = np.abs(dev) > EDGE_TOL * ref
    x = xl * L
    if end == "left":
        idx = np.nonzero(bad & (x < 0))[0]
        if idx.size == 0:
            return 0.0
        k = idx.max()
        return (x[k + 1] - x[0]) / T
    idx = np.nonzero(bad & (x > 0))[0]
    if idx.size == 0:
        return 0.0
    k = idx.min()
    return (x[-1] - x[k - 1]) / T


def summary(prof: dict):
    """Per-ratio summary rows (dimensionless, stresses in units of N/L)."""
    rows = []
    for r, d in prof.items():
        xl, p, tau = d["xl"], d["p"], d["tau"]
        inner = np.abs(xl * L) < L / 2 - 10 * T
        slope, icpt = np.polyfit(xl[inner], p[inner], 1)
        i0 = int(np.argmin(np.abs(xl)))
        rows.append({
            "FN": r, "N": d["N"], "F": d["F"],
            "p_slope": slope, "p_slope_model": 12 * r * H / L,
            "p_intercept": icpt,
            "tau_centre": tau[i0], "x_centre_over_L": xl[i0],
            "p_left": p[0], "p_right": p[-1],
            "tau_left": tau[0], "tau_right": tau[-1],
            "p_edge_left_t": edge_width(xl, p - d["p_model"], d["p_model"], "left"),
            "p_edge_right_t": edge_width(xl, p - d["p_model"], d["p_model"], "right"),
            "tau_edge_left_t": edge_width(xl, tau - d["tau_model"], d["tau_model"], "left"),
            "tau_edge_right_t": edge_width(xl, tau - d["tau_model"], d["tau_model"], "right"),
            **d["checks"],
        })
    return rows


SUMMARY_COLS = ["FN", "N", "F", "p_slope", "p_slope_model", "p_intercept",
                "tau_centre", "x_centre_over_L", "p_left", "p_right",
                "tau_left", "tau_right", "p_edge_left_t", "p_edge_right_t",
                "tau_edge_left_t", "tau_edge_right_t", "sumRy_minus_N_rel",
                "sumRx_plus_F_rel", "moment_minus_FH_rel"]


def print_summary(rows, title):
    print(f"\n== {title} ==  (stresses in units of N/L; widths in units of t)")
    print(f"{'F/N':>5} {'N [N/m]':>11} {'F [N/m]':>11} {'slope':>9} {'model':>7}"
          f" {'tau(0)':>8} {'p(-L/2)':>8} {'p(+L/2)':>8} {'tau(-L/2)':>9}"
          f" {'tau(+L/2)':>9} {'p edge L/R':>11} {'tau edge L/R':>12}")
    for s in rows:
        print(f"{s['FN']:5.2f} {s['N']:11.5g} {s['F']:11.5g} {s['p_slope']:9.5f}"
              f" {s['p_slope_model']:7.4f} {s['tau_centre']:8.5f} {s['p_left']:8.4f}"
              f" {s['p_right']:8.4f} {s['tau_left']:9.4f} {s['tau_right']:9.4f}"
              f" {s['p_edge_left_t']:5.1f}/{s['p_edge_right_t']:<5.1f}"
              f" {s['tau_edge_left_t']:6.1f}/{s['tau_edge_right_t']:<5.1f}")
    worst = max(max(abs(s[k]) for k in ("sumRy_minus_N_rel", "sumRx_plus_F_rel",
                                          "moment_minus_FH_rel")) for s in rows)
    print(f"equilibrium (sum Ry = N, sum Rx = -F, sum x Ry = F H): worst rel. residual {worst:.2e}")


def write_csv_atomic(path, header, rows):
    """Write rows (lists or dicts) via temp file + rename."""
    d = os.path.dirname(os.path.abspath(path))
    os.makedirs(d, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=d, prefix=".tmp_", suffix=".csv")
    try:
        with os.fdopen(fd, "w", newline="") as f:
            wr = csv.writer(f)
            wr.writerow(header)
            for row in rows:
                if isinstance(row, dict):
                    row = [row[k] for k in header]
                wr.writerow([f"{v:.12g}" if isinstance(v, (float, np.floating)) else v
                             for v in row])
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def write_text_atomic(path, text):
    d = os.path.dirname(os.path.abspath(path))
    os.makedirs(d, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=d, prefix=".tmp_")
    with os.fdopen(fd, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def write_profiles(prof: dict, outdir: str, prefix: str = "profile_FN"):
    for r, d in prof.items():
        rows = zip(d["xl"], d["p"], d["tau"], d["p_model"], d["tau_model"])
        write_csv_atomic(os.path.join(outdir, f"{prefix}{rust_fmt(r)}.csv"),
                         PROFILE_HEADER, [list(x) for x in rows])


def read_profile(path: str):
    """Read x_over_L, p_over_pmean, tau_over_pmean from a profile CSV."""
    if not os.path.isfile(path):
        die(f"missing profile file {path}")
    with open(path, newline="") as f:
        rd = csv.DictReader(f)
        need = ["x_over_L", "p_over_pmean", "tau_over_pmean"]
        if rd.fieldnames is None or any(c not in rd.fieldnames for c in need):
            die(f"{path}: header must contain {need}, got {rd.fieldnames}")
        rows = [(float(r[need[0]]), float(r[need[1]]), float(r[need[2]])) for r in rd]
    if not rows:
        die(f"{path}: no data rows")
    a = np.array(rows)
    a = a[np.argsort(a[:, 0])]
    return a[:, 0], a[:, 1], a[:, 2]


def read_summary_nf(path: str):
    """{FN: (N, F)} from a summary.csv with columns FN, N, F (None if absent)."""
    if not os.path.isfile(path):
        return None
    with open(path, newline="") as f:
        rd = csv.DictReader(f)
        if rd.fieldnames is None or any(c not in rd.fieldnames for c in ("FN", "N", "F")):
            print(f"warning: {path} lacks FN,N,F columns; N/F not compared")
            return None
        return {round(float(r["FN"]), 6): (float(r["N"]), float(r["F"])) for r in rd}


def compare_profiles(ref: dict, other_dir: str, label: str, nf_path: str | None = None):
    """Max abs difference of p/(N/L), tau/(N/L) (and N, F) vs a reference.

    ref is the output of profiles(); other_dir holds profile_FN<r>.csv.
    Returns list of dict rows.
    """
    nf = read_summary_nf(nf_path) if nf_path else None
    rows = []
    for r, d in ref.items():
        xo, po, to = read_profile(os.path.join(other_dir, f"profile_FN{rust_fmt(r)}.csv"))
        if xo.size != d["xl"].size:
            die(f"{label}: FN={rust_fmt(r)} has {xo.size} interface nodes, "
                f"reference has {d['xl'].size} (different mesh?)")
        dx = np.max(np.abs(xo - d["xl"]))
        if dx > 1e-9:
            die(f"{label}: FN={rust_fmt(r)} node positions differ by {dx:g} (x/L)")
        row = {"code": label, "FN": r,
               "max_dp": float(np.max(np.abs(po - d["p"]))),
               "max_dtau": float(np.max(np.abs(to - d["tau"]))),
               "N_ref": d["N"], "F_ref": d["F"], "N_rel": math.nan, "F_rel": math.nan}
        if nf is not None and round(r, 6) in nf:
            N, F = nf[round(r, 6)]
            row["N_rel"] = (N - d["N"]) / d["N"]
            row["F_rel"] = (F - d["F"]) / d["N"]  # relative to N: F = 0 for FN = 0
        rows.append(row)
    return rows


COMPARE_COLS = ["code", "FN", "max_dp", "max_dtau", "N_ref", "F_ref", "N_rel", "F_rel"]


def print_compare(rows, ref_label):
    print(f"\n== comparison against {ref_label} (abs diff in units of N/L; "
          f"N, F relative to N) ==")
    for c in rows:
        print(f"{c['code']:>10} F/N={c['FN']:4.2f}  max|dp|={c['max_dp']:.3e}  "
              f"max|dtau|={c['max_dtau']:.3e}  dN/N={c['N_rel']:.2e}  dF/N={c['F_rel']:.2e}")
