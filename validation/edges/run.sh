#!/usr/bin/env bash
# The block's ends on the frictional interface (README in this folder); about 2 minutes.
set -euo pipefail
cd "$(dirname "$0")/../.."
cargo build --release -q
./target/release/tribofe edges --length 0.05 --mu 0.1,0.2,0.3,0.4,0.45,0.5,0.6,0.65 --refine 2,4,8,16,32 \
    --t-over-l 0.02,0.01,0.005 --open-refine 2,4,8 --h-over-l 0.025,0.05,0.1,0.2 --end-grading 1 \
    --out validation/edges/study > validation/edges/summary.txt
mv validation/edges/summary.txt validation/edges/study/summary.txt
