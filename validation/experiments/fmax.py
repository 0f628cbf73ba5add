"""Study 4: the macroscopic static friction coefficient F_max/N against the rig, the
driving height and the block's aspect ratio (validation/experiments/README.md).
Run through fmax.sh; writes fmax.csv and fmax.svg beside this file."""
import csv
import math
import os
import shutil
import tempfile
import time

import common

HERE = os.path.dirname(os.path.abspath(__file__))
L = common.L
H_MESH = L / 100  # element length along x, m
ASPECTS = [0.05, 0.1, 0.2, 0.5, 1.0, 2.0]  # t/L
HEIGHTS = [0.1, 0.3, 0.5, 0.7, 0.9]  # driving height / t (H, or the push height h)
MU_S, MU_D = 0.4, 0.17  # Tromborg et al. 2011/2014's coefficients
MU_D_R09 = 0.36  # r = mu_d/mu_s = 0.9, the paper's default r, at height t/2
RIGS = ["top-plate", "side-push"]

scratch = tempfile.mkdtemp(prefix="tribofe_fmax_")
rows = []


def case(rig, a, d, mu_d, h, study):
    t, t0 = a * L, time.time()
    res = common.run(os.path.join(scratch, "run"), t, rig, d * t, MU_S, mu_d, h, push_width=0.15 * t)
    rows.append({
        "set": study,
        "rig": rig,
        "t_over_L": a,
        "height_over_t": d,
        "height_over_L": d * a,
        "mu_s": MU_S,
        "mu_d": mu_d,
        "h_over_L": h / L,
        "n_thick": res["n_thick"],
        "F_max_over_N": res["F_max_over_N"],
        "F_max_over_mu_s_N": res["F_max_over_N"] / MU_S,
        "ended_by": res["ended"],
        "g_paper": res["g_paper"],
        "F_max_paper_thin_layer_over_mu_s_N": res["F_max_paper_over_mu_s_N"],
        "instabilities_before_sliding": sum(e["kind"] in ("precursor", "nucleation", "tip-advance") for e in res["events"]),
        "max_violation_over_N_per_n": res["violation"],
    })
    print(f"{time.time() - t0:6.1f} s {study:9s} {rig:10s} t/L={a:<5} d/t={d:<4} mu_d={mu_d:<5} h/L={h / L:<6} F_max/N={res['F_max_over_N']:.4f}", flush=True)


try:
    for a in ASPECTS:
        for rig in RIGS:
            for d in HEIGHTS:
                case(rig, a, d, MU_D, H_MESH, "grid")
            case(rig, a, 0.5, MU_D_R09, H_MESH, "r0.9")
    for a in [0.05, 0.2, 1.0]:
        for rig in RIGS:
            case(rig, a, 0.5, MU_D, H_MESH / 2, "refine")
finally:
    shutil.rmtree(scratch)


def fmt(v):
    return f"{v:.6g}" if isinstance(v, float) else str(v)


with open(os.path.join(HERE, "fmax.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0]))
    w.writeheader()
    for r in rows:
        w.writerow({k: fmt(v) for k, v in r.items()})

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

plt.rcParams.update({"font.size": 9, "svg.hashsalt": "tribofe", "svg.fonttype": "none"})
fig, axes = plt.subplots(1, 2, figsize=(7.0, 3.6), sharey=True, constrained_layout=True)
cmap = plt.get_cmap("viridis")
for ax, rig, title in zip(axes, RIGS, ["(a) top plate, driven at H", "(b) side push at h"]):
    for k, d in enumerate(HEIGHTS):
        pts = sorted((r["t_over_L"], r["F_max_over_mu_s_N"]) for r in rows
                     if r["set"] == "grid" and r["rig"] == rig and r["height_over_t"] == d)
        ax.plot(*zip(*pts), "o-", ms=3, color=cmap(k / (len(HEIGHTS) - 1)),
                label=f"height {d} t (H or h)")
    # runs stopped at X_max before a whole slip: open markers (F_max is the peak so far)
    pts = [(r["t_over_L"], r["F_max_over_mu_s_N"]) for r in rows if r["rig"] == rig
           and r["set"] in ("grid", "r0.9") and r["ended_by"] == "X_max"]
    if pts:
        ax.plot(*zip(*pts), "o", ms=5, mfc="white", mec="k", mew=0.8, zorder=5)
    pts = [(r["t_over_L"], r["F_max_over_mu_s_N"]) for r in rows if r["set"] == "refine" and r["rig"] == rig]
    ax.plot(*zip(*pts), "x", ms=6, color="C3", zorder=6, label="height t/2, h = L/200")
    pts = sorted((r["t_over_L"], r["F_max_over_mu_s_N"]) for r in rows if r["set"] == "r0.9" and r["rig"] == rig)
    ax.plot(*zip(*pts), "s--", ms=3, color="0.4", label=r"$\mu_d/\mu_s$ = 0.9, height t/2")
    ax.axhline(1.0, color="k", lw=0.6)
    ax.axhline(MU_D / MU_S, color="k", lw=0.6, ls=":")
    ax.set_xscale("log")
    ax.set_xlabel("aspect ratio t/L")
    ax.set_title(title, fontsize=9)
axes[0].set_ylabel(r"$F_{max}/(\mu_s N)$")
axes[0].text(0.06, MU_D / MU_S + 0.02, r"$\mu_d/\mu_s$", fontsize=8)
axes[1].plot([], [], "o", ms=5, mfc="white", mec="k", mew=0.8, label="stopped at X_max, no whole slip")
fig.legend(*axes[1].get_legend_handles_labels(), loc="outside lower center", ncol=4, fontsize=7, frameon=False)
fig.savefig(os.path.join(HERE, "fmax.svg"), metadata={"Date": None})
print(f"wrote {os.path.join(HERE, 'fmax.csv')} and fmax.svg")
