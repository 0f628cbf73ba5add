"""The paper's fig. 2 from Python: interface pressure and shear under the tilted plate
against the model p/(N/L) = 1 + 12 (F/N)(H/L)(x/L), tau/(N/L) = F/N.

    python3 python/examples/fig2.py [--out fig2.png]
"""

import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

import tribofe

ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
ap.add_argument("--out", default="fig2_python.png")
args = ap.parse_args()

result = tribofe.check(tribofe.Scene())  # the paper's scene, 1 mm QUA4 mesh
fig, (ax_p, ax_t) = plt.subplots(2, 1, sharex=True, figsize=(6, 6))
for case in result.cases:
    inner = slice(1, -1)  # the end nodes are singular corners (docs/check.md)
    (line,) = ax_p.plot(case.x_over_L[inner], case.p_over_pmean[inner], label=f"F/N = {case.fn_ratio}")
    ax_p.plot(case.x_over_L, case.p_model, "--", color=line.get_color())
    ax_t.plot(case.x_over_L[inner], case.tau_over_pmean[inner], color=line.get_color())
    ax_t.plot(case.x_over_L, case.tau_model, "--", color=line.get_color())
ax_p.set_ylabel("p / (N/L)")
ax_t.set_ylabel("tau / (N/L)")
ax_t.set_xlabel("x / L")
ax_p.legend(title="FE (solid), model (dashed)")
fig.tight_layout()
fig.savefig(args.out, dpi=120)
print(result)
print(f"wrote {args.out}")
