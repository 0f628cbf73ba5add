//! Fields of a frictional state from the full model: with the interface and plate DOFs
//! prescribed at the state's values, the block's consistent reactions at the interface must
//! be the state's nodal forces, which the events solver got from the condensed matrix; the
//! two differ only by round-off (S is symmetrised at ~1e-17 of its largest entry).

use tribofe::fem::recovery::{elements_touching, internal_forces};
use tribofe::law::Law;
use tribofe::linalg::solve::SolverOptions;
use tribofe::scene::Scene;
use tribofe::studies::slide::{run, state_displacements, SlideOptions};

#[test]
fn full_field_reactions_are_the_condensed_interface_forces() {
    let mut s = Scene::default();
    s.mesh.h = 0.002;
    s.mesh.n_thick = Some(2);
    let o = SlideOptions { law: Law::coulomb(0.5).unwrap(), ..Default::default() };
    let r = run(&s, &o, tribofe::Progress::none()).unwrap();
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

/// `slide --fields`: one state per drive X, the .pvd's timesteps are those X (m), increasing,
/// and each file's `event` field is its state's row.
#[test]
fn field_series_is_indexed_by_x() {
    let mut s = Scene::default();
    s.mesh.h = 0.002;
    s.mesh.n_thick = Some(2);
    let o = SlideOptions {
        law: Law::static_kinetic(0.5, 0.45, "paper".parse().unwrap()).unwrap(),
        ..Default::default()
    };
    let r = run(&s, &o, tribofe::Progress::none()).unwrap();
    let picks = tribofe::report::slide::field_states(&r, 6);
    assert_eq!(picks.len(), 6);
    assert_eq!(*picks.last().unwrap(), r.run.states.len() - 1);
    let xs: Vec<f64> = picks.iter().map(|&k| r.run.states[k].x).collect();
    assert!(xs.windows(2).all(|w| w[1] > w[0]), "{xs:?}");
    // Each pick is the settled state of its X: the next state has moved on.
    assert!(picks.iter().all(|&k| k + 1 == r.run.states.len() || r.run.states[k + 1].x != r.run.states[k].x));
    // A huge request is capped at the number of distinct X, not allocated.
    assert!(tribofe::report::slide::field_states(&r, usize::MAX).len() <= r.run.states.len());
    let dir = tempfile::tempdir().unwrap();
    let written = tribofe::report::slide::write_fields(
        &r,
        &picks[..3],
        dir.path(),
        &SolverOptions::default(),
        tribofe::io::FieldFormat::Vtu,
    )
    .unwrap();
    assert_eq!(written.len(), 4);
    let pvd = std::fs::read_to_string(dir.path().join("fields.pvd")).unwrap();
    for &k in &picks[..3] {
        let line =
            format!("timestep=\"{:e}\" group=\"\" part=\"0\" file=\"fields_{k:06}.vtu\"", r.run.states[k].x);
        assert!(pvd.contains(&line), "{line}\n{pvd}");
        let bytes = std::fs::read(dir.path().join(format!("fields_{k:06}.vtu"))).unwrap();
        let text = String::from_utf8_lossy(&bytes[..4096.min(bytes.len())]).into_owned();
        assert!(text.contains("Name=\"event\"") && text.contains("Name=\"interface_state\""));
    }
    // Picks that do not advance X are refused: the .pvd would repeat a time.
    assert!(tribofe::report::slide::write_fields(
        &r,
        &[picks[1], picks[0]],
        dir.path(),
        &SolverOptions::default(),
        tribofe::io::FieldFormat::Vtu
    )
    .is_err());
}
