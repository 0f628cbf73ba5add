//! The paper's scene (Scheibert & Dysthe, EPL 2010, fig. 1 and the paragraph before fig. 2):
//! an elastic block bonded at y = 0, a plate bonded on its top, the plate's normal
//! displacement prescribed at the centre of its top and its tangential displacement at
//! height H on its left side. Every key of the TOML scene defaults to the paper's value.
//!
//! ```text
//!        V (normal, centre of plate top)
//!        v
//!   +-----------------------------+  y = t + plate thickness (elastic plate only)
//! U>|            plate            |  U applied at height H on the left side
//!   +-----------------------------+  y = t   (top, bonded)
//!   |            block            |
//!   +-----------------------------+  y = 0   (interface, u = v = 0)
//!  x = -L/2                     x = L/2
//! ```

mod build;
pub mod limits;
pub mod overrides;
pub mod rectangle;

pub use build::SidePushDofs;
pub use overrides::Overrides;

use crate::error::{num, Error, Result};
use crate::fem::assembly::Model;
use crate::fem::constraints::Constraints;
use crate::fem::element::stiffness::{ElementChoice, Technology};
use crate::fem::material::Material;
pub use crate::fem::material::State;
use crate::fem::mesh::Mesh;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum PlateModel {
    /// Exactly rigid: three unknowns (U, V, theta), every top node tied to them.
    Rigid,
    /// Meshed with its own elements and modulus, as Cast3M did in the paper.
    Elastic,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Block {
    /// L, m.
    pub length: f64,
    /// t, m.
    pub thickness: f64,
    /// E, Pa.
    pub young: f64,
    pub poisson: f64,
    /// kg/m^3, for the dynamic solver only (default 1000: a soft gel of this modulus is
    /// mostly water; the paper, being quasi-static, gives none). Sets the time scale only.
    pub density: f64,
    /// The material by its wave speeds instead of young and poisson (m/s, plane strain, with
    /// density): read from the file and turned into young and poisson there.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub c_p: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub c_s: Option<f64>,
    /// plane-strain (the default) or plane-stress (`--plane-stress`), for the whole 2D model.
    pub state: State,
    /// b, the plate's out-of-plane width, m (`--width`): turns the per-unit-width forces into
    /// newtons; plane stress requires it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub width: Option<f64>,
    /// The file's wave speeds (c_p, c_s) once turned into young and poisson, to turn them
    /// again if a flag changes the state.
    #[serde(skip)]
    pub(crate) wave_speeds: Option<(f64, f64)>,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Plate {
    pub model: PlateModel,
    /// m (elastic plate only; the default makes its left side reach height H).
    pub thickness: f64,
    /// Pa (elastic plate only).
    pub young: f64,
    pub poisson: f64,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Loading {
    /// H, height of the tangential loading point above the interface, m (top-plate rig only).
    pub height: f64,
    /// Requested load cases as ratios F/N (dimensionless).
    pub fn_ratios: Vec<f64>,
    /// The loading rig (`--rig`): top-plate (the paper's, the default) or side-push.
    #[serde(skip_serializing_if = "Rig::is_top_plate")]
    pub rig: Rig,
    /// Side push: the pusher's centre above the interface, m (`--push-height`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub push_height: Option<f64>,
    /// Side push: the pusher's contact length on the trailing face x = -L/2, m (`--push-width`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub push_width: Option<f64>,
    /// Side push: the driving spring's stiffness, N/m per metre of width (`--push-stiffness`);
    /// checked now, used by the frictional phases.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub push_stiffness: Option<f64>,
    /// Side push: how the normal load reaches the top face (`--top`; default uniform-pressure).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub top: Option<Top>,
}

/// The loading rig (`[loading] rig`, `--rig`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Rig {
    /// The paper's: a rigid plate bonded on the top, driven at height H.
    #[default]
    TopPlate,
    /// A rigid pusher on the trailing face x = -L/2 at `push_height`, `push_width` wide.
    SidePush,
}

impl Rig {
    pub const NAMES: &'static str = "top-plate or side-push";
    pub fn is_top_plate(&self) -> bool {
        *self == Rig::TopPlate
    }
    pub fn name(&self) -> &'static str {
        match self {
            Rig::TopPlate => "top-plate",
            Rig::SidePush => "side-push",
        }
    }
}

impl std::str::FromStr for Rig {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "top-plate" => Ok(Rig::TopPlate),
            "side-push" => Ok(Rig::SidePush),
            _ => Err(Error::input("--rig", format!("'{}': use {}", crate::error::quote(s), Rig::NAMES))),
        }
    }
}

/// The normal load on the top face under side push (`[loading] top`, `--top`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Top {
    /// A uniform pressure N/L on the top face.
    #[default]
    UniformPressure,
    /// A rigid plate bonded on the top, free to slide horizontally (no horizontal force) and
    /// to rotate (no moment), N applied at its centre: it carries no part of the push's torque.
    SlidingPlate,
}

impl Top {
    pub const NAMES: &'static str = "uniform-pressure or sliding-plate";
    pub fn name(&self) -> &'static str {
        match self {
            Top::UniformPressure => "uniform-pressure",
            Top::SlidingPlate => "sliding-plate",
        }
    }
}

impl std::str::FromStr for Top {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "uniform-pressure" => Ok(Top::UniformPressure),
            "sliding-plate" => Ok(Top::SlidingPlate),
            _ => Err(Error::input("--top", format!("'{}': use {}", crate::error::quote(s), Top::NAMES))),
        }
    }
}

/// The side-pushed rig's values, checked ([`Scene::side_push`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SidePush {
    /// The pusher's centre above the interface, m.
    pub height: f64,
    /// Its contact length on the trailing face, m.
    pub width: f64,
    /// N/m per metre of width, if given.
    pub stiffness: Option<f64>,
    pub top: Top,
}

/// What a mesh file must be: the scene's L x t block (the default), or the file's own shape
/// (holes, notches accepted), which the paper's model does not describe.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum MeshGeometry {
    #[default]
    Block,
    File,
}

/// What every verdict against the paper's model says of a mesh of the file's own shape.
pub const FILE_GEOMETRY_NOTE: &str =
    "the mesh file's own (mesh.geometry = file), not the L x t block; the paper's model does not describe it";

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct MeshSpec {
    /// Element size in the block, m (structured mesh); with `grading`, the size at both ends.
    pub h: f64,
    /// Geometric growth ratio of the element length along x from both ends towards the
    /// middle (dimensionless, >= 1); none = uniform mesh.
    pub grading: Option<f64>,
    /// Largest element length along x with grading, m (default: 2 t).
    pub h_max: Option<f64>,
    /// Elements through the thickness (default round(t / h)); with it, h sets only the size
    /// along x, so elements can be elongated (aspect h n_thick / t).
    pub n_thick: Option<usize>,
    /// Element formulation by name (qua4, qua4-sri, qua4-im, qua8, qua9, tri3, tri6).
    pub element: String,
    /// A Gmsh mesh of the block instead of the structured one.
    pub file: Option<PathBuf>,
    /// Physical-group names in a Gmsh file.
    pub interface: String,
    pub top: String,
    pub block: String,
    /// Whether the mesh file must be the L x t block (`block`) or has its own shape, holes
    /// and notches accepted (`file`, `--geometry`).
    pub geometry: MeshGeometry,
    /// Largest number of unknowns a run may have (`--max-dofs`); none = half this machine's
    /// memory at [`limits::BYTES_PER_DOF`], at most [`limits::DEFAULT_MAX_DOFS_CAP`].
    pub max_dofs: Option<usize>,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Report {
    /// Edge-zone tolerance: relative deviation from the local model value (dimensionless).
    pub tol: f64,
}

/// The interface's friction law and normal response as scene values (`[law]`), each the
/// flag of the same name without `--` (`kind` is `--law`); a flag or Python keyword given
/// overrides the key. Read by `slide` (and `slide --dynamics`); the values are checked where
/// the law is built (`studies::slide::LawChoice`), naming the key.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LawTable {
    /// coulomb, static-kinetic, slip-weakening or rate-state.
    pub kind: Option<String>,
    pub mu: Option<f64>,
    pub mu_s: Option<f64>,
    pub mu_d: Option<f64>,
    pub r: Option<f64>,
    pub g: Option<f64>,
    pub rule: Option<String>,
    /// m.
    pub dc: Option<f64>,
    pub a: Option<f64>,
    pub b: Option<f64>,
    /// m.
    pub l_rs: Option<f64>,
    /// m/s.
    pub v0: Option<f64>,
    pub f0: Option<f64>,
    pub state_law: Option<String>,
    /// s.
    pub theta0: Option<f64>,
    /// s.
    pub normal_lag: Option<f64>,
    /// m.
    pub normal_lag_length: Option<f64>,
    /// m/s.
    pub normal_lag_v_star: Option<f64>,
}

impl LawTable {
    pub fn is_empty(&self) -> bool {
        *self == Self::default()
    }

    /// The explicit base's normal response: of `given` (a front end's normal_lag,
    /// normal_lag_length, normal_lag_v_star) if any is given, else of this table (never a mix);
    /// instantaneous if neither says. A refusal names the flag (`--normal-lag`; a front end
    /// renders its own keyword) or the key (`[law] normal_lag`).
    pub fn normal(&self, given: [Option<f64>; 3]) -> Result<crate::law::Normal> {
        let (values, keys) = if given.iter().any(Option::is_some) {
            (given, ["--normal-lag", "--normal-lag-length", "--normal-lag-v-star"])
        } else {
            (
                [self.normal_lag, self.normal_lag_length, self.normal_lag_v_star],
                ["[law] normal_lag", "[law] normal_lag_length", "[law] normal_lag_v_star"],
            )
        };
        crate::law::Normal::from_inputs(
            values[0],
            values[1],
            values[2],
            crate::law::Normal::Instantaneous,
            keys,
        )
    }
}

#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Scene {
    pub block: Block,
    pub plate: Plate,
    pub loading: Loading,
    pub mesh: MeshSpec,
    pub report: Report,
    #[serde(skip_serializing_if = "LawTable::is_empty")]
    pub law: LawTable,
    /// The interface of a `rupture` scene: its kind, background stresses, pieces and patch.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub interface: Option<InterfaceTable>,
    /// A `rupture` run's time, step, stations and outputs.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rupture: Option<RuptureTable>,
}

/// `[interface]` of a `rupture` scene (docs/dynamics.md, "Rupture scenes"): the friction law's
/// background values are the `[law]` table's.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct InterfaceTable {
    /// bilateral, unilateral (a rigid flat) or symmetric (a symmetric fault), as `--contact`.
    pub kind: Option<String>,
    /// Background normal stress, compressive positive, Pa.
    pub sigma0: Option<f64>,
    /// Background shear, Pa; or `s`, the strength ratio that sets it.
    pub tau0: Option<f64>,
    pub s: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub nucleation: Option<PatchTable>,
    /// Values replacing the background's over intervals of x.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub intervals: Vec<IntervalTable>,
}

/// `[interface.nucleation]`: initial shear tau0 (Pa) over x_min <= x <= x_max (m), a cosine
/// ramp of width taper (m) centred on each edge.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PatchTable {
    pub x_min: f64,
    pub x_max: f64,
    pub tau0: f64,
    pub taper: f64,
}

/// One of `[[interface.intervals]]`: x_min, x_max (m), taper (m), and any of sigma0, tau0
/// (Pa), mu_s, mu_d, dc (m).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct IntervalTable {
    pub x_min: f64,
    pub x_max: f64,
    pub taper: f64,
    pub sigma0: Option<f64>,
    pub tau0: Option<f64>,
    pub mu_s: Option<f64>,
    pub mu_d: Option<f64>,
    pub dc: Option<f64>,
}

/// `[rupture]`: the run and its outputs.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RuptureTable {
    /// s.
    pub t_end: Option<f64>,
    pub courant: Option<f64>,
    /// Kelvin-Voigt coefficient, s.
    pub damping: Option<f64>,
    pub max_steps: Option<u64>,
    /// Station positions along the interface, m.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub stations: Vec<f64>,
    /// Station output interval, s (default: every step).
    pub dt_out: Option<f64>,
    /// The slip rate of a node's rupture time, m/s (default: the arrival rate).
    pub rate_threshold: Option<f64>,
    /// "refused" (the default: a block that lets waves back to the stations before t_end is
    /// refused) or "allowed".
    pub reflections: Option<String>,
    /// The front-speed fit's x range [a, b], m.
    pub speed_window: Option<[f64; 2]>,
}

impl Default for Block {
    fn default() -> Self {
        Self {
            length: 0.4,
            thickness: 0.002,
            young: 2e3,
            poisson: 0.4,
            density: 1000.0,
            c_p: None,
            c_s: None,
            state: State::PlaneStrain,
            width: None,
            wave_speeds: None,
        }
    }
}
impl Block {
    /// Sets young and poisson from c_p, c_s and density when the file gives the wave speeds
    /// (`text`: the file, to tell given keys from defaults), and clears them: the effective
    /// scene says E and nu.
    fn set_from_wave_speeds(&mut self, text: &str) -> Result<()> {
        let (Some(c_p), Some(c_s)) = (self.c_p, self.c_s) else {
            return match (self.c_p, self.c_s) {
                (None, None) => Ok(()),
                _ => Err(Error::input(
                    "block.c_p (m/s)",
                    "give c_p and c_s together (with density), or young and poisson",
                )),
            };
        };
        let raw: toml::Table = toml::from_str(text).unwrap_or_default();
        let given = |k: &str| raw.get("block").and_then(|b| b.get(k)).is_some();
        if given("young") || given("poisson") {
            return Err(Error::input(
                "block.c_p (m/s)",
                "the material is given twice: give c_p, c_s and density, or young, poisson and density",
            ));
        }
        crate::error::scaled("block.c_p (m/s)", c_p, "m/s")?;
        crate::error::scaled("block.c_s (m/s)", c_s, "m/s")?;
        self.set_young_poisson(c_p, c_s)?;
        (self.c_p, self.c_s) = (None, None);
        self.wave_speeds = Some((c_p, c_s));
        Ok(())
    }

    /// young and poisson of wave speeds c_p, c_s (m/s) at this density, in this state.
    pub(crate) fn set_young_poisson(&mut self, c_p: f64, c_s: f64) -> Result<()> {
        let g = self.density * c_s * c_s;
        let m = self.density * c_p * c_p;
        match self.state {
            State::PlaneStrain => {
                // G = rho c_s^2, lambda = rho c_p^2 - 2 G, nu = lambda / (2 (lambda + G)).
                let lambda = m - 2.0 * g;
                // nu > -1 is lambda > -2 G / 3, that is c_p > sqrt(4/3) c_s.
                let least = c_s * (4.0f64 / 3.0).sqrt();
                if !(c_p > least && lambda + g > 0.0) {
                    return Err(Error::input(
                        "block.c_s (m/s)",
                        format!("c_p = {c_p} m/s, c_s = {c_s} m/s: an isotropic solid (nu > -1) needs c_p > sqrt(4/3) c_s = {least:.6} m/s"),
                    ));
                }
                self.poisson = lambda / (2.0 * (lambda + g));
            }
            State::PlaneStress => {
                // rho c_p^2 = E / (1 - nu^2) = 2 G / (1 - nu): nu = 1 - 2 G / (rho c_p^2).
                let nu = 1.0 - 2.0 * g / m;
                if !(c_p > c_s && nu <= 0.5) {
                    return Err(Error::input(
                        "block.c_s (m/s)",
                        format!("c_p = {c_p} m/s, c_s = {c_s} m/s: an isotropic plate in plane stress (-1 < nu <= 0.5) needs c_s < c_p and c_p >= 2 c_s = {} m/s", 2.0 * c_s),
                    ));
                }
                self.poisson = nu;
            }
        }
        self.young = 2.0 * g * (1.0 + self.poisson);
        Ok(())
    }

    /// The block's material in its state.
    pub fn material(&self) -> Result<Material> {
        Material::new(self.young, self.poisson, self.state)
    }

    /// The material unchecked, for the closed forms below (validate has checked it).
    fn law(&self) -> Material {
        Material { e: self.young, nu: self.poisson, state: self.state }
    }

    /// [`Material::plane_strain_nu`]: the Poisson ratio closed forms written for plane strain
    /// take (poisson itself in plane strain).
    pub fn plane_strain_nu(&self) -> f64 {
        self.law().plane_strain_nu()
    }

    /// [`Material::e_star`]: E / (1 - nu^2) in plane strain, E in plane stress, Pa.
    pub fn e_star(&self) -> f64 {
        self.law().e_star()
    }

    /// The printed line on the out-of-plane state and width; none for plane strain without a
    /// width (the default scene).
    pub fn out_of_plane_note(&self) -> Option<String> {
        if self.state == State::PlaneStrain && self.width.is_none() {
            return None;
        }
        let state = match self.state {
            State::PlaneStrain => "plane strain (eps_zz = 0)",
            State::PlaneStress => "plane stress (sigma_zz = 0)",
        };
        let mut s = format!("{state}; forces per unit width (N/m)");
        if let Some(b) = self.width {
            s += &format!(", width b = {} m", crate::error::num(b));
        }
        Some(s)
    }
}

impl Default for Plate {
    fn default() -> Self {
        Self { model: PlateModel::Rigid, thickness: 0.048, young: 2e15, poisson: 0.4 }
    }
}
impl Default for Loading {
    fn default() -> Self {
        Self {
            height: 0.04,
            fn_ratios: vec![0.0, 0.41, 0.82],
            rig: Rig::TopPlate,
            push_height: None,
            push_width: None,
            push_stiffness: None,
            top: None,
        }
    }
}
impl Default for MeshSpec {
    fn default() -> Self {
        Self {
            h: 0.001,
            grading: None,
            h_max: None,
            n_thick: None,
            element: "qua4".into(),
            file: None,
            interface: "interface".into(),
            top: "top".into(),
            block: "block".into(),
            geometry: MeshGeometry::Block,
            max_dofs: None,
        }
    }
}
impl Default for Report {
    fn default() -> Self {
        Self { tol: 0.05 }
    }
}

/// The FE model of a scene, ready to solve: mesh, materials, constraints, and the DOFs the
/// loading acts on.
pub struct SceneModel {
    pub mesh: Mesh,
    pub materials: Vec<Material>,
    pub element_material: Vec<u32>,
    /// QUA4 technology from `mesh.element`.
    pub tech: Technology,
    pub constraints: Constraints,
    /// Interface nodes sorted by x, and the names of the interface and top edge sets.
    pub interface: Vec<usize>,
    pub interface_set: String,
    pub top_set: String,
    /// Full DOFs where U (tangential, at height H) and V (normal) are prescribed.
    pub dof_u: usize,
    pub dof_v: usize,
    /// Plate rotation DOF (rigid plate), for the tilt angle.
    pub dof_theta: Option<usize>,
}

impl SceneModel {
    /// Integral of each interface node's shape function along the interface (m): the width
    /// over which its consistent nodal force is spread (half the neighbouring edges for linear
    /// elements; L/6 and 2L/3 per edge for quadratic ones).
    pub fn tributary_widths(&self) -> Vec<f64> {
        let mut w = vec![0.0; self.mesh.n_nodes()];
        let mut f = vec![0.0; 2 * self.mesh.n_nodes()];
        // A unit normal traction's consistent forces are exactly these integrals.
        crate::fem::loads::add_edge_traction(&self.mesh, &self.interface_set, &|_| [0.0, 1.0], &mut f)
            .expect("interface edges exist");
        for k in 0..self.mesh.n_nodes() {
            w[k] = f[2 * k + 1];
        }
        self.interface.iter().map(|&k| w[k]).collect()
    }

    pub fn model(&self) -> Model<'_> {
        Model {
            mesh: &self.mesh,
            materials: self.materials.clone(),
            element_material: self.element_material.clone(),
            tech: self.tech,
        }
    }
}

impl Scene {
    /// Reads a scene file; unknown keys and bad values are errors naming the file and line.
    pub fn from_file(path: &Path) -> Result<Self> {
        let text =
            crate::io::input::read_text(path, "scene file (--scene)", crate::io::input::TOML_MAX_BYTES)?;
        let scene: Scene = toml::from_str(&text).map_err(|e| {
            let line = e.span().map_or(0, |s| text[..s.start].matches('\n').count() + 1);
            Error::Parse {
                file: path.to_path_buf(),
                at: format!("line {line}"),
                msg: e.message().to_string(),
            }
        })?;
        let mut scene = scene;
        let raw: toml::Table = toml::from_str(&text).unwrap_or_default();
        if scene.loading.rig == Rig::SidePush && raw.get("loading").and_then(|l| l.get("height")).is_some() {
            return Err(Error::Parse {
                file: path.to_path_buf(),
                at: key_line(&text, "loading.height").map_or("[loading]".into(), |l| format!("line {l}")),
                msg: format!("loading.height: {HEIGHT_WITH_SIDE_PUSH}"),
            });
        }
        scene.block.set_from_wave_speeds(&text).map_err(|e| match e {
            Error::Input { what, why } => Error::Parse {
                file: path.to_path_buf(),
                at: key_line(&text, &what).map_or("[block]".into(), |l| format!("line {l}")),
                msg: format!("{what}: {why}"),
            },
            e => e,
        })?;
        if let (Some(f), Some(dir)) = (&scene.mesh.file, path.parent()) {
            if f.is_relative() {
                scene.mesh.file = Some(dir.join(f));
            }
        }
        scene.validate().map_err(|e| match e {
            // A value read from this file: say where it is.
            Error::Input { what, why } => match key_line(&text, &what) {
                Some(line) => Error::Parse {
                    file: path.to_path_buf(),
                    at: format!("line {line}"),
                    msg: format!("{what}: {why}"),
                },
                None => Error::Input { what, why },
            },
            e => e,
        })?;
        Ok(scene)
    }

    pub fn validate(&self) -> Result<()> {
        let (pos, scaled) = (crate::error::positive, crate::error::scaled);
        scaled("block.length (m, --length)", self.block.length, "m")?;
        scaled("block.thickness (m, --thickness)", self.block.thickness, "m")?;
        // H = 0 is the paper's control case: the drive in the interface plane, no torque.
        if self.loading.height != 0.0 {
            scaled("loading.height (m, --height)", self.loading.height, "m")?;
        }
        scaled("mesh.h (m, --h)", self.mesh.h, "m")?;
        scaled("block.young (Pa, --young)", self.block.young, "Pa")?;
        scaled("block.density (kg/m^3, --density)", self.block.density, "kg/m^3")?;
        scaled("plate.young (Pa, --plate-modulus)", self.plate.young, "Pa")?;
        if self.loading.height > MAX_H_OVER_L * self.block.length {
            return Err(Error::input(
                "loading.height (--height)",
                format!(
                    "H = {} m is over {MAX_H_OVER_L} L (L = {} m): the plate's rotation then carries no precision \
                     (the global balance error grows like eps (H/L)^2); check the units",
                    num(self.loading.height),
                    num(self.block.length)
                ),
            ));
        }
        if self.mesh.h > self.block.length / 2.0 && self.mesh.file.is_none() {
            return Err(Error::input(
                "mesh.h (--h)",
                format!(
                    "{} m is larger than half the block length L = {} m: the mesh needs at least two elements along x",
                    num(self.mesh.h),
                    num(self.block.length)
                ),
            ));
        }
        pos("report.tol (--tol)", self.report.tol)?;
        if self.report.tol >= 1.0 {
            return Err(Error::input(
                "report.tol (--tol)",
                format!(
                    "{} is a relative deviation from the local model value: use a value in (0, 1)",
                    self.report.tol
                ),
            ));
        }
        if let Some(g) = self.mesh.grading {
            if !(g.is_finite() && g >= 1.0) {
                return Err(Error::input(
                    "mesh.grading (--grading)",
                    format!("{g} must be a growth ratio >= 1"),
                ));
            }
        }
        if let Some(m) = self.mesh.h_max {
            pos("mesh.h_max (m, --h-max)", m)?;
            if !self.mesh.grading.is_some_and(|g| g > 1.0) {
                return Err(Error::input(
                    "mesh.h_max (--h-max)",
                    "sets the largest element of a graded mesh: give mesh.grading > 1 (--grading) too",
                ));
            }
            if m < self.mesh.h {
                return Err(Error::input(
                    "mesh.h_max (--h-max)",
                    format!("{m} m is smaller than the end size mesh.h = {} m", self.mesh.h),
                ));
            }
        }
        if let Some(b) = self.block.width {
            scaled("block.width (m, --width)", b, "m")?;
        }
        if self.block.state == State::PlaneStress && self.block.width.is_none() {
            return Err(Error::input(
                "block.width (m, --width)",
                "plane stress (block.state = \"plane-stress\", --plane-stress) describes a plate of finite \
                 out-of-plane width b: give it with [block] width or --width (m), to turn the forces per unit \
                 width into the plate's newtons",
            ));
        }
        let state = self.block.state;
        material(
            self.block.young,
            self.block.poisson,
            state,
            "block.young (--young)",
            "block.poisson (--poisson)",
        )?;
        // The plate's keys are checked whatever the model, so a scene file never holds a
        // nonsense value that only a later switch to the elastic plate would reveal.
        material(
            self.plate.young,
            self.plate.poisson,
            state,
            "plate.young (--plate-modulus)",
            "plate.poisson (--plate-poisson)",
        )?;
        pos("plate.thickness (m, --plate-thickness)", self.plate.thickness)?;
        if self.plate.model == PlateModel::Elastic
            && (self.loading.height > self.block.thickness + self.plate.thickness
                || self.loading.height <= self.block.thickness)
        {
            return Err(Error::input(
                "loading.height",
                format!(
                    "H = {} m must lie on the elastic plate's left side, in ({}, {}] m",
                    self.loading.height,
                    self.block.thickness,
                    self.block.thickness + self.plate.thickness
                ),
            ));
        }
        limits::effective(self.mesh.max_dofs)?;
        if self.mesh.geometry == MeshGeometry::File && self.mesh.file.is_none() {
            return Err(Error::input(
                "mesh.geometry (--geometry)",
                "file accepts a mesh file that is not the L x t block, but there is none: \
                 the built-in mesh is the block; give mesh.file (--mesh) or remove the key",
            ));
        }
        if self.mesh.n_thick == Some(0) {
            return Err(Error::input(
                "mesh.n_thick (--n-thick)",
                "need at least one element through the thickness",
            ));
        }
        if self.mesh.h > self.block.thickness && self.mesh.n_thick.is_none() {
            return Err(Error::input(
                "mesh.h",
                format!(
                    "{} m is larger than the block thickness {} m: use at most t / 2",
                    num(self.mesh.h),
                    num(self.block.thickness)
                ),
            ));
        }
        let ratios = &self.loading.fn_ratios;
        if ratios.is_empty() || ratios.iter().any(|r| !r.is_finite()) {
            return Err(Error::input(
                "loading.fn_ratios (--fn-ratios)",
                "need at least one finite F/N ratio",
            ));
        }
        if let Some(r) = ratios.iter().find(|r| r.abs() > MAX_FN_RATIO) {
            return Err(Error::input(
                "loading.fn_ratios (--fn-ratios)",
                format!(
                    "F/N = {r:e} is far beyond any friction coefficient (|F/N| <= {MAX_FN_RATIO}); \
                     the ratio is dimensionless, F and N in the same units"
                ),
            ));
        }
        for (i, r) in ratios.iter().enumerate() {
            if ratios[..i].contains(r) {
                return Err(Error::input(
                    "loading.fn_ratios (--fn-ratios)",
                    format!("F/N = {r} is given twice; each load case writes its own files"),
                ));
            }
        }
        self.element()?;
        self.side_push()?;
        Ok(())
    }

    /// The side-pushed rig's values, checked (None for the top-plate rig, whose scene must
    /// then hold none of them). Each refusal names the key and its flag.
    pub fn side_push(&self) -> Result<Option<SidePush>> {
        let ld = &self.loading;
        let keys = [
            ("loading.push_height (m, --push-height)", ld.push_height.is_some()),
            ("loading.push_width (m, --push-width)", ld.push_width.is_some()),
            ("loading.push_stiffness (N/m per m of width, --push-stiffness)", ld.push_stiffness.is_some()),
            ("loading.top (--top)", ld.top.is_some()),
        ];
        if ld.rig == Rig::TopPlate {
            if let Some((key, _)) = keys.iter().find(|k| k.1) {
                return Err(Error::input(
                    *key,
                    "describes the side-pushed rig, but loading.rig is top-plate (the default): \
                     set rig = \"side-push\" (--rig side-push) or remove the key",
                ));
            }
            return Ok(None);
        }
        let t = self.block.thickness;
        let (Some(h), Some(w)) = (ld.push_height, ld.push_width) else {
            let key = if ld.push_height.is_none() { keys[0].0 } else { keys[1].0 };
            return Err(Error::input(
                key,
                "is required with loading.rig = side-push: give the pusher's centre above the interface \
                 (push_height) and its contact length on the trailing face (push_width), in m",
            ));
        };
        crate::error::scaled(keys[1].0, w, "m")?;
        if h != 0.0 {
            crate::error::scaled(keys[0].0, h, "m")?;
        }
        if w > t {
            return Err(Error::input(
                keys[1].0,
                format!(
                    "{} m is wider than the trailing face (the block thickness t = {} m): use push_width <= t",
                    num(w),
                    num(t)
                ),
            ));
        }
        // Round-off of the sums: a pusher flush with the interface or the top is accepted.
        let slack = 1e-12 * t;
        let num = |v: f64| num(format!("{v:.12e}").parse().unwrap_or(v));
        if h - w / 2.0 < -slack {
            return Err(Error::input(
                keys[0].0,
                format!(
                    "{} m puts the pusher's lower end at push_height - push_width/2 = {} m, below the \
                     interface: use push_height >= push_width/2 = {} m",
                    num(h),
                    num(h - w / 2.0),
                    num(w / 2.0)
                ),
            ));
        }
        if h + w / 2.0 > t + slack {
            return Err(Error::input(
                keys[0].0,
                format!(
                    "{} m puts the pusher's upper end at push_height + push_width/2 = {} m, above the \
                     block (t = {} m): use push_height <= t - push_width/2 = {} m",
                    num(h),
                    num(h + w / 2.0),
                    num(t),
                    num(t - w / 2.0)
                ),
            ));
        }
        if let Some(k) = ld.push_stiffness {
            if !(k.is_finite() && k > 0.0) {
                return Err(Error::input(
                    keys[2].0,
                    format!("{k} N/m: the driving spring needs a positive, finite stiffness"),
                ));
            }
            crate::error::scaled(keys[2].0, k, "N/m")?;
        }
        if self.plate.model == PlateModel::Elastic {
            return Err(Error::input(
                "plate.model (--plate)",
                "the elastic plate is the top-plate rig's; with side push the top is loading.top \
                 (--top uniform-pressure or sliding-plate): remove the key",
            ));
        }
        if self.mesh.file.is_some() {
            return Err(Error::input(
                "mesh.file (--mesh)",
                "side push needs the structured mesh in this phase (its pusher nodes are found on the \
                 built-in block's trailing face): remove the mesh file",
            ));
        }
        Ok(Some(SidePush {
            height: h,
            width: w,
            stiffness: ld.push_stiffness,
            top: ld.top.unwrap_or_default(),
        }))
    }

    /// The arm of the tangential force about the interface: H (top plate) or push_height.
    pub fn arm(&self) -> f64 {
        match (self.loading.rig, self.loading.push_height) {
            (Rig::SidePush, Some(h)) => h,
            _ => self.loading.height,
        }
    }

    /// Advice that does not stop the run: element and material pairs known to lock, a mesh
    /// of the file's own shape.
    pub fn warnings(&self) -> Vec<String> {
        let mut w = Vec::new();
        if self.mesh.geometry == MeshGeometry::File {
            w.push(format!(
                "geometry: {FILE_GEOMETRY_NOTE}: every comparison with it (model, corrected, deviations, \
                 edge zones) is one with a block this mesh is not"
            ));
        }
        let lock = |nu: f64, what: &str| {
            format!(
                "mesh.element = {} with {what} = {nu} (>= 0.499) locks volumetrically and underestimates \
                 the displacements; use qua8 (or qua4-sri, qua9, tri6)",
                self.mesh.element
            )
        };
        // Plane stress has no volumetric constraint to lock on.
        if matches!(self.mesh.element.as_str(), "qua4" | "tri3") && self.block.state == State::PlaneStrain {
            if self.block.poisson >= 0.499 {
                w.push(lock(self.block.poisson, "block.poisson"));
            }
            if self.plate.model == PlateModel::Elastic && self.plate.poisson >= 0.499 {
                w.push(lock(self.plate.poisson, "plate.poisson"));
            }
        }
        w
    }

    pub fn element(&self) -> Result<ElementChoice> {
        self.mesh.element.parse()
    }
}

/// Why `height` is refused with side push (the key or `--height`).
pub const HEIGHT_WITH_SIDE_PUSH: &str = "is the top plate's loading height H, but loading.rig is side-push: \
     the push acts at loading.push_height (--push-height); remove height (--height)";

/// Largest H/L accepted: far beyond any experiment (the paper's is 0.1).
pub const MAX_H_OVER_L: f64 = 1e3;

/// The line (1-based) of `table.key = ...` in a scene file's text, for a parameter named as
/// validation names it ("block.length (m, --length)"); None when the value is not in the file.
fn key_line(text: &str, what: &str) -> Option<usize> {
    let path = what.split_whitespace().next()?;
    let (table, key) = path.rsplit_once('.')?;
    let mut current = String::new();
    for (i, line) in text.lines().enumerate() {
        let l = line.split('#').next().unwrap_or("").trim();
        if let Some(h) = l.strip_prefix('[').and_then(|h| h.strip_suffix(']')) {
            current = h.trim().to_string();
        } else if let Some((k, _)) = l.split_once('=') {
            let k = k.trim().trim_matches('"');
            if (current == table && k == key) || (current.is_empty() && k == path) {
                return Some(i + 1);
            }
        }
    }
    None
}

/// Largest |F/N| accepted: far above any friction coefficient (rubber reaches ~3).
pub const MAX_FN_RATIO: f64 = 10.0;

/// [`Material::new`] with its refusal naming the scene key (`young` or `poisson`).
fn material(e: f64, nu: f64, state: State, young: &str, poisson: &str) -> Result<Material> {
    // A ratio this small is 0 to every digit the solve keeps, and its subnormal products
    // slow the arithmetic a hundredfold (issue 31: `edges --poisson 1e-308` ran past a minute).
    if nu != 0.0 && nu.abs() < 1e-100 {
        return Err(Error::input(
            poisson,
            format!("{nu:e} is 0 to every digit kept: give 0 or |nu| >= 1e-100"),
        ));
    }
    Material::new(e, nu, state).map_err(|err| match err {
        Error::Input { what, why } => {
            Error::input(if what.starts_with("Young") { young } else { poisson }, why)
        }
        other => other,
    })
}
