#!/bin/sh
# The paper's scene in dynamics: (r, g) = (0.9, 0.35), L = 0.4 m, t = 2 mm, H = 4 cm, first
# cycle, static phase on the banded operator.
# Usage: run.sh [H_MM [DC_M [ETA_S [TIMEOUT_S]]]]; defaults 1, 4.6214e-7 (the smallest D_c
# that h = 1 mm resolves: Lambda_0 = 3 h), the default damping (10 % of critical at the
# thickness mode), 1800. Writes out/dynamics/paper_<tag> (not committed: states.csv is
# large) and paper_<tag>.log next to this file (stdout + stderr + /usr/bin/time -v).
set -e
cd "$(dirname "$0")/../../.."
h=${1:-1}
dc=${2:-4.6214e-7}
eta=${3:-}
lim=${4:-1800}
cargo build --release
hm=$(python3 -c "print($h / 1000)")
tag="h${h}_dc${dc}"
damp=""
if [ -n "$eta" ]; then damp="--damping $eta"; tag="${tag}_eta$eta"; fi
timeout "$lim" /usr/bin/time -v ./target/release/tribofe slide --dynamics --law slip-weakening \
  --dc "$dc" --h "$hm" $damp --operator banded --cycles 1 \
  --out "out/dynamics/paper_$tag" --force 2>&1 | tee "validation/dynamics/paper/paper_$tag.log"
