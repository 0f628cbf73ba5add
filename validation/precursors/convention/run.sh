#!/bin/sh
# The `paper` rule's two conventions measured (issue 33): for each (r, g) and block thickness t,
# the four combinations of --residual (relaxed | pre-event) and --backslip (allowed | forbidden)
# of `slide --law static-kinetic --rule paper` (10 cycles, the banded operator: the same numbers
# as the dense one, measured on the paper's scene, and ~10x faster for the pre-event fixed
# point). Each run's summary is kept as runs/<name>.txt and its events.csv as
# runs/<name>.events.csv; table.py turns them into table.csv, shares.csv and convention.svg.
# About 2-3 minutes of CPU (release build).
# Usage: validation/precursors/convention/run.sh [TRIBOFE_BINARY]
set -e
cd "$(dirname "$0")/../../.."
if [ $# -ge 1 ]; then B=$1; else cargo build --release --quiet; B=./target/release/tribofe; fi
D=validation/precursors/convention
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
mkdir -p $D/runs
for rg in 0.9:0.35 0.8:0.5 0.95:0.2 0.7:0.3; do
  r=${rg%:*}; g=${rg#*:}
  # t = 2 mm is the paper's scene (h = 1 mm: 2 elements through t); the others keep h = t/2.
  for th in 0.001:0.0005 0.002:0.001 0.004:0.002; do
    t=${th%:*}; h=${th#*:}
    for res in relaxed pre-event; do
      for back in allowed forbidden; do
        name=r${r}_g${g}_t${t}_${res}_${back}
        start=$(date +%s.%N)
        $B slide --law static-kinetic --rule paper --r $r --g $g --thickness $t --h $h \
          --residual $res --backslip $back --operator banded --out $W/$name > $D/runs/$name.txt
        end=$(date +%s.%N)
        echo "wall_s = $(echo "$end - $start" | bc)" >> $D/runs/$name.txt
        cp $W/$name/events.csv $D/runs/$name.events.csv
        echo "$name: $(grep '^FE:' $D/runs/$name.txt)"
      done
    done
  done
done
python3 $D/table.py $D
