#!/usr/bin/env python3
"""Instability by instability across meshes: how far the dynamic sequences agree.

Usage: sequence.py LOG_COARSE LOG_FINER [LOG_FINEST ...] [--t 0.002] [--l 0.4] [--rows K]

Reads the per-instability lines `slide --dynamics` prints (event, kind, X, F/(mu_s N) before
and after, slipped region) from each log (a run still going is read as far as it got), keeps
the instabilities (kinds other than `slip`), and pairs them in order. A pair agrees when the
onset forces differ by less than 0.005 mu_s N and both ends of the slipped regions by less than
2 t. Prints the first K of each log and, for each mesh against the one before it, how many
leading instabilities agree, and the largest differences over them.
"""
import re
import sys

LINE = re.compile(r"event (\d+) \((\S+)\) at X = ([\d.e+-]+) m: F/\(mu_s N\) ([\d.]+) -> ([\d.]+), "
                  r"slipped ([-\d.]+)\.\.([-\d.]+) L")


def arg(name, default):
    return float(sys.argv[sys.argv.index(name) + 1]) if name in sys.argv else default


def instabilities(path):
    out = []
    for line in open(path, errors="replace"):
        m = LINE.search(line)
        if m and m.group(2) != "slip":
            out.append(dict(event=int(m.group(1)), kind=m.group(2), x=float(m.group(3)), f=float(m.group(4)),
                            after=float(m.group(5)), a=float(m.group(6)), b=float(m.group(7))))
    return out


def main():
    logs = [a for a in sys.argv[1:] if a.endswith(".log")]
    t_over_l = arg("--t", 0.002) / arg("--l", 0.4)
    k = int(arg("--rows", 12))
    runs = [instabilities(p) for p in logs]
    print("| # | " + " | ".join(f"F onset, region x/L ({p.rsplit('/', 1)[-1].removesuffix('.log')})" for p in logs) + " |")
    print("|---|" + "---|" * len(logs))
    for i in range(min(k, max(len(r) for r in runs))):
        cells = [f"{r[i]['f']:.4f}, {r[i]['a']:+.4f}..{r[i]['b']:+.4f}" if i < len(r) else "" for r in runs]
        print(f"| {i + 1} | " + " | ".join(cells) + " |")
    for q, base, p, r in zip(logs, runs, logs[1:], runs[1:]):
        n, df, dx = 0, 0.0, 0.0
        for u, v in zip(base, r):
            ef, ex = abs(u["f"] - v["f"]), max(abs(u["a"] - v["a"]), abs(u["b"] - v["b"]))
            if ef >= 0.005 or ex >= 2 * t_over_l:
                break
            n, df, dx = n + 1, max(df, ef), max(dx, ex)
        print(f"\n{p}: the first {n} of {min(len(base), len(r))} paired instabilities agree with {q} "
              f"(onset F within {df:.4f} mu_s N, region ends within {dx / t_over_l:.2f} t)")


if __name__ == "__main__":
    main()
