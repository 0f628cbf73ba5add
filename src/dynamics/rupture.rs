//! A block on a rigid flat with slip-weakening friction, run explicitly: the shared
//! cross-check scene "rupture" (the spec both this code and validation/dynamics implement).
//!
//! Perturbation about a uniform background (as SEM2DPACK): the body starts at rest with zero
//! displacement; the background normal stress sigma0 and shear tau0 act on the base only
//! through the friction rule. Each base node i (tributary width w_i, lumped mass m_i) at step
//! n, with f^n = -K u^n and v^{n-1/2} known:
//!
//! ```text
//! sigma_i = sigma0 - (f_y + m_i v_y / dt) / w_i          (the traction keeping v_y^{n+1/2} = 0)
//! T*      = tau0_i + (m_i v_x / dt + f_x) / w_i          (the traction that would stop it)
//! T_i     = T*  if |T*| <= mu(d_i) sigma_i,  else mu(d_i) sigma_i sign(T*)
//! v_x^{n+1/2} = v_x^{n-1/2} + dt (f_x + (tau0_i - T_i) w_i) / m_i,   d_i += dt |v_x^{n+1/2}|
//! ```
//!
//! the traction-at-split-node rule of Day et al. (2005, BSSA 95) against a rigid flat. With
//! [`Contact::Unilateral`] a node whose trial normal stress (now the one that keeps u_y = 0)
//! is tensile opens: sigma_i = 0, T_i = 0, and the node moves freely under -sigma0 w_i.
//! [`Contact::Symmetric`] replaces the flat by the mirror half of a symmetric fault (slip
//! 2 u_x, sigma = sigma0), the geometry Andrews' supershear threshold S ~ 1.77 is for.

use super::explicit::{Boundary, BoundaryStep, Elastodynamic, Explicit};
use super::waves::WaveSpeeds;
use crate::error::{Error, Result};
use crate::fem::material::Material;
use crate::fem::mesher::Rectangle;
use crate::law::{Law, Normal, Trial};

/// How the base meets the rigid flat.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Contact {
    /// u_y = 0 always (the spec; the minimum normal stress is reported to show it stays
    /// compressive).
    Bilateral,
    /// Opening allowed where the flat would have to pull.
    Unilateral,
    /// Not a flat: the plane y = 0 of a symmetric fault between two identical blocks (the
    /// control case of the dynamic-rupture literature). The mirror image moves by -u_x, so
    /// the slip is 2 u_x and the normal stress keeps sigma0 (perturbation sigma_yy = 0 there);
    /// u_y is free.
    Symmetric,
}

impl Contact {
    /// The name `--contact` takes.
    pub fn name(self) -> &'static str {
        match self {
            Self::Bilateral => "bilateral",
            Self::Unilateral => "unilateral",
            Self::Symmetric => "symmetric",
        }
    }
}

impl std::str::FromStr for Contact {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "bilateral" => Ok(Self::Bilateral),
            "unilateral" => Ok(Self::Unilateral),
            "symmetric" => Ok(Self::Symmetric),
            _ => Err(Error::input(
                "--contact",
                format!("'{}': use bilateral, unilateral or symmetric", crate::error::quote(s)),
            )),
        }
    }
}

/// The scene. [`Default`] is the shared spec (validation/dynamics, docs/dynamics.md).
#[derive(Debug, Clone, PartialEq)]
pub struct RuptureSpec {
    /// Block x in [-length/2, length/2], y in [0, height], m.
    pub length: f64,
    pub height: f64,
    /// Element size (square QUA4), m.
    pub h: f64,
    /// Pa, dimensionless, kg/m^3.
    pub young: f64,
    pub poisson: f64,
    pub density: f64,
    /// Background normal stress on the base (compressive positive), Pa.
    pub sigma0: f64,
    /// Strength ratio S = (mu_s sigma0 - tau0) / (tau0 - mu_d sigma0) outside the patch.
    pub s_ratio: f64,
    /// Slip weakening (mu_s > mu_d), the one law this scene runs.
    pub friction: Law,
    /// Nucleation patch |x| <= this, m, where tau0 = overstress * mu_s sigma0.
    pub patch_half_width: f64,
    pub overstress: f64,
    /// Width of a cosine ramp of tau0 centred on the patch edge, m; 0 (the spec): a jump. A
    /// ramp the mesh resolves takes the jump's mesh dependence out of the arrival times.
    pub patch_taper: f64,
    /// dt = courant h / c_p (the spec: 0.5).
    pub courant: f64,
    /// Run to this time (steps = round(t_end / dt)), s.
    pub t_end: f64,
    /// Kelvin-Voigt coefficient, s (the spec: 0).
    pub damping: f64,
    pub contact: Contact,
    /// Front speed: least-squares slope of x against arrival time over this x range, m.
    pub speed_window: (f64, f64),
    /// The normal response: the strength is mu(d) sigma*, sigma* relaxing towards sigma by
    /// Prakash-Clifton's law with a time or a length scale ([`Normal`]), implicit in each
    /// step. Instantaneous (the spec): the strength follows sigma at once.
    pub normal: Normal,
    /// Most explicit steps a run may take ([`DEFAULT_MAX_STEPS`]): t_end / dt above it is
    /// refused before any work ([`RuptureSpec::steps`]).
    pub max_steps: u64,
}

impl Default for RuptureSpec {
    fn default() -> Self {
        Self {
            length: 0.2,
            height: 0.1,
            h: 1e-3,
            young: 2000.0,
            poisson: 0.4,
            density: 1000.0,
            sigma0: 2.5,
            s_ratio: 2.0,
            friction: Law::SlipWeakening { mu_s: 0.648, mu_d: 0.583, dc: 7.7e-7 },
            patch_half_width: 0.01,
            overstress: 1.005,
            patch_taper: 0.0,
            courant: 0.5,
            t_end: 0.1,
            damping: 0.0,
            contact: Contact::Bilateral,
            speed_window: (0.03, 0.08),
            normal: Normal::Instantaneous,
            max_steps: DEFAULT_MAX_STEPS,
        }
    }
}

/// Default cap on a run's explicit steps: one step of the default mesh (200 x 100 elements)
/// takes about 1 ms here, so 1e6 steps are about 15 minutes; the spec's run is 414 steps.
/// The cost of a step grows with the elements (at most 2e7): the run's cost is printed first.
pub const DEFAULT_MAX_STEPS: u64 = 1_000_000;

/// The normal-stress lag T of `tribofe rupture` and `tribofe.dynamics.rupture` when none is
/// given, s: the time scale with which the rigid-flat rupture's arrival times converge at
/// order 2 as h halves (0.5, 0.25, 0.125 mm, with a patch ramp; docs/dynamics-findings.md). It is a
/// property of the interface, not of the mesh: T spans 4 explicit steps at the default
/// h = 1 mm (dt = 0.24 ms) and more on finer meshes. [`RuptureSpec::default`] stays the
/// cross-check spec, without it.
pub const DEFAULT_NORMAL_LAG: f64 = 1e-3;

/// Fewest elements across Lambda_0 a run accepts.
pub const MIN_ZONE_ELEMENTS: f64 = 3.0;

impl RuptureSpec {
    pub fn material(&self) -> Result<Material> {
        Material::plane_strain(self.young, self.poisson)
    }

    /// Background shear outside the patch, Pa: tau0 = sigma0 (mu_s + S mu_d) / (1 + S).
    pub fn tau0(&self) -> f64 {
        let f = &self.friction;
        self.sigma0 * (f.mu_s() + self.s_ratio * f.mu_d()) / (1.0 + self.s_ratio)
    }

    /// D_c, m (the law is slip weakening once validated).
    pub fn dc(&self) -> f64 {
        self.friction.dc().unwrap_or(f64::INFINITY)
    }

    /// The initial shear at x, Pa: overstress mu_s sigma0 on the patch, [`Self::tau0`] outside,
    /// across its edge a jump or the cosine ramp of [`Self::patch_taper`].
    pub fn prestress(&self, x: f64) -> f64 {
        let (tau_in, tau_out) = (self.overstress * self.friction.mu_s() * self.sigma0, self.tau0());
        let (a, w) = (self.patch_half_width, self.patch_taper);
        if w == 0.0 {
            // The patch edge is a node: include it whatever the rounding of its coordinate.
            return if x.abs() <= a + 1e-6 * self.h { tau_in } else { tau_out };
        }
        let s = ((x.abs() - (a - w / 2.0)) / w).clamp(0.0, 1.0);
        tau_out + (tau_in - tau_out) * 0.5 * (1.0 + (std::f64::consts::PI * s).cos())
    }

    /// Lambda_0 of [`Law::cohesive_zone`] at sigma0, m.
    pub fn lambda0(&self) -> Result<f64> {
        let m = self.material()?;
        Ok(self.friction.cohesive_zone(m.shear_modulus(), m.nu, self.sigma0))
    }

    /// The warning for a run on a rigid flat with the instantaneous normal stress: there the
    /// slip changes the normal stress at once, and an elastic body sliding on a rigid flat with
    /// Coulomb-type friction is ill-posed above a friction threshold (Adams 1995; Martins &
    /// Simoes 1995), which the lag regularises (Prakash & Clifton 1993; Cochard & Rice 2000).
    /// None on the symmetric fault, whose normal stress does not change with slip.
    pub fn instantaneous_normal_warning(&self) -> Option<String> {
        (self.normal == Normal::Instantaneous && self.contact != Contact::Symmetric).then(|| {
            format!(
                "the instantaneous normal stress on a rigid flat (--normal-lag 0): above a friction threshold the problem is ill-posed and the fronts depend on the mesh; the regularised default is --normal-lag {DEFAULT_NORMAL_LAG}"
            )
        })
    }

    /// The explicit step dt = courant h / c_p (s) and the steps to t_end, round(t_end / dt)
    /// (a float: it may be far above any count).
    pub fn steps(&self) -> Result<(f64, f64)> {
        let c_p = WaveSpeeds::new(&self.material()?, self.density).c_p;
        let dt = self.courant * self.h / c_p;
        Ok((dt, (self.t_end / dt).round()))
    }

    /// Refuses a run of more than [`Self::max_steps`] explicit steps, naming what sets them.
    fn check_steps(&self) -> Result<()> {
        let (dt, steps) = self.steps()?;
        let c_p = WaveSpeeds::new(&self.material()?, self.density).c_p;
        if !(steps <= self.max_steps as f64) {
            return Err(Error::input(
                "--t-end (with --courant, --h, --young, --poisson, --density)",
                format!(
                    "t_end / dt = {} s / {dt:.4e} s = {steps:.3e} explicit steps (dt = courant h / c_p, c_p = {c_p:.4e} m/s), above \
                     --max-steps {}: give --t-end <= {:.4e} s, a larger --h or --courant, or raise --max-steps",
                    self.t_end,
                    self.max_steps,
                    self.max_steps as f64 * dt
                ),
            ));
        }
        Ok(())
    }

    /// Every value checked before any work, with the flag to change.
    pub fn validate(&self) -> Result<()> {
        let (pos, scaled) = (crate::error::positive, crate::error::scaled);
        scaled("block length (m, --length)", self.length, "m")?;
        scaled("block height (m, --height)", self.height, "m")?;
        scaled("element size (m, --h)", self.h, "m")?;
        scaled("density (kg/m^3, --density)", self.density, "kg/m^3")?;
        scaled("sigma0 (Pa, --sigma0)", self.sigma0, "Pa")?;
        scaled("Young's modulus (Pa, --young)", self.young, "Pa")?;
        pos("t_end (s, --t-end)", self.t_end)?;
        pos("courant factor (--courant)", self.courant)?;
        if self.courant < super::explicit::MIN_COURANT {
            return Err(Error::input(
                "courant factor (--courant)",
                format!(
                    "{} is below {}: the steps grow as 1/courant and buy no accuracy (the time error is far below the mesh's); give --courant in [{}, the stable bound]",
                    crate::error::num(self.courant),
                    super::explicit::MIN_COURANT,
                    super::explicit::MIN_COURANT
                ),
            ));
        }
        // E is checked above: what the material refuses is nu.
        self.material().map_err(|e| match e {
            Error::Input { what, why } => Error::Input { what: format!("{what} (--poisson)"), why },
            e => e,
        })?;
        let Law::SlipWeakening { mu_s, mu_d, dc } = self.friction else {
            return Err(Error::input(
                "friction law (RuptureSpec::friction)",
                format!("{}: the rupture scene runs slip weakening", self.friction.name()),
            ));
        };
        if !(mu_s.is_finite() && mu_d.is_finite() && 0.0 <= mu_d && mu_d <= mu_s) {
            return Err(Error::input(
                "friction coefficients (--mu-s, --mu-d)",
                format!("mu_s = {mu_s}, mu_d = {mu_d}: need 0 <= mu_d <= mu_s (mu_d = mu_s is Coulomb)"),
            ));
        }
        if !(dc.is_finite() && dc > 0.0) {
            return Err(Error::input("D_c (m, --dc)", format!("{dc} must be a positive slip distance")));
        }
        if !(mu_s > mu_d) {
            return Err(Error::input(
                "friction coefficients (--mu-s, --mu-d)",
                "the rupture scene needs mu_s > mu_d (S is defined by the strength drop)",
            ));
        }
        if !(self.s_ratio.is_finite() && self.s_ratio >= 0.0) {
            return Err(Error::input(
                "strength ratio S (--s)",
                format!(
                    "{} must be >= 0 (S < 0 puts the background shear above the static strength)",
                    self.s_ratio
                ),
            ));
        }
        match self.normal {
            Normal::Time { t } => pos("normal-stress lag T (s, --normal-lag)", t)?,
            Normal::Length { l, v_star } => {
                Normal::length(
                    l,
                    v_star,
                    ("normal-stress lag length L (m, --normal-lag-length)", "--normal-lag-v-star"),
                )?;
            }
            Normal::Instantaneous => {}
        }
        if !(self.patch_taper >= 0.0 && self.patch_taper <= 2.0 * self.patch_half_width) {
            return Err(Error::input(
                "nucleation ramp width (m, --patch-taper)",
                format!(
                    "{} must be between 0 and the patch width {} m (the ramp is centred on its edge)",
                    self.patch_taper,
                    2.0 * self.patch_half_width
                ),
            ));
        }
        if !(self.damping.is_finite() && self.damping >= 0.0) {
            return Err(Error::input("damping (s, --damping)", format!("{} must be >= 0", self.damping)));
        }
        let half = self.length / 2.0;
        if !(self.patch_half_width > 0.0 && self.patch_half_width < half) {
            return Err(Error::input(
                "block length (m, --length)",
                format!(
                    "{} m: the nucleation patch |x| <= {} m must lie inside the interface with unbroken interface beyond it for the rupture to run into; give --length > {} m",
                    self.length,
                    self.patch_half_width,
                    2.0 * self.patch_half_width
                ),
            ));
        }
        // The front speed is fitted over the window's nodes inside the block: it must reach
        // into the half 0 <= x <= L/2 the +x front runs over (a short block measures less of it).
        let (a, b) = self.speed_window;
        if !(a.is_finite() && b.is_finite() && 0.0 <= a && a < b) {
            return Err(Error::input(
                "front-speed window (m, RuptureSpec::speed_window)",
                format!("({a}, {b}): give 0 <= a < b, finite"),
            ));
        }
        if a >= half {
            return Err(Error::input(
                "block length (m, --length)",
                format!(
                    "{} m: the front speed is measured over {a} <= x <= {b} m, which lies beyond the block's end x = L/2 = {half} m; give --length > {} m",
                    self.length,
                    2.0 * a
                ),
            ));
        }
        for (what, len) in [("--length", self.length), ("--height", self.height)] {
            let n = len / self.h;
            if (n - n.round()).abs() > 1e-6 * n || n.round() < 2.0 {
                return Err(Error::input(
                    format!("element size (m, --h) against {what}"),
                    format!("{} m / {} m = {n} must be a whole number of elements >= 2", len, self.h),
                ));
            }
        }
        let cells = (self.length / self.h).round() * (self.height / self.h).round();
        if cells > 2e7 {
            return Err(Error::input(
                "element size (m, --h)",
                format!("{cells:.3e} elements exceed the 2e7 this command runs; use a larger --h"),
            ));
        }
        self.check_step()?;
        let dt = self.dt()?;
        if (self.t_end / dt).round() < 1.0 {
            return Err(Error::input(
                "t_end (s, --t-end)",
                format!(
                    "{} s is shorter than one step dt = {dt:.4e} s: give --t-end >= {dt:.4e} s",
                    self.t_end
                ),
            ));
        }
        let lambda0 = self.lambda0()?;
        // Lambda_0 per metre of D_c (finite where Lambda_0 itself overflows).
        let m = self.material()?;
        let per_dc =
            Law::SlipWeakening { mu_s, mu_d, dc: 1.0 }.cohesive_zone(m.shear_modulus(), m.nu, self.sigma0);
        if !(lambda0 <= self.length / 2.0) {
            return Err(Error::input(
                "D_c (m, --dc)",
                format!(
                    "the cohesive zone Lambda_0 = {lambda0:.3e} m is longer than the half block L/2 = {} m the front runs over from the patch: no front can form; lower --dc to at most {:.3e} m",
                    self.length / 2.0,
                    self.length / 2.0 / per_dc
                ),
            ));
        }
        if lambda0 < MIN_ZONE_ELEMENTS * self.h {
            return Err(Error::input(
                "D_c (m, --dc) or element size (m, --h)",
                format!(
                    "the cohesive zone Lambda_0 = {lambda0:.3e} m spans {:.2} elements of h = {} m, fewer than \
                     {MIN_ZONE_ELEMENTS}: the front would be mesh dependent; raise --dc to at least {:.3e} m or \
                     lower --h to at most {:.3e} m",
                    lambda0 / self.h,
                    self.h,
                    dc * MIN_ZONE_ELEMENTS * self.h / lambda0,
                    lambda0 / MIN_ZONE_ELEMENTS
                ),
            ));
        }
        if self.max_steps == 0 {
            return Err(Error::input("--max-steps", "0: give at least 1 step"));
        }
        self.check_steps()
    }
}

impl RuptureSpec {
    /// dt = courant h / c_p, s.
    pub fn dt(&self) -> Result<f64> {
        Ok(self.courant * self.h / WaveSpeeds::new(&self.material()?, self.density).c_p)
    }

    /// The element bound on the largest eigenvalue of M^-1 K, 1/s^2: every element of the
    /// mesh is the same h x h square, so one element's (no mesh to build).
    fn lambda_bound(&self) -> Result<f64> {
        let one = Rectangle::new(0.0, self.h, 0.0, self.h, 1, 1).build()?;
        Ok(Elastodynamic::new(&one, self.material()?, self.density)?.lambda_bound)
    }

    /// Refuses a step above the stable one of the mesh and damping, naming what to change:
    /// --damping when the undamped step would admit dt (its largest value given), else
    /// --courant.
    fn check_step(&self) -> Result<()> {
        use super::explicit::{critical_dt, largest_damping};
        let (dt, lambda) = (self.dt()?, self.lambda_bound()?);
        let dt_stable = critical_dt(lambda, self.damping);
        if dt <= dt_stable {
            return Ok(());
        }
        let courant_max = self.courant * dt_stable / dt;
        if self.damping > 0.0 && dt <= critical_dt(lambda, 0.0) {
            // A courant far below the undamped bound is no remedy: the run's steps grow as 1/it.
            let or_courant = if courant_max >= 0.01 {
                format!(", or --courant <= {} at this damping", crate::error::num(courant_max))
            } else {
                String::new()
            };
            return Err(Error::input(
                "damping (s, --damping)",
                format!(
                    "{} s lowers the stable step to {dt_stable:.4e} s, below dt = {} h / c_p = {dt:.4e} s: give --damping <= {:.4e} s at --courant {}{or_courant}",
                    crate::error::num(self.damping),
                    self.courant,
                    largest_damping(lambda, dt),
                    self.courant
                ),
            ));
        }
        Err(Error::input(
            "courant factor (--courant)",
            format!(
                "dt = {} h / c_p = {dt:.4e} s exceeds the stable step {dt_stable:.4e} s of this mesh; use --courant <= {}",
                self.courant,
                crate::error::num(courant_max)
            ),
        ))
    }
}

/// Energies at the end of a run, J per metre of width.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct RuptureEnergy {
    /// 0.5 v M v at the last half step and 0.5 u^{N-1} K u^N (the scheme's shadow energy).
    pub kinetic: f64,
    pub strain: f64,
    /// Work of the background tractions on the base: sum dt vbar . (tau0 w, -sigma0 w).
    pub background_work: f64,
    /// Frictional dissipation sum dt vbar_x T w (discrete, matching the shadow energy)...
    pub friction: f64,
    /// ...and the physical sum T w delta d (d the slip path length).
    pub friction_path: f64,
    /// Work of the flat's normal reaction (zero for bilateral contact).
    pub contact: f64,
    /// Kelvin-Voigt dissipation (0 undamped, the spec).
    pub damping: f64,
    /// kinetic + strain + friction + damping - background_work - contact: zero up to round-off.
    pub residual: f64,
}

/// What a run measured.
#[derive(Debug, Clone)]
pub struct RuptureResult {
    /// Base nodes by x: position, tributary width, background shear.
    pub x: Vec<f64>,
    pub width: Vec<f64>,
    pub tau0: Vec<f64>,
    /// First time d >= D_c / 100 (linear between steps), s; None if never.
    pub t_arrival: Vec<Option<f64>>,
    /// First time d >= D_c (fully weakened), s.
    pub t_weakened: Vec<Option<f64>>,
    /// Slip path length at t_end, m.
    pub slip: Vec<f64>,
    /// Largest |v_x| of each base node over the run, m/s.
    pub peak_slip_rate: Vec<f64>,
    /// sum (tau0_i - T_i) w_i at t_end, N/m.
    pub force_drop: f64,
    /// Smallest total normal stress on the base over the run, Pa.
    pub min_sigma: f64,
    pub steps: usize,
    pub dt: f64,
    /// Stable step of the mesh (element bound), s.
    pub dt_stable: f64,
    pub front_speed: Option<f64>,
    pub speeds: WaveSpeeds,
    pub lambda0: f64,
    pub energy: RuptureEnergy,
}

/// Runs the scene; `progress` gets the fraction of the steps done and `cancel` is checked
/// every [`crate::cancel::BEAT`] of wall time.
pub fn run(spec: &RuptureSpec, cancel: &crate::Cancel, progress: crate::Progress) -> Result<RuptureResult> {
    spec.validate()?;
    let mat = spec.material()?;
    let speeds = WaveSpeeds::new(&mat, spec.density);
    let (nx, ny) = ((spec.length / spec.h).round() as usize, (spec.height / spec.h).round() as usize);
    let mesh = Rectangle::new(-spec.length / 2.0, spec.length / 2.0, 0.0, spec.height, nx, ny).build()?;
    let model = Elastodynamic::new(&mesh, mat, spec.density)?;
    // Checked against the stable step in validate().
    let dt = spec.dt()?;
    let dt_stable = model.critical_dt(spec.damping);
    let steps = spec.steps()?.1 as usize;
    // Base nodes, by x (the mesher numbers row by row: the first nx + 1 nodes).
    let base: Vec<usize> = (0..=nx).collect();
    debug_assert!(base.iter().all(|&k| mesh.nodes[k][1] == 0.0));
    let x: Vec<f64> = base.iter().map(|&k| mesh.nodes[k][0]).collect();
    let width: Vec<f64> = (0..=nx).map(|i| if i == 0 || i == nx { spec.h / 2.0 } else { spec.h }).collect();
    let tau0: Vec<f64> = x.iter().map(|&xi| spec.prestress(xi)).collect();

    let nb = base.len();
    let mut fl = Flat {
        spec,
        base: &base,
        width: &width,
        tau0: &tau0,
        d: vec![0.0; nb],
        t_arrival: vec![None; nb],
        t_weakened: vec![None; nb],
        peak: vec![0.0; nb],
        fbx: vec![0.0; nb],
        fby: vec![0.0; nb],
        tr: vec![0.0; nb],
        seff: vec![spec.sigma0; nb],
        theta: vec![0.0; nb],
        slip_factor: if spec.contact == Contact::Symmetric { 2.0 } else { 1.0 },
        min_sigma: f64::INFINITY,
        e: RuptureEnergy::default(),
    };
    let mut ex = Explicit::checked_by_caller(&model, dt, spec.damping, vec![false; model.n_dofs()])
        .with_boundary(&base);
    // The energies are read at t_end (`level`) and from the sums: not summed per step.
    ex.physical_energies = false;
    let mut beat = cancel.beat();
    for step in 0..steps {
        ex.step_boundary(&mut fl);
        if beat.due()? {
            progress.fraction(step as f64 / steps as f64);
        }
    }
    // The friction at t_end itself (step N), as the spec's force drop asks: the base rule on
    // K u^N (without damping forces) with sigma* advanced on a copy.
    let (u, v) = (ex.u.clone(), ex.v.clone());
    let (damping, mass) = (ex.ledger.damping, &model.mass);
    let (ku, kinetic, strain) = ex.level();
    let mut fl_end = fl.clone();
    fl.min_sigma = fl.min_sigma.min(fl_end.rule(&u, &v, &|i| -ku[i], dt, mass));
    let tr = fl_end.tr;
    let mut e = RuptureEnergy { kinetic, strain, damping, ..fl.e };
    e.residual = e.kinetic + e.strain + e.friction + e.damping - e.background_work - e.contact;
    let (min_sigma, d, t_arr, t_wk, peak) = (fl.min_sigma, fl.d, fl.t_arrival, fl.t_weakened, fl.peak);
    let force_drop: f64 = (0..nb).map(|b| (tau0[b] - tr[b]) * width[b]).sum();
    if !(force_drop.is_finite() && min_sigma.is_finite() && e.residual.is_finite()) {
        return Err(Error::Untrustworthy {
            detail: "the run produced non-finite values".into(),
            hint: "lower --courant; report the command line".into(),
        });
    }
    let mut r = RuptureResult {
        x,
        width,
        tau0,
        t_arrival: t_arr,
        t_weakened: t_wk,
        slip: d,
        peak_slip_rate: peak,
        force_drop,
        min_sigma,
        steps,
        dt,
        dt_stable,
        front_speed: None,
        speeds,
        lambda0: spec.lambda0()?,
        energy: e,
    };
    r.front_speed = r.front_speed_between(spec.speed_window.0, spec.speed_window.1);
    progress.fraction(1.0);
    Ok(r)
}

/// The base on the rigid flat (or the symmetric fault's plane) as the stepper's boundary:
/// the split-node rule of the module docs, per base node per step.
#[derive(Clone)]
struct Flat<'s> {
    spec: &'s RuptureSpec,
    base: &'s [usize],
    width: &'s [f64],
    tau0: &'s [f64],
    /// Slip path length, first times d >= D_c / 100 and d >= D_c, peak |v_x|.
    d: Vec<f64>,
    t_arrival: Vec<Option<f64>>,
    t_weakened: Vec<Option<f64>>,
    peak: Vec<f64>,
    /// The flat's forces on the base nodes at this step (perturbation), and their traction T.
    fbx: Vec<f64>,
    fby: Vec<f64>,
    tr: Vec<f64>,
    /// The regularised normal stress sigma*, and the rate-and-state state (unused by slip
    /// weakening; the split-node rule's one signature).
    seff: Vec<f64>,
    theta: Vec<f64>,
    /// Slip per unit displacement along x: 2 on a symmetric fault, else 1.
    slip_factor: f64,
    min_sigma: f64,
    e: RuptureEnergy,
}

impl Flat<'_> {
    /// The base rule at the current step: fills fbx, fby, tr from the mesh's force `f` on each
    /// DOF and v^{n-1/2}, advancing sigma* once; returns the smallest normal stress.
    fn rule(&mut self, u: &[f64], v: &[f64], f: &dyn Fn(usize) -> f64, dt: f64, mass: &[f64]) -> f64 {
        let spec = self.spec;
        let mut smin = f64::INFINITY;
        for (b, &k) in self.base.iter().enumerate() {
            let (m, w) = (mass[k], self.width[b]);
            let (fx, fy) = (f(2 * k), f(2 * k + 1));
            let mut sigma = spec.sigma0 - (fy + m * v[2 * k + 1] / dt) / w;
            if spec.contact == Contact::Symmetric {
                sigma = spec.sigma0;
            }
            if spec.contact == Contact::Unilateral {
                // The stress keeping u_y^{n+1} = 0; tensile means the node leaves the flat.
                sigma -= m * u[2 * k + 1] / (dt * dt * w);
                if sigma < 0.0 {
                    sigma = 0.0;
                }
            }
            smin = smin.min(sigma);
            let open = spec.contact == Contact::Unilateral && sigma == 0.0;
            // The slip rate of the half step before: the explicit rate the lag and the law read.
            let v_old = self.slip_factor * v[2 * k].abs();
            let s_eff = if spec.normal.lags() {
                self.seff[b] = spec.normal.relax(self.seff[b], sigma, dt, v_old);
                if open {
                    0.0
                } else {
                    self.seff[b]
                }
            } else {
                sigma
            };
            // Not clamped at sigma < 0 (possible under bilateral contact only): the spec's
            // rule as written, T = mu sigma sign(T*); the run reports min sigma to show it.
            let t_star = self.tau0[b] + (m * v[2 * k] / dt + fx) / w;
            let trial =
                Trial { t_star, p: s_eff, z: m / (dt * w * self.slip_factor), dt, slip: self.d[b], v_old };
            let (t, _) = spec.friction.split_node(trial, &mut self.theta[b]);
            self.tr[b] = t;
            self.fbx[b] = (self.tau0[b] - t) * w;
            self.fby[b] = (sigma - spec.sigma0) * w;
        }
        smin
    }
}

impl Boundary for Flat<'_> {
    fn nodes(&self) -> &[usize] {
        self.base
    }

    fn apply(&mut self, s: BoundaryStep<'_>) -> f64 {
        let (spec, dt) = (self.spec, s.dt);
        let smin = self.rule(s.u, s.v, &|i| s.force(i), dt, s.mass);
        self.min_sigma = self.min_sigma.min(smin);
        let e0 = self.e;
        let (dc, slip_factor) = (spec.dc(), self.slip_factor);
        let thr = dc / 100.0;
        for (b, &k) in self.base.iter().enumerate() {
            let (m, w) = (s.mass[k], self.width[b]);
            let (vxm, vym) = (s.v[2 * k], s.v[2 * k + 1]);
            let vx = vxm + dt * (s.force(2 * k) + self.fbx[b]) / m;
            let vy = vym + dt * (s.force(2 * k + 1) + self.fby[b]) / m;
            // In contact the flat holds u_y^{n+1} = 0 exactly (not to round-off), so a
            // unilateral run that never opens is the bilateral run bit for bit.
            let held = spec.contact == Contact::Unilateral && self.fby[b] > -spec.sigma0 * w;
            let vy = match spec.contact {
                Contact::Bilateral => 0.0,
                Contact::Unilateral if held => -s.u[2 * k + 1] / dt,
                _ => vy,
            };
            let (vbx, vby) = (0.5 * (vxm + vx), 0.5 * (vym + vy));
            self.e.background_work += dt * w * (vbx * self.tau0[b] - vby * spec.sigma0);
            self.e.friction += dt * vbx * self.tr[b] * w;
            self.e.contact += dt * vby * (self.fby[b] + spec.sigma0 * w);
            // (per half of a symmetric fault: the work on this block's face)
            self.e.friction_path += self.tr[b].abs() * w * dt * vx.abs();
            s.v[2 * k] = vx;
            s.v[2 * k + 1] = vy;
            s.u_next[2 * k] = s.u[2 * k] + dt * vx;
            s.u_next[2 * k + 1] = if held { 0.0 } else { s.u[2 * k + 1] + dt * vy };
            let d_new = self.d[b] + slip_factor * dt * vx.abs();
            let t0 = s.n as f64 * dt;
            if self.t_arrival[b].is_none() && d_new >= thr {
                self.t_arrival[b] = Some(t0 + dt * (thr - self.d[b]) / (d_new - self.d[b]));
            }
            if self.t_weakened[b].is_none() && d_new >= dc {
                self.t_weakened[b] = Some(t0 + dt * (dc - self.d[b]) / (d_new - self.d[b]));
            }
            self.peak[b] = f64::max(self.peak[b], vx.abs());
            self.d[b] = d_new;
        }
        let e = &self.e;
        (e.background_work - e0.background_work) + (e.contact - e0.contact) - (e.friction - e0.friction)
    }
}

impl RuptureResult {
    /// (x, t_arrival) of the nodes with x >= 0 that the front reached.
    pub fn arrivals(&self) -> Vec<(f64, f64)> {
        self.x
            .iter()
            .zip(&self.t_arrival)
            .filter(|(&x, _)| x >= -1e-12)
            .filter_map(|(&x, t)| t.map(|t| (x, t)))
            .collect()
    }

    /// Least-squares slope of x against arrival time over a <= x <= b (m), m/s; None with
    /// fewer than 3 arrivals there.
    pub fn front_speed_between(&self, a: f64, b: f64) -> Option<f64> {
        let eps = 1e-9;
        let pts: Vec<(f64, f64)> =
            self.arrivals().into_iter().filter(|&(x, _)| x >= a - eps && x <= b + eps).collect();
        if pts.len() < 3 {
            return None;
        }
        let nf = pts.len() as f64;
        let (mt, mx) = (pts.iter().map(|p| p.1).sum::<f64>() / nf, pts.iter().map(|p| p.0).sum::<f64>() / nf);
        let stt: f64 = pts.iter().map(|p| (p.1 - mt).powi(2)).sum();
        let stx: f64 = pts.iter().map(|p| (p.1 - mt) * (p.0 - mx)).sum();
        (stt > 0.0).then(|| stx / stt)
    }

    /// The same for the front running towards -x, over -b <= x <= -a (speed positive).
    pub fn front_speed_left(&self, a: f64, b: f64) -> Option<f64> {
        let mirrored = RuptureResult {
            x: self.x.iter().rev().map(|x| -x).collect(),
            t_arrival: self.t_arrival.iter().rev().copied().collect(),
            ..self.clone()
        };
        mirrored.front_speed_between(a, b)
    }

    /// Cohesive-zone length behind the front where node x became fully weakened (d = D_c):
    /// the front position (d = D_c / 100) at that time minus x, m. (x, zone) for x >= 0.
    pub fn cohesive_zone(&self) -> Vec<(f64, f64)> {
        let arr = self.arrivals();
        let mut out = Vec::new();
        for (i, &xi) in self.x.iter().enumerate() {
            let Some(tw) = self.t_weakened[i] else { continue };
            if xi < -1e-12 {
                continue;
            }
            if let Some(j) = (0..arr.len().saturating_sub(1)).find(|&j| arr[j].1 <= tw && tw < arr[j + 1].1) {
                let ((x0, t0), (x1, t1)) = (arr[j], arr[j + 1]);
                out.push((xi, x0 + (tw - t0) / (t1 - t0) * (x1 - x0) - xi));
            }
        }
        out
    }
}
