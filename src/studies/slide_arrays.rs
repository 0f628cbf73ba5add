//! A slide's run as struct-of-arrays, for hosts that hand it to numpy or a data frame: the
//! per-node fields of every recorded state as one events x nodes row-major array, and the
//! events as columns (the columns of `events.csv`, computed here, not parsed back from text).

use super::slide::SlideResult;
use crate::interface::events::NodeState;

/// A per-node field of the recorded states.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StateField {
    /// Tangential slip u of each node, m (the flat is at rest).
    Slip,
    /// Normal gap v of each node, m.
    Gap,
    /// Tangential force T of each node, N/m (traction x tributary width).
    TangentialForce,
    /// Normal force P of each node, N/m (compression positive).
    NormalForce,
    /// The node's state as a number: 0 stick, 1 slip, 2 open (dimensionless).
    Code,
    /// The real-contact-area proxy A(x)/A_0 = p(x)/p_mean (dimensionless,
    /// [`contact_area_over_a0`]).
    ContactAreaOverA0,
}

impl StateField {
    pub const ALL: [StateField; 6] = [
        StateField::Slip,
        StateField::Gap,
        StateField::TangentialForce,
        StateField::NormalForce,
        StateField::Code,
        StateField::ContactAreaOverA0,
    ];
}

/// The real contact area of a multicontact interface under Amontons friction, relative to its
/// mean: A(x)/A_0 = p(x)/p_mean (dimensionless), p the nodal pressure (normal force `p_force`,
/// N/m, over the tributary width `w`, m) and p_mean = N/L with N the state's own normal force
/// (the sum of `p_force`), so it averages to 1 over the interface of length `l` (m). A
/// state carrying no normal force has no contact: zeros. A proxy: it cannot show the
/// contact area's drop behind a front (ageing, rejuvenation).
pub fn contact_area_over_a0(p_force: &[f64], w: &[f64], l: f64) -> Vec<f64> {
    let n: f64 = p_force.iter().sum();
    if !(n > 0.0 && n.is_finite()) {
        return vec![0.0; p_force.len()];
    }
    let p_mean = n / l;
    p_force.iter().zip(w).map(|(p, w)| p / w / p_mean).collect()
}

/// The events as columns, one entry per event (read off the events and their summaries, so
/// kept states or not); forces in units of mu_s N where the name says so.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct EventColumns {
    /// The event kind's CSV name.
    pub kind: Vec<&'static str>,
    /// Drive X, m; friction force F, N/m; F/(mu_s N) and F^c/(mu_s N) (dimensionless).
    pub x_m: Vec<f64>,
    pub f_n_per_m: Vec<f64>,
    pub f_over_mu_s_n: Vec<f64>,
    pub fc_over_mu_s_n: Vec<f64>,
    /// Nucleation node and its x/L; arrest x/L (the region end farther from nucleation).
    pub node: Vec<usize>,
    pub x_nucleation_over_l: Vec<f64>,
    pub x_arrest_over_l: Vec<f64>,
    /// The slipped region's ends and length over L (the nucleation node when none).
    pub region_first_over_l: Vec<f64>,
    pub region_last_over_l: Vec<f64>,
    pub slipped_length_over_l: Vec<f64>,
    /// Relaxed force F*/(mu_s N); nodes that slipped backwards in the relaxation.
    pub f_relaxed_over_mu_s_n: Vec<f64>,
    pub backslip_nodes: Vec<usize>,
    /// Largest violation of the state after the event (N/n) and its overload.
    pub max_violation: Vec<f64>,
    pub overload: Vec<f64>,
}

impl SlideResult {
    /// The field over every recorded state: a row-major array of shape [states, nodes] (one
    /// row, the last state, for a run that did not keep its states).
    pub fn field(&self, which: StateField) -> (Vec<f64>, [usize; 2]) {
        let n = self.condensed.n;
        let states = &self.run.states;
        let mut out = Vec::with_capacity(states.len() * n);
        for s in states {
            match which {
                StateField::Slip => out.extend_from_slice(&s.u),
                StateField::Gap => out.extend_from_slice(&s.gap),
                StateField::TangentialForce => out.extend_from_slice(&s.t_force),
                StateField::NormalForce => out.extend_from_slice(&s.p_force),
                StateField::Code => out.extend(s.states.iter().map(|st| match st {
                    NodeState::Stick => 0.0,
                    NodeState::Slip(_) => 1.0,
                    NodeState::Open => 2.0,
                })),
                StateField::ContactAreaOverA0 => {
                    out.extend(contact_area_over_a0(&s.p_force, &self.condensed.w, self.condensed.l))
                }
            }
        }
        (out, [states.len(), n])
    }

    /// x/L of the region end farther from the nucleation node (the node itself without a
    /// region).
    pub fn arrest_over_l(&self, node: usize, region: Option<(usize, usize)>) -> f64 {
        let (x, l) = (&self.condensed.x, self.condensed.l);
        match region {
            Some((a, b)) if node.abs_diff(a) > node.abs_diff(b) => x[a] / l,
            Some((_, b)) => x[b] / l,
            None => x[node] / l,
        }
    }

    /// The events as columns (the numbers of `events.csv`).
    pub fn event_columns(&self) -> EventColumns {
        let mu_s = self.options.law.mu_s().max(f64::MIN_POSITIVE);
        let scale = mu_s * self.options.n_force;
        let c = &self.condensed;
        let mut t = EventColumns::default();
        for (e, st) in self.run.events.iter().zip(&self.run.summaries) {
            let (first, last, len) = match e.region {
                Some((a, b)) => (c.x[a] / c.l, c.x[b] / c.l, c.w[a..=b].iter().sum::<f64>() / c.l),
                None => (c.x[e.node] / c.l, c.x[e.node] / c.l, 0.0),
            };
            t.kind.push(e.kind.name());
            t.x_m.push(e.x);
            t.f_n_per_m.push(e.f);
            t.f_over_mu_s_n.push(e.f / scale);
            t.fc_over_mu_s_n.push(self.f_c(e.x) / scale);
            t.node.push(e.node);
            t.x_nucleation_over_l.push(c.x[e.node] / c.l);
            t.x_arrest_over_l.push(self.arrest_over_l(e.node, e.region));
            t.region_first_over_l.push(first);
            t.region_last_over_l.push(last);
            t.slipped_length_over_l.push(len);
            t.f_relaxed_over_mu_s_n.push(e.f_relaxed / scale);
            t.backslip_nodes.push(e.backslip);
            t.max_violation.push(st.max_violation);
            t.overload.push(st.overload);
        }
        t
    }
}
