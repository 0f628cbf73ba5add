#!/bin/sh
# The side-pushed rig in the quasi-static `slide` (issue 49; docs/friction.md, "Side push"):
# (and `slide --dynamics`, below): L = 10 cm, t = 2 cm, h = 2 mm, a rigid pusher 6 mm wide centred 5 mm above the interface on
# the trailing face, N = 1 N/m. Each run writes loading.csv, events.csv, states.csv,
# advances.csv (static-kinetic), fig4_fe.svg, fronts.svg, run.toml; its summary in <dir>.txt.
set -e
cd "$(dirname "$0")/../.."
cargo build --release --quiet
B=./target/release/tribofe
D=validation/friction
S="--length 0.1 --thickness 0.02 --h 0.002 --rig side-push --push-height 0.005 --push-width 0.006"
run() { out=$1; shift; $B slide $S "$@" --out $D/$out --force > $D/$out.txt; cat $D/$out.txt; }
# Static-kinetic, uniform pressure on the top, the pusher's displacement driven: one cycle.
run side_push_sk --law static-kinetic --mu-s 0.5 --mu-d 0.45 --cycles 1
# Coulomb, a rigid top plate free to slide, the pusher driven through a spring of 1e9 N/m per m.
run side_push_coulomb --mu 0.5 --top sliding-plate --push-stiffness 1e9
# Dynamics (slide --dynamics, held drive; outputs as docs/dynamics.md's, --states none):
# slip weakening on the thick block, whose quasi-static preslip from the pushed edge crosses
# most of the interface before its one instability, the whole slip...
run side_push_dyn_thick --dynamics --law slip-weakening --mu-s 0.5 --mu-d 0.3 --dc 1.2e-5
# ...and on a thin block (t = 4 mm, h = 0.5 mm, the pusher 2 mm wide at 2 mm) to its first
# cycle's end: precursors from the pushed edge first (tests/it/side_push.rs's scene).
T="--length 0.1 --thickness 0.004 --h 0.0005 --rig side-push --push-height 0.002 --push-width 0.002"
$B slide $T --dynamics --law slip-weakening --mu-s 0.6 --mu-d 0.2 --dc 6e-6 --out $D/side_push_dyn_thin --force > $D/side_push_dyn_thin.txt
cat $D/side_push_dyn_thin.txt
