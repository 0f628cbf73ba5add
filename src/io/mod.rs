//! Mesh input and result output: the two ends of the pipeline.
//!
//! - [`gmsh`] reads Gmsh `.msh` meshes (MSH 4.1 and 2.2, ASCII and binary).
//! - [`vtu`] writes VTK XML `.vtu` files and `.pvd` collections (ParaView).
//! - [`gmsh_post`] writes the mesh and `$NodeData`/`$ElementData` views as MSH 4.1 (Gmsh).
//! - [`csv`] formats CSV numbers (`{:.12e}`, fast) and screens cells for the output guard.
//! - [`input`] reads an input file: a regular file only, bounded by size.
//! - [`outdir`] makes an output folder a unit (written aside, renamed into place).
//!
//! Writers take [`Field`]s, plain named arrays, so they do not depend on the solver, and
//! write atomically: a temporary file in the target directory renamed into place, so a
//! failed write never leaves a partial file.

pub mod csv;
pub mod gmsh;
pub mod gmsh_post;
pub mod input;
pub mod outdir;
pub mod vtu;

use crate::error::{Error, Result};
use crate::fem::mesh::Mesh;
use std::io::Write;
use std::path::Path;

/// Which field files a command writes: `.vtu` for ParaView (raw binary, fast), `.msh` for
/// Gmsh (ASCII, several times larger and slower), both, or none.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FieldFormat {
    #[default]
    Vtu,
    Msh,
    Both,
    None,
}

impl FieldFormat {
    pub fn vtu(self) -> bool {
        matches!(self, Self::Vtu | Self::Both)
    }
    pub fn msh(self) -> bool {
        matches!(self, Self::Msh | Self::Both)
    }
    pub fn name(self) -> &'static str {
        match self {
            Self::Vtu => "vtu",
            Self::Msh => "msh",
            Self::Both => "both",
            Self::None => "none",
        }
    }
}

impl std::str::FromStr for FieldFormat {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "vtu" => Ok(Self::Vtu),
            "msh" => Ok(Self::Msh),
            "both" => Ok(Self::Both),
            "none" => Ok(Self::None),
            _ => Err(Error::input("--fields", format!("'{s}': use vtu, msh, both or none"))),
        }
    }
}

/// A named array over the points or the cells of a mesh, `components` values per entry
/// (entry-major: the components of entry 0, then of entry 1...).
#[derive(Debug, Clone, PartialEq)]
pub struct Field {
    pub name: String,
    pub components: usize,
    pub values: Vec<f64>,
}

impl Field {
    pub fn new(name: impl Into<String>, components: usize, values: Vec<f64>) -> Self {
        Self { name: name.into(), components, values }
    }

    pub fn scalar(name: impl Into<String>, values: Vec<f64>) -> Self {
        Self::new(name, 1, values)
    }

    /// An in-plane vector (e.g. displacement) stored with z = 0, so that viewers show a vector.
    pub fn vector_2d(name: impl Into<String>, values: &[[f64; 2]]) -> Self {
        Self::new(name, 3, values.iter().flat_map(|v| [v[0], v[1], 0.0]).collect())
    }

    /// A plane-strain symmetric tensor given as [xx, yy, xy, zz], the order of
    /// [`crate::fem::recovery::Stress`], stored as the full 3 x 3 row-major tensor that VTK
    /// and Gmsh views expect.
    pub fn tensor_2d(name: impl Into<String>, values: &[[f64; 4]]) -> Self {
        let full =
            values.iter().flat_map(|&[xx, yy, xy, zz]| [xx, xy, 0.0, xy, yy, 0.0, 0.0, 0.0, zz]).collect();
        Self::new(name, 9, full)
    }

    /// The nodal fields of a solution: displacement, stress (extrapolated from the
    /// integration points and averaged at nodes) and von Mises stress, in SI units.
    pub fn solution_fields(model: &crate::fem::assembly::Model, u: &[f64]) -> Vec<Self> {
        use crate::fem::recovery::{nodal_stresses, von_mises};
        let disp: Vec<[f64; 2]> = (0..model.mesh.n_nodes()).map(|k| [u[2 * k], u[2 * k + 1]]).collect();
        let s = nodal_stresses(model, u);
        vec![
            Self::vector_2d("displacement_m", &disp),
            Self::tensor_2d("stress_Pa", &s),
            Self::scalar("von_mises_Pa", s.iter().map(von_mises).collect()),
        ]
    }

    /// Checks the field fits `n` entries of kind `over` ("point", "cell"...) and holds finite
    /// numbers only. Names are kept free of quotes, markup and control characters, so no
    /// writer needs to escape them.
    pub fn check(&self, n: usize, over: &str) -> Result<()> {
        let what = || format!("field '{}'", self.name);
        if self.name.is_empty()
            || self.name.chars().any(|c| c.is_control() || matches!(c, '"' | '<' | '>' | '&' | '\''))
        {
            return Err(Error::input(
                what(),
                "a name must be non-empty, without quotes, <, >, & or control characters",
            ));
        }
        if self.components == 0 || self.values.len() != n * self.components {
            return Err(Error::input(
                what(),
                format!(
                    "has {} values, but {n} {over}s x {} components need {}",
                    self.values.len(),
                    self.components,
                    n * self.components
                ),
            ));
        }
        if let Some(i) = self.values.iter().position(|v| !v.is_finite()) {
            return Err(Error::input(
                what(),
                format!(
                    "value {} at {over} {} component {} is not finite",
                    self.values[i],
                    i / self.components,
                    i % self.components
                ),
            ));
        }
        Ok(())
    }
}

/// Checks every field of a list and that names are unique among them and `reserved`.
fn check_fields(fields: &[Field], n: usize, over: &str, reserved: &[&str]) -> Result<()> {
    for (i, f) in fields.iter().enumerate() {
        f.check(n, over)?;
        if reserved.contains(&f.name.as_str()) || fields[..i].iter().any(|g| g.name == f.name) {
            return Err(Error::input(
                format!("field '{}'", f.name),
                format!("the name is used twice among the {over} fields"),
            ));
        }
    }
    Ok(())
}

/// The user's number of element `e` (1-based index when the mesh has no tags), as in messages.
fn element_tag(mesh: &Mesh, e: usize) -> u64 {
    mesh.element_tags.as_ref().map_or(e as u64 + 1, |t| t[e])
}

/// Writers refuse what would make a broken file: non-finite coordinates, nodes out of range.
fn check_mesh(mesh: &Mesh) -> Result<()> {
    if let Some(n) = mesh.nodes.iter().position(|p| !(p[0].is_finite() && p[1].is_finite())) {
        return Err(Error::Mesh(format!(
            "node {} has the non-finite coordinates {:?}",
            mesh.node_tag(n),
            mesh.nodes[n]
        )));
    }
    if let Some(e) =
        (0..mesh.n_elements()).find(|&e| mesh.element_nodes(e).iter().any(|&n| n >= mesh.n_nodes()))
    {
        return Err(Error::Mesh(format!(
            "{} refers to a node index beyond the {} nodes",
            mesh.describe_element(e),
            mesh.n_nodes()
        )));
    }
    Ok(())
}

/// Writes `path` through a temporary file in the same directory, renamed into place only
/// once `body` succeeded and the data reached the disk.
fn write_atomic(path: &Path, body: impl FnOnce(&mut dyn Write) -> Result<()>) -> Result<()> {
    let _writing = crate::io::outdir::write_guard(path)?;
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let name = path
        .file_name()
        .ok_or_else(|| Error::input("output path", format!("'{}' has no file name", path.display())))?;
    // Unique per process and call, so concurrent writers never share a temporary file.
    static COUNTER: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = COUNTER.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let tmp = dir.join(format!(".{}.{}-{n}.tmp", name.to_string_lossy(), std::process::id()));
    let result = (|| {
        let file = std::fs::File::create(&tmp).map_err(|e| Error::io(&tmp, e))?;
        let mut w = std::io::BufWriter::new(file);
        body(&mut w)?;
        let file = w.into_inner().map_err(|e| Error::io(&tmp, e.into_error()))?;
        file.sync_all().map_err(|e| Error::io(&tmp, e))?;
        std::fs::rename(&tmp, path).map_err(|e| Error::io(path, e))
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// Maps `std::io::Error` of a writer to [`Error::Io`] on `path`.
fn io_err(path: &Path) -> impl Fn(std::io::Error) -> Error + '_ {
    move |e| Error::io(path, e)
}
