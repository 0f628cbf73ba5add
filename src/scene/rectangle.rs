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

impl RectangleProblem {
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
