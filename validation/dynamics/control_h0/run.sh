#!/bin/sh
# The paper's control case H = 0 in dynamics (README.md here): the paper's scene with the
# defaults of `slide --dynamics --law slip-weakening`, the drive in the interface plane.
# Keeps the small tables (summary.csv, advances.csv, dyn_events.csv, run.toml) and the log.
# Usage: run.sh [BIN] (default ./target/release/tribofe, built here).
set -e
cd "$(dirname "$0")/../../.."
BIN=${1:-}
if [ -z "$BIN" ]; then cargo build --release -q; BIN=./target/release/tribofe; fi
here=validation/dynamics/control_h0
tmp=$(mktemp -d)
"$BIN" slide --dynamics --law slip-weakening --height 0 --out "$tmp/h0" > "$here/h0.txt" 2> "$tmp/err"
for f in summary.csv advances.csv dyn_events.csv run.toml; do cp "$tmp/h0/$f" "$here/$f"; done
rm -rf "$tmp"
