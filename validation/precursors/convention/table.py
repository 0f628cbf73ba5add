"""Tables and figure of the `paper` rule's conventions (run by run.sh).

Reads runs/<name>.txt (slide's printed comparison with the paper's iteration) and
runs/<name>.events.csv; writes table.csv (one row per run), shares.csv (per scene: the model's
F_max minus the default run's last peak, and the share of that deficit each convention
removes) and convention.svg. F in units of mu_s N, x in units of L (dimensionless).
Usage: python3 table.py DIR
"""

import csv
import glob
import os
import re
import sys

D = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(__file__)
NAME = re.compile(r"r([0-9.]+)_g([0-9.]+)_t([0-9.]+)_(relaxed|pre-event)_(allowed|forbidden)$")
MODEL = re.compile(r"paper's iteration .*: n = (\d+), F_1 = ([-0-9.]+), x_1 = ([-0-9.]+), F_max = ([-0-9.]+)")
FE = re.compile(r"^FE: n = (\d+) .*F_1 = ([-0-9.]+|-), x_1 = ([-0-9.]+|-); last peak F = ([-0-9.]+|-)")
COMBOS = [("relaxed", "allowed"), ("pre-event", "allowed"), ("relaxed", "forbidden"), ("pre-event", "forbidden")]


def num(s):
    return None if s == "-" else float(s)


rows = []
for txt in sorted(glob.glob(os.path.join(D, "runs", "*.txt"))):
    m = NAME.match(os.path.basename(txt)[:-4])
    if not m:
        continue
    r, g, t, res, back = m.groups()
    text = open(txt).read()
    mm = MODEL.search(text)
    assert abs(float(mm.group(4)) - 1.0 / (1.0 + float(g) / float(r) * (1.0 - float(r)))) <= 5e-5, txt
    fe = next(FE.match(line) for line in text.splitlines() if FE.match(line))
    wall = float(re.search(r"wall_s = ([0-9.]+)", text).group(1))
    with open(txt[:-4] + ".events.csv") as f:
        ev = list(csv.DictReader(f))
    peaks = [float(e["F_over_mu_s_N"]) for e in ev if e["kind"] in ("sliding", "crossing")]
    rows.append(
        {
            "r": float(r),
            "g": float(g),
            "t_m": float(t),
            "residual": res,
            "backslip": back,
            "n_model": int(mm.group(1)),
            "n_fe": int(fe.group(1)),
            "F1_model": float(mm.group(2)),
            "F1_fe": num(fe.group(2)),
            "x1_model": float(mm.group(3)),
            "x1_fe": num(fe.group(3)),
            # The closed form F_max = 1/(1 + (g/r)(1 - r)) to full precision (slide prints 4 digits).
            "Fmax_model": 1.0 / (1.0 + float(g) / float(r) * (1.0 - float(r))),
            "peak_first_fe": peaks[0] if peaks else None,
            "peak_last_fe": peaks[-1] if peaks else None,
            "backslip_nodes": sum(int(e["backslip_nodes"]) for e in ev),
            "events": len(ev),
            "wall_s": wall,
        }
    )

rows.sort(key=lambda x: (-x["r"], x["g"], x["t_m"], COMBOS.index((x["residual"], x["backslip"]))))
with open(os.path.join(D, "table.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
    w.writeheader()
    for x in rows:
        w.writerow({k: ("" if v is None else (f"{v:.6f}" if isinstance(v, float) else v)) for k, v in x.items()})

scenes = sorted({(x["r"], x["g"], x["t_m"]) for x in rows}, key=lambda s: (-s[0], s[1], s[2]))
by = {(x["r"], x["g"], x["t_m"], x["residual"], x["backslip"]): x for x in rows}
shares = []
for s in scenes:
    base = by[s + COMBOS[0]]
    deficit = base["Fmax_model"] - base["peak_last_fe"]
    # The model's own peak with the relaxed convention: the residual at the trailing edge
    # mu_d p(-1/2, F*) = r - g r after a whole slip instead of r - g F_i, so the periodic peak
    # solves (r - g r) + F - r = 1 - (g/r) F.
    r_, g_ = s[0], s[1]
    fmax_relaxed = (1.0 + g_ * r_) / (1.0 + g_ / r_)
    out = {"r": s[0], "g": s[1], "t_m": s[2], "Fmax_model": base["Fmax_model"], "Fmax_model_relaxed": fmax_relaxed,
           "peak_default": base["peak_last_fe"], "deficit": deficit}
    for key, combo in (("residual", COMBOS[1]), ("backslip", COMBOS[2]), ("both", COMBOS[3])):
        p = by[s + combo]["peak_last_fe"]
        out["share_" + key] = (p - base["peak_last_fe"]) / deficit
    out["share_rest"] = 1.0 - out["share_both"]
    out["share_model_convention"] = (base["Fmax_model"] - fmax_relaxed) / deficit
    shares.append(out)
with open(os.path.join(D, "shares.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(shares[0].keys()))
    w.writeheader()
    for x in shares:
        w.writerow({k: f"{v:.6f}" if isinstance(v, float) else v for k, v in x.items()})

print(f"{'r':>5} {'g':>5} {'t mm':>5} {'deficit':>8} {'residual':>9} {'backslip':>9} {'both':>6} {'1D model':>9}   n: model, rel/all, pre/all, rel/forb, pre/forb")
for x in shares:
    s = (x["r"], x["g"], x["t_m"])
    ns = ", ".join(str(by[s + c]["n_fe"]) for c in COMBOS)
    print(
        f"{x['r']:5.2f} {x['g']:5.2f} {1e3 * x['t_m']:5.1f} {x['deficit']:8.4f} {100 * x['share_residual']:8.1f}% "
        f"{100 * x['share_backslip']:8.1f}% {100 * x['share_both']:5.1f}% {100 * x['share_model_convention']:8.1f}%   {by[s + COMBOS[0]]['n_model']}, {ns}"
    )

import matplotlib  # noqa: E402

matplotlib.use("Agg")
matplotlib.rcParams["svg.hashsalt"] = "tribofe"
matplotlib.rcParams["svg.fonttype"] = "none"
import matplotlib.pyplot as plt  # noqa: E402

fig, axes = plt.subplots(1, 3, figsize=(15, 4.8))
labels = [f"({s[0]}, {s[1]}) t={1e3 * s[2]:g} mm" for s in scenes]
xs = range(len(scenes))
marks = {COMBOS[0]: ("o", "C0"), COMBOS[1]: ("s", "C3"), COMBOS[2]: ("x", "C2"), COMBOS[3]: ("+", "C1")}
for c in COMBOS:
    mk, col = marks[c]
    lab = f"residual {c[0]}, back-slip {c[1]}"
    axes[0].plot(xs, [by[s + c]["Fmax_model"] - by[s + c]["peak_last_fe"] for s in scenes], mk, color=col, label=lab)
    axes[1].plot(xs, [by[s + c]["n_fe"] / by[s + c]["n_model"] for s in scenes], mk, color=col, label=lab)
    axes[2].plot(xs, [(by[s + c]["x1_fe"] or 0) - by[s + c]["x1_model"] for s in scenes], mk, color=col, label=lab)
sh = {(x["r"], x["g"], x["t_m"]): x for x in shares}
axes[0].plot(xs, [sh[s]["deficit"] - (sh[s]["Fmax_model"] - sh[s]["Fmax_model_relaxed"]) for s in scenes], "_", color="k",
             ms=14, label="default minus the 1D model's own pre-event gain")
axes[0].set_ylabel("model F_max - FE last peak (units of mu_s N)")
axes[1].set_ylabel("FE n (advancing) / model n")
axes[2].set_ylabel("FE x_1 - model x_1 (units of L)")
for ax in axes:
    ax.set_xticks(list(xs))
    ax.set_xticklabels(labels, fontsize=7, rotation=90)
    ax.axhline(0 if ax is not axes[1] else 1, color="k", lw=0.5)
axes[0].legend(fontsize=7)
fig.suptitle("The paper rule's conventions against the 1D model, (r, g) and t (h = t/2, L = 0.4 m, H = 0.04 m)")
fig.tight_layout()
fig.savefig(os.path.join(D, "convention.svg"), metadata={"Date": None})
print(f"wrote {D}/table.csv, shares.csv, convention.svg")
