//! Fields of a frictional state from the full model: with the interface and plate DOFs
//! prescribed at the state's values, the block's consistent reactions at the interface must
//! be the state's nodal forces, which the events solver got from the condensed matrix; the
//! two differ only by round-off (S is symmetrised at ~1e-17 of its largest entry).

use tribofe::fem::recovery::{elements_touching, internal_forces};
use tribofe::interface::law::Law;
use tribofe::linalg::solve::SolverOptions;
use tribofe::scene::Scene;
use tribofe::studies::slide::{run, state_displacements, SlideOptions};

#[test]
fn full_field_reactions_are_the_condensed_interface_forces() {
    let mut s = Scene::default();
    s.mesh.h = 0.002;
    s.mesh.n_thick = Some(2);
    let o = SlideOptions { law: Law::coulomb(0.5).unwrap(), ..Default::default() };
    let r = run(&s, &o, &|_| {}).unwrap();
    let last = r.run.states.len() - 1;
    let picks = [0, last / 2, last];
    let (sm, us) = state_displacements(&r, &picks, &SolverOptions::default()).unwrap();
    let model = sm.model();
    let elems = elements_touching(&model, &sm.interface);
    let nodal = o.n_force / r.condensed.n as f64;
    for (&k, u) in picks.iter().zip(&us) {
        let st = &r.run.states[k];
        let f = internal_forces(&model, u, &elems).unwrap();
        for (i, &node) in sm.interface.iter().enumerate() {
            // Both are the consistent reactions K u at the interface DOFs.
            let (t, p) = (f[2 * node], f[2 * node + 1]);
            let err = (t - st.t_force[i]).abs().max((p - st.p_force[i]).abs());
            assert!(
                err < 1e-9 * nodal,
                "state {k}, node {i}: {t} {p} vs {} {}",
                st.t_force[i],
                st.p_force[i]
            );
        }
    }
    assert!(state_displacements(&r, &[last + 1], &SolverOptions::default()).is_err());
}
