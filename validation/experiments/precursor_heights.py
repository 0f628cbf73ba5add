"""Study 2: precursor length against F/N as the push height h (side push) or the drive
height H (top plate) varies (validation/experiments/README.md). Run through
precursor_heights.sh; writes precursor_heights.csv (one row per case),
precursor_heights_events.csv (every instability before the whole slip) and
precursor_heights.svg beside this file."""
import csv
import math
import os
import shutil
import tempfile
import time

import common

HERE = os.path.dirname(os.path.abspath(__file__))
L = common.L
MU_S, MU_D = 0.4, 0.17
BLOCKS = [0.05, 0.2]  # t/L: a thin block (edge precursors) and t = L/5
H_MESH = L / 100
SIDE = [0.1, 0.3, 0.5, 0.7, 0.9]  # h/t
# H/L for the top plate: the side push's arms (0.1 ... 0.9 t), then a plate above the block
TOP = {0.05: [0.005, 0.025, 0.045, 0.1, 0.2], 0.2: [0.02, 0.06, 0.1, 0.14, 0.18, 0.5, 1.0]}
F_STAR = 0.4  # F/(mu_s N) at which the precursor length is read
KINDS = ("precursor", "nucleation", "tip-advance")

scratch = tempfile.mkdtemp(prefix="tribofe_prec_")
cases, events = [], []


def case(a, rig, d, h, study):
    """a = t/L, d = height/t."""
    t, t0 = a * L, time.time()
    res = common.run(os.path.join(scratch, "run"), t, rig, d * t, MU_S, MU_D, h, push_width=0.15 * t)
    ev = [e for e in res["events"] if e["kind"] in KINDS]
    pts = [(float(e["F_over_mu_s_N"]), float(e["slipped_length_over_L"]), e) for e in ev]
    # regions starting within t of the trailing (pushed) edge, which may itself be open: the
    # precursors of the experiments
    edge = [(f, l) for f, l, e in pts if float(e["region_first_over_L"]) <= -0.5 + a]
    for f, l, e in pts:
        events.append({"set": study, "rig": rig, "t_over_L": a, "height_over_L": d * a, "h_over_L": h / L,
                       "event": e["event"], "kind": e["kind"], "F_over_N": f * MU_S,
                       "F_over_mu_s_N": f, "slipped_length_over_L": l,
                       "x_nucleation_over_L": float(e["x_nucleation_over_L"]),
                       "region_first_over_L": float(e["region_first_over_L"])})
    half = [f for f, l, _ in pts if l >= 0.5]
    half_edge = [f for f, l in edge if l >= 0.5]
    upto = [l for f, l, _ in pts if f <= F_STAR]
    first_x = float(ev[0]["x_nucleation_over_L"]) if ev else math.nan
    cases.append({
        "set": study,
        "rig": rig,
        "t_over_L": a,
        "height_over_t": d,
        "height_over_L": d * a,
        "g_6_mu_d_height_over_L": 6 * MU_D * d * a,
        "h_over_L": h / L,
        "first_nucleation_x_over_L": first_x,
        "F_over_N_at_half_L": min(half) * MU_S if half else math.nan,
        "F_over_N_at_half_L_from_trailing_edge": min(half_edge) * MU_S if half_edge else math.nan,
        "length_over_L_at_F_0.4_mu_s_N": max(upto, default=0.0),
        "trailing_edge_length_over_L_at_F_0.4_mu_s_N": max((l for f, l in edge if f <= F_STAR), default=0.0),
        "F_max_over_N": res["F_max_over_N"],
        "ended_by": res["ended"],
        "instabilities": len(ev),
    })
    print(f"{time.time() - t0:6.1f} s {study:7s} t/L={a:<5} {rig:10s} d/t={d:<4.3g} h/L={h / L:<6} F(L/2)/N={cases[-1]['F_over_N_at_half_L']:.4f} "
          f"l(F*)/L={cases[-1]['length_over_L_at_F_0.4_mu_s_N']:.3f} F_max/N={res['F_max_over_N']:.4f}", flush=True)


try:
    for a in BLOCKS:
        for d in SIDE:
            case(a, "side-push", d, H_MESH, "grid")
        for hl in TOP[a]:
            case(a, "top-plate", hl / a, H_MESH, "grid")
    for a in BLOCKS:
        for rig in ("side-push", "top-plate"):
            case(a, rig, 0.5, H_MESH / 2, "refine")
finally:
    shutil.rmtree(scratch)


def write(name, rows):
    with open(os.path.join(HERE, name), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})


write("precursor_heights.csv", cases)
write("precursor_heights_events.csv", events)

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

plt.rcParams.update({"font.size": 9, "svg.hashsalt": "tribofe", "svg.fonttype": "none"})
fig, axes = plt.subplots(2, 2, figsize=(7.0, 5.6), sharey=True, constrained_layout=True)
cmap = plt.get_cmap("viridis")
for row, a in enumerate(BLOCKS):
    for ax, rig, hs, sym, title in [(axes[row, 0], "side-push", [d * a for d in SIDE], "h", "side push"),
                                    (axes[row, 1], "top-plate", TOP[a], "H", "top plate")]:
        for k, hl in enumerate(hs):
            pts = sorted((e["F_over_N"], e["slipped_length_over_L"]) for e in events
                         if e["set"] == "grid" and e["rig"] == rig and e["t_over_L"] == a
                         and abs(e["height_over_L"] - hl) < 1e-12)
            # running maximum: the longest slipped region reached at or below each force
            env, m = [], 0.0
            for f, l in pts:
                m = max(m, l)
                env.append((f, m))
            c = cmap(k / (len(hs) - 1))
            if env:
                ax.step(*zip(*env), where="post", color=c, lw=1.0, label=f"{sym} = {hl:g} L")
                ax.plot(*zip(*pts), ".", ms=2, color=c)
        ax.axvline(MU_D, color="k", lw=0.6, ls=":")
        ax.axhline(0.5, color="0.6", lw=0.6)
        ax.set_xlabel("F/N")
        ax.set_title(f"({'abcd'[2 * row + (rig == 'top-plate')]}) {title}, t = {a:g} L", fontsize=9)
        ax.legend(fontsize=6.5, frameon=False, loc="upper left")
    axes[row, 0].set_ylabel("slipped length / L")
fig.savefig(os.path.join(HERE, "precursor_heights.svg"), metadata={"Date": None})
print("wrote precursor_heights.csv, precursor_heights_events.csv, precursor_heights.svg")
