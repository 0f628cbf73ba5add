#!/usr/bin/env python3
"""Fig. 4-style comparison of the first cycle: dynamics, the paper's model, the quasi-static rules.

Usage: fig4.py OUT.svg MODEL_DIR [--fc-max F] LABEL=RUN_DIR [LABEL=RUN_DIR ...]

--fc-max: show the drive up to F^c/(mu_s N) = F only (e.g. the first cycle); the runs are
drawn in reverse order, so the first named is on top.

Left: F/(mu_s N) against F^c/(mu_s N) = k_bonded X/(mu_s N) (loading.csv of each run; the
model's loading.csv). Right: each instability's slipped region (x/L, horizontal bar) at its
onset force (events.csv rows that are not quasi-static slips; the first named run only), the
model's precursor fronts
as steps, and each run's front advances (advances.csv, where written) as dots joined by a
step line. mu_s of each run is read from its run.toml. Needs matplotlib.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STATIC = {"slip", "stick", "open", "close", "normal-load", "edge-preslip", "end", "creep", "sample"}


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def mu_s(run_dir):
    """mu_s from the [results] table of the run's run.toml."""
    with open(f"{run_dir}/run.toml") as f:
        for line in f:
            if line.startswith("mu_s = "):
                return float(line.split("=")[1])
    raise SystemExit(f"{run_dir}/run.toml: no mu_s")


def main():
    out, model = sys.argv[1], sys.argv[2]
    rest = sys.argv[3:]
    fc_max = float("inf")
    if "--fc-max" in rest:
        i = rest.index("--fc-max")
        fc_max = float(rest[i + 1])
        del rest[i : i + 2]
    runs = [a.rsplit("=", 1) for a in rest]
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 5))
    ml = rows(f"{model}/loading.csv")
    ax.plot([float(r["Fc_over_mu_s_N"]) for r in ml], [float(r["F_over_mu_s_N"]) for r in ml], "k-", lw=1.5, label="model (paper)")
    me = rows(f"{model}/events.csv")
    for r in me:
        if r["stick_slip"] == "1":
            break
        bx.plot([-0.5, float(r["x_arrest_over_L"])], [float(r["F_over_mu_s_N"])] * 2, "k-", lw=2.5, alpha=0.5)
    bx.plot([], [], "k-", lw=2.5, alpha=0.5, label="model precursors")
    for j, ((lab, d), c) in reversed(list(enumerate(zip(runs, ["C0", "C1", "C2", "C3", "C4"])))):
        w = 1.6 if j == 0 else 0.6
        ms = mu_s(d)
        lo = rows(f"{d}/loading.csv")
        lo = [r for r in lo if r["phase"] == "drive" and float(r["Fc_N_per_m"]) / (ms * float(r["N_N_per_m"])) <= fc_max]
        fc = [float(r["Fc_N_per_m"]) / (ms * float(r["N_N_per_m"])) for r in lo]
        f = [float(r["F_over_N"]) / ms for r in lo]
        ax.plot(fc, f, "-", color=c, lw=0.7, label=lab)
        ev = rows(f"{d}/events.csv") if j == 0 else []  # one run's bars keep the panel legible
        first = True
        for r in ev:
            if r["kind"] in STATIC or float(r["X_m"]) <= 0.0 or float(r["Fc_over_mu_s_N"]) > fc_max:
                continue
            y = float(r["F_over_mu_s_N"])
            bx.plot([float(r["region_first_over_L"]), float(r["region_last_over_L"])], [y, y], "-", color=c,
                    lw=w, label=lab if first else None)
            first = False
        try:
            adv = rows(f"{d}/advances.csv")
        except FileNotFoundError:
            adv = []
        if adv:
            xs = [float(r["front_over_L"]) for r in adv]
            ys = [float(r["F_over_mu_s_N"]) for r in adv]
            bx.step(xs, ys, where="post", color=c, lw=1.0, ls=":")
            bx.plot(xs, ys, "o", color=c, ms=3.5, mfc="white", label=f"{lab}: front advances ({len(adv)})")
    ax.set_xlabel("F^c / (mu_s N) (bonded-interface force at the same drive X)")
    ax.set_ylabel("F / (mu_s N)")
    ax.legend(fontsize=8)
    bx.set_xlabel("slipped region x / L (one bar per instability, at its onset force)")
    bx.set_ylabel("F / (mu_s N) at onset")
    bx.set_xlim(-0.5, 0.5)
    f1 = float(me[0]["F"])  # the model's F_1 sets the scale of both panels
    ax.set_ylim(f1 - 0.2, 1.0)
    ax.set_xlim(f1 - 0.2, min(fc_max, ax.get_xlim()[1]))
    bx.set_ylim(f1 - 0.03, 1.0)
    bx.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out)


if __name__ == "__main__":
    main()
