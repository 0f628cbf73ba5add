#!/bin/sh
# Reruns every study quoted in validation/friction/README.md but the round-off study
# (sensitivity.py); release build, about 20 minutes on 2 cores, most of it sw_nt16.
# Each run writes loading.csv, events.csv, states.csv, fig4_fe.svg, fronts.svg, run.toml and
# prints its summary, captured in <dir>/summary.txt.
set -e
cd "$(dirname "$0")/../.."
cargo build --release --quiet
B=./target/release/tribofe
D=validation/friction
run() { out=$1; shift; $B slide "$@" --out $D/$out > $D/$out.txt; cat $D/$out.txt; }
# The paper's block and mesh (t = 2 mm, h = 1 mm, QUA4, rigid plate, H = 4 cm).
run paper_coulomb --mu 0.5
run paper_sk_paper --law static-kinetic --r 0.9 --g 0.35 --rule paper
# Thin-layer limit of coulomb (mu = 0.5, g = 0.3): h = t, 2 elements through t.
for t in 0.008 0.004 0.002 0.001 0.0005; do
  run thin_coulomb_t$t --thickness $t --h $t --n-thick 2 --mu 0.5
done
# Mesh convergence of the coulomb fronts at the paper's t = 2 mm (h = t, t/2, t/4; 2 h through t).
for p in 2:0.002 4:0.001 8:0.0005; do
  nt=${p%:*}; h=${p#*:}
  run mesh_coulomb_nt$nt --h $h --n-thick $nt --mu 0.5
done
# The paper rule against the analytic iteration, t/L -> 0, (r, g) = (0.9, 0.35) and two others.
for t in 0.008 0.004 0.002 0.001; do
  run thin_sk_t$t --thickness $t --h $t --n-thick 2 --law static-kinetic --r 0.9 --g 0.35
done
run rg_0.8_0.5 --thickness 0.001 --h 0.001 --n-thick 2 --law static-kinetic --r 0.8 --g 0.5
run rg_0.95_0.2 --thickness 0.001 --h 0.001 --n-thick 2 --law static-kinetic --r 0.95 --g 0.2
# Abrupt drop: mesh dependence of both rules at t = 4 mm (h = t, t/2, t/4; 2 h through t).
for p in 2:0.004 4:0.002 8:0.001; do
  nt=${p%:*}; h=${p#*:}
  run mesh_paper_nt$nt --thickness 0.004 --h $h --n-thick $nt --law static-kinetic --r 0.9 --g 0.35 --rule paper --cycles 2
  run mesh_overdamped_nt$nt --thickness 0.004 --h $h --n-thick $nt --law static-kinetic --r 0.9 --g 0.35 --rule overdamped --cycles 2
done
# Speed: ~1000 interface nodes (coulomb to 5 % past whole sliding).
run speed_1000 --h 0.0004 --n-thick 2 --mu 0.5
# Slip weakening (L = 10 cm, t = 4 mm, (r, g) = (0.9, 0.35), one cycle): D_c = 0.3 um
# (kappa = 0.33) on h = 4, 2, 1, 0.5 mm; stable growth at D_c = 10 um (kappa = 11); the
# abrupt-drop limit D_c = 1e-10 m against the overdamped rule on h = 1 mm.
for p in 2:0.004 4:0.002 8:0.001 16:0.0005; do
  nt=${p%:*}; h=${p#*:}
  run sw_nt$nt --length 0.1 --thickness 0.004 --h $h --n-thick $nt --law slip-weakening --r 0.9 --g 0.35 --dc 3e-7 --cycles 1
done
# The same three coarsest runs with Newton on the coefficients (--newton).
for p in 2:0.004 4:0.002 8:0.001; do
  nt=${p%:*}; h=${p#*:}
  run sw_nt${nt}_newton --length 0.1 --thickness 0.004 --h $h --n-thick $nt --law slip-weakening --r 0.9 --g 0.35 --dc 3e-7 --cycles 1 --newton
done
run sw_stable --length 0.1 --thickness 0.004 --h 0.002 --n-thick 4 --law slip-weakening --r 0.9 --g 0.35 --dc 1e-5 --cycles 1
run sw_dc0 --length 0.1 --thickness 0.004 --h 0.001 --n-thick 8 --law slip-weakening --r 0.9 --g 0.35 --dc 1e-10 --cycles 1
run sw_overdamped --length 0.1 --thickness 0.004 --h 0.001 --n-thick 8 --law static-kinetic --rule overdamped --r 0.9 --g 0.35 --cycles 1
