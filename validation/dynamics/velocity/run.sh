#!/bin/sh
# Constant drive velocity against the held drive (issues 33, 43). Writes out/ here, then
# table.py prints the tables of README.md. Usage: sh validation/dynamics/velocity/run.sh [tribofe]
set -e
B=${1:-target/release/tribofe}
D=$(dirname "$0")/out
SW="--law slip-weakening --length 0.1 --h 0.0005 --x-max 5.2e-6"
# The held mode with its static coefficients updated every D_c/N of slip.
for N in 20 80 320 1280; do
  $B slide --dynamics $SW --weakening-steps $N --out $D/sw_held_$N --force
done
# The drive at the largest V accepted (a tenth of the event threshold, 1.917e-6 m/s) and
# two halvings.
for V in 1.9e-7 9.5e-8 4.75e-8; do
  $B slide --dynamics --drive-velocity $V $SW --out $D/sw_$V --force
done
C="--law coulomb --mu 0.5 --length 0.1 --h 0.001 --x-max 3.4e-5"
$B slide $C --out $D/c_qs --force
for V in 2e-5 1e-5 5e-6 2.5e-6 1.25e-6; do
  $B slide --dynamics --drive-velocity $V $C --out $D/c_$V --force
done
python3 "$(dirname "$0")/table.py" "$D"
