//! A general rectangle problem for the `solve` subcommand: a structured mesh of any element,
//! one condition per side (clamped, roller, prescribed displacement, traction, or free), solved
//! by the same pipeline as the paper's check. Reactions are reported per side.

use crate::error::{Error, Result};
use crate::fem::assembly::Model;
use crate::fem::constraints::{dof, Constraints};
use crate::fem::element::stiffness::ElementChoice;
use crate::fem::material::Material;
use crate::fem::mesh::Mesh;
use crate::fem::mesher::Rectangle;
use crate::fem::problem::{solve, LoadCase, Solution};
use crate::linalg::solve::SolverOptions;

pub const SIDES: [&str; 4] = ["bottom", "right", "top", "left"];

/// The `solve` command's defaults (`tribofe solve`, `tribofe.solve`): a 1 m x 0.1 m strip of
/// 40 x 4 QUA4 of the paper's material (E = 2 kPa, nu = 0.4), clamped at the bottom, its top
/// displaced 1 mm along x, the ends free.
pub const DEFAULT_LX: f64 = 1.0;
pub const DEFAULT_LY: f64 = 0.1;
pub const DEFAULT_NX: usize = 40;
pub const DEFAULT_NY: usize = 4;
pub const DEFAULT_ELEMENT: &str = "qua4";
pub const DEFAULT_YOUNG: f64 = 2e3;
pub const DEFAULT_POISSON: f64 = 0.4;
/// The conditions of bottom, right, top, left ([`SIDES`]).
pub const DEFAULT_SIDES: [&str; 4] = ["clamped", "free", "u=0.001,0", "free"];

/// What one side of the rectangle does.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Side {
    Free,
    /// u = v = 0.
    Clamped,
    /// Zero normal displacement, free to slide.
    Roller,
    /// Prescribed displacement (ux, uy), m.
    Displaced([f64; 2]),
    /// Uniform traction (tx, ty), Pa.
    Traction([f64; 2]),
}

impl std::str::FromStr for Side {
    type Err = Error;
    /// `free`, `clamped`, `roller`, `u=UX,UY` (m) or `t=TX,TY` (Pa).
    fn from_str(s: &str) -> Result<Self> {
        let pair = |v: &str| -> Result<[f64; 2]> {
            let p: Vec<f64> = v
                .split(',')
                .map(|x| x.trim().parse::<f64>())
                .collect::<std::result::Result<_, _>>()
                .map_err(|_| Error::input("side condition", format!("'{s}': expected two numbers")))?;
            match p.as_slice() {
                [a, b] if a.is_finite() && b.is_finite() => Ok([*a, *b]),
                _ => Err(Error::input("side condition", format!("'{s}': expected two finite numbers"))),
            }
        };
        match s {
            "free" => Ok(Side::Free),
            "clamped" => Ok(Side::Clamped),
            "roller" => Ok(Side::Roller),
            _ if s.starts_with("u=") => Ok(Side::Displaced(pair(&s[2..])?)),
            _ if s.starts_with("t=") => Ok(Side::Traction(pair(&s[2..])?)),
            _ => Err(Error::input(
                "side condition",
                format!("'{s}': use free, clamped, roller, u=UX,UY (m) or t=TX,TY (Pa)"),
            )),
        }
    }
}

#[derive(Debug, Clone)]
pub struct RectangleProblem {
    pub rect: Rectangle,
    pub material: Material,
    pub element: ElementChoice,
    /// Conditions of bottom, right, top, left, in that order. Corners shared by two sides take
    /// both sides' displacement conditions (the later side wins where they conflict).
    pub sides: [Side; 4],
}

pub struct RectangleResult {
    pub mesh: Mesh,
    pub solution: Solution,
    /// Reaction force on each side (bottom, right, top, left), N per metre of width; a corner
    /// node counts for both its sides.
    pub side_reactions: [[f64; 2]; 4],
    /// Sum of all reactions (each constrained DOF once), N/m: balances `applied`.
    pub total_reaction: [f64; 2],
    /// Total applied traction force, N/m.
    pub applied: [f64; 2],
}

/// A refusal of the library (`side condition`, `element`) named by the parameter the user
/// typed (`--bottom`, `--element`).
fn named(e: Error, flag: &str) -> Error {
    match e {
        Error::Input { why, .. } => Error::input(flag, why),
        e => e,
    }
}

impl RectangleProblem {
    /// The problem from the command's inputs, each refused naming its flag (`--lx`, `--nx`,
    /// `--element`, `--young`, `--poisson`, `--bottom`...): the rectangle [0, lx] x [0, ly] in
    /// m with nx x ny elements, plane strain, `sides` the conditions of bottom, right, top and
    /// left as [`Side`] reads them.
    #[allow(clippy::too_many_arguments)]
    pub fn from_inputs(
        lx: f64,
        ly: f64,
        nx: usize,
        ny: usize,
        element: &str,
        young: f64,
        poisson: f64,
        sides: [&str; 4],
    ) -> Result<RectangleProblem> {
        for (flag, v) in [("--lx", lx), ("--ly", ly)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::input(flag, format!("{v} m: a side length must be positive")));
            }
        }
        for (flag, n) in [("--nx", nx), ("--ny", ny)] {
            if n == 0 {
                return Err(Error::input(flag, "0: need at least one element per direction"));
            }
        }
        let element: ElementChoice = element.parse().map_err(|e| named(e, "--element"))?;
        let material = Material::plane_strain(young, poisson).map_err(|e| {
            // Which of the two is at fault: E alone with a valid nu.
            named(e, if Material::plane_strain(young, 0.0).is_err() { "--young" } else { "--poisson" })
        })?;
        let mut parsed = [Side::Free; 4];
        for ((side, text), name) in parsed.iter_mut().zip(sides).zip(SIDES) {
            *side = text.parse().map_err(|e| named(e, &format!("--{name}")))?;
        }
        Ok(RectangleProblem {
            rect: Rectangle::new(0.0, lx, 0.0, ly, nx, ny),
            material,
            element,
            sides: parsed,
        })
    }

    /// Refuses a rectangle above `limit` unknowns (none: [`super::limits::default_max_dofs`])
    /// before meshing: 2 (p nx + 1)(p ny + 1) for order p, in f64 so absurd counts cannot overflow.
    pub fn check_size(&self, limit: Option<usize>) -> Result<()> {
        let p = self.element.kind.order() as f64;
        let (nx, ny) = (self.rect.nx as f64, self.rect.ny as f64);
        super::limits::check(2.0 * (p * nx + 1.0) * (p * ny + 1.0), limit, |grow| {
            format!(
                "use fewer elements (--nx {} --ny {} or fewer), or raise --max-dofs if the memory is there",
                (nx / grow).floor().max(1.0),
                (ny / grow).floor().max(1.0)
            )
        })
    }

    pub fn solve(&self) -> Result<RectangleResult> {
        let mesh = self.rect.clone().kind(self.element.kind).build()?;
        let mut c = Constraints::new(mesh.n_nodes());
        let mut g = Vec::new();
        let mut f = vec![0.0; 2 * mesh.n_nodes()];
        for (name, side) in SIDES.iter().zip(&self.sides) {
            let nodes = mesh.set_nodes(name)?;
            // Normal of bottom/top is y (component 1), of left/right x (component 0).
            let normal = if *name == "bottom" || *name == "top" { 1 } else { 0 };
            let mut set = |d: usize, v: f64| match c.fixed_slot(d) {
                Some(j) => g[j] = v,
                None => {
                    c.fix(d);
                    g.push(v);
                }
            };
            match *side {
                Side::Free => {}
                Side::Clamped => nodes.iter().for_each(|&n| (0..2).for_each(|k| set(dof(n, k), 0.0))),
                Side::Roller => nodes.iter().for_each(|&n| set(dof(n, normal), 0.0)),
                Side::Displaced(u) => nodes.iter().for_each(|&n| (0..2).for_each(|k| set(dof(n, k), u[k]))),
                Side::Traction(t) => crate::fem::loads::add_edge_traction(&mesh, name, &|_| t, &mut f)?,
            }
        }
        let mut model = Model::new(&mesh, self.material);
        model.tech = self.element.tech;
        let case = LoadCase { prescribed: g, forces: f.clone() };
        let solution = solve(
            &model,
            &c,
            std::slice::from_ref(&case),
            &SolverOptions::default(),
            "check the side conditions",
        )?;
        let mut side_reactions = [[0.0; 2]; 4];
        let all: Vec<usize> = (0..mesh.n_elements()).collect();
        let r = solution.residual_forces(&model, &case, 0, &all)?;
        for (k, name) in SIDES.iter().enumerate() {
            // Reactions only where displacements are prescribed.
            for n in mesh.set_nodes(name)? {
                for d in 0..2 {
                    if c.fixed_slot(dof(n, d)).is_some() {
                        side_reactions[k][d] += r[dof(n, d)];
                    }
                }
            }
        }
        let mut total_reaction = [0.0; 2];
        for d in 0..c.n_full() {
            if c.fixed_slot(d).is_some() {
                total_reaction[d % 2] += r[d];
            }
        }
        let applied = [f.iter().step_by(2).sum(), f.iter().skip(1).step_by(2).sum()];
        Ok(RectangleResult { mesh, solution, side_reactions, total_reaction, applied })
    }
}
