//! Condensation of the block and the rig onto the interface DOFs and the rig's k border DOFs:
//! one factorisation, one solve with 2n + k unit load cases (a unit prescribed value on one
//! boundary DOF each); the consistent reactions of each case are a column of the dense
//! symmetric Schur complement S (f_b = S b, forces on the block/plate at the boundary DOFs).
//!
//! Boundary order: u_0..u_{n-1}, v_0..v_{n-1} (interface nodes sorted by x), then the border
//! ([`Condensed::border`]). The top-plate rig's is the plate's (U0, V0, theta) with
//! u = U0 - theta (y - t), v = V0 + theta x on the top y = t; the drive height H enters only
//! through [`Condensed::at_height`], which moves the drive point algebraically
//! (U_H = U0 - theta (H - t)), so one condensation serves every H. The side-pushed rig's
//! ([`condense_side_push`]): the pusher's U_p (or the far end of its spring, then U_p), then the sliding
//! plate's V, theta, U, or the uniform pressure's amplitude.

use crate::error::{Error, Result};
use crate::fem::assembly::Assembler;
use crate::fem::constraints::dof;
use crate::interface::events::{BorderRole, TOP_PLATE};
use crate::linalg::solve::Solver;
use crate::linalg::solve::SolverOptions;
use crate::scene::{PlateModel, Scene, SceneModel};
use rayon::prelude::*;

/// The condensed block + plate.
#[derive(Debug, Clone)]
pub struct Condensed {
    /// Interface nodes.
    pub n: usize,
    /// Node positions along the interface, m (sorted), and tributary widths, m.
    pub x: Vec<f64>,
    pub w: Vec<f64>,
    /// Block length, thickness, m.
    pub l: f64,
    pub t: f64,
    /// In-plane modulus E* (E/(1 - nu^2) in plane strain, E in plane stress), Pa (scales for
    /// tolerances).
    pub e_star: f64,
    /// Dense symmetric S, (2n + 3)^2, row-major, N/m per m.
    pub s: Vec<f64>,
    /// Largest |S_ij - S_ji| / max |S|, and largest |S r| / (max |S| |r|) over the three rigid motions.
    pub asymmetry: f64,
    pub rigid_residual: f64,
    /// The roles of the DOFs after the interface's 2n ([`TOP_PLATE`] for the top-plate rig).
    pub border: Vec<BorderRole>,
}

impl Condensed {
    pub fn dim(&self) -> usize {
        2 * self.n + self.border.len()
    }

    /// S with the plate DOFs (U_H, V, theta): U_H is the plate's horizontal displacement at
    /// height `h` (m) above the interface. Another rig's S as it is (H is the top plate's).
    pub fn at_height(&self, h: f64) -> Vec<f64> {
        if self.border[..] != TOP_PLATE[..] {
            return self.s.clone();
        }
        let nd = self.dim();
        let (iu, ith) = (2 * self.n, 2 * self.n + 2);
        // b_old = T b_new: U0 = U_H + (h - t) theta.
        let c = h - self.t;
        let mut s = self.s.clone();
        // Columns: S T.
        for i in 0..nd {
            s[i * nd + ith] += c * s[i * nd + iu];
        }
        // Rows: T^T (S T).
        for j in 0..nd {
            s[ith * nd + j] += c * s[iu * nd + j];
        }
        s
    }
}

/// Element kinds `slide` supports: linear ones, whose nodal forces over tributary widths are
/// the tractions.
fn check_element(scene: &Scene) -> Result<()> {
    let name = scene.mesh.element.as_str();
    if ["qua4", "qua4-sri", "qua4-im", "tri3"].contains(&name) {
        Ok(())
    } else {
        Err(Error::input(
            "mesh.element",
            format!("'{name}': the frictional interface supports linear elements only (qua4, qua4-sri, qua4-im, tri3); the node-wise laws assume nodal force = traction x tributary width, which quadratic edges (weights 1/6, 2/3, 1/6) break"),
        ))
    }
}

/// The scene's block and rigid plate with every boundary DOF prescribed (the interface's u
/// then v, in x order, then the plate's U0 at the block top, V0 and theta), and those DOFs
/// in boundary order: the model the condensation, and the fields of any interface state,
/// are computed on.
pub fn boundary_model(scene: &Scene) -> Result<(SceneModel, Vec<usize>)> {
    check_element(scene)?;
    if scene.plate.model != PlateModel::Rigid {
        return Err(Error::input(
            "plate.model",
            "the frictional interface needs the rigid plate (--plate rigid); the elastic plate is not condensed",
        ));
    }
    let mut sc = scene.clone();
    // Reference height of U0: the top of the block.
    sc.loading.height = scene.block.thickness;
    let mut sm = sc.build()?;
    let th = sm.dof_theta.expect("rigid plate has theta");
    sm.constraints.fix(th);
    if sm.interface.len() < 3 {
        return Err(Error::input("mesh", "the interface needs at least 3 nodes"));
    }
    crate::scene::limits::check_interface(sm.interface.len())?;
    let mut bdofs: Vec<usize> = sm.interface.iter().map(|&k| dof(k, 0)).collect();
    bdofs.extend(sm.interface.iter().map(|&k| dof(k, 1)));
    bdofs.extend([sm.dof_u, sm.dof_v, th]);
    let nf = sm.constraints.n_fixed();
    if nf != bdofs.len() {
        return Err(Error::input("scene", format!("{nf} prescribed DOFs, expected {}", bdofs.len())));
    }
    Ok((sm, bdofs))
}

/// Condenses the scene's rig: [`condense`] for the top plate, [`condense_side_push`] for the
/// side push (for the callers that run both; the others call [`condense`], which refuses the
/// side push naming what runs it).
pub fn condense_rig(scene: &Scene, opts: &SolverOptions) -> Result<Condensed> {
    if scene.loading.rig.is_top_plate() {
        condense(scene, opts)
    } else {
        condense_side_push(scene, opts)
    }
}

/// Condenses the scene's block and rigid plate (the loading height of `scene` is ignored); the
/// side-pushed rig is [`condense_side_push`]'s (this refuses it, naming what runs it).
pub fn condense(scene: &Scene, opts: &SolverOptions) -> Result<Condensed> {
    let (sm, bdofs) = boundary_model(scene)?;
    let mut touch = sm.interface.clone();
    touch.extend(sm.mesh.set_nodes(&sm.top_set)?);
    let (s, _) = schur(scene, &sm, &bdofs, &touch, None, opts)?;
    let n = sm.interface.len();
    let nd = bdofs.len();
    let x: Vec<f64> = sm.interface.iter().map(|&k| sm.mesh.nodes[k][0]).collect();
    let t = scene.block.thickness;
    let mut rigid = vec![vec![0.0; nd]; 3];
    for i in 0..n {
        rigid[0][i] = 1.0;
        rigid[1][n + i] = 1.0;
        rigid[2][n + i] = x[i];
    }
    rigid[0][2 * n] = 1.0;
    rigid[1][2 * n + 1] = 1.0;
    rigid[2][2 * n] = -t;
    rigid[2][2 * n + 2] = 1.0;
    finish(scene, &sm, s, &rigid, &TOP_PLATE)
}

/// The checks of a condensed S (nd x nd, the FE part unsymmetrised): its asymmetry, then S
/// symmetrised, and its residual on the `rigid` motions over every row but a pressure's
/// (its row is the load's work, not an equilibrium); refused beyond 1e-9.
fn finish(
    scene: &Scene,
    sm: &SceneModel,
    mut s: Vec<f64>,
    rigid: &[Vec<f64>],
    border: &[BorderRole],
) -> Result<Condensed> {
    let n = sm.interface.len();
    let nd = 2 * n + border.len();
    let smax = s.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut asym = 0.0f64;
    for i in 0..nd {
        for j in 0..i {
            asym = asym.max((s[i * nd + j] - s[j * nd + i]).abs() / smax);
        }
    }
    // Symmetrise (the asymmetry is round-off, reported above).
    for i in 0..nd {
        for j in 0..i {
            let a = 0.5 * (s[i * nd + j] + s[j * nd + i]);
            s[i * nd + j] = a;
            s[j * nd + i] = a;
        }
    }
    let x: Vec<f64> = sm.interface.iter().map(|&k| sm.mesh.nodes[k][0]).collect();
    let t = scene.block.thickness;
    let mut rigid_residual = 0.0f64;
    for r in rigid {
        let rn = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for i in (0..nd).filter(|&i| i < 2 * n || border[i - 2 * n] != BorderRole::Pressure) {
            let v: f64 = (0..nd).map(|j| s[i * nd + j] * r[j]).sum();
            rigid_residual = rigid_residual.max(v.abs() / (smax * rn));
        }
    }
    if !(asym < 1e-9 && rigid_residual < 1e-9) {
        return Err(Error::Untrustworthy {
            detail: format!(
                "the condensed interface stiffness is not symmetric ({asym:.1e}) or does not annihilate the rigid motions ({rigid_residual:.1e}) to 1e-9"
            ),
            hint: "refine the mesh or check the material values".into(),
        });
    }
    let w = sm.tributary_widths();
    let e_star = scene.block.e_star();
    Ok(Condensed {
        n,
        x,
        w,
        l: scene.block.length,
        t,
        e_star,
        s,
        asymmetry: asym,
        rigid_residual,
        border: border.to_vec(),
    })
}

/// Where a side-pushed border DOF comes from: a DOF of the FE model (its index in the
/// boundary), the pressure's amplitude, or the far end of the pusher's spring.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Src {
    Fe(usize),
    Load,
    End,
}

/// The side-pushed rig's model with its boundary prescribed ([`side_push_model`]): what the
/// condensation and the fields of any interface state (`slide --dynamics`) are computed on.
pub struct SidePushModel {
    pub sm: SceneModel,
    pub dofs: crate::scene::SidePushDofs,
    /// The prescribed FE DOFs in boundary order: the interface's u, then v (x order), then
    /// the pusher's U_p and the sliding plate's V, theta, U.
    pub bdofs: Vec<usize>,
    /// The border's roles (after the interface's 2n) and where each comes from.
    pub border: Vec<BorderRole>,
    pub src: Vec<Src>,
    /// The nodes tied to boundary DOFs.
    pub touch: Vec<usize>,
    /// The top's consistent nodal forces of the uniform pressure of N = 1 N/m (full DOF
    /// vector), None with the sliding plate.
    pub load: Option<Vec<f64>>,
}

/// The side-pushed rig ([`Scene::build_side_push`]) with the interface, the pusher's U_p and
/// the sliding plate's V, theta, U prescribed; the border drive first: (D, U_p) with the
/// spring (D, its far end, has no FE DOF), else U_p; then the top's (V, theta, U), or the
/// uniform pressure's amplitude.
pub fn side_push_model(scene: &Scene) -> Result<SidePushModel> {
    check_element(scene)?;
    let (mut sm, sp) = scene.build_side_push()?;
    if sm.interface.len() < 3 {
        return Err(Error::input("mesh", "the interface needs at least 3 nodes"));
    }
    crate::scene::limits::check_interface(sm.interface.len())?;
    let n = sm.interface.len();
    let mut bdofs: Vec<usize> = sm.interface.iter().map(|&k| dof(k, 0)).collect();
    bdofs.extend(sm.interface.iter().map(|&k| dof(k, 1)));
    bdofs.push(sp.pusher);
    let mut src: Vec<Src> = vec![];
    let mut border = vec![];
    if sp.rig.stiffness.is_some() {
        src.extend([Src::End, Src::Fe(2 * n)]);
        border.extend([BorderRole::Drive, BorderRole::Free]);
    } else {
        src.push(Src::Fe(2 * n));
        border.push(BorderRole::Drive);
    }
    let mut touch = sm.interface.clone();
    touch.extend(&sp.pusher_nodes);
    let load = match sp.plate {
        Some([pu, pv, pth]) => {
            bdofs.extend([pv, pth, pu]);
            src.extend([Src::Fe(2 * n + 1), Src::Fe(2 * n + 2), Src::Fe(2 * n + 3)]);
            border.extend([BorderRole::Normal, BorderRole::Tilt, BorderRole::Free]);
            touch.extend(sm.mesh.set_nodes(&sm.top_set)?);
            None
        }
        None => {
            src.push(Src::Load);
            border.push(BorderRole::Pressure);
            // The top's consistent nodal forces of the mean pressure of N = 1 N/m.
            let l = scene.block.length;
            let mut p = vec![0.0; sm.constraints.n_full()];
            crate::fem::loads::add_edge_traction(&sm.mesh, &sm.top_set, &|_| [0.0, -1.0 / l], &mut p)?;
            Some(p)
        }
    };
    for &d in &bdofs[2 * n..] {
        sm.constraints.fix(d);
    }
    let nf = sm.constraints.n_fixed();
    if nf != bdofs.len() {
        return Err(Error::input("scene", format!("{nf} prescribed DOFs, expected {}", bdofs.len())));
    }
    Ok(SidePushModel { sm, dofs: sp, bdofs, border, src, touch, load })
}

/// The side-pushed rig ([`side_push_model`]) condensed: the interface, the pusher's
/// U_p and the sliding plate's V, theta, U (all prescribed for the condensation), or the
/// uniform pressure as one more column (the held boundary's reactions to N = 1). With
/// push_stiffness k the spring's far end D is the drive and U_p is free: S gains
/// k [[1, -1], [-1, 1]] on (D, U_p). The rigid motions checked are the two translations (the
/// pusher's flat face admits no rotation).
pub fn condense_side_push(scene: &Scene, opts: &SolverOptions) -> Result<Condensed> {
    let SidePushModel { sm, dofs: sp, bdofs, border, src, touch, load } = side_push_model(scene)?;
    let n = sm.interface.len();
    let (s_fe, ell) = schur(scene, &sm, &bdofs, &touch, load.as_deref(), opts)?;
    let (nb, nd) = (bdofs.len(), 2 * n + border.len());
    let k = sp.rig.stiffness.unwrap_or(0.0);
    let src: Vec<Src> = (0..2 * n).map(Src::Fe).chain(src).collect();
    let up = Src::Fe(2 * n);
    let entry = |a: Src, b: Src| match (a, b) {
        (Src::Fe(i), Src::Fe(j)) => s_fe[i * nb + j] + if a == up && b == up { k } else { 0.0 },
        (Src::Fe(i), Src::Load) | (Src::Load, Src::Fe(i)) => ell.as_ref().map_or(0.0, |l| l[i]),
        (Src::End, Src::End) => k,
        (Src::End, x) | (x, Src::End) if x == up => -k,
        _ => 0.0,
    };
    let mut s = vec![0.0; nd * nd];
    for i in 0..nd {
        for j in 0..nd {
            s[i * nd + j] = entry(src[i], src[j]);
        }
    }
    // The translations: x moves the interface's u, the pusher (and its spring's end) and the
    // plate's U; y the interface's v and the plate's V.
    let mut rigid = vec![vec![0.0; nd]; 2];
    for i in 0..n {
        rigid[0][i] = 1.0;
        rigid[1][n + i] = 1.0;
    }
    for (p, &b) in src[2 * n..].iter().enumerate() {
        let d = 2 * n + p;
        match b {
            Src::End => rigid[0][d] = 1.0,
            Src::Fe(j) if j == 2 * n || j == 2 * n + 3 => rigid[0][d] = 1.0,
            Src::Fe(j) if j == 2 * n + 1 => rigid[1][d] = 1.0,
            _ => {}
        }
    }
    finish(scene, &sm, s, &rigid, &border)
}

/// The Schur complement S (nd x nd, row-major, not yet symmetrised) of `sm` onto its
/// prescribed boundary DOFs `bdofs`, and the held boundary's reactions to the distributed
/// load `load` (full DOF vector, N/m), if given. `touch`: the nodes tied to boundary DOFs
/// (their elements carry every unit case's right-hand side and reactions).
fn schur(
    scene: &Scene,
    sm: &SceneModel,
    bdofs: &[usize],
    touch: &[usize],
    load: Option<&[f64]>,
    opts: &SolverOptions,
) -> Result<(Vec<f64>, Option<Vec<f64>>)> {
    let model = sm.model();
    let n = sm.interface.len();
    let nd = bdofs.len();
    let nf = sm.constraints.n_fixed();
    let slots: Vec<usize> = bdofs.iter().map(|&d| sm.constraints.fixed_slot(d).unwrap()).collect();
    // One assembly and factorisation; the 2n + 3 right-hand sides -T^T K G e_j are built here
    // from the few elements each unit value touches (the pipeline's per-case assembly of
    // prescribed values costs elements x cases, 2 s at 1000 interface nodes).
    let interior = (0..sm.mesh.n_nodes()).any(|k| {
        sm.constraints.fixed_slot(dof(k, 0)).is_none() && {
            let y = sm.mesh.nodes[k][1];
            y > 0.0 && y < scene.block.thickness
        }
    });
    if !interior {
        return Err(Error::input(
            "mesh.n_thick",
            "the block has no node between the interface and the plate: use at least 2 elements through the thickness (--n-thick 2)",
        ));
    }
    let red = sm.constraints.reduce()?;
    // The 2n + 3 right-hand sides are held twice (built, then solved in one block), next to
    // the factor (BYTES_PER_DOF per unknown covers it).
    let nfree_f = red.n_free() as f64;
    crate::scene::limits::check_bytes(
        2.0 * 8.0 * nd as f64 * nfree_f + crate::scene::limits::BYTES_PER_DOF * nfree_f,
        "--thickness / --h (block.thickness, mesh.h)",
        &format!("condensing the {n}-node interface out of {:.3e} unknowns", nfree_f),
        "make the block thinner, h larger, or the block shorter",
    )?;
    let asm = Assembler::new(&sm.mesh, &red)?;
    let (values, _) = asm.assemble(&model, &red, &[vec![]], &[vec![0.0; nf]])?;
    let solver = Solver::analyse(&asm.pattern, opts.clone())?;
    let factor = solver.factorize(&asm.pattern, &values).map_err(|e| Error::Singular {
        detail: format!(
            "the block's stiffness is not positive definite ({e}) with the interface and plate held"
        ),
        node: None,
        component: None,
    })?;
    // Element stiffnesses of the elements touching the interface or the top, once.
    let elems = crate::fem::recovery::elements_touching(&model, touch);
    let kes: Vec<(Vec<usize>, Vec<f64>)> = elems
        .iter()
        .map(|&e| {
            let mut ke = vec![0.0; crate::fem::element::stiffness::MAX_DOFS.pow(2)];
            model.element_stiffness(e, &mut ke)?;
            Ok((model.mesh.element_nodes(e).to_vec(), ke))
        })
        .collect::<Result<_>>()?;
    let nfull = red.n_full;
    let k_times = |u: &[f64], only_nonzero: bool| -> Vec<f64> {
        let mut r = vec![0.0; nfull];
        for (nodes, ke) in &kes {
            if only_nonzero && nodes.iter().all(|&k| u[2 * k] == 0.0 && u[2 * k + 1] == 0.0) {
                continue;
            }
            let nd = 2 * nodes.len();
            for a in 0..nd {
                let mut fa = 0.0;
                for b in 0..nd {
                    fa += ke[a * nd + b] * u[2 * nodes[b / 2] + b % 2];
                }
                r[2 * nodes[a / 2] + a % 2] += fa;
            }
        }
        r
    };
    let unit = |j: usize| {
        let mut g = vec![0.0; nf];
        g[slots[j]] = 1.0;
        g
    };
    let nfree = red.n_free();
    let zero_r = vec![0.0; nfree];
    let rhs: Vec<Vec<f64>> = (0..nd)
        .into_par_iter()
        .map(|j| {
            let up = red.expand(&zero_r, &unit(j));
            let f: Vec<f64> = k_times(&up, true).into_iter().map(|v| -v).collect();
            let mut out = vec![0.0; nfree];
            red.project_add(&f, &mut out);
            out
        })
        .collect();
    let mut x: Vec<f64> = rhs.concat();
    factor.solve_in_place(&mut x, nd);
    // The distributed load's column (b = 0): reactions r = K u - p at the held boundary.
    let load_reactions = match load {
        Some(p) => {
            let mut y = vec![0.0; nfree];
            red.project_add(p, &mut y);
            factor.solve_in_place(&mut y, 1);
            let u = red.expand(&y, &vec![0.0; nf]);
            let r: Vec<f64> = k_times(&u, false).iter().zip(p).map(|(k, p)| k - p).collect();
            let fixed = red.fixed_reactions(&r);
            Some(slots.iter().map(|&j| fixed[j]).collect())
        }
        None => None,
    };
    if x.iter().chain(load_reactions.iter().flatten()).any(|v: &f64| !v.is_finite()) {
        return Err(Error::Untrustworthy {
            detail: "the condensation produced non-finite displacements".into(),
            hint: "check the mesh and the material values".into(),
        });
    }
    let cols: Vec<Vec<f64>> = (0..nd)
        .into_par_iter()
        .map(|j| {
            let u = red.expand(&x[j * nfree..(j + 1) * nfree], &unit(j));
            let fixed = red.fixed_reactions(&k_times(&u, false));
            slots.iter().map(|&j| fixed[j]).collect()
        })
        .collect();
    let mut s = vec![0.0; nd * nd];
    for (j, c) in cols.iter().enumerate() {
        for i in 0..nd {
            s[i * nd + j] = c[i];
        }
    }
    Ok((s, load_reactions))
}
