#!/usr/bin/env bash
# CalculiX cross-check of `tribofe slide` (coulomb, mu = 0.5, N = 40 N/m, the paper's scene and
# mesh): installs CalculiX, runs it at two contact penalties 10x apart, runs tribofe, compares.
# Usage: bash validation/friction/calculix/run.sh [OUT]   (default out/calculix)
set -euo pipefail
cd "$(dirname "$0")/../../.."
out=${1:-out/calculix}
bash validation/friction/calculix/install.sh
export OMP_NUM_THREADS=1 CCX_NPROC_EQUATION_SOLVER=1
mkdir -p "$out"
cargo build --release -q
/usr/bin/time -f "tribofe wall %e s" ./target/release/tribofe slide --mu 0.5 --n-force 40 --out "$out/tribofe" | tail -4
for k in 1e9 1e10; do
  python3 validation/friction/calculix/ccx_slide.py --out "$out/ccx_K$k" --penalty "$k" --mu 0.5 --normal-force 40 --increments 100
  python3 validation/friction/calculix/compare.py --tribofe-out "$out/tribofe" --ccx-out "$out/ccx_K$k" --out "$out/compare_K$k"
done
