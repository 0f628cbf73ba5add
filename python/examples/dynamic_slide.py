"""A dynamic slide from Python: the paper's scene to its first front crossing with the
command's defaults for `slide --dynamics --law slip-weakening` (about a minute), plotted as
the paper's fig. 4 (the friction force F against F^c, both in units of mu_s N, each
instability a drop) beside the space-time picture of the first precursor
(log10 of the slip rate along the interface against the time since its onset).

    python3 python/examples/dynamic_slide.py [--out dynamic_slide.png] [--length L]
"""

import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import tribofe

ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
ap.add_argument("--out", default="dynamic_slide.png")
ap.add_argument("--length", type=float, default=None, help="block length L, m (default: the paper's 0.4)")
args = ap.parse_args()

scene = tribofe.Scene() if args.length is None else tribofe.Scene(length=args.length)
run = tribofe.dynamics.slide(scene, law="slip-weakening", progress=True)
for note in run.notes:
    print(note)
s = run.summary
loading = run.loading
mu_s_n = run.mu_s * np.asarray(loading["N_N_per_m"])[-1]  # mu_s N, N/m
drive = np.asarray(loading["phase"]) == "drive"
fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4))
a.plot(np.asarray(loading["Fc_N_per_m"])[drive] / mu_s_n, np.asarray(loading["F_N_per_m"])[drive] / mu_s_n, lw=0.8)
a.set_xlabel("F^c / (mu_s N)")
a.set_ylabel("F / (mu_s N)")
a.set_title(f"F_1 = {s['first_advance_F_over_mu_s_N']:.4f} mu_s N, x_1 = {s['first_advance_front_over_L']:.4f} L")
first = next((e for e in run.samples if e["instability"]), None)
if first is not None:
    rate = np.log10(np.maximum(first["slip_rate_m_per_s"], 1e-12))
    x = run.x_over_L
    im = b.imshow(rate, aspect="auto", origin="upper", cmap="inferno",
                  extent=[x[0], x[-1], first["slip_rate_t_s"][-1], first["slip_rate_t_s"][0]], vmin=rate.max() - 4)
    fig.colorbar(im, ax=b, label="log10 slip rate (m/s)")
    b.set_xlabel("x / L")
    b.set_ylabel("time since onset (s)")
    b.set_title(f"event {first['event']}: the first instability")
fig.tight_layout()
fig.savefig(args.out, dpi=120)
print(run)
print(f"wrote {args.out}")
