#!/usr/bin/env python3
"""Compare two runs of the rupture scene (e.g. xcheck_rupture.py's and tribofe's).

Each folder holds arrival.csv (x_m,t_arrival_s) and summary.csv (force_drop_n_per_m,
min_sigma_pa, steps, dt_s, front_speed_m_per_s). Prints max |dt_arrival| (s and in units of
dt), the relative force-drop difference, the front-speed difference and the min-sigma
difference; exits 1 when one is above its tolerance, 2 on unreadable or inconsistent input.

  python3 compare.py /tmp/xc /tmp/rust                 # 1 dt, 1e-6 relative, 1e-2 relative
  python3 compare.py A B --arrival-dt 1e-3 --force-drop-rel 1e-9
"""
from __future__ import annotations

import argparse
import csv
import math
import os
import sys

ARRIVAL_COLS = ["x_m", "t_arrival_s"]
SUMMARY_COLS = ["force_drop_n_per_m", "min_sigma_pa", "steps", "dt_s", "front_speed_m_per_s"]


class BadInput(Exception):
    pass


def read_csv(path, cols):
    try:
        with open(path, newline="") as fh:
            rows = list(csv.reader(fh))
    except OSError as e:
        raise BadInput(f"{path}: {e.strerror}") from e
    if not rows or [c.strip() for c in rows[0]] != cols:
        raise BadInput(f"{path}: header must be {','.join(cols)}")
    out = []
    for k, row in enumerate(rows[1:], start=2):
        if not row:
            continue
        if len(row) != len(cols):
            raise BadInput(f"{path}:{k}: {len(row)} fields, expected {len(cols)}")
        try:
            out.append([float(v) for v in row])
        except ValueError as e:
            raise BadInput(f"{path}:{k}: {e}") from e
    return out


def load(folder):
    arr = read_csv(os.path.join(folder, "arrival.csv"), ARRIVAL_COLS)
    summ = read_csv(os.path.join(folder, "summary.csv"), SUMMARY_COLS)
    if len(summ) != 1:
        raise BadInput(f"{os.path.join(folder, 'summary.csv')}: {len(summ)} data rows, expected 1")
    return arr, dict(zip(SUMMARY_COLS, summ[0]))


def rel(a, b):
    den = max(abs(a), abs(b))
    return 0.0 if den == 0 else abs(a - b) / den


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("a", help="first run folder (e.g. xcheck_rupture.py --out)")
    ap.add_argument("b", help="second run folder (e.g. tribofe's)")
    ap.add_argument("--arrival-dt", type=float, default=1.0,
                    help="tolerance on max |t_a - t_b| over common nodes, in dt (default 1)")
    ap.add_argument("--force-drop-rel", type=float, default=1e-6,
                    help="tolerance on the relative force-drop difference (default 1e-6)")
    ap.add_argument("--front-speed-rel", type=float, default=1e-2,
                    help="tolerance on the relative front-speed difference (default 1e-2: a "
                    "1 dt scatter of 51 arrivals over ~0.05 s moves the fitted slope by ~0.5 %%)")
    ap.add_argument("--x-match", type=float, default=1e-9,
                    help="two arrival rows are the same node when |x_a - x_b| <= this, m")
    a = ap.parse_args(argv)
    for name in ("arrival_dt", "force_drop_rel", "front_speed_rel", "x_match"):
        v = getattr(a, name)
        if not (math.isfinite(v) and v >= 0):
            ap.error(f"--{name.replace('_', '-')} {v}: must be a finite number >= 0")
    try:
        arr_a, sa = load(a.a)
        arr_b, sb = load(a.b)
    except BadInput as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    if int(sa["steps"]) != int(sb["steps"]) or rel(sa["dt_s"], sb["dt_s"]) > 1e-12:
        print(f"error: the runs differ in time stepping: steps {int(sa['steps'])} vs "
              f"{int(sb['steps'])}, dt {sa['dt_s']:.17g} vs {sb['dt_s']:.17g} s", file=sys.stderr)
        return 2
    dt = sa["dt_s"]
    t_end = sa["steps"] * dt
    tol_t = a.arrival_dt * dt
    failures = []

    # Match arrival rows by x. A node that arrived in one run only is a disagreement unless
    # its arrival is within the arrival tolerance of t_end (the other run may be just short).
    b_sorted = sorted(arr_b)
    used = [False] * len(b_sorted)
    max_dt, at_x, n_common, only = 0.0, math.nan, 0, []
    j0 = 0
    for x, t in sorted(arr_a):
        while j0 < len(b_sorted) and b_sorted[j0][0] < x - a.x_match:
            j0 += 1
        if j0 < len(b_sorted) and abs(b_sorted[j0][0] - x) <= a.x_match:
            used[j0] = True
            n_common += 1
            d = abs(t - b_sorted[j0][1])
            if d > max_dt or math.isnan(at_x):
                max_dt, at_x = d, x
        else:
            only.append(("a", x, t))
    only += [("b", x, t) for (x, t), u in zip(b_sorted, used) if not u]
    late_only = [o for o in only if t_end - o[2] <= tol_t]
    early_only = [o for o in only if t_end - o[2] > tol_t]
    print(f"arrivals: {len(arr_a)} in a, {len(arr_b)} in b, {n_common} common")
    print(f"  max |dt_arrival| = {max_dt:.6e} s = {max_dt / dt:.6e} dt (at x = {at_x:.6g} m); "
          f"tolerance {a.arrival_dt:g} dt")
    if max_dt > tol_t:
        failures.append("arrival times")
    if only:
        print(f"  in one run only: {len(only)} nodes ({len(late_only)} within the tolerance of "
              f"t_end): " + ", ".join(f"{w}:x={x:.6g},t={t:.6g}" for w, x, t in only[:8]))
    if early_only:
        failures.append("arrival sets")
    if n_common == 0:
        failures.append("no common arrivals")

    fd = rel(sa["force_drop_n_per_m"], sb["force_drop_n_per_m"])
    print(f"force drop: {sa['force_drop_n_per_m']:.12e} vs {sb['force_drop_n_per_m']:.12e} N/m, "
          f"relative difference {fd:.3e} (tolerance {a.force_drop_rel:g})")
    if not fd <= a.force_drop_rel:
        failures.append("force drop")
    fa, fb = sa["front_speed_m_per_s"], sb["front_speed_m_per_s"]
    if math.isfinite(fa) and math.isfinite(fb):
        fs = rel(fa, fb)
        print(f"front speed: {fa:.9f} vs {fb:.9f} m/s, difference {fa - fb:+.3e} m/s, "
              f"relative {fs:.3e} (tolerance {a.front_speed_rel:g})")
        if not fs <= a.front_speed_rel:
            failures.append("front speed")
    else:
        print(f"front speed: {fa} vs {fb} m/s (not both finite)")
        if math.isfinite(fa) != math.isfinite(fb):
            failures.append("front speed")
    print(f"min sigma: {sa['min_sigma_pa']:.9f} vs {sb['min_sigma_pa']:.9f} Pa "
          f"(difference {sa['min_sigma_pa'] - sb['min_sigma_pa']:+.3e}, reported only)")
    if failures:
        print("FAIL: " + ", ".join(failures))
        return 1
    print("OK: the two runs agree within the tolerances")
    return 0


if __name__ == "__main__":
    sys.exit(main())
