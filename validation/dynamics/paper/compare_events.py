#!/usr/bin/env python3
"""Compare two `slide --dynamics` outputs event by event (drive phase, X > 0).

Usage: compare_events.py A B [--mu-s-n SCALE]
Prints the number of drive events of each, the first index where kind or nucleation node
differ, the largest |dX|/X_scale and |dF|/(mu_s N) over the common prefix, and the dynamic
events (dyn_events.csv) side by side.
"""
import csv, sys

def load(d):
    with open(f"{d}/events.csv") as f:
        ev = [r for r in csv.DictReader(f)]
    with open(f"{d}/dyn_events.csv") as f:
        dy = [r for r in csv.DictReader(f)]
    drive = [r for r in ev if float(r["X_m"]) > 0.0]
    return drive, dy

a, b = sys.argv[1], sys.argv[2]
(ea, da), (eb, db) = load(a), load(b)
print(f"drive events: {len(ea)} vs {len(eb)}; dynamic: {len(da)} vs {len(db)}")
xs = max(float(r["X_m"]) for r in ea + eb)
first = None
dx = df = 0.0
for k, (p, q) in enumerate(zip(ea, eb)):
    same = p["kind"] == q["kind"] and p["x_nucleation_over_L"] == q["x_nucleation_over_L"]
    if not same and first is None:
        first = k
    if first is None:
        dx = max(dx, abs(float(p["X_m"]) - float(q["X_m"])) / xs)
        df = max(df, abs(float(p["F_over_mu_s_N"]) - float(q["F_over_mu_s_N"])))
print(f"first differing drive event (kind or node): {first}; before it max |dX|/X_end = {dx:.2e}, max |dF|/(mu_s N) = {df:.2e}")
if first is not None:
    for r in (ea[first - 1:first + 2] if first else ea[:2]):
        print("  A", r["event"], r["kind"], r["X_m"], r["F_over_mu_s_N"], r["x_nucleation_over_L"])
    for r in (eb[first - 1:first + 2] if first else eb[:2]):
        print("  B", r["event"], r["kind"], r["X_m"], r["F_over_mu_s_N"], r["x_nucleation_over_L"])
print("dynamic events (A | B): kind X F_onset F_after region")
for k in range(max(len(da), len(db))):
    f = lambda r: (f"{r['kind']:>10} {float(r['X_m']):.6e} {float(r['F_onset_over_mu_s_N']):.6f} "
                   f"{float(r['F_after_over_mu_s_N']):.6f} {float(r['region_first_over_L']):+.4f}..{float(r['region_last_over_L']):+.4f}") if r else " " * 60
    print(f"{k:3d} {f(da[k] if k < len(da) else None)} | {f(db[k] if k < len(db) else None)}")
