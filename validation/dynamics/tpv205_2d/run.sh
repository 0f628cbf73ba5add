#!/bin/sh
# TPV205-2D (issue 47): the committed scene at h = 200, 100, 50 m, then compare.py writes
# table.csv, table.md and stations.svg against PyLith's 2D run (reference/README.md).
# Usage: sh validation/dynamics/tpv205_2d/run.sh [tribofe]   (about 2.5 minutes here)
set -e
B=${1:-target/release/tribofe}
D=$(dirname "$0")
for H in 200 100 50; do
  $B rupture --scene "$D/tpv205_2d.toml" --h $H --out "$D/h$H" --force | tee "$D/h$H.log"
done
python3 "$D/compare.py" "$D"
