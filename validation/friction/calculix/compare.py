#!/usr/bin/env python3
"""Compares a `tribofe slide` run with a CalculiX run of the same scene (ccx_slide.py).

  compare.py --tribofe-out DIR --ccx-out DIR [--mu 0.5] [--out DIR]

Both folders hold tribofe-format `loading.csv` and `states.csv`. tribofe's F(X) is exact and
piecewise linear between its events, so it is interpolated at CalculiX's increments. The slip
front is the end of the run of slipping nodes grown from the trailing edge x = -L/2 (open nodes
at the edge skipped); CalculiX counts a node as slipping when |tau| >= 0.999 mu p. Fronts are
compared at equal F/(mu N). Writes compare.csv and compare.svg (matplotlib) into --out and
prints the largest differences.
"""
import argparse
import csv
import os
import sys

import numpy as np


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"error: {path}: no rows")
    return rows


def fronts(states_path):
    """event -> trailing front x/L (None: the trailing edge does not slip)."""
    by_event = {}
    for r in read(states_path):
        by_event.setdefault(int(r["event"]), []).append((float(r["x_over_L"]), r["state"]))
    out = {}
    for e, nodes in by_event.items():
        nodes.sort()
        k = 0
        while k < len(nodes) and nodes[k][1] == "open":
            k += 1
        if k == len(nodes) or nodes[k][1] != "slip":
            out[e] = None
            continue
        while k < len(nodes) and nodes[k][1] in ("slip", "open"):
            k += 1
        out[e] = 0.5 if k == len(nodes) else 0.5 * (nodes[k - 1][0] + nodes[k][0])
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--tribofe-out", required=True)
    ap.add_argument("--ccx-out", required=True)
    ap.add_argument("--mu", type=float, default=0.5)
    ap.add_argument("--out", default=None, help="folder for compare.csv and compare.svg (default: --ccx-out)")
    a = ap.parse_args()
    out = a.out or a.ccx_out
    os.makedirs(out, exist_ok=True)

    # The drive starts from the last state of the normal phase (X = 0).
    all_rows = read(os.path.join(a.tribofe_out, "loading.csv"))
    normal = [r for r in all_rows if r["phase"] == "normal"]
    tl = normal[-1:] + [r for r in all_rows if r["phase"] == "drive"]
    tx = np.array([float(r["X_m"]) for r in tl])
    tf = np.array([float(r["F_N_per_m"]) / float(r["N_N_per_m"]) for r in tl]) / a.mu
    t_front = fronts(os.path.join(a.tribofe_out, "states.csv"))
    t_ev = [int(r["event"]) for r in tl]
    # tribofe front as a function of F/(mu N): fronts only move at events, so take the front
    # of the last event at or below that force.
    t_pairs = sorted((f, t_front[e]) for f, e in zip(tf, t_ev) if t_front.get(e) is not None)

    cl = [r for r in read(os.path.join(a.ccx_out, "loading.csv")) if r["step"] == "2"]
    c_front = fronts(os.path.join(a.ccx_out, "states.csv"))
    rows = []
    for r in cl:
        x = float(r["X_m"])
        fc = float(r["F_over_mu_N"])
        ft = float(np.interp(x, tx, tf)) if x <= tx[-1] else 1.0
        xc = c_front.get(int(r["event"]))
        below = [p for p in t_pairs if p[0] <= fc + 1e-12]
        xt = below[-1][1] if below else None
        rows.append((x, fc, ft, xc, xt))

    with open(os.path.join(out, "compare.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["X_m", "F_over_mu_N_ccx", "F_over_mu_N_tribofe", "front_x_over_L_ccx", "front_x_over_L_tribofe"])
        for x, fc, ft, xc, xt in rows:
            w.writerow([f"{x:.6e}", f"{fc:.7f}", f"{ft:.7f}", "" if xc is None else f"{xc:.4f}", "" if xt is None else f"{xt:.4f}"])

    df = max(abs(fc - ft) for _, fc, ft, _, _ in rows)
    fr = [(fc, xc - xt) for _, fc, _, xc, xt in rows if xc is not None and xt is not None and abs(xc) < 0.3 and abs(xt) < 0.3]
    x_ccx = next((x for x, fc, *_ in rows if fc >= 1 - 1e-6), float("nan"))
    x_tri = next((float(r["X_m"]) for r, f in zip(tl, tf) if f >= 1 - 1e-9), float("nan"))
    print(f"loading curve: largest |F_ccx - F_tribofe| / (mu N) = {df:.2e} over {len(rows)} increments")
    if fr:
        d = np.array([v for _, v in fr])
        print(f"slip front (|x| < 0.3 L, {len(fr)} increments): x_ccx - x_tribofe = {d.mean():+.4f} L mean, {d.min():+.4f} .. {d.max():+.4f} L")
    print(f"whole sliding: X = {x_ccx:.4e} m (CalculiX, first increment at mu N), {x_tri:.4e} m (tribofe, exact)")

    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib missing: no compare.svg")
        return
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    ax[0].plot(tx * 1e6, tf, "-", label="tribofe (exact events)")
    ax[0].plot([r[0] * 1e6 for r in rows], [r[1] for r in rows], "o", ms=3, label="CalculiX 2.20")
    ax[0].set_xlabel("X (um)")
    ax[0].set_ylabel("F / (mu N)")
    ax[0].legend()
    tp = np.array(t_pairs)
    if len(tp):
        ax[1].step(tp[:, 0], tp[:, 1], where="post", label="tribofe")
    cp = [(fc, xc) for _, fc, _, xc, _ in rows if xc is not None]
    if cp:
        ax[1].plot([p[0] for p in cp], [p[1] for p in cp], "o", ms=3, label="CalculiX")
    ax[1].set_xlabel("F / (mu N)")
    ax[1].set_ylabel("trailing slip front x_s / L")
    ax[1].legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out, "compare.svg"))


if __name__ == "__main__":
    main()
