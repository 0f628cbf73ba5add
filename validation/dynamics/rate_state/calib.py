"""The rate-and-state calibration of validation/dynamics/rate_state (README.md, "Calibration").

Prints the flags of run.sh. Inputs: the paper's scene (E = 2 kPa, nu = 0.4, L = 0.4 m,
t = 2 mm, N = 1 N/m, rho = 1000 kg/m^3) and its law's mu_s, mu_d ((r, g) = (0.9, 0.35), as
`tribofe slide --dynamics --law slip-weakening` prints them), and the choices:

  V_load = V_drive = 1e-6 m/s   the loading rate of the peak: the plate's
  t_hold = 100 s                the hold before the drive (theta_0 = t_hold, aging law)
  V_slip = (mu_s - mu_d) sigma / (rho c_s)  the fronts' slip rate: the particle velocity of a
                                 shear wave carrying the strength drop (physics::rate_scale)
  a / b = 0.1                   rate weakening, a/b as large as the mesh allows (below)
  k / k_c = 0.509               the layer's stiffness G/t over the critical one sigma (b - a)/L:
                                 the slip-weakening runs' kappa = 0.509

Closed forms (aging law, regularisation negligible: V >> 2 V_0 exp(-psi/a)):
  steady state       mu_ss(V) = f_0 + (a - b) ln(V / V_0)
  peak after a hold  mu_pk = f_0 + a ln(V_load / V_0) + b ln(V_0 t_hold / L)
So mu_pk - mu_ss(V_slip) = a ln(V_load / V_slip) + b ln(t_hold V_slip / L), with
L = (k/k_c) t sigma (b - a) / G: one equation for b. f_0 = mu_s by the choice of V_0
(a change of V_0 with f_0 -> f_0 + (a - b) ln(V_0'/V_0) is the same law), so
F / (f_0 N) in the outputs is F / (mu_s N), and V_0 = V_slip exp(-(mu_s - mu_d)/(b - a)).
Mesh: L_b = G L / ((1 - nu) b sigma) = (k/k_c) t (1 - a/b) / (1 - nu) >= 3 h.

The rate-strengthening control keeps b, L, t_hold, V_load and puts a = b + (b - a_rw)
(a - b = +0.9 b); V_0 keeps the peak after the hold at mu_s (f_0 = mu_s):
ln V_0 = (a ln V_load + b ln(t_hold / L)) / (a - b).
"""
import math

E, NU, LEN, T, N, RHO = 2e3, 0.4, 0.4, 0.002, 1.0, 1000.0
# mu_s, mu_d of (r, g) = (0.9, 0.35) as run.toml of the slip-weakening run writes them.
MU_S, MU_D = 0.648148148148148, 0.5833333333333333
V_LOAD, T_HOLD, AB, KK = 1e-6, 100.0, 0.1, 0.509
G = E / (2 * (1 + NU))
SIG = N / LEN
CS = math.sqrt(G / RHO)
V_SLIP = (MU_S - MU_D) * SIG / (RHO * CS)


def l_of(b):
    return KK * T * SIG * b * (1 - AB) / G


def drop(b):
    a = AB * b
    return a * math.log(V_LOAD / V_SLIP) + b * math.log(T_HOLD * V_SLIP / l_of(b))


lo, hi = 1e-5, 1.0
for _ in range(200):
    mid = math.sqrt(lo * hi)
    if drop(mid) > MU_S - MU_D:
        hi = mid
    else:
        lo = mid
b = math.sqrt(lo * hi)
a = AB * b
L = l_of(b)
v0 = V_SLIP * math.exp(-(MU_S - MU_D) / (b - a))
lb = G * L / ((1 - NU) * b * SIG)


def mu_ss(a_, b_, v0_, v):
    return MU_S + (a_ - b_) * math.log(v / v0_)


def mu_pk(a_, b_, v0_, l_):
    return MU_S + a_ * math.log(V_LOAD / v0_) + b_ * math.log(v0_ * T_HOLD / l_)


ac = b + (b - a)
v0c = math.exp((ac * math.log(V_LOAD) + b * math.log(T_HOLD / L)) / (ac - b))
rows = [
    ("mu_s", MU_S), ("mu_d", MU_D), ("G_Pa", G), ("sigma_Pa", SIG), ("c_s_m_per_s", CS),
    ("V_load_m_per_s", V_LOAD), ("t_hold_s", T_HOLD), ("V_slip_m_per_s", V_SLIP),
    ("a", a), ("b", b), ("L_m", L), ("V0_m_per_s", v0), ("f0", MU_S),
    ("L_crit_m", T * SIG * (b - a) / G), ("L_b_m", lb), ("L_b_over_h_at_0.5mm", lb / 5e-4),
    ("check_peak", mu_pk(a, b, v0, L)), ("check_mu_ss_V_slip", mu_ss(a, b, v0, V_SLIP)),
    ("mu_ss_V_load", mu_ss(a, b, v0, V_LOAD)),
    ("control_a", ac), ("control_b", b), ("control_V0_m_per_s", v0c),
    ("control_check_peak", mu_pk(ac, b, v0c, L)),
    ("control_mu_ss_V_load", mu_ss(ac, b, v0c, V_LOAD)),
    ("control_mu_ss_V_slip", mu_ss(ac, b, v0c, V_SLIP)),
]
for k, v in rows:
    print(f"{k},{v:.6g}")
