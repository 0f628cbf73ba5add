#!/usr/bin/env bash
# Hostile inputs, second round (issue 45): every numeric flag of `slide --dynamics` (held and
# constant-velocity drive) and `rupture` at NaN, inf, -inf, -1, 0, 1e-308, 1e308 and 2^64 - 1,
# the issue's reproductions, the output-folder cases (a user's files inside and beside a
# tribofe folder, --write-scene onto what is not a new regular file) and, when the package is
# installed, the Python API (hostile_python.py). Each run: `timeout` under `ulimit -v 8000000`
# (KiB), its exit status and time in the TSV. BAD: a panic (101), an abort (134), a hang
# (124), exit 0 with a non-finite number or a violated self-check (loading.csv's
# max_violation above 1e-6 of the load) in its output, or a user file lost or changed.
# Usage: bash validation/inputs/hostile_dynamics.sh [--quick] [TSV]
#   --quick: four values a flag and a 30 s timeout (CI, under 3 minutes); otherwise eight
#   values and 60 s (about 10 minutes on 2 busy cores).
set -uo pipefail
cd "$(dirname "$0")/../.."
QUICK=0
if [ "${1:-}" = --quick ]; then QUICK=1; shift; fi
cargo build --release -q
BIN=$PWD/target/release/tribofe
TSV=${1:-validation/inputs/hostile_dynamics.tsv}
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
if [ $QUICK = 1 ]; then
    VALUES=(nan -inf 0 1e308); LIMIT=30
else
    VALUES=(nan inf -inf -1 0 1e-308 1e308 18446744073709551615); LIMIT=60
fi
printf 'command\tflag\tvalue\texit\tseconds\tverdict\tmessage\n' > "$TSV"
bad=0
total=0

# row LABEL FLAG VALUE CODE SECONDS VERDICT: appends a row and counts it.
row() {
    local msg
    msg=$(grep -m1 -E '^error' "$WORK/stderr" 2>/dev/null | cut -c1-160 | tr '\t' ' ')
    [ -n "$msg" ] || msg=$( [ "$4" = 0 ] && echo "(finished)" || head -c 160 "$WORK/stderr" 2>/dev/null | tr '\n\t' '  ')
    [ "$6" = ok ] || bad=$((bad + 1))
    total=$((total + 1))
    printf '%s\t%s\t%s\t%s\t%.2f\t%s\t%s\n' "$1" "$2" "$3" "$4" "$5" "$6" "$msg" >> "$TSV"
}

# verdict CODE OUT: the class of a finished run whose output folder is OUT.
verdict() {
    case $1 in
        101) echo PANIC ;;
        134) echo ABORT ;;
        124) echo HANG ;;
        0)
            if grep -qiwE 'nan|[-+]?inf' "$WORK/stdout" || { [ -d "$2" ] && grep -rqiwE 'nan|[-+]?inf' "$2" --include='*.csv'; }; then
                echo NONFINITE
            elif [ -f "$2/loading.csv" ] && ! awk -F, 'NR > 1 && ($NF + 0 > 1e-6) {bad = 1} END {exit bad}' "$2/loading.csv"; then
                echo VIOLATED
            else
                echo ok
            fi ;;
        *) echo ok ;;
    esac
}

# one LABEL FLAG VALUE ARGS...: runs tribofe ARGS --out DIR, appends a row.
one() {
    local label=$1 flag=$2 value=$3; shift 3
    local out=$WORK/out t0 code
    rm -rf "$out"
    t0=$(date +%s.%N)
    ( ulimit -v 8000000; exec timeout "$LIMIT" "$BIN" "$@" --out "$out" ) >"$WORK/stdout" 2>"$WORK/stderr" </dev/null
    code=$?
    row "$label" "$flag" "$value" "$code" "$(echo "$(date +%s.%N) - $t0" | bc)" "$(verdict "$code" "$out")"
}

sweep_flag() {
    local label=$1 flag=$2; shift 3
    for v in "${VALUES[@]}"; do
        one "$label" "$flag" "$v" "$@" "$flag=$v"
    done
}

# slide --dynamics on a short block (L = 0.1 m, a few seconds at most when accepted). A flag
# is given once (a repeated one is refused by the parser before any check), so the base
# leaves out the flag under test.
DYN=(slide --dynamics --law slip-weakening --length 0.1)
for f in --dc --damping --courant --weakening-steps --density --cycles --max-events \
    --h --n-force --height --plate-mass --plate-inertia; do
    sweep_flag "slide --dynamics" "$f" -- "${DYN[@]}" --x-max 2e-6
done
sweep_flag "slide --dynamics" --x-max -- "${DYN[@]}"
# The constant-velocity drive at the largest V slip weakening accepts (a tenth of its event
# threshold), to X = 2e-7 m (2e4 steps).
for f in --plate-mass --plate-inertia; do
    sweep_flag "slide --dynamics --drive-velocity 1.9e-7" "$f" -- "${DYN[@]}" --x-max 2e-7 --drive-velocity 1.9e-7
done
sweep_flag "slide --dynamics --drive-velocity" --drive-velocity -- "${DYN[@]}" --x-max 2e-7
sweep_flag "slide --dynamics --drive-velocity 1.9e-7" --x-max -- "${DYN[@]}" --drive-velocity 1.9e-7
sweep_flag "slide --dynamics --law coulomb" --x-max -- slide --dynamics --law coulomb --length 0.1
# Rate-and-state under the constant-velocity drive (a block driven at its top, 620 steps), each
# of its flags and the normal response's swept with the others at accepted values.
declare -A RS=([--a]=0.01 [--b]=0.005 [--l-rs]=4e-7 [--f0]=0.6)
for f in --a --b --l-rs --f0 --v0 --theta0 --normal-lag --normal-lag-length; do
    base=(slide --dynamics --law rate-state --length 0.1 --height 0.002 --drive-velocity 2e-5 --x-max 2e-6)
    for k in "${!RS[@]}"; do [ "$k" = "$f" ] || base+=("$k" "${RS[$k]}"); done
    sweep_flag "slide --dynamics --law rate-state" "$f" -- "${base[@]}"
done

# rupture at a short end time.
for f in --s --h --dc --t-end --length --height --mu-s --mu-d --sigma0 --young --poisson \
    --density --courant --damping --normal-lag --normal-lag-length --patch-taper; do
    sweep_flag rupture "$f" -- rupture --t-end 0.02
done

# The reproductions of issue 45.
one "slide --dynamics --law coulomb" --x-max -1 slide --dynamics --law coulomb --x-max -1
one "slide --dynamics" --cycles 0 "${DYN[@]}" --cycles 0
one "slide --dynamics" --drive-velocity 10 "${DYN[@]}" --drive-velocity 10
one rupture --damping 1e200 rupture --damping 1e200
one rupture --t-end 1e12 rupture --t-end 1e12
one rupture --young 1e300 rupture --young 1e300
one rupture --density 1e-300 rupture --density 1e-300
one rupture --courant 1e-300 rupture --courant 1e-300
one "precursors thin-layer" "" default precursors thin-layer
one slide "--n-force" 0 slide --n-force 0
# Plane stress (issue 49): the out-of-plane width of every numeric kind, and no width at all.
sweep_flag "check --plane-stress" --width -- check --plane-stress --no-converged --no-fields
sweep_flag "slide --dynamics --plane-stress" --width -- "${DYN[@]}" --x-max 2e-6 --plane-stress
one "check --plane-stress" "--width" none check --plane-stress --no-converged --no-fields

# Output folders: nothing of the user's lost or changed.
# folder LABEL CHECK-COMMAND: records ok when CHECK-COMMAND succeeds, LOST otherwise.
folder() {
    local v=ok
    eval "$2" || v=LOST
    : > "$WORK/stderr"
    row folders "$1" - "$code" 0 "$v"
}
F=$WORK/f
mkdir -p "$F"
"$BIN" check --no-converged --no-fields --out "$F/run" >/dev/null 2>&1
echo note > "$F/run/my_note.txt"; mkdir -p "$F/run/mine"; echo x > "$F/run/mine/data"
"$BIN" check --no-converged --no-fields --out "$F/run" --force >/dev/null 2>&1; code=$?
folder "a user's file and subfolder inside a previous output survive a rerun" \
    '[ "$(cat "$F/run/my_note.txt")" = note ] && [ "$(cat "$F/run/mine/data")" = x ]'
mkdir -p "$F/user"; echo mine > "$F/user/keep.txt"; cp "$F/run/run.toml" "$F/user/run.toml"
"$BIN" check --no-converged --no-fields --out "$F/user" >/dev/null 2>&1; code=$?
folder "a copied run.toml does not make a user's folder replaceable (refused, kept)" \
    '[ $code != 0 ] && [ "$(cat "$F/user/keep.txt")" = mine ]'
mkfifo "$F/fifo"
"$BIN" check --no-converged --no-fields --out "$F/o1" --write-scene "$F/fifo" >/dev/null 2>&1; code=$?
folder "--write-scene onto a FIFO refused" '[ $code != 0 ] && [ -p "$F/fifo" ] && [ ! -e "$F/o1" ]'
echo 'mine' > "$F/scene.toml"
"$BIN" check --no-converged --no-fields --out "$F/o2" --write-scene "$F/scene.toml" >/dev/null 2>&1; code=$?
folder "--write-scene onto an existing file refused, file unchanged" '[ $code != 0 ] && [ "$(cat "$F/scene.toml")" = mine ]'
ln -s "$F/scene.toml" "$F/link.toml"
"$BIN" check --no-converged --no-fields --out "$F/o3" --write-scene "$F/link.toml" --force >/dev/null 2>&1; code=$?
folder "--write-scene onto a link refused even with --force" '[ $code != 0 ] && [ "$(cat "$F/scene.toml")" = mine ] && [ -L "$F/link.toml" ]'
"$BIN" slide --law nonsense --out "$F/o4" --write-scene "$F/new.toml" >/dev/null 2>&1; code=$?
folder "a refused run writes nothing (no folder, no scene)" '[ $code = 2 ] && [ ! -e "$F/o4" ] && [ ! -e "$F/new.toml" ]'
"$BIN" rupture --t-end 0.01 --normal-lag 0 --out "$F/rup" >/dev/null 2>&1
echo keep > "$F/rup/keep.txt"
"$BIN" rupture --t-end 0.01 --out "$F/rup" --force >/dev/null 2>&1; code=$?
folder "rupture: a user's file inside its previous output survives a rerun" '[ "$(cat "$F/rup/keep.txt")" = keep ]'

# The Python API, when the package is installed.
if python3 -c 'import tribofe' 2>/dev/null; then
    python3 validation/inputs/hostile_python.py --timeout "$LIMIT" $( [ $QUICK = 1 ] && echo --quick ) > "$WORK/py.tsv"
    while IFS=$'\t' read -r label flag value code secs verdict msg; do
        [ "$verdict" = ok ] || bad=$((bad + 1))
        total=$((total + 1))
        printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$label" "$flag" "$value" "$code" "$secs" "$verdict" "$msg" >> "$TSV"
    done < "$WORK/py.tsv"
else
    echo "(the Python package is not installed: its cases are skipped)"
fi

echo "$total runs, $bad bad (panic, abort, hang, non-finite output, violated self-check or user file lost); table: $TSV"
awk -F'\t' 'NR > 1 && $6 != "ok"' "$TSV"
[ "$bad" = 0 ]
