#!/bin/sh
# Assumption 5 measured as the model needs it (README.md here): the first cycle to the front
# crossing in dynamics on the paper's scene and two more (r, g), at the convergence study's
# fixed kappa = 0.51 and h = 0.5 mm (validation/dynamics/converge/run.sh's command), then
# table.py over their dyn_events.csv. ~1 min of CPU in all. From the environment: BIN
# (default $CARGO_TARGET_DIR/release/tribofe or ./target/release/tribofe, built) and OUT_ROOT
# (default /tmp/assumption5: the runs' outputs, not kept). Writes here: one log per scene
# (progress redraws removed), instabilities_<scene>.csv (the assumption-5 columns of each
# instability), table.csv and table.md.
set -e
cd "$(dirname "$0")/../../.."
if [ -z "$BIN" ]; then
  cargo build --release
  BIN=${CARGO_TARGET_DIR:-./target}/release/tribofe
fi
root=${OUT_ROOT:-/tmp/assumption5}
here=validation/dynamics/assumption5
mkdir -p "$root"
# r g D_c (m): kappa = G D_c / ((mu_s - mu_d) p t) = 0.51 on each (validation/dynamics/converge).
for scene in "0.9 0.35 2.3107e-7" "0.8 0.2 2.9709e-7" "0.7 0.5 1.274e-6"; do
  set -- $scene
  tag="r$1_g$2_h0.5_dc$3"
  nice /usr/bin/time -v "$BIN" slide --dynamics --law slip-weakening --dc "$3" --r "$1" --g "$2" \
    --h 0.0005 --operator banded --cycles 1 --cycle-end crossing --states none \
    --max-events 60000 --out "$root/$tag" --force > "$root/$tag.log" 2>&1 || echo "exit $?" >> "$root/$tag.log"
  sed 's/slide [-a-z]* *[0-9.]* %//g' "$root/$tag.log" > "$here/$tag.log"
done
python3 "$here/table.py" "$root" "$here"
