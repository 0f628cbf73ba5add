#!/bin/sh
# The paper's scene in the unstable regime (kappa < 0.7): one `slide --dynamics` run, its log
# and its per-instability summary (regime.py) next to this file; the big outputs in $OUT_ROOT.
# Usage: regime.sh H_MM DC_M KAPPA X_MAX HEAL [TIMEOUT_S]
#   regime.sh 0.5 2.3107e-7 0.5093 2.0e-5 all       # kappa = 0.51 (README: "unstable regime")
#   regime.sh 0.5 2.3107e-7 0.5093 2.0e-5 slipped
#   MAX_EVENTS=60000 regime.sh 0.25 1.1554e-7 0.2547 4.4e-6 all 1800
# BIN (default ./target/release/tribofe, built), OUT_ROOT (default /tmp/regime) and MAX_EVENTS
# (default 200000; h = 0.25 mm needs 60000: the states kept must fit half the memory) from the
# environment. --x-max ends the run cleanly: the event cap (--max-events) is an error that
# writes nothing, and states.csv (~80 bytes a node an event, built in memory) bounds the run.
set -e
cd "$(dirname "$0")/../../.."
h=$1; dc=$2; kappa=$3; xmax=$4; heal=$5; lim=${6:-2700}
if [ -z "$BIN" ]; then cargo build --release; BIN=./target/release/tribofe; fi
root=${OUT_ROOT:-/tmp/regime}
here=validation/dynamics/paper
hm=$(python3 -c "print($h / 1000)")
tag="regime_h${h}_dc${dc}_heal_${heal}"
mkdir -p "$root"
nice timeout "$lim" /usr/bin/time -v "$BIN" slide --dynamics --law slip-weakening --dc "$dc" \
  --h "$hm" --operator banded --cycles 1 --max-events "${MAX_EVENTS:-200000}" --x-max "$xmax" --heal "$heal" \
  --out "$root/$tag" --force > "$root/$tag.log" 2>&1 || echo "exit $?" >> "$root/$tag.log"
# the progress bar's redraws removed, the rest kept
sed 's/slide --dynamics *[0-9.]* %//g' "$root/$tag.log" > "$here/$tag.log"
"$BIN" precursors model --r 0.9 --g 0.35 --out "$root/model" --force > /dev/null
python3 "$here/regime.py" "$root/$tag" "$kappa" --summary "$here/$tag.csv" \
  --model "$root/model/events.csv" | tee "$here/$tag.txt"
