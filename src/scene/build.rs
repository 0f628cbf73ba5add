//! A scene turned into a model: the structured mesh (or the Gmsh file, checked against the
//! scene), the plate, the constraints and the interface's nodes in x order.

use super::{limits, PlateModel, Rig, Scene, SceneModel, Top};
use crate::error::{Error, Result};
use crate::fem::constraints::{dof, Constraints};
use crate::fem::element::stiffness::Technology;
use crate::fem::material::Material;
use crate::fem::mesh::Mesh;
use crate::fem::mesher::{Grading, Rectangle};
use std::path::Path;

impl Scene {
    /// Builds the structured mesh (or reads the Gmsh one) and the constraints.
    pub fn build(&self) -> Result<SceneModel> {
        self.validate()?;
        if self.loading.rig == Rig::SidePush {
            return Err(Error::input(
                "loading.rig (--rig)",
                "side-push is run by `tribofe check` and `tribofe slide` (with or without \
                 --dynamics) in this phase; this command supports rig = \"top-plate\"",
            ));
        }
        if self.mesh.file.is_none() {
            self.check_rows()?;
            self.check_size()?;
        }
        let hgt = self.loading.height;
        let tech = self.element()?.tech;
        let block_mat = self.block.material()?;
        let (nx, ny) = self.grid();
        let (interface_name, top_name) = (self.mesh.interface.clone(), self.mesh.top.clone());
        let mesh = match &self.mesh.file {
            Some(path) => self.read_mesh(path)?,
            None => self.block_mesh(nx, ny)?,
        };
        match self.plate.model {
            PlateModel::Rigid => {
                let mut c = Constraints::new(mesh.n_nodes());
                let du = c.add_extra_dof("plate U (tangential displacement at height H)");
                let dv = c.add_extra_dof("plate V (normal displacement)");
                let dth = c.add_extra_dof("plate rotation theta");
                let interface = sorted_by_x(&mesh, mesh.set_nodes(&interface_name)?);
                for &n in &interface {
                    c.fix(dof(n, 0));
                    c.fix(dof(n, 1));
                }
                c.fix(du);
                c.fix(dv);
                // Small rotation about (0, H): u = U - theta (y - H), v = V + theta x.
                for n in mesh.set_nodes(&top_name)? {
                    let [x, y] = mesh.nodes[n];
                    c.tie(dof(n, 0), &[(du, 1.0), (dth, hgt - y)]);
                    c.tie(dof(n, 1), &[(dv, 1.0), (dth, x)]);
                }
                let n_el = mesh.n_elements();
                Ok(SceneModel {
                    mesh,
                    materials: vec![block_mat],
                    element_material: vec![0; n_el],
                    tech,
                    constraints: c,
                    interface,
                    interface_set: interface_name,
                    top_set: top_name,
                    dof_u: du,
                    dof_v: dv,
                    dof_theta: Some(dth),
                })
            }
            PlateModel::Elastic => self.build_elastic(mesh, &interface_name, block_mat, nx, tech),
        }
    }

    /// The side-pushed rig on the bonded block (the check): the interface fixed, the rigid
    /// pusher's face nodes tied to its horizontal displacement U_p (an extra DOF, loaded by F;
    /// their vertical displacements free: a frictionless pusher), and with the sliding plate
    /// the top nodes tied to its U, V and rotation (all free: N acts on V, no horizontal force,
    /// no moment). The returned model's `dof_u` is U_p and `dof_v` the plate's V (U_p with the
    /// uniform pressure, which has no DOF); neither is prescribed.
    pub fn build_side_push(&self) -> Result<(SceneModel, SidePushDofs)> {
        self.validate()?;
        let Some(sp) = self.side_push()? else {
            return Err(Error::input("loading.rig (--rig)", "the scene's rig is top-plate, not side-push"));
        };
        self.check_rows()?;
        self.check_size()?;
        let (l, t) = (self.block.length, self.block.thickness);
        let tech = self.element()?.tech;
        let order = self.element()?.kind.order();
        let block_mat = self.block.material()?;
        let (nx, ny) = self.grid();
        let (interface_name, top_name) = (self.mesh.interface.clone(), self.mesh.top.clone());
        let mesh = self.block_mesh(nx, ny)?;
        let tol = 1e-9 * t;
        let (lo, hi) = (sp.height - sp.width / 2.0, sp.height + sp.width / 2.0);
        let mut face: Vec<usize> = (0..mesh.n_nodes())
            .filter(|&k| {
                let [x, y] = mesh.nodes[k];
                (x + l / 2.0).abs() < 1e-9 * l && y >= lo - tol && y <= hi + tol
            })
            .collect();
        face.sort_by(|&a, &b| mesh.nodes[a][1].total_cmp(&mesh.nodes[b][1]));
        // The contact must span at least two element edges of the trailing face.
        let edges = face.len().saturating_sub(1) as f64 / order as f64;
        if edges < 2.0 {
            let dy = t / ny as f64;
            let (key, fix) = match self.mesh.n_thick {
                Some(_) => {
                    ("mesh.n_thick (--n-thick)", format!("n_thick >= {}", (3.0 * t / sp.width).ceil()))
                }
                None => ("mesh.h (--h)", format!("h <= {:.3e} m (push_width / 3)", sp.width / 3.0)),
            };
            return Err(Error::input(
                key,
                format!(
                    "the pusher's contact (push_width = {} m) spans {edges} element edge(s) of the trailing face \
                     (edges {dy:.3e} m long): at least 2 are needed to resolve it; use {fix}",
                    crate::error::num(sp.width)
                ),
            ));
        }
        let interface = sorted_by_x(&mesh, mesh.set_nodes(&interface_name)?);
        let mut c = Constraints::new(mesh.n_nodes());
        for &n in &interface {
            c.fix(dof(n, 0));
            c.fix(dof(n, 1));
        }
        let up = c.add_extra_dof("pusher U_p (horizontal displacement of the rigid pusher)");
        let sliding = sp.top == Top::SlidingPlate;
        // The interface corner is fixed, and with the sliding plate the top corner is the plate's.
        face.retain(|&k| mesh.nodes[k][1] > tol && !(sliding && mesh.nodes[k][1] > t - tol));
        for &k in &face {
            c.tie(dof(k, 0), &[(up, 1.0)]);
        }
        let plate = if sliding {
            let pu = c.add_extra_dof("top plate U (horizontal, free)");
            let pv = c.add_extra_dof("top plate V (normal, loaded by N)");
            let pth = c.add_extra_dof("top plate rotation (free, no moment)");
            // Small rotation about (0, t): u = U - theta (y - t) = U on the top, v = V + theta x.
            for n in mesh.set_nodes(&top_name)? {
                let x = mesh.nodes[n][0];
                c.tie(dof(n, 0), &[(pu, 1.0)]);
                c.tie(dof(n, 1), &[(pv, 1.0), (pth, x)]);
            }
            Some([pu, pv, pth])
        } else {
            None
        };
        let n_el = mesh.n_elements();
        let sm = SceneModel {
            mesh,
            materials: vec![block_mat],
            element_material: vec![0; n_el],
            tech,
            constraints: c,
            interface,
            interface_set: interface_name,
            top_set: top_name,
            dof_u: up,
            dof_v: plate.map_or(up, |p| p[1]),
            dof_theta: None,
        };
        Ok((sm, SidePushDofs { rig: sp, pusher: up, pusher_nodes: face, plate }))
    }

    /// The block from a Gmsh file: its element set `mesh.block`, with the edge sets
    /// `mesh.interface` and `mesh.top`; the element kind comes from the file, the element name
    /// chooses only the integration technology.
    fn read_mesh(&self, path: &Path) -> Result<Mesh> {
        let full = crate::io::gmsh::read(path)?;
        let m = full
            .restrict_to(&self.mesh.block)
            .map_err(|e| Error::Mesh(format!("{}: {e}", path.display())))?;
        for name in [&self.mesh.interface, &self.mesh.top] {
            m.edges(name).map_err(|e| Error::Mesh(format!("{}: {e}", path.display())))?;
        }
        let mut used = vec![false; m.n_nodes()];
        m.elements().for_each(|(_, v)| v.iter().for_each(|&n| used[n] = true));
        if let Some(n) = used.iter().position(|u| !u) {
            return Err(Error::Mesh(format!(
                "{}: node {} does not belong to the '{}' surface; the file must hold the block only",
                path.display(),
                m.node_tag(n),
                self.mesh.block
            )));
        }
        self.check_mesh_geometry(&m, path)?;
        crate::fem::mesh_check::check_block(
            &m,
            &self.mesh.block,
            &self.mesh.interface,
            &self.mesh.top,
            self.block.thickness,
            self.mesh.geometry == super::MeshGeometry::File,
        )
        .map_err(|e| match e {
            Error::Mesh(why) => {
                Error::Mesh(format!("{}: {why}", crate::error::quote(&path.display().to_string())))
            }
            other => other,
        })?;
        let want = self.element()?;
        let kinds = m.kinds_present();
        // The kind comes from the file: plain `qua4` (the default) names no kind, only the
        // standard technology; any other name must match an element the file holds.
        if !kinds.contains(&want.kind) && self.mesh.element != "qua4" {
            let names: Vec<&str> = kinds.iter().map(|k| k.name()).collect();
            return Err(Error::input(
                "mesh.element",
                format!(
                    "'{}' but {} holds {} elements; the kind comes from the mesh file",
                    self.mesh.element,
                    path.display(),
                    names.join(" and ")
                ),
            ));
        }
        Ok(m)
    }

    /// Refuses a structured mesh with one element through the thickness that only the
    /// rounding of h produced (checked when the mesh is built: a study may replace h).
    fn check_rows(&self) -> Result<()> {
        let (_, ny) = self.grid();
        // One element through the thickness (no free node for QUA4) only when asked for
        // by n_thick, never as the rounding of h.
        if ny == 1 && self.mesh.n_thick.is_none() {
            return Err(Error::input(
                "mesh.h (--h)",
                format!(
                    "h = {} m gives round(t / h) = 1 element through the thickness t = {} m; \
                     use h <= {:.3e} m (t / 2), or set n_thick = 1 (--n-thick 1) if one \
                     element is meant",
                    self.mesh.h,
                    self.block.thickness,
                    self.block.thickness / 2.0
                ),
            ));
        }
        Ok(())
    }

    /// Unknowns of the structured mesh, estimated from the scene alone (no allocation; f64
    /// so that absurd sizes do not overflow).
    pub fn estimate_dofs(&self) -> Result<f64> {
        let (t, h) = (self.block.thickness, self.mesh.h);
        let nx = self.estimate_nx();
        let ny = self.estimate_rows();
        let rows = match self.plate.model {
            PlateModel::Rigid => ny,
            PlateModel::Elastic => ny + self.plate.thickness / (t / 2.0).max(h) + 1.0,
        };
        let p = self.element()?.kind.order() as f64;
        Ok(2.0 * (p * nx + 1.0) * (p * rows + 1.0))
    }

    /// Element rows through the block's thickness of the structured mesh.
    pub fn estimate_rows(&self) -> f64 {
        let (t, h) = (self.block.thickness, self.mesh.h);
        self.mesh.n_thick.map_or((t / h).round().max(1.0), |n| n as f64)
    }

    /// Elements along x of the structured mesh, uniform or graded, estimated from the scene
    /// alone (f64 so that absurd sizes do not overflow).
    pub fn estimate_nx(&self) -> f64 {
        let (l, t, h) = (self.block.length, self.block.thickness, self.mesh.h);
        match self.mesh.grading {
            Some(r) if r > 1.0 => {
                // Elements grow from h by r up to h_max, from both ends.
                let hm = self.mesh.h_max.unwrap_or(2.0 * t).max(h);
                let k = ((hm / h).ln() / r.ln()).floor();
                let ramp = h * (r.powf(k) - 1.0) / (r - 1.0);
                if 2.0 * ramp >= l {
                    2.0 * (1.0 + l / 2.0 * (r - 1.0) / h).ln() / r.ln()
                } else {
                    2.0 * k + (l - 2.0 * ramp) / hm
                }
            }
            _ => (l / h).round(),
        }
        .max(2.0)
    }

    /// Refuses a scene above its size limit (`mesh.max_dofs`, [`limits::effective`]) before
    /// meshing.
    pub fn check_size(&self) -> Result<()> {
        limits::check(self.estimate_dofs()?, self.mesh.max_dofs, |grow| {
            format!(
                "check the units of block.length = {:e} m and block.thickness = {:e} m, use a \
                 coarser mesh ({}, or --grading), or raise --max-dofs if the memory is there",
                self.block.length,
                self.block.thickness,
                match self.mesh.h * grow {
                    h if h.is_finite() => format!("--h {h:.2e} or more"),
                    _ => "a much larger --h".to_string(),
                }
            )
        })
    }

    /// Refuses a mesh whose geometry contradicts the scene: the figures are normalised by L
    /// and t, and the plate acts on the interface at y = 0 and the top at y = t.
    fn check_mesh_geometry(&self, m: &Mesh, path: &Path) -> Result<()> {
        let (l, t) = (self.block.length, self.block.thickness);
        let tol = 1e-6 * t;
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in &m.nodes {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let bad =
            |why: String| Error::Mesh(format!("{}: {why}", crate::error::quote(&path.display().to_string())));
        if (lo[0] + l / 2.0).abs() > tol
            || (hi[0] - l / 2.0).abs() > tol
            || lo[1].abs() > tol
            || (hi[1] - t).abs() > tol
        {
            return Err(bad(format!(
                "the block spans x in [{:.6e}, {:.6e}] m, y in [{:.6e}, {:.6e}] m, but the scene has \
                 length L = {l} m and thickness t = {t} m (x in [-L/2, L/2], y in [0, t]); set \
                 block.length / block.thickness (--length, --thickness) to the mesh's or move the mesh",
                lo[0], hi[0], lo[1], hi[1]
            )));
        }
        let order = m.kinds_present().iter().map(|k| k.order()).max().unwrap_or(1);
        for (name, y) in [(&self.mesh.interface, 0.0), (&self.mesh.top, t)] {
            let edges = m.edges(name).map_err(|e| bad(e.to_string()))?;
            let (mut covered, mut y_off) = (0.0, 0.0f64);
            for e in edges {
                let [a, b] = e.ends.map(|n| m.nodes[n]);
                covered += (b[0] - a[0]).abs();
                y_off = e.nodes().fold(y_off, |d, n| d.max((m.nodes[n][1] - y).abs()));
                if e.mid.is_some() != (order == 2) {
                    return Err(bad(format!(
                        "group '{}' holds {}-node lines but the elements are of order {order}: \
                         use {} lines",
                        crate::error::quote(name),
                        2 + usize::from(e.mid.is_some()),
                        if order == 2 { "3-node (line3)" } else { "2-node (line2)" }
                    )));
                }
            }
            if y_off > tol || (covered - l).abs() > tol {
                return Err(bad(format!(
                    "group '{}' must be the whole side y = {y} m spanning [-L/2, L/2] (L = {l} m): \
                     its nodes lie up to {y_off:.3e} m off that line and its edges cover {covered:.6e} m",
                    crate::error::quote(name)
                )));
            }
        }
        Ok(())
    }

    /// A layer y0 < y < y1 spanning the block's length, with the block's spacing along x
    /// (uniform with nx elements, or graded) and ny uniform rows.
    /// The structured block's elements along x (even) and through the thickness.
    fn grid(&self) -> (usize, usize) {
        let (l, t, h) = (self.block.length, self.block.thickness, self.mesh.h);
        (
            even((l / h).round().max(2.0) as usize),
            self.mesh.n_thick.unwrap_or(((t / h).round() as usize).max(1)),
        )
    }

    /// The structured block, nx x ny elements, its bottom and top edges named as the scene's
    /// interface and top sets and its elements as its block set.
    fn block_mesh(&self, nx: usize, ny: usize) -> Result<Mesh> {
        let mut m = self.layer(0.0, self.block.thickness, ny, nx)?;
        let (bottom, top) = (m.edge_sets["bottom"].clone(), m.edge_sets["top"].clone());
        m.edge_sets.insert(self.mesh.interface.clone(), bottom);
        m.edge_sets.insert(self.mesh.top.clone(), top);
        m.element_sets.insert(self.mesh.block.clone(), m.element_sets["all"].clone());
        Ok(m)
    }

    fn layer(&self, y0: f64, y1: f64, ny: usize, nx: usize) -> Result<Mesh> {
        let l = self.block.length;
        let mut r = Rectangle::new(-l / 2.0, l / 2.0, y0, y1, nx, ny).kind(self.element()?.kind);
        if let Some(ratio) = self.mesh.grading {
            r = r.graded_x(Grading {
                end: self.mesh.h,
                ratio,
                max: Some(self.mesh.h_max.unwrap_or(2.0 * self.block.thickness)),
            });
        }
        r.build()
    }

    /// Block plus a meshed plate sharing the top nodes; rows of the plate are placed so that
    /// a node lies exactly at height H on the left side.
    fn build_elastic(
        &self,
        block: Mesh,
        interface_name: &str,
        block_mat: Material,
        nx: usize,
        tech: Technology,
    ) -> Result<SceneModel> {
        if self.mesh.file.is_some() {
            return Err(Error::input("plate.model", "the elastic plate needs the structured mesh"));
        }
        let (l, t, hgt, tp) =
            (self.block.length, self.block.thickness, self.loading.height, self.plate.thickness);
        let row = (t / 2.0).max(self.mesh.h);
        let n1 = (((hgt - t) / row).round() as usize).max(1);
        let n2 = ((t + tp - hgt) / row).round() as usize;
        let mut plate = self.layer(t, hgt, n1, nx)?;
        if n2 > 0 {
            let upper = self.layer(hgt, t + tp, n2, nx)?;
            plate = merge(&plate, &upper);
        }
        let mesh = merge(&block, &plate);
        let nb = block.n_elements();
        let element_material: Vec<u32> = (0..mesh.n_elements()).map(|e| u32::from(e >= nb)).collect();
        let plate_mat = Material::new(self.plate.young, self.plate.poisson, self.block.state)?;
        let mut c = Constraints::new(mesh.n_nodes());
        let interface = sorted_by_x(&mesh, mesh.set_nodes(interface_name)?);
        for &n in &interface {
            c.fix(dof(n, 0));
            c.fix(dof(n, 1));
        }
        let find = |x: f64, y: f64| -> Result<usize> {
            mesh.nodes
                .iter()
                .position(|p| (p[0] - x).abs() < 1e-9 * l && (p[1] - y).abs() < 1e-9 * l)
                .ok_or_else(|| Error::Mesh(format!("no plate node at ({x}, {y}) m")))
        };
        let du = dof(find(-l / 2.0, hgt)?, 0);
        let dv = dof(find(0.0, t + tp)?, 1);
        c.fix(du);
        c.fix(dv);
        Ok(SceneModel {
            mesh,
            materials: vec![block_mat, plate_mat],
            element_material,
            tech,
            constraints: c,
            interface,
            interface_set: self.mesh.interface.clone(),
            top_set: self.mesh.top.clone(),
            dof_u: du,
            dof_v: dv,
            dof_theta: None,
        })
    }
}

fn even(n: usize) -> usize {
    n + n % 2
}

fn cmp_x(m: &Mesh, a: usize, b: usize) -> std::cmp::Ordering {
    m.nodes[a][0].total_cmp(&m.nodes[b][0])
}

fn sorted_by_x(m: &Mesh, mut v: Vec<usize>) -> Vec<usize> {
    v.sort_by(|&a, &b| cmp_x(m, a, b));
    v
}

/// Union of two meshes whose coincident nodes (to 1e-12 of the size) are merged; sets of
/// the first mesh are kept.
fn merge(a: &Mesh, b: &Mesh) -> Mesh {
    let scale = a.nodes.iter().chain(&b.nodes).fold(0.0f64, |m, p| m.max(p[0].abs()).max(p[1].abs()));
    let key = |p: &[f64; 2]| ((p[0] / scale * 1e12).round() as i64, (p[1] / scale * 1e12).round() as i64);
    let mut index: std::collections::HashMap<(i64, i64), usize> =
        a.nodes.iter().enumerate().map(|(i, p)| (key(p), i)).collect();
    let mut nodes = a.nodes.clone();
    let map: Vec<usize> = b
        .nodes
        .iter()
        .map(|p| {
            *index.entry(key(p)).or_insert_with(|| {
                nodes.push(*p);
                nodes.len() - 1
            })
        })
        .collect();
    let mut m = Mesh::new(nodes);
    for (k, v) in a.elements() {
        m.push_element(k, v);
    }
    for (k, v) in b.elements() {
        let v: Vec<usize> = v.iter().map(|&n| map[n]).collect();
        m.push_element(k, &v);
    }
    m.node_sets = a.node_sets.clone();
    m.edge_sets = a.edge_sets.clone();
    m.element_sets = a.element_sets.clone();
    m
}

/// The side-pushed model's own DOFs ([`Scene::build_side_push`]).
#[derive(Debug, Clone)]
pub struct SidePushDofs {
    pub rig: super::SidePush,
    /// U_p, the pusher's horizontal displacement (extra DOF, free, loaded by F).
    pub pusher: usize,
    /// The trailing-face nodes tied to U_p, bottom to top.
    pub pusher_nodes: Vec<usize>,
    /// The sliding plate's U, V, rotation (extra DOFs, free), None with the uniform pressure.
    pub plate: Option<[usize; 3]>,
}
