#!/bin/sh
# Reruns every FE precursor study quoted in validation/precursors/README.md and in README.md
# (release build; about 6 minutes on 2 cores, 4.5 of them the overdamped fig. 5). Each command's
# printed summary is saved as <name>.txt next to its output folder.
set -e
cd "$(dirname "$0")/../.."
cargo build --release --quiet
B=./target/release/tribofe
D=validation/precursors
# --force: the folders committed before run.toml existed are not recognised as tribofe's.
run() { out=$1; shift; $B precursors "$@" --out $D/$out --force > $D/$out.txt; cat $D/$out.txt; }
# Fig. 4 on the paper's scene, both rules, with the field checks.
run fe_fig4 fe
# Where the overdamped rule's instabilities happen: in fig. 4's run, and at (0.5, 0.5) up to
# X = 0.1 mm (its 80 MB states.csv is not kept).
python3 $D/chatter.py $D/fe_fig4/overdamped/events.csv > $D/chatter.txt
$B slide --law static-kinetic --r 0.5 --g 0.5 --rule overdamped --x-max 1e-4 --out $D/chatter_r0.5_g0.5 > /dev/null
rm $D/chatter_r0.5_g0.5/states.csv
python3 $D/chatter.py $D/chatter_r0.5_g0.5/events.csv >> $D/chatter.txt
cat $D/chatter.txt
# Fig. 5 on the paper's scene: the paper rule (the default, ~45 s), then both rules.
run fe_fig5 fe-map
run fe_fig5_overdamped fe-map --rules paper,overdamped
# Thin-layer limit at H/L = 0.1 (h = t, 2 elements through t) for five (r, g).
for rg in 0.9:0.35 0.8:0.5 0.95:0.2 0.7:0.3 0.5:0.6; do
  r=${rg%:*}; g=${rg#*:}
  run thin_layer_r${r}_g$g thin-layer --t-over-l 0.02,0.01,0.005,0.0025,0.00125,0.000625 --r $r --g $g
done
# Height of the drive at the coefficients of (0.9, 0.35) (mu_s = 0.648, mu_d = 0.583).
run heights heights --h-over-l 0.01,0.025,0.05,0.075,0.1,0.125,0.15,0.175,0.2,0.225,0.25,0.275
# Event rule and D_c on the slip-weakening scene of validation/friction (L = 10 cm, t = 4 mm,
# h = 1 mm): the paper rule, then D_c from stable (kappa = 1.1) to under-resolved (L_c/h = 0.44).
run dc dc --dc 1e-6,3e-7,1e-7 --length 0.1 --thickness 0.004 --h 0.001 --n-thick 8 --max-events 20000
