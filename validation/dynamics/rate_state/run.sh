#!/bin/sh
# The paper's scene under rate-and-state friction (issue 47): the rate-weakening calibration
# of calib.py, the rate-strengthening control and slip weakening, each driven at constant
# velocity. Writes out/<run>/ and out/<run>.log here, then table.py writes table.csv,
# table.md and envelope.svg. Usage: sh validation/dynamics/rate_state/run.sh [tribofe]
set -e
B=${1:-target/release/tribofe}
D=$(dirname "$0")
mkdir -p "$D/out"
python3 "$D/calib.py" > "$D/calib.csv"
# The paper's scene (its defaults: L = 0.4 m, t = 2 mm, H = 4 cm, N = 1 N/m, E = 2 kPa,
# nu = 0.4, rho = 1000 kg/m^3), h = 0.5 mm (the slip-weakening default at kappa = 0.509;
# rate-and-state's L_b = 3.05 h), to X = 1e-5 m (the held slip-weakening crossing is at
# 7.65e-6 m).
S="--h 0.0005 --x-max 1e-5"
RS="--law rate-state --b 0.00479753 --l-rs 1.53842e-8 --f0 0.648148148148148 --theta0 100"
run() { name=$1; shift; $B slide --dynamics $S "$@" --out "$D/out/$name" --force > "$D/out/$name.log" 2>&1; }
# The two rate-and-state runs side by side (one core each, about 8-15 min), slip weakening
# after the first of them.
# (a) rate weakening, a = b/10, at the drive V = V_load = 1e-6 m/s
run rw $RS --a 0.000479753 --v0 5.79986e-11 --drive-velocity 1e-6 &
P1=$!
# (b) the rate-strengthening control, a = 1.9 b, same b, L, hold and drive
run rs_control $RS --a 0.00911531 --v0 0.0172418 --drive-velocity 1e-6 &
P2=$!
wait $P1
# (c) slip weakening (the defaults: D_c = 2.3107e-7 m) at the largest V it accepts
run sw --law slip-weakening --drive-velocity 1.9e-7
wait $P2
python3 "$D/table.py" "$D"
