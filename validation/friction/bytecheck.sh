#!/bin/sh
# Byte-for-byte check of a change to the event solver: runs two tribofe binaries on the same
# scenes and compares every output file but run.toml (dates); the `seconds` columns of dc.csv
# and fig5_fe.csv are timings and left out. About 2 minutes of CPU per binary.
# Usage: validation/friction/bytecheck.sh OLD_BINARY NEW_BINARY [WORK_DIR]
set -u
OLD=$1; NEW=$2; W=${3:-/tmp/tribofe_bytecheck}
rm -rf "$W"; mkdir -p "$W"
scenes() {
  B=$1; D=$2; mkdir -p "$D"
  r() { name=$1; shift; $B "$@" --out "$D/$name" > "$D/$name.txt" 2>&1 || echo "FAIL $B $name"; }
  r coulomb slide
  r sk_paper slide --law static-kinetic --rule paper
  r sk_over slide --law static-kinetic --rule overdamped
  r sw slide --length 0.1 --thickness 0.004 --h 0.004 --n-thick 2 --law slip-weakening --r 0.9 --g 0.35 --dc 3e-7 --cycles 1
  r sw_newton slide --length 0.1 --thickness 0.004 --h 0.002 --n-thick 4 --law slip-weakening --r 0.9 --g 0.35 --dc 3e-7 --cycles 1 --newton
  r sw_stable slide --length 0.1 --thickness 0.004 --h 0.002 --n-thick 4 --law slip-weakening --r 0.9 --g 0.35 --dc 1e-5 --cycles 1
  r mesh_over4 slide --thickness 0.004 --h 0.002 --n-thick 4 --law static-kinetic --r 0.9 --g 0.35 --rule overdamped --cycles 2
  r pfe precursors --fe
  r pfe_dc precursors --fe --dc 3e-7,1e-6
  r pfe_map precursors --fe --map
}
scenes "$OLD" "$W/old"; scenes "$NEW" "$W/new"
n=0; bad=0
for f in $(cd "$W/old" && find . -type f ! -name run.toml ! -name '*.txt' | sort); do
  n=$((n + 1))
  case $f in
    */dc.csv|*/fig5_fe.csv)
      # Leave out the timing columns (named *seconds).
      keep=$(head -1 "$W/old/$f" | tr ',' '\n' | grep -n -v seconds | cut -d: -f1 | paste -sd,)
      { cut -d, -f"$keep" "$W/old/$f" > "$W/a"; cut -d, -f"$keep" "$W/new/$f" > "$W/b"; cmp -s "$W/a" "$W/b"; } ||
        { echo "DIFFER $f"; bad=$((bad + 1)); } ;;
    *) cmp -s "$W/old/$f" "$W/new/$f" || { echo "DIFFER $f"; bad=$((bad + 1)); } ;;
  esac
done
echo "$n files compared, $bad differ"
[ "$bad" -eq 0 ]
