#!/usr/bin/env python3
"""Checks CalculiX runs of ccx_slide.py on their own against theory, and against each other
(two penalties 10x apart), optionally with a tribofe `slide` run on the same plots:
under N alone sum(p w) = N; whole sliding at F = mu N; the slip front against the thin-layer
closed form F/(mu N) = 1/(1 + g (1/2 - x_s/L)^2), g = 6 mu H/L (start at 1/(1 + g)).
(compare.py, from main, is the tribofe-vs-CalculiX comparison proper.)

  theory_check.py --ccx-out D1 [D2 ...] [--tribofe-out DIR] [--out DIR]
  theory_check.py --make-closed-form DIR --ccx-out D1   # tribofe-format CSVs of the closed form

Several --ccx-out directories (e.g. two penalties 10x apart) are compared with the first.
The slip front x_s/L is the last node of the run of slipping/open nodes that starts at the
trailing edge x = -L/2, ignoring stuck nodes within 0.01 L of it (a node slips when |tau| >= 0.999 mu p, the rule of ccx_slide.py;
tribofe's own `state` column is used for tribofe). Writes theory_check.csv and theory_check.png.
"""
from __future__ import annotations

import argparse
import csv
import json
import os
import sys

import numpy as np


# Stuck nodes within this distance of the trailing corner do not end the slip run: under N
# the corner pre-slips while its neighbour is unloaded by it and sticks a little longer.
EDGE_SKIP = 0.01


def die(msg):
    print(f"error: {msg}", file=sys.stderr)
    sys.exit(2)


def read_csv(path):
    if not os.path.isfile(path):
        die(f"missing {path}")
    with open(path) as f:
        return list(csv.DictReader(f))


def load(d, mu):
    lo = read_csv(os.path.join(d, "loading.csv"))
    st = read_csv(os.path.join(d, "states.csv"))
    for c in ("event", "X_m", "F_N_per_m", "N_N_per_m"):
        if c not in lo[0]:
            die(f"{d}/loading.csv has no column {c}")
    for c in ("event", "x_over_L", "state"):
        if c not in st[0]:
            die(f"{d}/states.csv has no column {c}")
    ev = np.array([int(r["event"]) for r in lo])
    X = np.array([float(r["X_m"]) for r in lo])
    F = np.array([float(r["F_N_per_m"]) for r in lo])
    N = np.array([float(r["N_N_per_m"]) for r in lo])
    by = {}
    for r in st:
        by.setdefault(int(r["event"]), []).append((float(r["x_over_L"]), r["state"]))
    xs = []
    for e in ev:
        nodes = sorted(by.get(e, []))
        front = np.nan
        for x, s in nodes:
            if s in ("slip", "open"):
                front = x
            elif x > -0.5 + EDGE_SKIP:
                break
        xs.append(front)
    # Keep step 2 only: N at its final value (N ramps in step 1 for CalculiX).
    keep = np.isclose(N, N[-1], rtol=1e-6)
    return {"X": X[keep], "r": F[keep] / (mu * N[keep]), "xs": np.array(xs)[keep], "dir": d}


def closed_form_xs(r, g):
    """Slip front of the thin-layer closed form at r = F/(mu N) (nan before slip starts)."""
    r = np.asarray(r, float)
    out = np.full_like(r, np.nan)
    ok = (r >= 1 / (1 + g)) & (r < 1)
    out[ok] = 0.5 - np.sqrt((1 / r[ok] - 1) / g)
    out[r >= 1] = 0.5
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--ccx-out", nargs="+", required=True)
    ap.add_argument("--tribofe-out")
    ap.add_argument("--out", default=".")
    ap.add_argument("--make-closed-form", metavar="DIR")
    a = ap.parse_args()
    meta = json.load(open(os.path.join(a.ccx_out[0], "run.json")))
    mu, H, L, N = meta["mu"], meta["H_m"], meta["L_m"], meta["N_N_per_m"]
    g = 6 * mu * H / L
    ccx = [load(d, mu) for d in a.ccx_out]
    if a.make_closed_form:
        # Synthetic tribofe-format output: the closed form's front at CalculiX's X and F
        # (only to exercise this script until `tribofe slide` exists).
        c = ccx[0]
        os.makedirs(a.make_closed_form, exist_ok=True)
        xn = np.linspace(-0.5, 0.5, 401)
        with open(os.path.join(a.make_closed_form, "loading.csv"), "w") as f:
            f.write("event,X_m,F_N_per_m,N_N_per_m\n")
            for e, (X, r) in enumerate(zip(c["X"], c["r"])):
                f.write(f"{e},{X:.10g},{r * mu * N:.10g},{N:.10g}\n")
        with open(os.path.join(a.make_closed_form, "states.csv"), "w") as f:
            f.write("event,x_over_L,p_over_pmean,tau_over_pmean,slip_m,state\n")
            for e, r in enumerate(c["r"]):
                xs = closed_form_xs([r], g)[0]
                for x in xn:
                    s = "slip" if (np.isfinite(xs) and x <= xs + 1e-12) else "stick"
                    f.write(f"{e},{x:.6g},nan,nan,nan,{s}\n")
        print(f"wrote closed-form tribofe-format CSVs to {a.make_closed_form}")
        return
    runs = [("ccx K=%g" % json.load(open(os.path.join(d, "run.json")))["penalty_Pa_per_m"], c)
            for d, c in zip(a.ccx_out, ccx)]
    if a.tribofe_out:
        runs.append(("tribofe", load(a.tribofe_out, mu)))
    os.makedirs(a.out, exist_ok=True)
    rows = []
    ref = runs[0][1]
    r0 = 1 / (1 + g)
    print(f"mu = {mu}, g = 6 mu H/L = {g:.4f}, closed-form slip start F/(mu N) = {r0:.4f}")
    for d in a.ccx_out:
        lo = read_csv(os.path.join(d, "loading.csv"))
        s1 = [r for r in lo if r.get("step") == "1"][-1]
        n1 = float(s1["N_N_per_m"])
        last = lo[-1]
        print(f"{d}: under N alone sum(p w)/N - 1 = {float(s1['sum_p_w_N_per_m']) / n1 - 1:.2e}, "
              f"{s1['n_slip']} nodes pre-slip (the corners); at the last X F/(mu N) - 1 = "
              f"{float(last['F_N_per_m']) / (mu * float(last['N_N_per_m'])) - 1:.2e}, "
              f"sum(tau w)/F - 1 = {float(last['sum_tau_w_N_per_m']) / float(last['F_N_per_m']) - 1:.2e}")
    for name, c in runs:
        # Slip start: first r where the front leaves the corner node.
        moving = np.isfinite(c["xs"]) & (c["xs"] > -0.5 + 1e-9)
        r_start = c["r"][np.argmax(moving)] if moving.any() else np.nan
        band = (c["r"] > r0 + 0.02) & (c["r"] < 0.99) & np.isfinite(c["xs"])
        d_cf = np.abs(c["xs"][band] - closed_form_xs(c["r"][band], g))
        dF = dxs = np.nan
        if c is not ref:
            Fi = np.interp(c["X"], ref["X"], ref["r"])
            dF = np.max(np.abs(c["r"] - Fi))
            xi = np.interp(c["r"][band], ref["r"], ref["xs"])
            dxs = np.nanmax(np.abs(c["xs"][band] - xi)) if band.any() else np.nan
        rows.append([name, r_start, d_cf.max() if d_cf.size else np.nan, dF, dxs])
        print(f"{name:>14}: slip leaves the corner at F/(mu N) = {r_start:.4f}; "
              f"max |x_s/L - closed form| = {rows[-1][2]:.4f} (F/(mu N) in [{r0 + 0.02:.3f}, 0.99]); "
              f"vs {runs[0][0]}: max |dF/(mu N)| at same X = {dF:.2e}, max |d x_s/L| at same F = {dxs:.4f}")
    with open(os.path.join(a.out, "theory_check.csv"), "w") as f:
        f.write("run,slip_start_F_over_mu_N,max_dxs_over_L_vs_closed_form,max_dF_over_mu_N_vs_first,"
                "max_dxs_over_L_vs_first\n")
        for r in rows:
            f.write(",".join([r[0]] + [f"{v:.6g}" for v in r[1:]]) + "\n")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.2))
    for name, c in runs:
        a1.plot(c["X"] * 1e6, c["r"], label=name)
        a2.plot(c["r"], c["xs"], ".-", ms=3, label=name)
    rr = np.linspace(r0, 1, 200)
    a2.plot(rr, closed_form_xs(rr, g), "k--", label="thin-layer closed form")
    a1.set_xlabel("X (um)"); a1.set_ylabel("F/(mu N)"); a1.grid(alpha=.3); a1.legend()
    a2.set_xlabel("F/(mu N)"); a2.set_ylabel("slip front x_s/L"); a2.set_xlim(r0 - 0.05, 1.005)
    a2.grid(alpha=.3); a2.legend()
    fig.suptitle(f"coulomb mu={mu}, L={L} m, t={meta['t_m']} m, H={H} m, {meta['nx']}x{meta['ny']} CPE4")
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "theory_check.png"), dpi=90)
    print(f"wrote {a.out}/theory_check.csv and theory_check.png")


if __name__ == "__main__":
    main()
