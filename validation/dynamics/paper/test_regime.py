"""Checks of regime.py's arrest predictions against their closed forms (pytest, < 1 s).

Run: python3 -m pytest -q validation/dynamics/paper/test_regime.py
Scene: uniform prestress tau0 = T and p(x) = 1 + a x (units of N/L, x in units of L), the
paper's layer state just before its first precursor. The arrest node must be the first node at
or past the closed-form arrest point x*, so the tolerance is one node spacing.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import regime as rg  # noqa: E402

N = 801
X = [-0.5 + i / (N - 1) for i in range(N)]
A = 0.56  # 12 (F/N)(H/L) at F = 0.72 mu_s N: the model's tilt of p
P = [1.0 + A * x for x in X]
T = 0.72 * rg.MU_S  # F_1 / L of the model


def first_at_or_past(xs):
    return next(i for i, x in enumerate(X) if x >= xs - 1e-12)


def test_zero_gc_arrest_is_where_tau0_equals_mu_d_p():
    """tau0 = mu_d (1 + a x*): x* = (T / mu_d - 1) / a, the model's x_1 = -0.357 at (0.9, 0.35)."""
    xs = (T / rg.MU_D - 1.0) / A
    assert abs(xs - (-0.357)) < 2e-3
    i = rg.arrest(X, P, [T] * N, 0, 0.5, False)
    assert i == first_at_or_past(xs)


def test_griffith_arrest_solves_the_thin_layer_energy_balance():
    """T - mu_d P = (mu_s - mu_d) sqrt(kappa P): a quadratic in s = sqrt(P)."""
    for kappa in (0.05, 0.25, 0.51, 0.9):
        b = (rg.MU_S - rg.MU_D) * math.sqrt(kappa)
        s = (-b + math.sqrt(b * b + 4 * rg.MU_D * T)) / (2 * rg.MU_D)
        xs = (s * s - 1.0) / A
        i = rg.arrest(X, P, [T] * N, 0, kappa, True)
        assert i == first_at_or_past(xs), kappa
        # a finite fracture energy stops the front short of the zero-G_c point
        assert X[i] < X[rg.arrest(X, P, [T] * N, 0, kappa, False)]


def test_griffith_at_kappa_one_lets_no_front_run_into_weaker_prestress():
    """Local kappa = 1: the condition is tau0 >= mu_s p, so with tau0 at the strength at the
    nucleus and tau0/p falling ahead of it the front stops at the next node. (kappa(x) =
    kappa_mean p_mean / p(x): kappa_mean = P[0] makes it 1 at the first node.)"""
    tau = [rg.MU_S * P[0]] * N
    assert rg.arrest(X, P, tau, 0, P[0] * (1 - 1e-12), True) == 1
    # and a mean kappa above 1 there: not even the nucleus node can run
    assert rg.arrest(X, P, tau, 0, 1.0, True) == 0
