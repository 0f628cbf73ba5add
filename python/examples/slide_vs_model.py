"""A frictional slide from Python: the friction force F against the elastic force F^c, from
the FE (the paper's static-kinetic law and rule) and from the paper's 1D model, for the same
(r, g) = (0.9, 0.35) (the paper's fig. 4).

    python3 python/examples/slide_vs_model.py [--out fig4.png]
"""

import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import tribofe

ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
ap.add_argument("--out", default="fig4_python.png")
args = ap.parse_args()

run = tribofe.slide(law="static-kinetic", r=0.9, g=0.35, cycles=1)
model = tribofe.precursors.model(0.9, 0.35)
fig, ax = plt.subplots(figsize=(6, 4))
ax.plot(run.curve_Fc_over_mu_s_N, run.curve_F_over_mu_s_N, lw=1, label="FE, rule paper")
ax.plot(model.curve_Fc_over_mu_s_N, model.curve_F_over_mu_s_N, lw=1, label="model (paper's iteration)")
ax.plot([0, 1.2], [0, 1.2], ":", color="grey", label="F = F^c (stuck)")
ax.set_xlabel("F^c / (mu_s N)")
ax.set_ylabel("F / (mu_s N)")
ax.legend()
fig.tight_layout()
fig.savefig(args.out, dpi=120)
print(run)
print(f"model: n = {model.n}, F_1 = {model.F_1:.4f}, F_max = {model.F_max:.4f}")
print(f"wrote {args.out}")
