#!/usr/bin/env python3
"""Which slide outputs are set by the physics and which by round-off.

Reruns `tribofe slide` with the block length L multiplied by 1 + k 1e-11 (k = 0..7), a change
far below any physical or mesh scale, for the static-kinetic rules on the paper's scene and for
slip weakening on the D_c scene of README.md, and writes sensitivity.csv (one row per run) and
sensitivity.txt (the spread of each output per case). Needs a release build
(`cargo build --release`); about 5 minutes on 2 cores.

    python3 validation/friction/sensitivity.py
"""
import concurrent.futures
import csv
import os
import re
import subprocess
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
BIN = os.path.join(HERE, "..", "..", "target", "release", "tribofe")
SW = "--thickness 0.004 --law slip-weakening --r 0.9 --g 0.35 --dc 3e-7 --cycles 1"
SK = "--law static-kinetic --r 0.9 --g 0.35 --cycles 1"
# name, L (m), the other flags
CASES = [
    ("paper rule, paper scene", 0.4, SK + " --rule paper"),
    ("overdamped rule, paper scene", 0.4, SK + " --rule overdamped"),
    ("slip weakening h = 4 mm (L_c/h = 0.33)", 0.1, SW + " --h 0.004 --n-thick 2"),
    ("slip weakening h = 1 mm (L_c/h = 1.3)", 0.1, SW + " --h 0.001 --n-thick 8"),
    ("slip weakening h = 1 mm, --newton", 0.1, SW + " --h 0.001 --n-thick 8 --newton"),
]
KS = range(8)
SUMMARY = re.compile(
    r"nodes, (?P<events>\d+) events.*?FE: n = (?P<advancing>\d+) \(advancing; of (?P<precursors>\d+) precursors.*?"
    r"F_1 = (?P<f_long>[-\d.]+), x_1 = (?P<x_long>[-\d.]+); "
    r"last peak F = (?P<peak>[-\d.]+)",
    re.S,
)
COLUMNS = ["events", "precursors", "advancing", "f_long", "x_long", "peak"]


def one(case, k, tmp):
    name, length, flags = case
    l = length * (1 + k * 1e-11)
    out = os.path.join(tmp, f"{CASES.index(case)}_{k}")
    cmd = [BIN, "slide", "--length", repr(l), *flags.split(), "--out", out]
    r = subprocess.run(cmd, capture_output=True, text=True)
    m = SUMMARY.search(r.stdout)
    if r.returncode != 0 or not m:
        said = (r.stderr or r.stdout).strip().splitlines()
        return name, k, l, None, said[-1] if said else f"exit status {r.returncode}"
    return name, k, l, m.groupdict(), ""


def main():
    with tempfile.TemporaryDirectory() as tmp, concurrent.futures.ThreadPoolExecutor(2) as pool:
        rows = list(pool.map(lambda a: one(*a, tmp), [(c, k) for c in CASES for k in KS]))
    with open(os.path.join(HERE, "sensitivity.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["case", "k", "length_m", "events", "precursors", "advancing",
                    "first_long_F_over_mu_s_N", "first_long_x_over_L", "peak_F_over_mu_s_N", "error"])
        for name, k, l, v, err in rows:
            w.writerow([name, k, repr(l)] + ([v[c] for c in COLUMNS] if v else [""] * 6) + [err])
    lines = [f"L -> L (1 + k 1e-11), k = 0..{len(KS) - 1}: range of each output over the runs that finished",
             f"{'case':42} {'failed':>6} {'events':>13} {'precursors':>11} {'advancing':>9} "
             f"{'first long F':>15} {'x/L':>15} {'peak F':>15}"]
    for name, *_ in CASES:
        done = [v for n, _, _, v, _ in rows if n == name and v]
        failed = sum(1 for n, _, _, v, _ in rows if n == name and not v)

        def span(c, fmt):
            vals = sorted(float(v[c]) for v in done)
            return "-" if not vals else fmt.format(vals[0]) + (" " + fmt.format(vals[-1]) if vals[0] != vals[-1] else "")
        lines.append(f"{name:42} {failed:>6} {span('events', '{:.0f}'):>13} {span('precursors', '{:.0f}'):>11} "
                     f"{span('advancing', '{:.0f}'):>9} {span('f_long', '{:.4f}'):>15} "
                     f"{span('x_long', '{:.4f}'):>15} {span('peak', '{:.4f}'):>15}")
    text = "\n".join(lines) + "\n"
    with open(os.path.join(HERE, "sensitivity.txt"), "w") as f:
        f.write(text)
    print(text, end="")


if __name__ == "__main__":
    main()
