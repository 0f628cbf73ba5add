#!/bin/sh
# The side-pushed rig in the quasi-static `slide` (issue 49; docs/friction.md, "Side push"):
# L = 10 cm, t = 2 cm, h = 2 mm, a rigid pusher 6 mm wide centred 5 mm above the interface on
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
