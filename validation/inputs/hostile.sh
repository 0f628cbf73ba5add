#!/usr/bin/env bash
# Hostile numeric inputs (issue 31): NaN, inf, -inf, negative, zero, tiny and huge values for
# every numeric flag of slide, precursors, edges and sweep, plus the examples of the issue.
# Each run: `timeout 60` under `ulimit -v 8000000` (KiB), its exit status and wall time
# tabulated in hostile.tsv next to this script. A result is BAD when the run panicked (101),
# aborted (134), hung (124), or exited 0 with a non-finite number in its output.
# Usage: bash validation/inputs/hostile.sh [TSV]   (about 10 minutes on 2 busy cores)
set -uo pipefail
cd "$(dirname "$0")/../.."
cargo build --release -q
BIN=$PWD/target/release/tribofe
TSV=${1:-validation/inputs/hostile.tsv}
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
VALUES=(nan inf -inf -1 0 1e-308 1e308 18446744073709551615)
printf 'command\tflag\tvalue\texit\tseconds\tverdict\tmessage\n' > "$TSV"
bad=0
total=0

# one COMMAND-WORDS... -- ARGS...: runs tribofe with the words and args, appends a row.
one() {
    local label=$1 flag=$2 value=$3; shift 3
    local out=$WORK/out
    rm -rf "$out"
    local t0 t1 code
    t0=$(date +%s.%N)
    ( ulimit -v 8000000; exec timeout 60 "$BIN" "$@" --out "$out" ) >"$WORK/stdout" 2>"$WORK/stderr" </dev/null
    code=$?
    t1=$(date +%s.%N)
    local verdict=ok
    case $code in
        101) verdict=PANIC ;;
        134) verdict=ABORT ;;
        124) verdict=HANG ;;
        0)
            if grep -qiwE 'nan|[-+]?inf' "$WORK/stdout" || { [ -d "$out" ] && grep -rqiwE 'nan|[-+]?inf' "$out" --include='*.csv'; }; then
                verdict=NONFINITE
            fi ;;
    esac
    [ "$verdict" = ok ] || bad=$((bad + 1))
    total=$((total + 1))
    local msg
    msg=$(grep -m1 -E '^error' "$WORK/stderr" | cut -c1-160 | tr '\t' ' ')
    [ -n "$msg" ] || msg=$( [ $code = 0 ] && echo "(finished)" || head -c 160 "$WORK/stderr" | tr '\n\t' '  ')
    printf '%s\t%s\t%s\t%s\t%.2f\t%s\t%s\n' "$label" "$flag" "$value" "$code" "$(echo "$t1 - $t0" | bc)" "$verdict" "$msg" >> "$TSV"
}

# sweep_flag COMMAND-LABEL FLAG -- PREFIX ARGS: every value of VALUES for FLAG.
sweep_flag() {
    local label=$1 flag=$2; shift 3
    for v in "${VALUES[@]}"; do
        one "$label" "$flag" "$v" "$@" "$flag=$v"
    done
}

SCENE_FLAGS=(--length --thickness --young --poisson --height --plate-thickness --plate-modulus
    --plate-poisson --h --grading --h-max --n-thick --max-dofs)

# slide: the scene flags, then each law's flags with the law that uses them.
for f in "${SCENE_FLAGS[@]}" --n-force --x-max --max-events --fields; do
    sweep_flag slide "$f" -- slide
done
sweep_flag "slide coulomb" --mu -- slide --law coulomb
sweep_flag "slide static-kinetic" --mu-s -- slide --law static-kinetic --mu-d 0.5
sweep_flag "slide static-kinetic" --mu-d -- slide --law static-kinetic --mu-s 0.65
sweep_flag "slide static-kinetic" --r -- slide --law static-kinetic --g 0.35
sweep_flag "slide static-kinetic" --g -- slide --law static-kinetic --r 0.9
sweep_flag "slide static-kinetic" --cycles -- slide --law static-kinetic
sweep_flag "slide slip-weakening" --dc -- slide --law slip-weakening

# precursors: the model, the FE and its studies, the map.
for f in --r --g --events; do sweep_flag precursors "$f" -- precursors; done
sweep_flag "precursors --map" --resolution -- precursors --map
for f in "${SCENE_FLAGS[@]}" --r --g --cycles --max-events; do
    sweep_flag "precursors --fe" "$f" -- precursors --fe
done
sweep_flag "precursors --fe" --thin-layer -- precursors --fe
sweep_flag "precursors --fe" --heights -- precursors --fe
sweep_flag "precursors --fe" --dc -- precursors --fe
sweep_flag "precursors --fe --dc 1e-6" --max-events -- precursors --fe --dc 1e-6

# edges: its own flags at the defaults, then the scene flags.
for f in --mu --refine --mu-s --mu-d --t-over-l --open-refine --end-grading --h-over-l \
    --length --thickness --young --poisson --max-dofs; do
    sweep_flag edges "$f" -- edges
done

# sweep: the scene flags as single values, its own flags, the friction sweep's cycles.
for f in "${SCENE_FLAGS[@]}" --interior-tol --edge-fraction --tension-fn; do
    sweep_flag sweep "$f" -- sweep
done
sweep_flag "sweep --friction 0.65,0.58" --cycles -- sweep --friction 0.65,0.58

# The examples of issue 31, as given there.
one slide "--law coulomb --mu" 0 slide --law coulomb --mu 0
one slide "--law slip-weakening --dc" 1e-300 slide --law slip-weakening --dc 1e-300
one slide "--law slip-weakening --dc" 1e300 slide --law slip-weakening --dc 1e300
one slide "--law static-kinetic --cycles" 1e9 slide --law static-kinetic --cycles 1e9
one slide "--law static-kinetic --cycles" 1000000000 slide --law static-kinetic --cycles 1000000000
one "precursors --fe --dc 1e-6" --max-events 1 precursors --fe --dc 1e-6 --max-events 1
one precursors --events 18446744073709551615 precursors --events 18446744073709551615
one sweep --length 0.1:1:1000000000 sweep --length 0.1:1:1000000000
one slide --fields 18446744073709551615 slide --fields 18446744073709551615
one slide --thickness 1 slide --thickness 1
one edges "(defaults)" - edges

echo "$total runs, $bad bad (panic, abort, hang or non-finite output); table: $TSV"
awk -F'\t' 'NR > 1 && $6 != "ok"' "$TSV"
