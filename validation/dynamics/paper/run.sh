#!/bin/sh
# The paper's scene in dynamics: (r, g) = (0.9, 0.35), L = 0.4 m, t = 2 mm, H = 4 cm,
# D_c = 4.62e-7 m (the smallest h = 1 mm resolves: Lambda_0 = 3 h), first cycle, static
# phase on the banded operator. Usage: run.sh [H_MM [ETA_S [TIMEOUT_S]]] (defaults 1, the
# default damping, 1200). Writes out/dynamics/paper_h<H> (not committed: states.csv is
# large) and the log next to this file.
set -e
cd "$(dirname "$0")/../../.."
h=${1:-1}
eta=${2:-}
lim=${3:-1200}
cargo build --release
hm=$(python3 -c "print($h / 1000)")
tag="h$h"
damp=""
if [ -n "$eta" ]; then damp="--damping $eta"; tag="${tag}_eta$eta"; fi
timeout "$lim" /usr/bin/time -v ./target/release/tribofe slide --dynamics --law slip-weakening \
  --dc 4.6214e-7 --h "$hm" $damp --operator banded --cycles 1 \
  --out "out/dynamics/paper_$tag" --force 2>&1 | tee "validation/dynamics/paper/paper_$tag.log"
