"""Hostile inputs through the Python API (issue 45): every numeric keyword of
`tribofe.dynamics.rupture` and `tribofe.slide` at NaN, inf, -inf, -1, 0, 1e-308, 1e308 and
2^64 - 1, one interpreter per keyword (an abort or a hang is seen), each call under an alarm
that the package must turn into a cancellation. Prints one TSV row per call (label, keyword,
value, exit, seconds, verdict, message) for hostile_dynamics.sh. A tribofe error or a Python
conversion error is a refusal (ok); BAD is a Rust panic reaching Python (PanicException), the
interpreter dying, a run the alarm cannot stop (HANG), an infinite number in a result (NaN is
the package's empty cell), or a refusal whose message carries a control byte.
Usage: python3 validation/inputs/hostile_python.py [--quick] [--timeout S]"""

import argparse
import subprocess
import sys
import time

CALL = r"""
import math, signal, sys, warnings
import numpy as np
import tribofe
warnings.simplefilter("ignore")
fn, key, kind, limit = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4])
f = tribofe.dynamics.rupture if fn == "rupture" else tribofe.slide


class Hang(Exception):
    pass


def alarm(*_):
    raise Hang()


signal.signal(signal.SIGALRM, alarm)


def infinite(x):
    # NaN is the package's empty cell (a quantity a run does not have); inf is never right.
    if isinstance(x, dict):
        return any(infinite(v) for v in x.values())
    if isinstance(x, (list, tuple)):
        return any(infinite(v) for v in x)
    if isinstance(x, np.ndarray):
        return x.dtype.kind in "fc" and bool(np.isinf(x).any())
    if isinstance(x, float):
        return math.isinf(x)
    if hasattr(x, "columns") and hasattr(x, "to_numpy"):  # a DataFrame (a result's table)
        return any(infinite(np.asarray(x[c])) for c in x.columns)
    if hasattr(x, "__dict__"):
        return infinite(vars(x))
    return False


for v in sys.argv[5:]:
    base = {"rupture": {"t_end": 0.02}, "slide": {"law": "coulomb", "x_max": 2e-6}}[fn]
    base[key] = float(v) if kind == "f" else int(v)
    signal.setitimer(signal.ITIMER_REAL, limit)
    try:
        r = f(progress=False, **base)
        word = "NONFINITE" if infinite(r) else "FINISHED"
    except Hang:
        word = "HANG"  # the interrupt reached the run: it stopped, but only at the limit
    except tribofe.TribofeError as e:
        m = str(e)
        word = ("REFUSED " if all(c >= " " or c == "\n" for c in m) else "CONTROL ") + m.splitlines()[0][:150]
    except (TypeError, ValueError, OverflowError) as e:
        word = "REFUSED " + type(e).__name__ + " " + str(e).splitlines()[0][:140]
    except BaseException as e:
        word = ("PANIC " if type(e).__name__ == "PanicException" else "OTHER ") + type(e).__name__ + " " + str(e)[:140]
    signal.setitimer(signal.ITIMER_REAL, 0)
    print(v + "\t" + word, flush=True)
"""

KEYS = {
    "rupture": ["s", "h", "dc", "t_end", "length", "height", "mu_s", "mu_d", "sigma0", "young",
                "poisson", "density", "courant", "damping", "normal_lag", "patch_taper", "max_steps"],
    "slide": ["mu", "n_force", "x_max", "cycles", "max_events"],
}
INTS = {"cycles", "max_events", "max_steps"}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--timeout", type=float, default=60)
    a = ap.parse_args()
    values = ["nan", "-inf", "0", "1e308"] if a.quick else \
        ["nan", "inf", "-inf", "-1", "0", "1e-308", "1e308", "18446744073709551615"]
    # One interpreter per keyword (its values in turn, each under an alarm): an abort or a
    # hang that the interrupt cannot stop is seen, and costs the rest of that keyword only.
    for fn, keys in KEYS.items():
        for key in keys:
            kind = "i" if key in INTS else "f"
            # Not an int: Python's own TypeError, nothing of ours.
            vals = [v for v in values if kind == "f" or v not in ("nan", "inf", "-inf", "1e308", "1e-308")]
            t0 = time.time()
            try:
                p = subprocess.run([sys.executable, "-c", CALL, fn, key, kind, str(a.timeout), *vals],
                                   capture_output=True, text=True, timeout=a.timeout * (len(vals) + 1))
                code, out = p.returncode, p.stdout
            except subprocess.TimeoutExpired as e:
                code, out = 124, (e.stdout or b"").decode() if isinstance(e.stdout, bytes) else (e.stdout or "")
            done = dict(line.split("\t", 1) for line in out.splitlines() if "\t" in line)
            secs = (time.time() - t0) / max(len(vals), 1)
            for v in vals:
                if v in done:
                    word = done[v]
                    verdict = {"REFUSED": "ok", "FINISHED": "ok"}.get(word.split(" ")[0], word.split(" ")[0])
                    c = 0
                else:
                    word, verdict, c = "(the interpreter died or hung)", "HANG" if code == 124 else "ABORT", code
                msg = word.replace("\t", " ")[:160]
                print(f"python {fn}\t{key}=\t{v}\t{c}\t{secs:.2f}\t{verdict}\t{msg}")


if __name__ == "__main__":
    main()
