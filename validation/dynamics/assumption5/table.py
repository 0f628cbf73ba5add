#!/usr/bin/env python3
"""Per-scene statistics of the assumption-5 columns of dyn_events.csv (run.sh here).

Usage: table.py OUT_ROOT HERE

For each OUT_ROOT/r*_g*_h*_dc* run: the instabilities' largest changes of p (over p_pre) and
tau (over the strength drop (mu_s - mu_d) p_pre) ahead of the running tip, from 2.5 t ahead
and anywhere ahead, and the dynamic arrest against the arrests predicted from the pre-event
field (zero fracture energy: tau = mu_d p; the thin-layer Griffith balance; the Griffith balance
on the whole body's energy release, src/studies/dynamic_slide/fracture.rs). Writes
HERE/instabilities_<scene>.csv (those columns per instability), HERE/table.csv and
HERE/table.md. Standard library only.
"""
import csv
import glob
import os
import statistics
import sys

KEEP = ["event", "kind", "X_m", "F_onset_over_mu_s_N", "x_nucleation_over_L", "arrest_over_L",
        "predicted_arrest_mu_d_over_L", "predicted_arrest_griffith_over_L", "predicted_arrest_fracture_over_L",
        "dp_ahead_2_5t_over_p_pre",
        "dtau_ahead_2_5t_over_strength_drop", "dp_ahead_over_p_pre", "dtau_ahead_over_strength_drop",
        "force_drop_at_arrest_over_event_drop"]


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def q90(v):
    v = sorted(v)
    return v[int(0.9 * (len(v) - 1))]


def scene(run):
    """(rows kept per instability, one summary row) of one run directory."""
    tag = os.path.basename(run)
    ev = {r["event"]: r for r in read(os.path.join(run, "events.csv"))}
    dy = [r for r in read(os.path.join(run, "dyn_events.csv")) if r["instability"] == "1"]
    if dy and "predicted_arrest_fracture_over_L" not in dy[0]:
        sys.exit(f"{run}/dyn_events.csv has no assumption-5 columns: rerun with a current tribofe")
    rows = []
    for r in dy:
        if not r["arrest_over_L"]:
            continue
        k = dict((c, r[c]) for c in KEEP if c in r)
        k["x_nucleation_over_L"] = ev[r["event"]]["x_nucleation_over_L"]
        rows.append(k)
    f = lambda c: [float(r[c]) for r in rows]
    err = lambda c: [abs(float(r["arrest_over_L"]) - float(r[c])) for r in rows]
    eg, e0 = err("predicted_arrest_griffith_over_L"), err("predicted_arrest_mu_d_over_L")
    ef = err("predicted_arrest_fracture_over_L")
    signed = [float(r["arrest_over_L"]) - float(r["predicted_arrest_griffith_over_L"]) for r in rows]
    drop = f("force_drop_at_arrest_over_event_drop")
    r_, g_ = tag.split("_")[0][1:], tag.split("_")[1][1:]
    first = rows[0]
    out = dict(
        scene=tag, r=r_, g=g_, instabilities=len(rows),
        dp_2_5t_median=statistics.median(f("dp_ahead_2_5t_over_p_pre")),
        dp_2_5t_90=q90(f("dp_ahead_2_5t_over_p_pre")), dp_2_5t_max=max(f("dp_ahead_2_5t_over_p_pre")),
        dtau_2_5t_median=statistics.median(f("dtau_ahead_2_5t_over_strength_drop")),
        dtau_2_5t_90=q90(f("dtau_ahead_2_5t_over_strength_drop")),
        dtau_2_5t_max=max(f("dtau_ahead_2_5t_over_strength_drop")),
        dp_ahead_median=statistics.median(f("dp_ahead_over_p_pre")),
        dp_ahead_max=max(f("dp_ahead_over_p_pre")),
        dtau_ahead_median=statistics.median(f("dtau_ahead_over_strength_drop")),
        dtau_ahead_max=max(f("dtau_ahead_over_strength_drop")),
        griffith_err_median_over_L=statistics.median(eg), griffith_err_90_over_L=q90(eg),
        griffith_err_max_over_L=max(eg), griffith_signed_median_over_L=statistics.median(signed),
        fracture_err_median_over_L=statistics.median(ef), fracture_err_90_over_L=q90(ef),
        fracture_err_max_over_L=max(ef),
        mu_d_err_median_over_L=statistics.median(e0), mu_d_err_90_over_L=q90(e0), mu_d_err_max_over_L=max(e0),
        first_arrest_over_L=float(first["arrest_over_L"]),
        first_griffith_over_L=float(first["predicted_arrest_griffith_over_L"]),
        first_fracture_over_L=float(first["predicted_arrest_fracture_over_L"]),
        first_mu_d_over_L=float(first["predicted_arrest_mu_d_over_L"]),
        force_drop_at_arrest_median=statistics.median(drop), force_drop_at_arrest_min=min(drop),
        force_drop_at_arrest_max=max(drop), force_drop_at_arrest_above_1=sum(d > 1 for d in drop),
    )
    return rows, out


def main():
    root, here = sys.argv[1], sys.argv[2]
    runs = sorted(d for d in glob.glob(os.path.join(root, "r*_g*_h*_dc*")) if os.path.isdir(d))
    if not runs:
        sys.exit(f"no runs under {root}")
    table = []
    for run in runs:
        rows, out = scene(run)
        with open(os.path.join(here, f"instabilities_{out['scene']}.csv"), "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=KEEP)
            w.writeheader()
            w.writerows(rows)
        table.append(out)
    with open(os.path.join(here, "table.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(table[0]))
        w.writeheader()
        for t in table:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in t.items()})
    pct = lambda v: f"{100 * v:.3g} %"
    lines = [
        "# Assumption 5 per scene (`sh validation/dynamics/assumption5/run.sh`)",
        "",
        "h = 0.5 mm (0.00125 L), kappa = 0.51, first cycle to the front crossing; instabilities with a",
        "measured front. Changes ahead of the running tip over the samples from nucleation to arrest:",
        "dp over p_pre, dtau over the strength drop (mu_s - mu_d) p_pre. Arrests in units of L.",
        "",
        "| (r, g) | instabilities | dp 2.5 t ahead: median / 90 % / max | dtau 2.5 t ahead: median / 90 % / max "
        "| dp anywhere ahead: median / max | dtau anywhere ahead: median / max "
        "| \\|arrest - Griffith\\|: median / 90 % / max | \\|arrest - fracture (whole body)\\|: median / 90 % / max "
        "| \\|arrest - (tau = mu_d p)\\|: median / 90 % / max "
        "| first instability: arrest, Griffith, fracture, mu_d | force drop at arrest / event drop: median (min-max), > 1 |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for t in table:
        lines.append(
            f"| ({t['r']}, {t['g']}) | {t['instabilities']} | {pct(t['dp_2_5t_median'])} / {pct(t['dp_2_5t_90'])} / {pct(t['dp_2_5t_max'])} "
            f"| {t['dtau_2_5t_median']:.3g} / {t['dtau_2_5t_90']:.3g} / {t['dtau_2_5t_max']:.3g} "
            f"| {pct(t['dp_ahead_median'])} / {pct(t['dp_ahead_max'])} "
            f"| {t['dtau_ahead_median']:.3g} / {t['dtau_ahead_max']:.3g} "
            f"| {t['griffith_err_median_over_L']:.4f} / {t['griffith_err_90_over_L']:.4f} / {t['griffith_err_max_over_L']:.4f} "
            f"| {t['fracture_err_median_over_L']:.4f} / {t['fracture_err_90_over_L']:.4f} / {t['fracture_err_max_over_L']:.4f} "
            f"| {t['mu_d_err_median_over_L']:.4f} / {t['mu_d_err_90_over_L']:.4f} / {t['mu_d_err_max_over_L']:.4f} "
            f"| {t['first_arrest_over_L']:+.4f}, {t['first_griffith_over_L']:+.4f}, {t['first_fracture_over_L']:+.4f}, {t['first_mu_d_over_L']:+.4f} "
            f"| {t['force_drop_at_arrest_median']:.3f} ({t['force_drop_at_arrest_min']:.3f}-{t['force_drop_at_arrest_max']:.3f}), "
            f"{t['force_drop_at_arrest_above_1']} |")
    with open(os.path.join(here, "table.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
