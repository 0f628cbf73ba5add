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
    /// The background shear outside the patch and the pieces, Pa; None: from [`Self::s_ratio`].
    pub tau0_background: Option<f64>,
    /// A nucleation patch anywhere on the interface; None: the centred patch of
    /// [`Self::patch_half_width`], [`Self::overstress`] and [`Self::patch_taper`].
    pub nucleation: Option<Patch>,
    /// Values that differ from the background over intervals of x (a scene's `[interface]
    /// intervals`): no two setting the same value overlap.
    pub pieces: Vec<Piece>,
    /// Stations along the interface, m: one time series each ([`Station`]).
    pub stations: Vec<f64>,
    /// Station output interval, s; None: every step.
    pub dt_out: Option<f64>,
    /// The slip rate whose first crossing is a node's rupture time, m/s; None: the project's
    /// arrival rate 0.01 (mu_s - mu_d) sigma0 / (rho c_s) of the background.
    pub rate_threshold: Option<f64>,
    /// Whether waves may come back from the block's far edges to the stations (or the patch)
    /// before t_end: the spec's small block is such a domain by design; a scene file must say so.
    pub reflections_allowed: bool,
}

/// A nucleation patch x_min <= x <= x_max with initial shear tau0 (Pa) and a cosine ramp of
/// width `taper` (m) centred on each edge (0: a jump).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Patch {
    pub x_min: f64,
    pub x_max: f64,
    pub tau0: f64,
    pub taper: f64,
}

/// Values over x_min <= x <= x_max that replace the background's (None: the background's),
/// with a cosine ramp of width `taper` (m) centred on each edge.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Piece {
    pub x_min: f64,
    pub x_max: f64,
    pub taper: f64,
    /// Pa.
    pub sigma0: Option<f64>,
    /// Pa.
    pub tau0: Option<f64>,
    pub mu_s: Option<f64>,
    pub mu_d: Option<f64>,
    /// m.
    pub dc: Option<f64>,
}

/// The names of a [`Piece`]'s values, in its order (the scene keys).
pub const PIECE_KEYS: [&str; 5] = ["sigma0", "tau0", "mu_s", "mu_d", "dc"];

impl Piece {
    /// Its values in [`PIECE_KEYS`] order.
    pub fn values(&self) -> [Option<f64>; 5] {
        [self.sigma0, self.tau0, self.mu_s, self.mu_d, self.dc]
    }
}

/// `inside` over [x_min, x_max], `outside` beyond, across each edge a jump (the edge node
/// inside whatever the rounding of its coordinate) or a cosine ramp of width `taper` centred
/// on it. Written about the interval's centre so a centred patch gives the same bits as |x|.
fn ramp(x: f64, (x_min, x_max, taper): (f64, f64, f64), h: f64, inside: f64, outside: f64) -> f64 {
    let (c, a) = (0.5 * (x_min + x_max), 0.5 * (x_max - x_min));
    let r = (x - c).abs();
    if taper == 0.0 {
        return if r <= a + 1e-6 * h { inside } else { outside };
    }
    let s = ((r - (a - taper / 2.0)) / taper).clamp(0.0, 1.0);
    outside + (inside - outside) * 0.5 * (1.0 + (std::f64::consts::PI * s).cos())
}

/// The interface's values at each base node.
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    pub sigma0: Vec<f64>,
    pub tau0: Vec<f64>,
    pub law: Vec<Law>,
    /// Nodes whose static strength is over [`BARRIER_FACTOR`] times the largest initial shear:
    /// no front breaks them, so no cohesive zone there needs resolving.
    pub barrier: Vec<bool>,
}

/// A node is a barrier when mu_s sigma0 exceeds this many times the largest initial shear.
pub const BARRIER_FACTOR: f64 = 10.0;

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
            tau0_background: None,
            nucleation: None,
            pieces: Vec::new(),
            stations: Vec::new(),
            dt_out: None,
            rate_threshold: None,
            reflections_allowed: true,
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

    /// Background shear outside the patch, Pa: given, or tau0 = sigma0 (mu_s + S mu_d) / (1 + S).
    pub fn tau0(&self) -> f64 {
        let f = &self.friction;
        self.tau0_background
            .unwrap_or_else(|| self.sigma0 * (f.mu_s() + self.s_ratio * f.mu_d()) / (1.0 + self.s_ratio))
    }

    /// The nucleation patch: [`Self::nucleation`], or the centred one of the flags.
    pub fn patch(&self) -> Patch {
        self.nucleation.unwrap_or(Patch {
            x_min: -self.patch_half_width,
            x_max: self.patch_half_width,
            tau0: self.overstress * self.friction.mu_s() * self.sigma0,
            taper: self.patch_taper,
        })
    }

    /// The base nodes' x, m (the mesher numbers row by row: the first nx + 1 nodes).
    pub fn base_x(&self) -> Vec<f64> {
        let nx = (self.length / self.h).round() as usize;
        let x0 = -self.length / 2.0;
        (0..=nx).map(|i| x0 + (self.length / 2.0 - x0) * (i as f64) / (nx as f64)).collect()
    }

    /// The background with the pieces, then the patch, at each of `x`.
    pub fn layout(&self, x: &[f64]) -> Layout {
        let Law::SlipWeakening { mu_s, mu_d, dc } = self.friction else {
            unreachable!("validated: slip weakening")
        };
        let background = [self.sigma0, self.tau0(), mu_s, mu_d, dc];
        let patch = self.patch();
        let vals: Vec<[f64; 5]> = x
            .iter()
            .map(|&xi| {
                let mut v = background;
                for p in &self.pieces {
                    for (k, pv) in p.values().into_iter().enumerate() {
                        if let Some(pv) = pv {
                            v[k] = ramp(xi, (p.x_min, p.x_max, p.taper), self.h, pv, v[k]);
                        }
                    }
                }
                v[1] = ramp(xi, (patch.x_min, patch.x_max, patch.taper), self.h, patch.tau0, v[1]);
                v
            })
            .collect();
        let tau_max = vals.iter().map(|v| v[1]).fold(0.0, f64::max);
        Layout {
            sigma0: vals.iter().map(|v| v[0]).collect(),
            tau0: vals.iter().map(|v| v[1]).collect(),
            law: vals.iter().map(|v| Law::SlipWeakening { mu_s: v[2], mu_d: v[3], dc: v[4] }).collect(),
            barrier: vals.iter().map(|v| v[2] * v[0] > BARRIER_FACTOR * tau_max).collect(),
        }
    }

    /// D_c, m (the law is slip weakening once validated).
    pub fn dc(&self) -> f64 {
        self.friction.dc().unwrap_or(f64::INFINITY)
    }

    /// The initial shear at x, Pa ([`Self::layout`] at one point).
    pub fn prestress(&self, x: f64) -> f64 {
        self.layout(&[x]).tau0[0]
    }

    /// The project's arrival rate of the background, m/s: 0.01 (mu_s - mu_d) sigma0 / (rho c_s),
    /// the slip rate a front's arrival is read at (as `slide --dynamics`).
    pub fn arrival_rate(&self, speeds: &WaveSpeeds) -> f64 {
        0.01 * (self.friction.mu_s() - self.friction.mu_d()) * self.sigma0 / (self.density * speeds.c_s)
    }

    /// Lambda_0 of [`Law::cohesive_zone`], m: the shortest over the base nodes that are not
    /// barriers (the background's at sigma0 when the interface is uniform).
    pub fn lambda0(&self) -> Result<f64> {
        Ok(self.zones()?[0].0)
    }

    /// The shortest and the longest Lambda_0 over the non-barrier base nodes, each with the
    /// node's D_c (m) and x (m).
    fn zones(&self) -> Result<[(f64, f64, f64); 2]> {
        let m = self.material()?;
        let x = self.base_x();
        let lay = self.layout(&x);
        let mut z = [(f64::INFINITY, 0.0, 0.0), (0.0, 0.0, 0.0)];
        for (i, law) in lay.law.iter().enumerate() {
            if lay.barrier[i] {
                continue;
            }
            let l = law.cohesive_zone(m.shear_modulus(), m.nu, lay.sigma0[i]);
            let dc = law.dc().unwrap_or(f64::INFINITY);
            if l < z[0].0 {
                z[0] = (l, dc, x[i]);
            }
            if l > z[1].0 {
                z[1] = (l, dc, x[i]);
            }
        }
        Ok(z)
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
        // The scene file's values (before the checks that read the patch and the window).
        self.check_interface()?;
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
        let [(lambda0, dc, x_at), (longest, dc_long, _)] = self.zones()?;
        if !(longest <= self.length / 2.0) {
            return Err(Error::input(
                "D_c (m, --dc)",
                format!(
                    "the cohesive zone Lambda_0 = {longest:.3e} m is longer than the half block L/2 = {} m the front runs over from the patch: no front can form; lower --dc to at most {:.3e} m",
                    self.length / 2.0,
                    dc_long * (self.length / 2.0) / longest
                ),
            ));
        }
        if lambda0 < MIN_ZONE_ELEMENTS * self.h {
            let at = if self.pieces.is_empty() { String::new() } else { format!(" (at x = {x_at} m)") };
            return Err(Error::input(
                "D_c (m, --dc) or element size (m, --h)",
                format!(
                    "the cohesive zone Lambda_0 = {lambda0:.3e} m{at} spans {:.2} elements of h = {} m, fewer than \
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
    /// The scene-file values: the background shear, the pieces, the patch, the stations, the
    /// output interval and threshold, and the reflections' timing. Each message names the
    /// scene key.
    fn check_interface(&self) -> Result<()> {
        let half = self.length / 2.0;
        let inside = |x: f64| x.is_finite() && (-half..=half).contains(&x);
        if let Some(t) = self.tau0_background {
            crate::error::scaled("background shear ([interface] tau0, Pa)", t, "Pa")?;
        }
        for (i, p) in self.pieces.iter().enumerate() {
            let key = format!("[interface] intervals[{i}]");
            if !(inside(p.x_min) && inside(p.x_max) && p.x_min < p.x_max) {
                return Err(Error::input(
                    format!("{key}.x_min, x_max (m)"),
                    format!(
                        "[{}, {}] must be an interval x_min < x_max inside the block [-{half}, {half}] m",
                        p.x_min, p.x_max
                    ),
                ));
            }
            if !(p.taper.is_finite() && p.taper >= 0.0 && p.taper <= p.x_max - p.x_min) {
                return Err(Error::input(
                    format!("{key}.taper (m)"),
                    format!("{} must be between 0 and the interval's width {} m", p.taper, p.x_max - p.x_min),
                ));
            }
            if p.values().iter().all(Option::is_none) {
                return Err(Error::input(
                    key,
                    format!(
                        "sets none of {}: give at least one, or remove the interval",
                        PIECE_KEYS.join(", ")
                    ),
                ));
            }
            for (k, v) in p.values().into_iter().enumerate() {
                if let Some(v) = v {
                    if !(v.is_finite() && (v > 0.0 || ((2..=3).contains(&k) && v == 0.0))) {
                        return Err(Error::input(
                            format!("{key}.{}", PIECE_KEYS[k]),
                            format!("{v} must be finite and positive"),
                        ));
                    }
                }
            }
            // Intervals (with their ramps) setting the same value must not overlap.
            for (j, q) in self.pieces[..i].iter().enumerate() {
                let shared: Vec<&str> = (0..5)
                    .filter(|&k| p.values()[k].is_some() && q.values()[k].is_some())
                    .map(|k| PIECE_KEYS[k])
                    .collect();
                let (a0, a1) = (p.x_min - p.taper / 2.0, p.x_max + p.taper / 2.0);
                let (b0, b1) = (q.x_min - q.taper / 2.0, q.x_max + q.taper / 2.0);
                if !shared.is_empty() && a0.max(b0) < a1.min(b1) {
                    return Err(Error::input(
                        format!("[interface] intervals[{j}] and intervals[{i}]"),
                        format!(
                            "[{}, {}] and [{}, {}] m overlap (ramps included) and both set {}: each point takes one value",
                            q.x_min, q.x_max, p.x_min, p.x_max, shared.join(", ")
                        ),
                    ));
                }
            }
        }
        let lay = self.layout(&self.base_x());
        for (i, law) in lay.law.iter().enumerate() {
            let (mu_s, mu_d) = (law.mu_s(), law.mu_d());
            if !(mu_d <= mu_s) {
                return Err(Error::input(
                    "[interface] intervals mu_s, mu_d",
                    format!("at x = {} m mu_s = {mu_s} < mu_d = {mu_d}: need mu_d <= mu_s", self.base_x()[i]),
                ));
            }
        }
        if let Some(p) = self.nucleation {
            if !(inside(p.x_min) && inside(p.x_max) && p.x_min < p.x_max && p.x_min > -half && p.x_max < half)
            {
                return Err(Error::input(
                    "[interface.nucleation] x_min, x_max (m)",
                    format!(
                        "[{}, {}] must lie inside the block (-{half}, {half}) m with unbroken interface beyond it for the rupture to run into",
                        p.x_min, p.x_max
                    ),
                ));
            }
            if !(p.taper.is_finite() && p.taper >= 0.0 && p.taper <= p.x_max - p.x_min) {
                return Err(Error::input(
                    "[interface.nucleation] taper (m)",
                    format!("{} must be between 0 and the patch width {} m", p.taper, p.x_max - p.x_min),
                ));
            }
            crate::error::scaled("[interface.nucleation] tau0 (Pa)", p.tau0, "Pa")?;
            for p2 in self.pieces.iter().filter(|q| q.tau0.is_some()) {
                if (p.x_min - p.taper / 2.0).max(p2.x_min - p2.taper / 2.0)
                    < (p.x_max + p.taper / 2.0).min(p2.x_max + p2.taper / 2.0)
                {
                    return Err(Error::input(
                        "[interface.nucleation] x_min, x_max (m)",
                        format!(
                            "the patch [{}, {}] m overlaps an interval setting tau0 ([{}, {}] m): each point takes one initial shear",
                            p.x_min, p.x_max, p2.x_min, p2.x_max
                        ),
                    ));
                }
            }
            let x = self.base_x();
            if !x.iter().enumerate().any(|(i, &xi)| {
                xi >= p.x_min - 1e-6 * self.h
                    && xi <= p.x_max + 1e-6 * self.h
                    && lay.tau0[i] > lay.law[i].mu_s() * lay.sigma0[i]
            }) {
                return Err(Error::input(
                    "[interface.nucleation] tau0 (Pa)",
                    format!(
                        "{} Pa is nowhere above the static strength mu_s sigma0 on the patch's nodes: nothing would start; give tau0 above it",
                        p.tau0
                    ),
                ));
            }
        }
        for (i, &x) in self.stations.iter().enumerate() {
            if !inside(x) {
                return Err(Error::input(
                    format!("[rupture] stations[{i}] (m)"),
                    format!("x = {x} m is off the interface [-{half}, {half}] m"),
                ));
            }
            if self.stations[..i].contains(&x) {
                return Err(Error::input(
                    format!("[rupture] stations[{i}] (m)"),
                    format!("x = {x} m is given twice"),
                ));
            }
        }
        if let Some(d) = self.dt_out {
            crate::error::scaled("[rupture] dt_out (s)", d, "s")?;
        }
        if let Some(r) = self.rate_threshold {
            crate::error::scaled("[rupture] rate_threshold (m/s)", r, "m/s")?;
        }
        if !self.reflections_allowed {
            let (t_back, from) = self.clean_time()?;
            if t_back < self.t_end {
                return Err(Error::input(
                    "[rupture] reflections",
                    format!(
                        "waves from the nucleation patch come back from the block's {from} to the {} at t = {t_back:.4} s, before t_end = {} s: \
                         enlarge the block (block.length, block.thickness), shorten t_end, or say reflections = \"allowed\"",
                        if self.stations.is_empty() { "patch" } else { "stations" },
                        self.t_end
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The earliest time a wave leaving the patch at t = 0 (at most c_p) comes back from the
    /// block's top or sides to the stations' span (the patch without stations), s, and which
    /// edge sends it.
    pub fn clean_time(&self) -> Result<(f64, &'static str)> {
        let c_p = WaveSpeeds::new(&self.material()?, self.density).c_p;
        let p = self.patch();
        let (r0, r1) = match (
            self.stations.iter().copied().reduce(f64::min),
            self.stations.iter().copied().reduce(f64::max),
        ) {
            (Some(a), Some(b)) => (a.min(p.x_min), b.max(p.x_max)),
            _ => (p.x_min, p.x_max),
        };
        let half = self.length / 2.0;
        let sides = f64::min((half - p.x_max) + (half - r1), (p.x_min + half) + (r0 + half));
        Ok(if 2.0 * self.height <= sides { (2.0 * self.height / c_p, "top") } else { (sides / c_p, "sides") })
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
    /// One time series per station of [`RuptureSpec::stations`], in their order.
    pub stations: Vec<Station>,
    /// Each base node's first time its slip rate exceeds [`Self::rate_threshold`], s.
    pub rupture_time: Vec<Option<f64>>,
    /// m/s.
    pub rate_threshold: f64,
    /// The slip rate of every base node at about [`MAP_ROWS`] times: the space-time picture.
    pub map: RateMap,
    /// x of the barrier nodes that slipped past D_c / 100 (m): a barrier the run broke.
    pub barrier_slipped: Vec<f64>,
    /// Slip per unit displacement along x: 2 on a symmetric fault, else 1.
    pub slip_factor: f64,
}

/// A station's time series in the field's conventions: slip (the jump across the interface,
/// 2 u_x on a symmetric fault), slip rate, shear and normal traction (Pa, the normal one
/// negative in compression as SCEC's) at each output time: every `dt_out` from t = 0 and at
/// t_end (whose slip rate is the last half step's).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Station {
    pub x: f64,
    pub t: Vec<f64>,
    pub slip: Vec<f64>,
    pub slip_rate: Vec<f64>,
    pub shear: Vec<f64>,
    pub normal: Vec<f64>,
}

/// Slip rates (m/s, as f32: a picture) of every base node at the times `t` (s).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RateMap {
    pub t: Vec<f64>,
    pub rates: Vec<Vec<f32>>,
}

/// Rows the space-time picture keeps at most.
pub const MAP_ROWS: usize = 600;

/// What a run writes down as it goes: the stations (linear between the two base nodes about
/// each), the rupture times, the space-time map.
#[derive(Clone)]
struct Recorder {
    stride: usize,
    stations: Vec<Probe>,
    map_stride: usize,
    map: RateMap,
    threshold: f64,
    rupture_time: Vec<Option<f64>>,
    /// Each base node's slip rate at t_n on a recorded step.
    mid: Vec<f64>,
}

#[derive(Clone)]
struct Probe {
    /// Base node index left of the station and the weight of the right one.
    left: usize,
    w: f64,
    series: Station,
}

impl Recorder {
    fn new(spec: &RuptureSpec, x: &[f64], dt: f64, steps: usize, threshold: f64) -> Self {
        let n = x.len();
        let stations = spec
            .stations
            .iter()
            .map(|&xs| {
                let left = x.partition_point(|&xi| xi <= xs).saturating_sub(1).min(n - 2);
                let w = ((xs - x[left]) / (x[left + 1] - x[left])).clamp(0.0, 1.0);
                Probe { left, w, series: Station { x: xs, ..Default::default() } }
            })
            .collect();
        Self {
            stride: spec.dt_out.map_or(1, |d| ((d / dt).round() as usize).max(1)),
            stations,
            map_stride: steps.div_ceil(MAP_ROWS).max(1),
            map: RateMap::default(),
            threshold,
            rupture_time: vec![None; n],
            mid: vec![0.0; n],
        }
    }
    /// One row of every station at time t (s) from the base's displacements `u`, tractions
    /// `tr` and normal forces `fby` (perturbation) and the slip rates in `mid`.
    #[allow(clippy::too_many_arguments)]
    fn stations(
        &mut self,
        t: f64,
        u: &[f64],
        base: &[usize],
        tr: &[f64],
        fby: &[f64],
        width: &[f64],
        sigma0: &[f64],
        slip_factor: f64,
    ) {
        let mid = &self.mid;
        for p in &mut self.stations {
            let (b0, b1, w) = (p.left, p.left + 1, p.w);
            let at = |a: f64, b: f64| (1.0 - w) * a + w * b;
            // The normal stress (compressive positive here): sigma0 + fby / w.
            let sig = |b: usize| sigma0[b] + fby[b] / width[b];
            let st = &mut p.series;
            st.t.push(t);
            st.slip_rate.push(at(mid[b0], mid[b1]));
            st.slip.push(slip_factor * at(u[2 * base[b0]], u[2 * base[b1]]));
            st.shear.push(at(tr[b0], tr[b1]));
            st.normal.push(-at(sig(b0), sig(b1)));
        }
    }
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
    let Layout { sigma0, tau0, law, barrier } = spec.layout(&x);
    let slip_factor = if spec.contact == Contact::Symmetric { 2.0 } else { 1.0 };
    let threshold = spec.rate_threshold.unwrap_or_else(|| spec.arrival_rate(&speeds));
    let rec = Recorder::new(spec, &x, dt, steps, threshold);

    let nb = base.len();
    let mut fl = Flat {
        spec,
        base: &base,
        width: &width,
        tau0: &tau0,
        sigma0: &sigma0,
        law: &law,
        rec,
        d: vec![0.0; nb],
        t_arrival: vec![None; nb],
        t_weakened: vec![None; nb],
        peak: vec![0.0; nb],
        fbx: vec![0.0; nb],
        fby: vec![0.0; nb],
        tr: vec![0.0; nb],
        seff: sigma0.clone(),
        theta: vec![0.0; nb],
        slip_factor,
        min_sigma: f64::INFINITY,
        e: RuptureEnergy::default(),
    };
    let mut ex = Explicit::checked_by_caller(&model, dt, spec.damping, vec![false; model.n_dofs()])
        .with_boundary(&base);
    // The energies are read at t_end (`level`) and from the sums: not summed per step.
    ex.sums = crate::dynamics::explicit::Sums::Running;
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
    // The stations' last row at t_end (its slip rate the last half step's).
    for (b, &k) in base.iter().enumerate() {
        fl.rec.mid[b] = fl.slip_factor * v[2 * k];
    }
    fl.rec.stations(steps as f64 * dt, &u, &base, &fl_end.tr, &fl_end.fby, &width, &sigma0, fl.slip_factor);
    let tr = fl_end.tr;
    let mut e = RuptureEnergy { kinetic, strain, damping, ..fl.e };
    e.residual = e.kinetic + e.strain + e.friction + e.damping - e.background_work - e.contact;
    let barrier_slipped =
        (0..nb).filter(|&b| barrier[b] && fl.t_arrival[b].is_some()).map(|b| x[b]).collect();
    let (min_sigma, d, t_arr, t_wk, peak, rec) =
        (fl.min_sigma, fl.d, fl.t_arrival, fl.t_weakened, fl.peak, fl.rec);
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
        stations: rec.stations.into_iter().map(|st| st.series).collect(),
        rupture_time: rec.rupture_time,
        rate_threshold: threshold,
        map: rec.map,
        barrier_slipped,
        slip_factor,
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
    sigma0: &'s [f64],
    law: &'s [Law],
    rec: Recorder,
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
            let sigma0 = self.sigma0[b];
            let mut sigma = sigma0 - (fy + m * v[2 * k + 1] / dt) / w;
            if spec.contact == Contact::Symmetric {
                sigma = sigma0;
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
            let (t, _) = self.law[b].split_node(trial, &mut self.theta[b]);
            self.tr[b] = t;
            self.fbx[b] = (self.tau0[b] - t) * w;
            self.fby[b] = (sigma - sigma0) * w;
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
        let slip_factor = self.slip_factor;
        let t0 = s.n as f64 * dt;
        let (record, mapped) = (s.n.is_multiple_of(self.rec.stride), s.n.is_multiple_of(self.rec.map_stride));
        if mapped {
            self.rec.map.t.push(t0);
            self.rec.map.rates.push(Vec::with_capacity(self.base.len()));
        }
        for (b, &k) in self.base.iter().enumerate() {
            let (m, w) = (s.mass[k], self.width[b]);
            let law = self.law[b];
            let (dc, thr) = (law.dc().unwrap_or(f64::INFINITY), law.dc().unwrap_or(f64::INFINITY) / 100.0);
            let (vxm, vym) = (s.v[2 * k], s.v[2 * k + 1]);
            let vx = vxm + dt * (s.force(2 * k) + self.fbx[b]) / m;
            let vy = vym + dt * (s.force(2 * k + 1) + self.fby[b]) / m;
            // In contact the flat holds u_y^{n+1} = 0 exactly (not to round-off), so a
            // unilateral run that never opens is the bilateral run bit for bit.
            let held = spec.contact == Contact::Unilateral && self.fby[b] > -self.sigma0[b] * w;
            let vy = match spec.contact {
                Contact::Bilateral => 0.0,
                Contact::Unilateral if held => -s.u[2 * k + 1] / dt,
                _ => vy,
            };
            let (vbx, vby) = (0.5 * (vxm + vx), 0.5 * (vym + vy));
            self.e.background_work += dt * w * (vbx * self.tau0[b] - vby * self.sigma0[b]);
            self.e.friction += dt * vbx * self.tr[b] * w;
            self.e.contact += dt * vby * (self.fby[b] + self.sigma0[b] * w);
            // (per half of a symmetric fault: the work on this block's face)
            self.e.friction_path += self.tr[b].abs() * w * dt * vx.abs();
            s.v[2 * k] = vx;
            s.v[2 * k + 1] = vy;
            s.u_next[2 * k] = s.u[2 * k] + dt * vx;
            s.u_next[2 * k + 1] = if held { 0.0 } else { s.u[2 * k + 1] + dt * vy };
            let d_new = self.d[b] + slip_factor * dt * vx.abs();
            // The rate at t_{n+1/2} against the one at t_{n-1/2}.
            let (r_old, r_new) = (slip_factor * vxm.abs(), slip_factor * vx.abs());
            if self.rec.rupture_time[b].is_none() && r_new > self.rec.threshold {
                let f = ((self.rec.threshold - r_old) / (r_new - r_old)).clamp(0.0, 1.0);
                // Not before the start: the patch's first half step starts from rest at t = 0.
                self.rec.rupture_time[b] = Some((t0 - 0.5 * dt + f * dt).max(0.0));
            }
            if mapped {
                self.rec.map.rates.last_mut().expect("row pushed").push(r_new as f32);
            }
            if record {
                // The slip rate at t_n, the mean of the two half steps'.
                self.rec.mid[b] = slip_factor * 0.5 * (vxm + vx);
            }
            if self.t_arrival[b].is_none() && d_new >= thr {
                self.t_arrival[b] = Some(t0 + dt * (thr - self.d[b]) / (d_new - self.d[b]));
            }
            if self.t_weakened[b].is_none() && d_new >= dc {
                self.t_weakened[b] = Some(t0 + dt * (dc - self.d[b]) / (d_new - self.d[b]));
            }
            self.peak[b] = f64::max(self.peak[b], vx.abs());
            self.d[b] = d_new;
        }
        if record {
            self.rec.stations(t0, s.u, self.base, &self.tr, &self.fby, self.width, self.sigma0, slip_factor);
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

/// A `rupture` scene read from a scene file: the spec, and for each value the file set, the
/// flag that would set it and the file's key (to name the key when a check refuses it).
#[derive(Debug, Clone)]
pub struct SceneSpec {
    pub spec: RuptureSpec,
    pub keys: Vec<(&'static str, &'static str)>,
}

impl SceneSpec {
    /// The spec of `scene` (`[block]` length and thickness as the block, `[mesh]` h, `[law]` the
    /// background law and normal response, `[interface]`, `[rupture]`); a value the file does not
    /// give is [`RuptureSpec::default`]'s (the normal response: `tribofe rupture`'s default
    /// lag, [`DEFAULT_NORMAL_LAG`]), the block's and the mesh's are the scene's.
    pub fn from_scene(scene: &crate::scene::Scene) -> Result<Self> {
        use crate::scene::{InterfaceTable, RuptureTable};
        if scene.block.state != crate::scene::State::PlaneStrain {
            return Err(Error::input(
                "[block] state",
                "'plane-stress': a rupture scene runs plane strain only (its benchmarks are plane strain); remove the key",
            ));
        }
        let d = RuptureSpec::default();
        let mut keys = vec![
            ("--length", "block.length"),
            ("--height", "block.thickness"),
            ("--h", "mesh.h"),
            ("--young", "block.young"),
            ("--poisson", "block.poisson"),
            ("--density", "block.density"),
        ];
        let law = &scene.law;
        if let Some(k) = &law.kind {
            if k != "slip-weakening" {
                return Err(Error::input(
                    "[law] kind",
                    format!("'{}': a rupture scene runs slip-weakening", crate::error::quote(k)),
                ));
            }
        }
        for (flag, key, v) in [
            ("--mu-s", "[law] mu_s", law.mu_s),
            ("--mu-d", "[law] mu_d", law.mu_d),
            ("--dc", "[law] dc", law.dc),
        ] {
            if v.is_some() {
                keys.push((flag, key));
            }
        }
        let unused = [
            ("mu", law.mu.is_some()),
            ("r", law.r.is_some()),
            ("g", law.g.is_some()),
            ("rule", law.rule.is_some()),
            ("a", law.a.is_some()),
            ("b", law.b.is_some()),
            ("l_rs", law.l_rs.is_some()),
            ("v0", law.v0.is_some()),
            ("f0", law.f0.is_some()),
            ("state_law", law.state_law.is_some()),
            ("theta0", law.theta0.is_some()),
        ];
        if let Some((k, _)) = unused.iter().find(|u| u.1) {
            return Err(Error::input(
                format!("[law] {k}"),
                "cannot act in a rupture scene (slip weakening: mu_s, mu_d, dc, and the normal_lag keys)",
            ));
        }
        let f = (
            law.mu_s.unwrap_or(d.friction.mu_s()),
            law.mu_d.unwrap_or(d.friction.mu_d()),
            law.dc.unwrap_or(d.dc()),
        );
        let it = scene.interface.clone().unwrap_or_default();
        let InterfaceTable { kind, sigma0, tau0, s, nucleation, intervals } = it;
        if tau0.is_some() && s.is_some() {
            return Err(Error::input(
                "[interface] tau0",
                "give the background shear as tau0 or as s, not both",
            ));
        }
        for (flag, key, given) in [
            ("--contact", "[interface] kind", kind.is_some()),
            ("--sigma0", "[interface] sigma0", sigma0.is_some()),
            ("--s", "[interface] s", s.is_some()),
            ("--normal-lag", "[law] normal_lag", law.normal_lag.is_some()),
            ("--normal-lag-length", "[law] normal_lag_length", law.normal_lag_length.is_some()),
            ("--normal-lag-v-star", "[law] normal_lag_v_star", law.normal_lag_v_star.is_some()),
        ] {
            if given {
                keys.push((flag, key));
            }
        }
        let r = scene.rupture.clone().unwrap_or_default();
        let RuptureTable {
            t_end,
            courant,
            damping,
            max_steps,
            stations,
            dt_out,
            rate_threshold,
            reflections,
            speed_window,
        } = r;
        for (flag, key, given) in [
            ("--t-end", "[rupture] t_end", t_end.is_some()),
            ("--courant", "[rupture] courant", courant.is_some()),
            ("--damping", "[rupture] damping", damping.is_some()),
            ("--max-steps", "[rupture] max_steps", max_steps.is_some()),
        ] {
            if given {
                keys.push((flag, key));
            }
        }
        let reflections_allowed = match reflections.as_deref() {
            None | Some("refused") => false,
            Some("allowed") => true,
            Some(o) => {
                return Err(Error::input(
                    "[rupture] reflections",
                    format!("'{}': use refused or allowed", crate::error::quote(o)),
                ))
            }
        };
        // A value with no background must be set everywhere by the intervals.
        let backgrounds = [
            ("[interface] sigma0", sigma0.is_some()),
            ("[interface] tau0 (or s)", tau0.is_some() || s.is_some()),
            ("[law] mu_s", law.mu_s.is_some()),
            ("[law] mu_d", law.mu_d.is_some()),
            ("[law] dc", law.dc.is_some()),
        ];
        let half = scene.block.length / 2.0;
        for (k, (key, given)) in backgrounds.iter().enumerate() {
            if *given {
                continue;
            }
            let mut spans: Vec<(f64, f64)> = intervals
                .iter()
                .filter(|p| [p.sigma0, p.tau0, p.mu_s, p.mu_d, p.dc][k].is_some())
                .map(|p| (p.x_min, p.x_max))
                .collect();
            spans.sort_by(|a, b| a.0.total_cmp(&b.0));
            let mut reached = -half;
            for (a, b) in &spans {
                if *a > reached {
                    break;
                }
                reached = reached.max(*b);
            }
            if reached < half {
                let next = spans.iter().map(|s| s.0).find(|&a| a > reached).unwrap_or(half);
                return Err(Error::input(
                    *key,
                    format!(
                        "is not given, and the intervals setting {} leave {reached} < x < {next} m uncovered: give the background value or cover the block [-{half}, {half}] m",
                        PIECE_KEYS[k]
                    ),
                ));
            }
        }
        let nucleation =
            nucleation.map(|p| Patch { x_min: p.x_min, x_max: p.x_max, tau0: p.tau0, taper: p.taper });
        let speed_window = match (speed_window, nucleation) {
            (Some([a, b]), _) => (a, b),
            // From the patch's right edge to halfway to the block's end.
            (None, Some(p)) => (p.x_max.max(0.0), 0.5 * (p.x_max.max(0.0) + half)),
            (None, None) => d.speed_window,
        };
        let spec = RuptureSpec {
            length: scene.block.length,
            height: scene.block.thickness,
            h: scene.mesh.h,
            young: scene.block.young,
            poisson: scene.block.poisson,
            density: scene.block.density,
            sigma0: sigma0.unwrap_or(d.sigma0),
            s_ratio: s.unwrap_or(d.s_ratio),
            friction: Law::SlipWeakening { mu_s: f.0, mu_d: f.1, dc: f.2 },
            courant: courant.unwrap_or(d.courant),
            t_end: t_end.unwrap_or(d.t_end),
            damping: damping.unwrap_or(d.damping),
            contact: kind.as_deref().map_or(Ok(d.contact), str::parse)?,
            speed_window,
            // As the command's flags: the regularised lag unless the file says.
            normal: if [law.normal_lag, law.normal_lag_length, law.normal_lag_v_star]
                .iter()
                .all(Option::is_none)
            {
                Normal::Time { t: DEFAULT_NORMAL_LAG }
            } else {
                law.normal([None; 3])?
            },
            max_steps: max_steps.unwrap_or(d.max_steps),
            tau0_background: tau0,
            nucleation,
            pieces: intervals
                .iter()
                .map(|p| Piece {
                    x_min: p.x_min,
                    x_max: p.x_max,
                    taper: p.taper,
                    sigma0: p.sigma0,
                    tau0: p.tau0,
                    mu_s: p.mu_s,
                    mu_d: p.mu_d,
                    dc: p.dc,
                })
                .collect(),
            stations,
            dt_out,
            rate_threshold,
            reflections_allowed,
            ..d
        };
        Ok(Self { spec, keys })
    }

    /// `e` with each flag of [`Self::keys`] not in `given` replaced by the file's key.
    pub fn name_keys(&self, e: Error, given: &dyn Fn(&str) -> bool) -> Error {
        let Error::Input { mut what, mut why } = e else { return e };
        for (flag, key) in &self.keys {
            if !given(flag) {
                // A flag followed by a letter or '-' is another flag (--normal-lag-length).
                let swap = |s: &str| {
                    let mut out = String::new();
                    let mut rest = s;
                    while let Some(i) = rest.find(flag) {
                        let after = rest[i + flag.len()..].chars().next();
                        out.push_str(&rest[..i]);
                        if after.is_some_and(|c| c.is_ascii_alphanumeric() || c == '-') {
                            out.push_str(flag);
                        } else {
                            out.push_str(key);
                        }
                        rest = &rest[i + flag.len()..];
                    }
                    out.push_str(rest);
                    out
                };
                what = swap(&what);
                why = swap(&why);
            }
        }
        Error::Input { what, why }
    }
}

/// The values a front end (the command's flags, the Python keywords) gives on top of a scene
/// file: each `Some` replaces the file's key (the normal-response ones the file's normal
/// response as a whole).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SceneInputs {
    pub s: Option<f64>,
    pub h: Option<f64>,
    pub dc: Option<f64>,
    pub t_end: Option<f64>,
    pub length: Option<f64>,
    pub height: Option<f64>,
    pub mu_s: Option<f64>,
    pub mu_d: Option<f64>,
    pub sigma0: Option<f64>,
    pub young: Option<f64>,
    pub poisson: Option<f64>,
    pub density: Option<f64>,
    pub courant: Option<f64>,
    pub damping: Option<f64>,
    pub contact: Option<String>,
    pub normal_lag: Option<f64>,
    pub normal_lag_length: Option<f64>,
    pub normal_lag_v_star: Option<f64>,
    pub patch_taper: Option<f64>,
    pub max_steps: Option<u64>,
}

impl SceneInputs {
    /// Whether the front end gave the value of flag `flag` (`--normal-lag`).
    pub fn gives(&self, flag: &str) -> bool {
        match flag {
            "--s" => self.s.is_some(),
            "--h" => self.h.is_some(),
            "--dc" => self.dc.is_some(),
            "--t-end" => self.t_end.is_some(),
            "--length" => self.length.is_some(),
            "--height" => self.height.is_some(),
            "--mu-s" => self.mu_s.is_some(),
            "--mu-d" => self.mu_d.is_some(),
            "--sigma0" => self.sigma0.is_some(),
            "--young" => self.young.is_some(),
            "--poisson" => self.poisson.is_some(),
            "--density" => self.density.is_some(),
            "--courant" => self.courant.is_some(),
            "--damping" => self.damping.is_some(),
            "--contact" => self.contact.is_some(),
            "--normal-lag" => self.normal_lag.is_some(),
            "--normal-lag-length" => self.normal_lag_length.is_some(),
            "--normal-lag-v-star" => self.normal_lag_v_star.is_some(),
            "--patch-taper" => self.patch_taper.is_some(),
            "--max-steps" => self.max_steps.is_some(),
            _ => false,
        }
    }

    /// The spec of the scene file at `path` with these values on top, checked, and that
    /// effective scene (for run.toml): a refusal names the file's key where the file set the
    /// value, the flag where the front end did.
    pub fn spec(&self, path: &std::path::Path) -> Result<(RuptureSpec, crate::scene::Scene)> {
        let mut sc = crate::scene::Scene::from_file(path)?;
        let b = &mut sc.block;
        for (v, slot) in [
            (self.length, &mut b.length),
            (self.height, &mut b.thickness),
            (self.young, &mut b.young),
            (self.poisson, &mut b.poisson),
            (self.density, &mut b.density),
            (self.h, &mut sc.mesh.h),
        ] {
            if let Some(v) = v {
                *slot = v;
            }
        }
        let law = &mut sc.law;
        for (v, slot) in [(self.mu_s, &mut law.mu_s), (self.mu_d, &mut law.mu_d), (self.dc, &mut law.dc)] {
            if v.is_some() {
                *slot = v;
            }
        }
        if self.normal_lag.is_some() || self.normal_lag_length.is_some() || self.normal_lag_v_star.is_some() {
            (law.normal_lag, law.normal_lag_length, law.normal_lag_v_star) =
                (self.normal_lag, self.normal_lag_length, self.normal_lag_v_star);
        }
        let it = sc.interface.get_or_insert_with(Default::default);
        for (v, slot) in [(self.sigma0, &mut it.sigma0), (self.s, &mut it.s)] {
            if v.is_some() {
                *slot = v;
            }
        }
        if self.contact.is_some() {
            it.kind.clone_from(&self.contact);
        }
        let r = sc.rupture.get_or_insert_with(Default::default);
        for (v, slot) in
            [(self.t_end, &mut r.t_end), (self.courant, &mut r.courant), (self.damping, &mut r.damping)]
        {
            if v.is_some() {
                *slot = v;
            }
        }
        if self.max_steps.is_some() {
            r.max_steps = self.max_steps;
        }
        let named = |e: Error| match e {
            // A key of the file (not a flag): say which file.
            Error::Input { what, why } if !what.contains("--") => Error::Input {
                what: format!("{what} in {}", crate::error::quote(&path.display().to_string())),
                why,
            },
            e => e,
        };
        sc.validate().map_err(named)?;
        let ss = SceneSpec::from_scene(&sc).map_err(named)?;
        let mut spec = ss.spec.clone();
        if let Some(w) = self.patch_taper {
            match (&mut spec.nucleation, &mut sc.interface) {
                (Some(p), Some(it)) => {
                    p.taper = w;
                    if let Some(n) = &mut it.nucleation {
                        n.taper = w;
                    }
                }
                _ => spec.patch_taper = w,
            }
        }
        spec.validate().map_err(|e| named(ss.name_keys(e, &|f| self.gives(f))))?;
        Ok((spec, sc))
    }
}

impl SceneInputs {
    /// The flag-driven scene (no file): [`RuptureSpec::default`] with the command's normal lag
    /// ([`DEFAULT_NORMAL_LAG`]) and these values on top, checked.
    pub fn flag_spec(&self) -> Result<RuptureSpec> {
        let mut spec = RuptureSpec { normal: Normal::Time { t: DEFAULT_NORMAL_LAG }, ..Default::default() };
        for (v, slot) in [
            (self.s, &mut spec.s_ratio),
            (self.h, &mut spec.h),
            (self.t_end, &mut spec.t_end),
            (self.length, &mut spec.length),
            (self.height, &mut spec.height),
            (self.sigma0, &mut spec.sigma0),
            (self.young, &mut spec.young),
            (self.poisson, &mut spec.poisson),
            (self.density, &mut spec.density),
            (self.courant, &mut spec.courant),
            (self.damping, &mut spec.damping),
            (self.patch_taper, &mut spec.patch_taper),
        ] {
            if let Some(v) = v {
                *slot = v;
            }
        }
        let f = spec.friction;
        spec.friction = Law::SlipWeakening {
            mu_s: self.mu_s.unwrap_or(f.mu_s()),
            mu_d: self.mu_d.unwrap_or(f.mu_d()),
            dc: self.dc.unwrap_or(spec.dc()),
        };
        if let Some(c) = &self.contact {
            spec.contact = c.parse()?;
        }
        spec.normal = Normal::from_inputs(
            self.normal_lag,
            self.normal_lag_length,
            self.normal_lag_v_star,
            spec.normal,
            ["--normal-lag", "--normal-lag-length", "--normal-lag-v-star"],
        )?;
        if let Some(n) = self.max_steps {
            spec.max_steps = n;
        }
        spec.validate()?;
        Ok(spec)
    }
}
