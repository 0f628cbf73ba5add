"""Shared by the validation/experiments/ studies: one quasi-static `tribofe slide` case
(side push or top plate), run into a scratch folder, read back from loading.csv and
events.csv (column names as tribofe writes them; docs/outputs.md)."""
import csv
import os
import re
import subprocess

B = os.path.join(os.path.dirname(__file__), "..", "..", "target", "release", "tribofe")
L = 0.1  # block length, m (every study)
# The drive's bound, m: a thin side-pushed block creeps forward by successive precursors and
# tip advances without ever slipping whole at once; its F_max is then the run's peak up to X.
X_MAX = 2e-3


def num(x):
    return f"{x:.6g}"


def run(out, t, rig, height, mu_s, mu_d, h, push_width=None, extra=()):
    """Static-kinetic (rule paper), one stick-slip cycle (up to the first whole-interface
    slip, or X_MAX). rig: "top-plate" (height = H) or "side-push" (height = push height, pusher
    push_width wide, U_p driven, uniform pressure on top). Mesh: h along x and at least 20
    rows through t (the pusher, 0.15 t wide in the studies, needs 2 element edges)."""
    n_thick = max(20, round(t / h))
    cmd = [B, "slide", "--length", str(L), "--thickness", num(t), "--h", num(h),
           "--n-thick", str(n_thick), "--law", "static-kinetic", "--mu-s", num(mu_s),
           "--mu-d", num(mu_d), "--cycles", "1", "--x-max", num(X_MAX), "--states", "none", "--out", out, "--force",
           # dense for both rigs: the automatic choice (banded above 200 interface nodes)
           # ignores the thickness; the top plate at t/L = 0.5, h = L/200 took 465 s banded,
           # 2.9 s dense, the same F_max to 1e-10
           "--operator", "dense"]
    if rig == "side-push":
        cmd += ["--rig", "side-push", "--push-height", num(height), "--push-width", num(push_width)]
    else:
        cmd += ["--height", num(height)]
    cmd += list(extra)
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise SystemExit(f"tribofe failed ({p.returncode}): {' '.join(cmd)}\n{p.stderr}")
    m = re.search(r"paper's iteration \(r = [0-9.]+, g = ([0-9.]+)\):.*F_max = ([0-9.]+)", p.stdout)
    rows = lambda f: list(csv.DictReader(open(os.path.join(out, f))))
    loading, events = rows("loading.csv"), rows("events.csv")
    return {
        "stdout": p.stdout,
        "n_thick": n_thick,
        "F_max_over_N": max(float(r["F_over_N"]) for r in loading),
        "ended": "whole slip" if any(e["kind"] == "sliding" for e in events) else "X_max",
        "g_paper": float(m.group(1)) if m else float("nan"),
        "F_max_paper_over_mu_s_N": float(m.group(2)) if m else float("nan"),
        "events": events,
        "violation": max(float(r["max_violation"]) for r in loading),
    }
