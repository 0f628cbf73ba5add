#!/bin/sh
# One run of the convergence study (README.md here): the first cycle to the front crossing in
# dynamics at fixed kappa (D_c fixed as h halves, so the cohesive zone spans 3, 6, 12 elements
# at h = 0.5, 0.25, 0.125 mm).
# Usage: run.sh R G H_MM DC_M [TIMEOUT_S]; from the environment: ETA (the damping eta, s;
# default the solver's, 10 % of critical at the thickness mode), WSTEPS (the static loading's
# slip-weakening coefficient updates per D_c of slip; default the solver's 20), X_MAX (m: stop there, before
# the crossing, e.g. past the peak when the whole cycle is too long), RULE (paper or overdamped:
# the quasi-static static-kinetic rule instead, same scene and mesh, DC ignored), BIN (default
# ./target/release/tribofe, built), OUT_ROOT (default /tmp/converge) and LOG_DIR (default
# this folder). Writes the log (progress redraws removed) in LOG_DIR and the outputs
# (events.csv, advances.csv, loading.csv, ...) in OUT_ROOT.
set -e
cd "$(dirname "$0")/../../.."
r=$1; g=$2; h=$3; dc=$4; lim=${5:-7200}
if [ -z "$BIN" ]; then cargo build --release; BIN=./target/release/tribofe; fi
root=${OUT_ROOT:-/tmp/converge}
here=${LOG_DIR:-validation/dynamics/converge}
hm=$(python3 -c "print($h / 1000)")
tag="r${r}_g${g}_h${h}_dc${dc}"
damp=""
if [ -n "$ETA" ]; then damp="--damping $ETA"; tag="${tag}_eta$ETA"; fi
if [ -n "$WSTEPS" ]; then damp="$damp --weakening-steps $WSTEPS"; tag="${tag}_ws$WSTEPS"; fi
law="--dynamics --law slip-weakening --dc $dc $damp"
if [ -n "$X_MAX" ]; then law="$law --x-max $X_MAX"; fi
if [ -n "$RULE" ]; then law="--law static-kinetic --rule $RULE"; tag="r${r}_g${g}_h${h}_qs_$RULE"; fi
mkdir -p "$root" "$here"
nice timeout "$lim" /usr/bin/time -v "$BIN" slide $law --r "$r" --g "$g" --h "$hm" --operator banded \
  --cycles 1 --cycle-end crossing --states none --max-events "${MAX_EVENTS:-60000}" \
  --out "$root/$tag" --force > "$root/$tag.log" 2>&1 || echo "exit $?" >> "$root/$tag.log"
sed 's/slide [-a-z]* *[0-9.]* %//g' "$root/$tag.log" > "$here/$tag.log"
