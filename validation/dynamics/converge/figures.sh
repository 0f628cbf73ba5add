#!/bin/sh
# The convergence study's table and figures from the runs of run.sh (README.md here).
# Usage: figures.sh [OUT_ROOT]  (default /tmp/converge); BIN as in run.sh. Writes table.md,
# table.csv, cost.png and fig4_r<R>_g<G>.png next to this file (needs matplotlib).
set -e
cd "$(dirname "$0")/../../.."
root=${1:-${OUT_ROOT:-/tmp/converge}}
if [ -z "$BIN" ]; then cargo build --release; BIN=./target/release/tribofe; fi
export BIN
here=validation/dynamics/converge
python3 $here/table.py "$root" --csv $here/table.csv > $here/table.md
python3 $here/cost.py $here/table.csv $here/cost.png
for rg in "0.9 0.35" "0.7 0.5" "0.8 0.2"; do
  set -- $rg
  "$BIN" precursors model --r "$1" --g "$2" --out "$root/model_r$1_g$2" --force > /dev/null
  runs=""
  for h in 0.125 0.25 0.5; do  # the finest first: its instabilities are drawn
    d=$(ls -d "$root"/r$1_g$2_h${h}_dc* 2>/dev/null | grep -v -e _eta -e _ws | head -1)
    if [ -n "$d" ] && [ -f "$d/advances.csv" ]; then runs="$runs dynamics_h${h}mm=$d"; fi
  done
  for rule in paper overdamped; do
    d="$root/r$1_g$2_h0.25_qs_$rule"
    if [ -f "$d/advances.csv" ]; then runs="$runs quasi-static_${rule}_h0.25mm=$d"; fi
  done
  # shellcheck disable=SC2086
  [ -n "$runs" ] && python3 validation/dynamics/paper/fig4.py "$here/fig4_r$1_g$2.png" "$root/model_r$1_g$2" \
    --fc-max 2.0 $runs 2>/dev/null
done
