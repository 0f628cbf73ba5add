#!/bin/sh
# The paper's scene in dynamics: (r, g) = (0.9, 0.35), L = 0.4 m, t = 2 mm, H = 4 cm,
# h = 1 mm, D_c the smallest the mesh resolves (Lambda_0 = 3 h, printed), first cycle.
# Writes out/paper_h1 (not committed: states.csv is large) and the log next to this file.
set -e
cd "$(dirname "$0")/../../.."
cargo build --release
/usr/bin/time -v ./target/release/tribofe slide --dynamics --law slip-weakening --cycles 1 \
  --out out/dynamics/paper_h1 --force 2>&1 | tee validation/dynamics/paper/paper_h1.log
