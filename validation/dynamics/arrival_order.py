#!/usr/bin/env python3
"""Convergence of rupture arrival times over three meshes (docs/dynamics-findings.md, the regularised flat).

Usage: arrival_order.py COARSE MEDIUM FINE [--x-min M ...]

Each argument is a `tribofe rupture --out` folder (h halving from one to the next). At the
coarse mesh's base nodes with x >= x_min (default 0 and 0.015 m) where all three runs
arrived, prints the largest difference of consecutive meshes' arrival times, e1 (coarse -
medium) and e2 (medium - fine), and the observed order log2(e1 / e2).
"""
import math
import os
import sys

from compare import ARRIVAL_COLS, BadInput, read_csv


def arrivals(folder):
    """x (rounded to 0.1 um, so the meshes' common nodes match) -> arrival time, s."""
    rows = read_csv(os.path.join(folder, "arrival.csv"), ARRIVAL_COLS)
    return {round(x * 1e7): t for x, t in rows if math.isfinite(t)}


def main():
    args = sys.argv[1:]
    x_mins = [0.0, 0.015]
    if "--x-min" in args:
        i = args.index("--x-min")
        x_mins = [float(v) for v in args[i + 1:]]
        args = args[:i]
    if len(args) != 3:
        sys.exit("usage: arrival_order.py COARSE MEDIUM FINE [--x-min M ...]")
    try:
        a, b, c = (arrivals(d) for d in args)
    except BadInput as e:
        sys.exit(f"arrival_order.py: {e}")
    for x_min in x_mins:
        keys = [k for k in a if k >= round(x_min * 1e7) and k in b and k in c]
        e1 = max((abs(a[k] - b[k]) for k in keys), default=0.0)
        e2 = max((abs(b[k] - c[k]) for k in keys), default=0.0)
        order = math.log2(e1 / e2) if e1 > 0 and e2 > 0 else float("nan")
        print(f"x >= {x_min} m: {len(keys)} nodes, e1 = {e1:.3e} s, e2 = {e2:.3e} s, order {order:.2f}")


if __name__ == "__main__":
    main()
