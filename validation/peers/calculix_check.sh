#!/usr/bin/env bash
# CalculiX (CPE4, rigid plate) peer of the tribofe check problem.
# Usage: calculix_check.sh [--ny N] [--tie rigid|equation] [--tribofe-out DIR]
#                          [--workdir DIR] [--keep]
#   --ny 2 (default) is the paper's mesh h = 1 mm (400 x 2 elements).
# Writes results/calculix_ny<N>/profile_FN*.csv + summary.csv and
# results/calculix_vs_peers_ny<N>.csv (vs scikit-fem, and tribofe if given).
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
NY=2; TIE=rigid; TRIB=""; WORK=""; KEEP=0
while [ $# -gt 0 ]; do
  case "$1" in
    --ny) NY="${2:?--ny needs a value}"; shift 2;;
    --tie) TIE="${2:?--tie needs rigid|equation}"; shift 2;;
    --tribofe-out) TRIB="${2:?--tribofe-out needs a directory}"; shift 2;;
    --workdir) WORK="${2:?--workdir needs a directory}"; shift 2;;
    --keep) KEEP=1; shift;;
    -h|--help) sed -n '2,7p' "$0"; exit 0;;
    *) echo "error: unknown option $1 (see --help)" >&2; exit 2;;
  esac
done
command -v ccx >/dev/null || { echo "error: ccx not found; run $HERE/install.sh" >&2; exit 2; }
[[ "$NY" =~ ^[1-9][0-9]*$ ]] || { echo "error: --ny must be a positive integer" >&2; exit 2; }
if [ -n "$TRIB" ] && [ ! -d "$TRIB" ]; then echo "error: --tribofe-out $TRIB is not a directory" >&2; exit 2; fi
echo "calculix_check: $(ccx -v 2>&1 | grep -m1 -i version | sed 's/^ *//'), python $(python3 -V 2>&1 | cut -d' ' -f2)"

if [ -z "$WORK" ]; then WORK="$(mktemp -d /tmp/ccx_check.XXXXXX)"; [ "$KEEP" = 1 ] || trap 'rm -rf "$WORK"' EXIT; fi
mkdir -p "$WORK"
REF="$HERE/results/skfem_ny$NY"
# scikit-fem reference on the same mesh (cheap; rerun so it is current).
python3 "$HERE/skfem_check.py" --ny "$NY" --out "$REF" --quiet
python3 "$HERE/ccx_model.py" write --ny "$NY" --dir "$WORK" --tie "$TIE"
( cd "$WORK" && OMP_NUM_THREADS=1 ccx -i check > ccx.log 2>&1 ) \
  || { echo "error: ccx failed, see $WORK/ccx.log" >&2; tail -20 "$WORK/ccx.log" >&2; exit 1; }
ARGS=(post --ny "$NY" --dir "$WORK" --tie "$TIE" --out "$HERE/results/calculix_ny$NY"
      --ref "$REF" --cmp-csv "$HERE/results/calculix_vs_peers_ny$NY.csv")
[ -n "$TRIB" ] && ARGS+=(--tribofe-out "$TRIB")
python3 "$HERE/ccx_model.py" "${ARGS[@]}"
