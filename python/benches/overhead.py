"""The cost of calling tribofe from Python on the paper's mesh: whole call time against the
Rust core's own wall time (measured inside the extension), the rest being argument
conversion, result conversion to numpy/dicts and the Python wrapper.

    python3 python/benches/overhead.py [--repeat 50]
"""

import argparse
import statistics
import time

import tribofe

ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
ap.add_argument("--repeat", type=int, default=50)
args = ap.parse_args()


def measure(call):
    total, core = [], []
    for _ in range(args.repeat):
        t0 = time.perf_counter()
        r = call()
        total.append(time.perf_counter() - t0)
        core.append(r.core_s)
    t, c = statistics.median(total), statistics.median(core)
    return t, c, t - c


scene = tribofe.Scene()
rows = [
    ("check (paper's mesh, 3 F/N)", lambda: tribofe.check(scene)),
    (
        "slide static-kinetic, 1 cycle",
        lambda: tribofe.slide(scene, "static-kinetic", r=0.9, g=0.35, cycles=1, progress=False),
    ),
]
print(f"median of {args.repeat} calls; times in ms")
print(f"{'call':34s} {'whole':>8s} {'core':>8s} {'overhead':>9s} {'share':>6s}")
for name, call in rows:
    t, c, o = measure(call)
    print(f"{name:34s} {1e3 * t:8.2f} {1e3 * c:8.2f} {1e3 * o:9.2f} {100 * o / t:5.1f}%")
