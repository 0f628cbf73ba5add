//! The dynamic set-up both drive modes share: the block with its boundary prescribed (for
//! full fields), the explicit model, wave speeds, damping, time step, the event's windows and
//! the friction law; and [`FullField`], the whole block's displacement from boundary values.

use super::{DynEvent, DynamicOptions, DynamicResult, DEFAULT_DAMPING_RATIO};
use crate::dynamics::driven::{Driven, Layout};
use crate::dynamics::explicit::Elastodynamic;
use crate::dynamics::waves::WaveSpeeds;
use crate::error::{Error, Result};
use crate::fem::assembly::Assembler;
use crate::fem::constraints::Reduction;
use crate::fem::material::Material;
use crate::interface::banded::{BandedOperator, Solving};
use crate::interface::condense::{
    boundary_model, condense_rig, side_push_model, Condensed, SidePushModel, Src,
};
use crate::interface::events::Run;
use crate::interface::events::{self, Operator};
use crate::law::{Law, Normal};
use crate::linalg::solve::{Factor, Solver, SolverOptions};
use crate::scene::{Scene, SceneModel};
use crate::studies::slide::{SlideOptions, SlideResult};

/// What both modes build before their drive phase.
pub(super) struct Setup {
    sm: SceneModel,
    /// Slot of each boundary DOF (boundary order: interface u, v, then U0, V0, theta, or the
    /// side push's prescribed DOFs).
    slots: Vec<usize>,
    /// How the event solver's boundary values set the model's.
    rig: RigMap,
    red: Reduction,
    asm: Assembler,
    values: Vec<f64>,
    solver: Solver,
    pub model: Elastodynamic,
    pub mat: Material,
    pub speeds: WaveSpeeds,
    /// Thickness-shear mode omega_t = pi c_s / (2 t), rad/s, and its period, s.
    pub omega_t: f64,
    pub period: f64,
    pub eta: f64,
    pub dt_stable: f64,
    pub dt: f64,
    /// One thickness period in steps (at least 10), and the event's sampling stride (16 a period).
    pub quiet_steps: usize,
    pub sample_every: usize,
    /// The law the explicit events run (the quasi-static phase's own, as given).
    pub law: Law,
    pub normal: Normal,
    pub weakens: bool,
    /// H - t, m.
    pub arm: f64,
    /// Lambda_0 at the mean pressure, m (infinite for Coulomb).
    pub lambda0: f64,
    /// A front reaches a base node when its |v_x| first exceeds this, m/s
    /// ([`super::physics::arrival_rate`]).
    pub arrival_rate: f64,
}

/// The rig behind the event solver's border (after the interface's 2n boundary values).
enum RigMap {
    /// (U_H, V, theta): the model's U0 at the block top is U_H + (H - t) theta.
    TopPlate,
    /// The side push's border sources ([`side_push_model`]), its face nodes, its spring
    /// (N/m per m) and the top's pressure of N = 1 N/m (full DOF vector; None: the sliding plate).
    SidePush { src: Vec<Src>, pusher: Vec<usize>, stiffness: Option<f64>, load: Option<Vec<f64>> },
}

impl Setup {
    pub fn new(scene: &Scene, o: &SlideOptions, d: &DynamicOptions) -> Result<Self> {
        let (sm, bdofs, rig) = if scene.loading.rig.is_top_plate() {
            let (sm, bdofs) = boundary_model(scene)?;
            (sm, bdofs, RigMap::TopPlate)
        } else {
            let SidePushModel { sm, dofs, bdofs, src, load, .. } = side_push_model(scene)?;
            let (pusher, stiffness) = (dofs.pusher_nodes, dofs.rig.stiffness);
            (sm, bdofs, RigMap::SidePush { src, pusher, stiffness, load })
        };
        let nf = sm.constraints.n_fixed();
        let slots: Vec<usize> =
            bdofs.iter().map(|&k| sm.constraints.fixed_slot(k).expect("boundary DOF fixed")).collect();
        let red = sm.constraints.reduce()?;
        let asm = Assembler::new(&sm.mesh, &red)?;
        let (values, _) = asm.assemble(&sm.model(), &red, &[vec![]], &[vec![0.0; nf]])?;
        let solver = Solver::analyse(&asm.pattern, SolverOptions::default())?;
        let b = &scene.block;
        let mat = b.material()?;
        let model = Elastodynamic::new(&sm.mesh, mat, b.density)?;
        let speeds = WaveSpeeds::new(&mat, b.density);
        let omega_t = std::f64::consts::PI * speeds.c_s / (2.0 * b.thickness);
        let period = 2.0 * std::f64::consts::PI / omega_t;
        let eta = d.damping.unwrap_or(2.0 * DEFAULT_DAMPING_RATIO / omega_t);
        let dt_stable = model.critical_dt(eta);
        let dt = d.courant * dt_stable;
        let (law, normal) = (o.law, d.normal);
        let weakens = law.weakens();
        let lambda0 = law.cohesive_zone(mat.shear_modulus(), mat.plane_strain_nu(), o.n_force / b.length);
        Ok(Self {
            sm,
            slots,
            rig,
            red,
            asm,
            values,
            solver,
            model,
            mat,
            speeds,
            omega_t,
            period,
            eta,
            dt_stable,
            dt,
            quiet_steps: ((period / dt).ceil() as usize).max(10),
            sample_every: ((period / dt / 16.0).floor() as usize).max(1),
            law,
            normal,
            weakens,
            arm: if scene.loading.rig.is_top_plate() { scene.loading.height - b.thickness } else { 0.0 },
            lambda0,
            arrival_rate: super::physics::arrival_rate(&law, o.n_force / b.length, b.density, speeds.c_s),
        })
    }

    /// Damping ratio at the thickness mode.
    pub fn xi(&self) -> f64 {
        0.5 * self.eta * self.omega_t
    }

    /// One event's step cap at damping `eta` (s): its periods ([`super::event_cap_periods`],
    /// or the options' own) over the step the damping allows.
    pub fn event_steps(&self, scene: &Scene, d: &DynamicOptions, eta: f64) -> f64 {
        let xi = 0.5 * eta * self.omega_t;
        let periods = d.max_periods.unwrap_or_else(|| {
            super::event_cap_periods(scene.block.length, scene.block.thickness, xi, d.ke_fraction)
        });
        (periods * self.period / (d.courant * self.model.critical_dt(eta))).ceil()
    }

    /// Refuses a damping whose event cap is above [`super::MAX_EVENT_STEPS`], naming the range of --damping this scene accepts: light damping rings down
    /// slowly (the cap's decay term grows as 1/eta), heavy damping shrinks the stable step
    /// (dt ~ 2/(omega_max^2 eta)); both ran past 30 s where the default takes 0.5 s.
    pub fn check_event_work(&self, scene: &Scene, d: &DynamicOptions) -> Result<()> {
        let work = |eta: f64| self.event_steps(scene, d, eta);
        let cap = super::MAX_EVENT_STEPS as f64;
        if work(self.eta) <= cap {
            return Ok(());
        }
        // The cap is least near critical damping of the thickness mode: search 1e-8 to 1e4 of it.
        let eta_c = 2.0 / self.omega_t;
        let grid: Vec<f64> = (0..=240).map(|k| eta_c * 10f64.powf(-8.0 + 0.05 * k as f64)).collect();
        let best = grid.iter().copied().min_by(|a, b| work(*a).total_cmp(&work(*b))).unwrap_or(eta_c);
        let steps = work(self.eta);
        // Extreme damping makes the count infinite (the ring-down, or dt underflowing to 0).
        let steps = if steps.is_finite() { format!("{steps:.3e}") } else { "more than 1e308".into() };
        let head = format!(
            "{:.4e} s: an event may take up to {steps} explicit steps (its cap: 4 x (a front crossing + the ring-down of the kinetic energy to {:e} of the dissipation) at dt = {:.3e} s), above the {cap:.1e} an event is allowed",
            self.eta,
            d.ke_fraction,
            d.courant * self.model.critical_dt(self.eta)
        );
        if work(best) > cap {
            return Err(Error::input(
                "--damping",
                format!(
                    "{head}; no damping fits this mesh (at best {:.3e} steps): use a larger --h",
                    work(best)
                ),
            ));
        }
        // Bisection in log eta on each side of the best, to where the work meets the cap.
        let edge = |mut inside: f64, mut outside: f64| {
            for _ in 0..60 {
                let mid = (inside * outside).sqrt();
                if work(mid) <= cap {
                    inside = mid;
                } else {
                    outside = mid;
                }
            }
            inside
        };
        let (lo, hi) = (edge(best, grid[0]), edge(best, grid[grid.len() - 1]));
        Err(Error::input(
            "--damping",
            format!(
                "{head}; give --damping between {lo:.2e} and {hi:.2e} s for this scene (default {:.3e} s, {DEFAULT_DAMPING_RATIO} of critical at the thickness mode)",
                2.0 * DEFAULT_DAMPING_RATIO / self.omega_t
            ),
        ))
    }

    /// The block with its boundary held, factorised (once per run).
    pub fn full_field(&self) -> Result<FullField<'_>> {
        let factor = self.solver.factorize(&self.asm.pattern, &self.values).map_err(|e| Error::Singular {
            detail: format!("the block with its boundary held is not positive definite ({e})"),
            node: None,
            component: None,
        })?;
        Ok(FullField { s: self, factor })
    }

    /// The event loop's view of the mesh (`x`: the interface nodes' x) with the options' plate.
    /// The slip that marks a node as slipped in an event, times 100: D_c under slip weakening,
    /// L under rate-and-state, and 1 m under Coulomb (no slip scale of its own; its events
    /// are read off the slip rates, this only sets the recorded tip's threshold, 1 cm).
    pub fn slip_scale(&self) -> f64 {
        match self.law {
            Law::SlipWeakening { dc, .. } => dc,
            Law::RateState(r) => r.l,
            _ => 1.0,
        }
    }

    pub fn layout(&self, x: Vec<f64>, d: &DynamicOptions) -> Result<Layout> {
        let top: Vec<usize> = self.sm.mesh.set_nodes(&self.sm.top_set)?;
        let top_x: Vec<f64> = top.iter().map(|&k| self.sm.mesh.nodes[k][0]).collect();
        let base = self.sm.interface.clone();
        match &self.rig {
            RigMap::TopPlate => Layout::new(&self.model, base, x, top, top_x, self.arm)
                .with_plate(d.plate_mass, d.plate_inertia),
            RigMap::SidePush { pusher, stiffness, load, .. } => {
                let pressure = load.as_ref().map_or(vec![], |p| top.iter().map(|&k| p[2 * k + 1]).collect());
                Ok(Layout::side_push(
                    &self.model,
                    (base, x),
                    (top, top_x),
                    pusher.clone(),
                    *stiffness,
                    pressure,
                ))
            }
        }
    }

    /// The rig's moving coordinates at the event solver's boundary values `b(j)`: a plate's
    /// (V, theta) and the side push's free (U_p, the sliding plate's U) ([`crate::dynamics::driven::DynState`]).
    pub fn coordinates(&self, n: usize, b: impl Fn(usize) -> f64) -> ([f64; 2], [f64; 2]) {
        let (mut q, mut free) = ([0.0; 2], [0.0; 2]);
        match &self.rig {
            RigMap::TopPlate => q = [b(2 * n + 1), b(2 * n + 2)],
            RigMap::SidePush { src, .. } => {
                for (p, &from) in src.iter().enumerate() {
                    let v = b(2 * n + p);
                    match from {
                        Src::Fe(j) if j == 2 * n => free[0] = v,
                        Src::Fe(j) if j == 2 * n + 1 => q[0] = v,
                        Src::Fe(j) if j == 2 * n + 2 => q[1] = v,
                        Src::Fe(_) => free[1] = v,
                        Src::Load | Src::End => {}
                    }
                }
            }
        }
        (q, free)
    }

    /// The run's result: `times` (setup, static, dynamic) in s.
    #[allow(clippy::too_many_arguments)]
    pub fn result(
        &self,
        scene: &Scene,
        o: &SlideOptions,
        condensed: Condensed,
        run: Run,
        events: Vec<DynEvent>,
        steps: usize,
        times: [f64; 3],
    ) -> DynamicResult {
        let [setup_s, static_s, dynamic_s] = times;
        DynamicResult {
            slide: SlideResult {
                scene: scene.clone(),
                options: o.clone(),
                condensed,
                run,
                condense_s: setup_s,
                events_s: static_s + dynamic_s,
            },
            events,
            dt: self.dt,
            dt_stable: self.dt_stable,
            eta: self.eta,
            xi_thickness: self.xi(),
            omega_thickness: self.omega_t,
            speeds: self.speeds,
            lambda0: self.lambda0,
            steps,
            dofs: self.model.n_dofs(),
            setup_s,
            static_s,
            dynamic_s,
            incomplete: None,
            weakening_steps: f64::NAN,
        }
    }

    pub fn driven<'a>(&'a self, layout: &'a Layout, n_force: f64) -> Driven<'a> {
        Driven {
            model: &self.model,
            layout,
            law: self.law,
            normal: self.normal,
            n_force,
            dt: self.dt,
            eta: self.eta,
        }
    }
}

/// The whole block's displacement for given boundary values, the block's interior in static
/// equilibrium with them.
pub(super) struct FullField<'a> {
    s: &'a Setup,
    factor: Factor<'a>,
}

impl FullField<'_> {
    /// `b` in the event solver's boundary order (interface u, v, then U_H at the drive height
    /// H, V, theta); the model's U0 is at the block top: U0 = U_H + (H - t) theta. Under side
    /// push the border's values go to their FE DOFs, the pressure's amplitude scales the
    /// top's load, the spring's far end sets none.
    pub fn field(&self, b: &[f64]) -> Vec<f64> {
        let s = self.s;
        let mut g = vec![0.0; s.sm.constraints.n_fixed()];
        let mut load = None;
        match &s.rig {
            RigMap::TopPlate => {
                let n2 = s.slots.len() - 3;
                for (j, &slot) in s.slots.iter().enumerate() {
                    g[slot] = if j == n2 { b[j] + s.arm * b[n2 + 2] } else { b[j] };
                }
            }
            RigMap::SidePush { src, load: top, .. } => {
                let n2 = 2 * s.sm.interface.len();
                for j in 0..n2 {
                    g[s.slots[j]] = b[j];
                }
                for (p, &from) in src.iter().enumerate() {
                    match from {
                        Src::Fe(j) => g[s.slots[j]] = b[n2 + p],
                        Src::Load => load = top.as_ref().map(|l| (b[n2 + p], l)),
                        Src::End => {}
                    }
                }
            }
        }
        let red = &s.red;
        let nd = 2 * s.sm.mesh.n_nodes();
        let up = red.expand(&vec![0.0; red.n_free()], &g);
        let mut ku = vec![0.0; nd];
        s.model.apply_k(&up[..nd], &mut ku);
        let mut f = vec![0.0; red.n_full];
        for (fi, k) in f.iter_mut().zip(&ku) {
            *fi = -k;
        }
        if let Some((amp, l)) = load {
            for (fi, li) in f.iter_mut().zip(l) {
                *fi += amp * li;
            }
        }
        let mut r = vec![0.0; red.n_free()];
        red.project_add(&f, &mut r);
        self.factor.solve_in_place(&mut r, 1);
        red.expand(&r, &g)[..nd].to_vec()
    }
}

/// The static phase's operator, `--operator`'s choice in both drive modes: the dense
/// condensed S at the drive height, or the banded block (O(n) a solve, no n x n condensation).
pub(super) struct StaticOperator {
    pub c: Condensed,
    banded: Option<BandedOperator>,
    s_h: Vec<f64>,
}

impl StaticOperator {
    pub fn new(scene: &Scene, operator: Operator) -> Result<Self> {
        let h = scene.loading.height;
        Ok(if operator == Operator::Banded {
            let op = BandedOperator::new(scene, h)?;
            Self { c: Condensed::of_banded(scene, &op), banded: Some(op), s_h: vec![] }
        } else {
            let c = condense_rig(scene, &SolverOptions::default())?;
            let s_h = c.at_height(h);
            Self { c, banded: None, s_h }
        })
    }

    /// The interface's stiffness with every boundary DOF held, for the fracture arrest.
    pub fn held(&self) -> Result<super::fracture::HeldStiffness<'_>> {
        Ok(match &self.banded {
            Some(b) => super::fracture::HeldStiffness::Banded(b.held_columns()?),
            None => super::fracture::HeldStiffness::Dense(&self.c),
        })
    }

    /// The event solver's operator over the 2n + k boundary DOFs.
    pub fn solver(&self) -> Box<dyn events::operator::Operator + '_> {
        match &self.banded {
            Some(b) => Box::new(Solving::new(b)),
            None => Box::new(events::operator::Dense::with_border(&self.s_h, &self.c.border)),
        }
    }
}
