#!/usr/bin/env python3
"""Accuracy against cost of the dynamic first cycle (README.md here).

Usage: cost.py TABLE_CSV OUT.png

One panel per quantity (the first front advance's force, the largest force before the
crossing, the front x/L at F = 0.80 mu_s N on the curve through the advances), each against
the run's CPU seconds on a log axis: one line per scene (r, g), one marker per mesh h at the
default damping, labelled with h in mm; an open marker is a run stopped before its crossing
(run.sh's X_MAX, past the peak), timed for its part of the cycle. Where a scene's line turns
flat, refining buys nothing more in that quantity. The shaded band about each scene's mean
peak is the round-off scatter the replicates measured (+-0.006 mu_s N, README.md "Round-off
replicates"). Reads table.csv as table.py writes it. Needs matplotlib.
"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PANELS = [
    ("f1_front", "first front advance, F/(mu_s N)"),
    ("f_peak", "largest F/(mu_s N) before the crossing"),
    ("tip_curve_over_L_at_F_0.8", "front x/L at F = 0.80 mu_s N (advances' curve)"),
]
ROUND_OFF_PEAK = 0.006


def main():
    table, out = sys.argv[1], sys.argv[2]
    with open(table) as f:
        runs = [r for r in csv.DictReader(f) if r["run"] == "dynamics" and r["eta"] == r["ws"] == "default"]
    scenes = sorted({(r["r"], r["g"]) for r in runs}, reverse=True)
    fig, axes = plt.subplots(1, len(PANELS), figsize=(13, 4.2))
    for ax, (key, label) in zip(axes, PANELS):
        for i, (r, g) in enumerate(scenes):
            pts = sorted((float(x["cpu_s"]), float(x[key]), x["h_mm"], math.isnan(float(x["f_cross"]))) for x in runs
                         if (x["r"], x["g"]) == (r, g) and not math.isnan(float(x[key])))
            if not pts:
                continue
            c = f"C{i}"
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "-", color=c, label=f"(r, g) = ({r}, {g})")
            for cpu, v, h, stopped in pts:
                ax.plot(cpu, v, "o", color=c, mfc="white" if stopped else c)
                ax.annotate(f"{h}", (cpu, v), textcoords="offset points", xytext=(4, 4), fontsize=7, color=c)
            if key == "f_peak":
                v = sum(p[1] for p in pts) / len(pts)
                ax.axhspan(v - ROUND_OFF_PEAK, v + ROUND_OFF_PEAK, color=c, alpha=0.12, lw=0)
        ax.set_xscale("log")
        ax.set_xlabel("CPU time of the first cycle (s)")
        ax.set_title(label, fontsize=10)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8, loc="best")
    fig.suptitle("Dynamic first cycle: each quantity against its cost as h halves (labels: h in mm)", fontsize=11)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main()
