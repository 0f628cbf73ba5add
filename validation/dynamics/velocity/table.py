"""Tables of validation/dynamics/velocity/README.md from the folders run.sh writes."""
import bisect
import csv
import sys
import tomllib
from pathlib import Path

D = Path(sys.argv[1])


def rows(p):
    with open(p) as f:
        return list(csv.DictReader(f))


def instabilities(folder):
    return [r for r in rows(folder / "dyn_events.csv") if r["instability"] == "1"]


print("Slip weakening, L = 0.1 m, h = 0.5 mm, (r, g) = (0.9, 0.35), D_c = 2.31e-7 m, to X = 5.2e-6 m")
print()
print("| drive | instabilities | 1st X (m) | 1st F_onset / mu_s N | dF vs held D_c/320 | 2nd X | 2nd F_onset | 3rd X | 3rd F_onset |")
print("|---|---|---|---|---|---|---|---|---|")
ref = instabilities(D / "sw_held_320")
f_ref = float(ref[0]["F_onset_over_mu_s_N"])
HELD = ["20", "80", "320", "1280"]
VS = ["1.9e-7", "9.5e-8", "4.75e-8"]
first = {}
for name in [f"held_{n}" for n in HELD] + VS:
    ev = instabilities(D / f"sw_{name}")
    cells = []
    for k in range(3):
        if k < len(ev):
            cells += [f"{float(ev[k]['X_m']):.5e}", f"{float(ev[k]['F_onset_over_mu_s_N']):.6f}"]
        else:
            cells += ["-", "-"]
        if k == 0:
            cells.append(f"{float(ev[0]['F_onset_over_mu_s_N']) - f_ref:+.2e}" if ev else "-")
    first[name] = float(ev[0]["F_onset_over_mu_s_N"])
    label = f"held, coefficients every D_c/{name[5:]}" if name.startswith("held") else f"V = {name} m/s"
    print(f"| {label} | {len(ev)} | " + " | ".join(cells) + " |")
# The V -> 0 limit: each instability's onset against the held mode at D_c/320, per halving
# of V (a slow passage through a saddle-node is late by ~V^(2/3) in X: ratio 2^(2/3) = 1.59).
print()
print("| instability | held D_c/320 X (m) | X gap at V = " + ", ".join(VS) + " (m) | ratios per halving | F gap (mu_s N) at the same V |")
print("|---|---|---|---|---|")
for k in range(3):
    xh = float(ref[k]["X_m"])
    fh = float(ref[k]["F_onset_over_mu_s_N"])
    gx, gf = [], []
    for name in VS:
        e = instabilities(D / f"sw_{name}")[k]
        gx.append(float(e["X_m"]) - xh)
        gf.append(float(e["F_onset_over_mu_s_N"]) - fh)
    ratios = ", ".join(f"{gx[i] / gx[i + 1]:.2f}" for i in range(len(gx) - 1))
    print(f"| {k + 1} | {xh:.5e} | " + ", ".join(f"{g:+.2e}" for g in gx) + f" | {ratios} | " + ", ".join(f"{g:+.2e}" for g in gf) + " |")
held = [first[f"held_{n}"] for n in HELD[1:]]
print()
print(f"first onset: held D_c/80 .. D_c/1280 {min(held):.6f} .. {max(held):.6f}; drive at V = {VS[-1]} m/s {first[VS[-1]]:.6f} mu_s N")
print()
print("Coulomb mu = 0.5, L = 0.1 m, h = 1 mm, to X = 3.4e-5 m, against `slide --law coulomb`")
print()
print("| V (m/s) | max abs(F_V - F_qs) / mu N | Kelvin-Voigt lag eta V k_bonded / mu N | ratio to previous V | samples with slipping count off by > 1 | samples |")
print("|---|---|---|---|---|---|")
qs = [r for r in rows(D / "c_qs" / "loading.csv") if r["phase"] == "drive"]
X = [float(r["X_m"]) for r in qs]
F = [float(r["F_N_per_m"]) for r in qs]
S = [int(r["n_slip"]) for r in qs]
with open(D / "c_qs" / "run.toml", "rb") as f:
    t = tomllib.load(f)
k_b = next(v["k_bonded_N_per_m_per_m"] for v in [t, *t.values()] if isinstance(v, dict) and "k_bonded_N_per_m_per_m" in v)
prev = None
for v in ["2e-5", "1e-5", "5e-6", "2.5e-6", "1.25e-6"]:
    folder = D / f"c_{v}"
    with open(folder / "run.toml", "rb") as f:
        t = tomllib.load(f)
    eta = next(x["damping_eta_s"] for x in [t, *t.values()] if isinstance(x, dict) and "damping_eta_s" in x)
    err, bad, tot = 0.0, 0, 0
    for r in rows(folder / "loading.csv"):
        x = float(r["X_m"])
        if r["phase"] != "drive" or x <= X[0] or x >= X[-1]:
            continue
        k = bisect.bisect_right(X, x) - 1
        fq = F[k] + (F[k + 1] - F[k]) * (x - X[k]) / (X[k + 1] - X[k]) if X[k + 1] > X[k] else F[k]
        err = max(err, abs(float(r["F_N_per_m"]) - fq) / 0.5)
        tot += 1
        bad += abs(int(r["n_slip"]) - S[k]) > 1
    ratio = f"{prev / err:.2f}" if prev else "-"
    print(f"| {v} | {err:.3e} | {eta * float(v) * k_b / 0.5:.3e} | {ratio} | {bad} | {tot} |")
    prev = err
