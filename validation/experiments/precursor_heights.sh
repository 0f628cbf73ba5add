#!/bin/sh
# Study 2 (issue 49): precursor length against F/N as the push height h (side push) and the
# drive height H (top plate) vary, on one block t = L/5, static-kinetic mu_s = 0.4,
# mu_d = 0.17. Writes validation/experiments/precursor_heights.csv, _events.csv and .svg
# (python3 with matplotlib, an optional tool of the validation scripts only).
set -e
cd "$(dirname "$0")/../.."
cargo build --release --quiet
python3 validation/experiments/precursor_heights.py
