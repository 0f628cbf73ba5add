#!/bin/sh
# Study 4 (issue 49): the macroscopic static friction coefficient F_max/N against the rig
# (top plate, side push), the driving height and the aspect ratio t/L, with static-kinetic
# friction (mu_s = 0.4, mu_d = 0.17; and mu_d = 0.36). Writes validation/experiments/fmax.csv
# and fmax.svg (python3 with matplotlib, an optional tool of the validation scripts only).
set -e
cd "$(dirname "$0")/../.."
cargo build --release --quiet
python3 validation/experiments/fmax.py
