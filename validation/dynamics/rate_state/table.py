"""Tables and the figure of validation/dynamics/rate_state/README.md from what run.sh writes.

Usage: python3 table.py DIR (DIR: this folder, holding out/<run>/ and out/<run>.log). Writes
DIR/table.csv, DIR/table.md and DIR/envelope.svg. Forces in units of mu_s N (the rate-and-state
runs have f_0 = mu_s, so their F / (f_0 N) is F / (mu_s N)), positions in units of L.
"""
import csv
import re
import sys
import tomllib
from pathlib import Path

D = Path(sys.argv[1])
OUT = D / "out"
HELD = D.resolve().parent / "refine" / "paper" / "refinement.csv"
ENV = ["0.75", "0.80", "0.85", "0.90"]
RUNS = [
    ("rw", "rate-state, rate weakening (a = b/10)"),
    ("rs_control", "rate-state, rate strengthening control (a = 1.9 b)"),
    ("sw", "slip weakening (D_c = 2.31e-7 m)"),
]


def rows(p):
    with open(p) as f:
        return list(csv.DictReader(f))


def num(s):
    return float(s) if s not in ("", None) else float("nan")


def fmt(v, spec=".4f"):
    return "-" if v != v else format(v, spec)


def wall(name):
    m = re.search(r"wall time ([0-9.]+) s", (OUT / f"{name}.log").read_text())
    return float(m.group(1)) if m else float("nan")


def run_info(name):
    with open(OUT / name / "run.toml", "rb") as f:
        return tomllib.load(f)["results"]


T_OVER_L = 0.002 / 0.4
GAP = 5 * T_OVER_L  # the definition's resolution (src/precursors/definition.rs: ZONE_T = ADVANCE_T = 5 t)
H_OVER_L = 0.0005 / 0.4


def advances(dyn):
    """The front advances from the trailing edge, as src/precursors/definition.rs::advances
    reads them, on the run's dynamic events (dyn_events.csv: every event whose slip rate passed
    the threshold, X > 0; the X = 0 slip of the explicit start at the leading edge left out).
    Needed because under rate-and-state every node creeps, so the summary's preslip run is the
    whole interface and its first advance is the start's slip at X = 0. Returns the advances
    [(F_onset, front x/L, X)] and the crossing event (the one after which the runs reached from
    the trailing edge, across stuck gaps of at most 5 t, reach the leading edge) or None."""
    runs, counted, out = [], -0.5, []
    for e in sorted(dyn, key=lambda e: (num(e["X_m"]), int(e["event"]))):
        if num(e["X_m"]) <= 0.0:
            continue
        runs.append((num(e["region_first_over_L"]), num(e["region_last_over_L"])))
        runs.sort()
        merged = []
        for a, b in runs:
            if merged and a <= merged[-1][1] + H_OVER_L * 1.01:
                merged[-1] = (merged[-1][0], max(merged[-1][1], b))
            else:
                merged.append((a, b))
        runs = merged
        reach, got = -0.5, False
        for a, b in runs:
            if a - reach > GAP:
                break
            if b >= reach:
                reach, got = b, True
        if not got:
            continue
        if reach >= 0.5 - 1e-9:
            return out, e
        if reach > counted + GAP:
            counted = reach
            out.append((num(e["F_onset_over_mu_s_N"]), reach, num(e["X_m"])))
    return out, None


def envelope(curve, f):
    for (f0, x0), (f1, x1) in zip(curve, curve[1:]):
        if f0 <= f <= f1 and f1 > f0:
            return x0 + (f - f0) / (f1 - f0) * (x1 - x0)
    return float("nan")


def after_crossing(load, x_end, mu_s):
    """F over the loading rows past the crossing (the rest of the run): mean, least, largest."""
    f = [num(l["F_over_N"]) / mu_s for l in load if num(l["X_m"]) > x_end]
    if not f:
        return {}
    return {"F_after_crossing_mean_over_mu_s_N": sum(f) / len(f), "F_after_crossing_min_over_mu_s_N": min(f),
            "F_after_crossing_max_over_mu_s_N": max(f)}


CALIB = {k: float(v) for k, v in (line.split(",") for line in (D / "calib.csv").read_text().split())}

table = []
for name, label in RUNS:
    s = rows(OUT / name / "summary.csv")[0]
    r = run_info(name)
    dyn = rows(OUT / name / "dyn_events.csv")
    inst = [e for e in dyn if num(e["X_m"]) > 0.0]
    adv, cross = advances(dyn)
    curve = [(f, x) for f, x, _ in adv]
    x_end = num(cross["X_m"]) if cross else float("inf")
    load = rows(OUT / name / "loading.csv")
    mu_s = float(r["mu_s"])
    # The largest force up to and including the crossing: the samples and the events' onsets.
    peak = max([num(l["F_over_N"]) / mu_s for l in load if num(l["X_m"]) <= x_end]
               + [num(e["F_onset_over_mu_s_N"]) for e in inst if num(e["X_m"]) <= x_end])
    k = float(r["k_bonded_N_per_m_per_m"]) / (float(r["mu_s"]) * float(r["n_force_N_per_m"]))
    first = inst[0] if inst else None
    # The drive's share carried elastically at the first instability: F / (k_bonded X) in
    # units of mu_s N (1: no slip anywhere before it; below 1: creep or stable slip took the rest).
    elastic = num(first["F_onset_over_mu_s_N"]) / (k * num(first["X_m"])) if first else float("nan")
    table.append({
        "run": name,
        "law": label,
        "drive_velocity_m_per_s": r["drive_velocity_m_per_s"],
        "instabilities": len(inst),
        "dynamic_events": len(dyn),
        "first_instability_X_m": num(first["X_m"]) if first else float("nan"),
        "first_instability_F_over_mu_s_N": num(first["F_onset_over_mu_s_N"]) if first else float("nan"),
        "first_instability_region_first_over_L": num(first["region_first_over_L"]) if first else float("nan"),
        "first_instability_region_last_over_L": num(first["region_last_over_L"]) if first else float("nan"),
        "elastic_share_at_first_instability": elastic,
        "F_1_over_mu_s_N": curve[0][0] if curve else float("nan"),
        "x_1_over_L": curve[0][1] if curve else float("nan"),
        **{f"envelope_over_L_at_F_{f}": envelope(curve, float(f)) for f in ENV},
        "largest_F_before_crossing_over_mu_s_N": peak,
        "crossing_F_over_mu_s_N": num(cross["F_onset_over_mu_s_N"]) if cross else float("nan"),
        "crossing_X_m": x_end if cross else float("nan"),
        "front_advances": float(len(adv)),
        "summary_F_1_over_mu_s_N": num(s["first_advance_F_over_mu_s_N"]),
        "summary_x_1_over_L": num(s["first_advance_front_over_L"]),
        "summary_largest_F_over_mu_s_N": num(s["largest_F_before_crossing_over_mu_s_N"]),
        "largest_F_whole_run_over_mu_s_N": max(num(l["F_over_N"]) / mu_s for l in load),
        "F_at_end_over_mu_s_N": num(load[-1]["F_over_N"]) / mu_s,
        "events_after_crossing": sum(1 for e in inst if num(e["X_m"]) > x_end),
        **after_crossing(load, x_end, mu_s),
        "largest_peak_slip_rate_m_per_s": max((num(e["peak_slip_rate_m_per_s"]) for e in inst), default=float("nan")),
        "complete": num(s["complete"]),
        "wall_s": wall(name),
    })

held = {r["quantity"]: num(r["value_at_h_5e-4_m"]) for r in rows(HELD)}
table.append({
    "run": "sw_held",
    "law": "slip weakening, held drive (validation/dynamics/refine/paper)",
    "drive_velocity_m_per_s": "held",
    "F_1_over_mu_s_N": held["first_advance_F_over_mu_s_N"],
    "x_1_over_L": held["first_advance_front_over_L"],
    **{f"envelope_over_L_at_F_{f}": held[f"envelope_front_over_L_at_F_{f}"] for f in ENV},
    "largest_F_before_crossing_over_mu_s_N": held["largest_F_before_crossing_over_mu_s_N"],
    "crossing_F_over_mu_s_N": held["crossing_F_over_mu_s_N"],
    "front_advances": held["front_advances"],
})

cols = list(table[0].keys())
with open(D / "table.csv", "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=cols, restval="")
    w.writeheader()
    for t in table:
        w.writerow({k: (f"{v:.10g}" if isinstance(v, float) else v) for k, v in t.items()})

md = []
md.append("| run | drive V (m/s) | dynamic events (X > 0) | F_1 | x_1 | front at F = 0.75 | 0.80 | 0.85 | 0.90 | largest F before crossing | crossing F | crossing X (m) | front advances | wall (s) |")
md.append("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
for t in table:
    g = lambda k, spec=".4f": fmt(t.get(k, float("nan")), spec)
    md.append(
        f"| {t['law']} | {t['drive_velocity_m_per_s']} | {t.get('instabilities', '-')} | {g('F_1_over_mu_s_N')} | {g('x_1_over_L')} | "
        + " | ".join(g(f"envelope_over_L_at_F_{f}") for f in ENV)
        + f" | {g('largest_F_before_crossing_over_mu_s_N')} | {g('crossing_F_over_mu_s_N')} | {g('crossing_X_m', '.4e')} | {g('front_advances', '.0f')} | {g('wall_s', '.0f')} |"
    )
md.append("")
md.append("| run | first instability X (m) | its F_onset | its region (x/L) | F / (k_bonded X) there | largest peak slip rate (m/s) | dynamic events |")
md.append("|---|---|---|---|---|---|---|")
for t in table[:3]:
    g = lambda k, spec=".4f": fmt(t.get(k, float("nan")), spec)
    md.append(
        f"| {t['run']} | {g('first_instability_X_m', '.4e')} | {g('first_instability_F_over_mu_s_N')} | "
        f"{g('first_instability_region_first_over_L')} .. {g('first_instability_region_last_over_L')} | "
        f"{g('elastic_share_at_first_instability')} | {g('largest_peak_slip_rate_m_per_s', '.3e')} | {t['dynamic_events']} |"
    )
md.append("")
md.append(
    f"Closed form mu_ss(V_load) / mu_s = {CALIB['mu_ss_V_load'] / CALIB['mu_s']:.5f} (calib.csv; both laws); "
    f"control's F at X = 1e-5 m: {table[1]['F_at_end_over_mu_s_N']:.5f} mu_s N. "
    f"Rate weakening past its crossing (X > {table[0]['crossing_X_m']:.4e} m): "
    f"{table[0]['events_after_crossing']} more events, F mean {table[0].get('F_after_crossing_mean_over_mu_s_N', float('nan')):.4f}, "
    f"range {table[0].get('F_after_crossing_min_over_mu_s_N', float('nan')):.4f} .. {table[0].get('F_after_crossing_max_over_mu_s_N', float('nan')):.4f} mu_s N."
)
(D / "table.md").write_text("\n".join(md) + "\n")
print("\n".join(md))

# envelope.svg: every event's onset force (up) against the far end of its slipped run (across),
# circles, and the front advances joined (the envelope), one colour per run.
W, H, M = 640, 420, 60
COL = {"rw": "#d62728", "rs_control": "#2ca02c", "sw": "#1f77b4"}


def px(x):
    return M + (x + 0.5) * (W - 2 * M)


def py(f):
    return H - M - (f - 0.6) / 0.4 * (H - 2 * M)


svg = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="12">',
       f'<rect x="{M}" y="{M}" width="{W - 2 * M}" height="{H - 2 * M}" fill="none" stroke="black"/>']
for i in range(5):
    x = -0.5 + 0.25 * i
    svg.append(f'<text x="{px(x):.1f}" y="{H - M + 16}" text-anchor="middle">{x:g}</text>')
for i in range(5):
    f = 0.6 + 0.1 * i
    svg.append(f'<text x="{M - 6}" y="{py(f) + 4:.1f}" text-anchor="end">{f:.1f}</text>')
svg.append(f'<text x="{W / 2}" y="{H - 16}" text-anchor="middle">far end of the slipped run (toward +x), x / L</text>')
svg.append(f'<text x="16" y="{H / 2}" transform="rotate(-90 16 {H / 2})" text-anchor="middle">F_onset / (mu_s N)</text>')
for j, (name, label) in enumerate(RUNS):
    dyn = rows(OUT / name / "dyn_events.csv")
    inst = [e for e in dyn if num(e["X_m"]) > 0.0]
    # Every event (open circle: far end of its slipped run) and the advances (the envelope: line).
    for e in inst:
        x, f = num(e["region_last_over_L"]), num(e["F_onset_over_mu_s_N"])
        if 0.6 <= f <= 1.0:
            svg.append(f'<circle cx="{px(x):.1f}" cy="{py(f):.1f}" r="2.5" fill="none" stroke="{COL[name]}" stroke-opacity="0.6"/>')
    adv, _ = advances(dyn)
    if adv:
        path = " ".join(f"{px(x):.1f},{py(f):.1f}" for f, x, _ in adv)
        svg.append(f'<polyline points="{path}" fill="none" stroke="{COL[name]}" stroke-width="2"/>')
    svg.append(f'<text x="{M + 10}" y="{M + 18 + 16 * j}" fill="{COL[name]}">{label}: {len(inst)} events, {len(adv)} advances (line)</text>')
svg.append("</svg>")
(D / "envelope.svg").write_text("\n".join(svg) + "\n")
