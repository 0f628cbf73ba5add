//! The events manager: the complementarity checks of a state (violations, the recorded
//! state), the rate problem at a fixed load (which change the current solution asks for) and
//! the search for the next event (the smallest load increment at which an inequality of the
//! current states reaches equality). Reads the solution only, never S.

use super::active::Solver;
use super::operator::Affine;
use super::{tolerances, EventKind, NodeState, Phase, State, Violations};
use crate::error::Result;

/// What one rate-consistency check did.
#[derive(Debug, Clone, Copy)]
pub(super) enum Fix {
    None,
    Changed(usize, EventKind),
    /// A stuck node must start an instability (static-kinetic).
    Instability(usize),
}

/// Which inequality an event reaches.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Hit {
    Open,
    Close,
    /// Slip direction s that the threshold implies.
    Friction(f64),
}

impl Solver<'_> {
    /// Applies one rate-consistency change at lam if any is needed (the first in node order,
    /// contact before friction); returns what it did. [`Fix::Instability`] names a stuck node
    /// past its threshold when continuous slip is not allowed (static-kinetic): it is returned
    /// only once no other change is needed.
    pub(super) fn rate_fix(&mut self, a: &Affine, lam: f64, allow_continuous_slip: bool) -> Result<Fix> {
        let n = self.set.n;
        let (tf, td) = (tolerances::STATE * self.fscale, tolerances::STATE * self.dscale);
        let (rate_f, rate_d) = self.rate_tols(a);
        if self.stick_fastest_first {
            // The slipping node running back fastest sticks first (see the field).
            let back = (0..n)
                .filter_map(|i| match self.set.states[i] {
                    NodeState::Slip(s) if s * a.b1[i] < -rate_d => Some((i, s * a.b1[i])),
                    _ => None,
                })
                .min_by(|x, y| x.1.total_cmp(&y.1));
            if let Some((i, _)) = back {
                self.set_state(i, NodeState::Stick, a.b(i, lam))?;
                return Ok(Fix::Changed(i, EventKind::Stick));
            }
        }
        if allow_continuous_slip {
            // Static overloads first: a stuck node in contact past its threshold at lam slips
            // before any slipping node sticks by its rate. Node by node, with the rate sticks
            // in between, an overloaded patch (pre-slipped nodes re-armed below their force
            // by slip weakening) relaxes by a Gauss-Seidel sweep that ends only at the cap.
            for i in 0..n {
                let (t, p) = (a.f(i, lam), a.f(n + i, lam));
                if self.set.states[i] == NodeState::Stick && p > tf && t.abs() - self.mu_stick(i) * p > tf {
                    self.set_state(i, NodeState::Slip(-t.signum()), 0.0)?;
                    return Ok(Fix::Changed(i, EventKind::Slip));
                }
            }
        }
        let mut unstable = None;
        for i in 0..n {
            let mu_s = self.mu_stick(i);
            let (t, p, u, g) = (a.f(i, lam), a.f(n + i, lam), a.b(i, lam), a.b(n + i, lam));
            let (t1, p1, u1, g1) = (a.f1[i], a.f1[n + i], a.b1[i], a.b1[n + i]);
            match self.set.states[i] {
                NodeState::Stick | NodeState::Slip(_) => {
                    if p < -tf || (p <= tf && p1 < -rate_f) {
                        self.set_state(i, NodeState::Open, 0.0)?;
                        return Ok(Fix::Changed(i, EventKind::Open));
                    }
                }
                NodeState::Open => {
                    let close = if self.hold_open[i] {
                        g < -td && g1 <= rate_d
                    } else {
                        g < -td || (g <= td && g1 < -rate_d)
                    };
                    if close {
                        self.set_state(i, NodeState::Stick, u)?;
                        return Ok(Fix::Changed(i, EventKind::Close));
                    }
                }
            }
            if let NodeState::Slip(s) = self.set.states[i] {
                if s * u1 < -rate_d {
                    self.set_state(i, NodeState::Stick, u)?;
                    return Ok(Fix::Changed(i, EventKind::Stick));
                }
            }
            if self.set.states[i] == NodeState::Stick {
                let sg = if t.abs() > tf { t.signum() } else { t1.signum() };
                let excess = t.abs() - mu_s * p;
                if excess > tf || (excess >= -tf && sg * t1 - mu_s * p1 > rate_f) {
                    let creep = p < self.fscale * self.creep;
                    if allow_continuous_slip || creep {
                        self.set_state(i, NodeState::Slip(-sg), 0.0)?;
                        return Ok(Fix::Changed(
                            i,
                            if creep && !allow_continuous_slip { EventKind::Creep } else { EventKind::Slip },
                        ));
                    }
                    unstable = unstable.or(Some(i));
                }
            }
        }
        // An instability starts from a consistent state: every other change comes first.
        Ok(unstable.map_or(Fix::None, Fix::Instability))
    }

    /// Rate thresholds (forces, displacements) below which a rate counts as zero.
    pub(super) fn rate_tols(&self, a: &Affine) -> (f64, f64) {
        let n = self.set.n;
        let rf = (0..2 * n).map(|i| a.f1[i].abs()).fold(0.0, f64::max).max(1e-300) * tolerances::RATE;
        let rd = (0..2 * n).map(|i| a.b1[i].abs()).fold(0.0, f64::max).max(1e-300) * tolerances::RATE;
        (rf, rd)
    }

    /// Violations of the state at lam (prev_u: u at the previous record, for directions).
    pub(super) fn violations(&self, a: &Affine, lam: f64, prev_u: Option<&[f64]>) -> Violations {
        let n = self.set.n;
        let (fs, ds) = (self.fscale, self.dscale);
        let mut v = Violations::default();
        let mu_s = self.law().mu_s();
        let mu_d = self.law().mu_d();
        for i in 0..n {
            let (t, p, u, g) = (a.f(i, lam), a.f(n + i, lam), a.b(i, lam), a.b(n + i, lam));
            v.pressure = v.pressure.max(-p / fs);
            v.gap = v.gap.max(-g / ds);
            v.complementarity = v.complementarity.max((p * g).abs() / (fs * ds));
            match self.set.states[i] {
                NodeState::Stick if mu_d < mu_s => {
                    v.overload = v.overload.max((t.abs() - self.mu_stick(i) * p) / fs)
                }
                NodeState::Stick => v.friction = v.friction.max((t.abs() - mu_s * p) / fs),
                NodeState::Slip(s) => {
                    v.friction = v.friction.max((t.abs() - self.set.mu_slip[i] * p).abs() / fs);
                    v.direction = v.direction.max(s * t / fs);
                    if let Some(pu) = prev_u {
                        v.direction = v.direction.max(-s * (u - pu[i]) / ds);
                    }
                }
                NodeState::Open => {
                    v.friction = v.friction.max(t.abs() / fs).max(p.abs() / fs);
                }
            }
        }
        // Equilibrium: the free rows' forces equal the applied ones.
        let nk = match self.set.phase {
            Phase::Normal => -self.set.n_force * lam,
            Phase::Drive => -self.set.n_force,
        };
        for d in 0..self.set.nd() {
            // The border's free DOFs carry N (a plate's V) or nothing; its pinned ones (the
            // drive, the pressure's amplitude) are not equations.
            let target = if d >= 2 * n {
                self.set.is_free(d).then(|| if self.set.ext_force(d) == (0.0, 0.0) { 0.0 } else { nk })
            } else if self.set.is_free(d) {
                Some(if d < n { -self.set.slip_coef(d) * a.f(n + d, lam) } else { 0.0 })
            } else {
                None
            };
            if let Some(tg) = target {
                v.equilibrium = v.equilibrium.max((a.f(d, lam) - tg).abs() / fs);
            }
        }
        v
    }

    pub(crate) fn record(&self, a: &Affine, lam: f64, prev_u: Option<&[f64]>) -> State {
        let n = self.set.n;
        let x = if self.set.phase == Phase::Drive { lam } else { 0.0 };
        let nf = if self.set.phase == Phase::Normal { self.set.n_force * lam } else { self.set.n_force };
        State {
            phase: self.set.phase,
            x,
            n_force: nf,
            f: a.f(self.iu(), lam),
            tilt: self.set.ith().map_or(0.0, |d| a.b(d, lam)),
            v: self.set.iv().map_or(0.0, |d| a.b(d, lam)),
            t_force: (0..n).map(|i| a.f(i, lam)).collect(),
            p_force: (0..n).map(|i| a.f(n + i, lam)).collect(),
            u: (0..n).map(|i| a.b(i, lam)).collect(),
            gap: (0..n).map(|i| a.b(n + i, lam)).collect(),
            states: self.set.states.clone(),
            violations: self.violations(a, lam, prev_u),
        }
    }

    /// Whether an inequality of the current states is violated at lam beyond the state
    /// tolerances (a stuck node past its threshold, a node in contact pulled, an open node
    /// penetrating): the load step that led here passed an event.
    pub(super) fn overshoots(&self, a: &Affine, lam: f64) -> bool {
        let n = self.set.n;
        let (tf, td) = (tolerances::STATE * self.fscale, tolerances::STATE * self.dscale);
        (0..n).any(|i| {
            let (t, p, g) = (a.f(i, lam), a.f(n + i, lam), a.b(n + i, lam));
            match self.set.states[i] {
                NodeState::Stick => p < -tf || t.abs() - self.mu_stick(i) * p > tf,
                NodeState::Slip(_) => p < -tf,
                NodeState::Open => g < -td,
            }
        })
    }

    /// Smallest lam increment at which an inequality of the current states reaches equality:
    /// (increment, node, what).
    pub(super) fn next_event(&self, a: &Affine, lam: f64) -> Option<(f64, usize, Hit)> {
        let n = self.set.n;
        let (rf, rd) = self.rate_tols(a);
        let mut best: Option<(f64, usize, Hit)> = None;
        let mut consider = |g: f64, g1: f64, i: usize, h: Hit| {
            let tol = if matches!(h, Hit::Close) { rd } else { rf };
            if g1 < -tol {
                let d = (g / -g1).max(0.0);
                if best.is_none_or(|b| d < b.0) {
                    best = Some((d, i, h));
                }
            }
        };
        for i in 0..n {
            let (t, p, g) = (a.f(i, lam), a.f(n + i, lam), a.b(n + i, lam));
            let (t1, p1, g1) = (a.f1[i], a.f1[n + i], a.b1[n + i]);
            match self.set.states[i] {
                NodeState::Stick => {
                    let mu_s = self.mu_stick(i);
                    consider(p, p1, i, Hit::Open);
                    consider(mu_s * p - t, mu_s * p1 - t1, i, Hit::Friction(-1.0));
                    consider(mu_s * p + t, mu_s * p1 + t1, i, Hit::Friction(1.0));
                }
                NodeState::Slip(_) => consider(p, p1, i, Hit::Open),
                NodeState::Open => consider(g, g1, i, Hit::Close),
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::super::springs;
    use super::*;
    use crate::interface::events::Problem;
    use crate::law::{Law, Rule};

    // Two nodes at x = -a, +a; kt = 1, kn = 2 N/m per m, a = 1, h = 0.5, N = 1 (any units).
    // The drive's moment tilts the plate (theta < 0), unloading the trailing node 0.
    const KT: f64 = 1.0;
    const KN: f64 = 2.0;
    const H: f64 = 0.5;
    const N: f64 = 1.0;

    fn problem(mu_s: f64, mu_d: f64) -> Problem {
        Problem {
            n_force: N,
            law: Law::static_kinetic(mu_s, mu_d, Rule::Paper).unwrap(),
            ..Default::default()
        }
    }

    /// Both nodes stuck at 0: V = -N/(2 kn); the moment balance
    /// 2 kt h (lam + h theta) + 2 kn a^2 theta = 0 gives theta = -c lam, c = kt h/(kt h^2 + kn a^2);
    /// T_i = -kt (1 - h c) lam, P_0 = N/2 - kn a c lam. Node 0 reaches T = -mu_s P at
    /// lam* = mu_s N/2 / (mu_s kn c + kt (1 - h c)), before node 1 (more pressure) and before
    /// it opens (P_0 = 0 at N/(2 kn c)).
    #[test]
    fn two_stuck_nodes_reach_the_hand_computed_threshold() {
        let s = springs::operator(&[-1.0, 1.0], &[KT, KT], KN, H);
        let mu_s = 0.6;
        let sv = springs::solver(&s, 2, &problem(mu_s, 0.3));
        let mut sv = sv;
        let a = sv.solve().unwrap();
        let c = KT * H / (KT * H * H + KN);
        let want = mu_s * N / 2.0 / (mu_s * KN * c + KT * (1.0 - H * c));
        let (d, i, hit) = sv.next_event(&a, 0.0).unwrap();
        assert_eq!((i, hit), (0, Hit::Friction(1.0)));
        assert!((d - want).abs() < 1e-12 * want, "lam {d} vs {want}");
        // From lam = 0.1 the increment is what remains.
        let (d, ..) = sv.next_event(&a, 0.1).unwrap();
        assert!((d - (want - 0.1)).abs() < 1e-12 * want, "increment {d} vs {}", want - 0.1);
        // At lam*: T_0 = -mu_s P_0, the state is admissible and nothing needs a fix before.
        let st = sv.record(&a, want, None);
        assert!((st.t_force[0] + mu_s * st.p_force[0]).abs() < 1e-12 * N);
        assert!((st.f - 2.0 * KT * (1.0 - H * c) * want).abs() < 1e-12 * N, "F {}", st.f);
        assert!(st.violations.max() < 1e-12, "{:?}", st.violations);
        assert!(matches!(sv.rate_fix(&a, 0.5 * want, false).unwrap(), Fix::None));
        // Past it the static-kinetic node must start an instability.
        assert!(matches!(sv.rate_fix(&a, want * (1.0 + 1e-6), false).unwrap(), Fix::Instability(0)));
    }

    /// Node 0 slipping forward at mu_d (T_0 = -mu_d P_0), node 1 stuck at the anchor al: the
    /// moment balance -h (T_0 + T_1) + 2 kn a^2 theta = 0 with P_0 = N/2 + kn a theta and
    /// T_1 = kt (al - lam - h theta) gives theta(lam) = h (kt (al - lam) - mu_d N/2) / D,
    /// D = 2 kn a^2 + h mu_d kn a + h^2 kt; node 1 reaches -T_1 = mu_s P_1 = mu_s (N/2 - kn a
    /// theta) where that linear function of lam vanishes.
    #[test]
    fn a_slipping_and_an_anchored_node_reach_the_hand_computed_threshold() {
        let s = springs::operator(&[-1.0, 1.0], &[KT, KT], KN, H);
        let (mu_s, mu_d, al) = (0.6, 0.3, 0.05);
        let mut sv = springs::solver(&s, 2, &problem(mu_s, mu_d));
        sv.set_state(0, NodeState::Slip(1.0), 0.0).unwrap();
        sv.move_anchor(1, al);
        let a = sv.solve().unwrap();
        let dd = 2.0 * KN + H * mu_d * KN + H * H * KT;
        let theta = |lam: f64| H * (KT * (al - lam) - mu_d * N / 2.0) / dd;
        let excess = |lam: f64| -KT * (al - lam - H * theta(lam)) - mu_s * (N / 2.0 - KN * theta(lam));
        let want = -excess(0.0) / (excess(1.0) - excess(0.0));
        let (d, i, hit) = sv.next_event(&a, 0.0).unwrap();
        assert_eq!((i, hit), (1, Hit::Friction(1.0)));
        assert!((d - want).abs() < 1e-12 * want, "lam {d} vs {want}");
        let st = sv.record(&a, want, None);
        assert!(
            (st.tilt - theta(want)).abs() < 1e-12 * theta(want).abs(),
            "theta {} vs {}",
            st.tilt,
            theta(want)
        );
        assert!((st.t_force[0] + mu_d * st.p_force[0]).abs() < 1e-12 * N);
        assert!((st.u[1] - al).abs() == 0.0, "the anchor holds exactly");
    }
}
