//! VTK XML output for ParaView (last stage of the pipeline: results -> file).
//!
//! [`write_vtu`] writes one `UnstructuredGrid` piece: points in 3D with z = 0, connectivity,
//! offsets and cell types (VTK 5, 22, 9, 23, 28; node order is Gmsh's, which VTK shares), the
//! given point and cell fields, and three bookkeeping arrays: `node_tag` (points),
//! `element_tag` and `element_kind` (cells; the kind as its Gmsh element type code). Arrays are
//! raw appended binary (VTK file format, "XML File Formats": `format="appended"`, one
//! `<AppendedData encoding="raw">` block of UInt64 byte counts each followed by the
//! little-endian data, uncompressed): no base64 pass, a third smaller and written at disk speed.
//! [`write_pvd`] writes a `.pvd` collection, one data set per load case or time.

use super::{check_fields, check_mesh, element_tag, io_err, write_atomic, Field};
use crate::error::{Error, Result};
use crate::fem::mesh::Mesh;
use std::io::Write;
use std::path::Path;

/// Names the writer adds itself; fields may not use them.
pub const POINT_ARRAYS: [&str; 1] = ["node_tag"];
pub const CELL_ARRAYS: [&str; 2] = ["element_tag", "element_kind"];

/// The values of one `DataArray`, borrowed where the caller holds them.
enum Values<'a> {
    F64(&'a [f64]),
    I64(Vec<i64>),
    I32(Vec<i32>),
    U8(Vec<u8>),
}

impl Values<'_> {
    fn vtk_type(&self) -> &'static str {
        match self {
            Values::F64(_) => "Float64",
            Values::I64(_) => "Int64",
            Values::I32(_) => "Int32",
            Values::U8(_) => "UInt8",
        }
    }
    fn bytes(&self) -> usize {
        match self {
            Values::F64(v) => 8 * v.len(),
            Values::I64(v) => 8 * v.len(),
            Values::I32(v) => 4 * v.len(),
            Values::U8(v) => v.len(),
        }
    }
    /// The byte count then the little-endian data, in chunks so no second copy of a large
    /// array is held.
    fn write(&self, w: &mut dyn Write) -> std::io::Result<()> {
        w.write_all(&(self.bytes() as u64).to_le_bytes())?;
        let mut buf = Vec::with_capacity(1 << 16);
        macro_rules! put {
            ($v:expr) => {
                for chunk in $v.chunks(8192) {
                    buf.clear();
                    chunk.iter().for_each(|x| buf.extend_from_slice(&x.to_le_bytes()));
                    w.write_all(&buf)?;
                }
            };
        }
        match self {
            Values::F64(v) => put!(v),
            Values::I64(v) => put!(v),
            Values::I32(v) => put!(v),
            Values::U8(v) => w.write_all(v)?,
        }
        Ok(())
    }
}

struct Array<'a> {
    name: &'a str,
    components: usize,
    values: Values<'a>,
}

fn field(f: &Field) -> Array<'_> {
    Array { name: &f.name, components: f.components, values: Values::F64(&f.values) }
}

/// Writes `mesh` with its point and cell fields as a VTK XML `.vtu` file.
pub fn write_vtu(path: &Path, mesh: &Mesh, point_data: &[Field], cell_data: &[Field]) -> Result<()> {
    check_mesh(mesh)?;
    check_fields(point_data, mesh.n_nodes(), "point", &POINT_ARRAYS)?;
    check_fields(cell_data, mesh.n_elements(), "cell", &CELL_ARRAYS)?;
    let (np, nc) = (mesh.n_nodes(), mesh.n_elements());
    let points: Vec<f64> = mesh.nodes.iter().flat_map(|p| [p[0], p[1], 0.0]).collect();
    let mut end = 0i64;
    let offsets: Vec<i64> = mesh
        .elements()
        .map(|(k, _)| {
            end += k.n_nodes() as i64;
            end
        })
        .collect();
    // Sections in file order; the appended data follows the same order.
    let mut pd: Vec<Array> = point_data.iter().map(field).collect();
    pd.push(Array {
        name: "node_tag",
        components: 1,
        values: Values::I64((0..np).map(|n| mesh.node_tag(n) as i64).collect()),
    });
    let mut cd: Vec<Array> = cell_data.iter().map(field).collect();
    cd.push(Array {
        name: "element_tag",
        components: 1,
        values: Values::I64((0..nc).map(|c| element_tag(mesh, c) as i64).collect()),
    });
    cd.push(Array {
        name: "element_kind",
        components: 1,
        values: Values::I32((0..nc).map(|c| mesh.kind(c).gmsh_type() as i32).collect()),
    });
    let pts = vec![Array { name: "Points", components: 3, values: Values::F64(&points) }];
    let cells = vec![
        Array {
            name: "connectivity",
            components: 1,
            values: Values::I64(
                mesh.elements().flat_map(|(_, nodes)| nodes.iter().map(|&n| n as i64)).collect(),
            ),
        },
        Array { name: "offsets", components: 1, values: Values::I64(offsets) },
        Array {
            name: "types",
            components: 1,
            values: Values::U8(mesh.elements().map(|(k, _)| k.vtk_type()).collect()),
        },
    ];
    let sections = [("PointData", &pd), ("CellData", &cd), ("Points", &pts), ("Cells", &cells)];
    write_atomic(path, |w| {
        let e = io_err(path);
        writeln!(w, "<?xml version=\"1.0\"?>").map_err(&e)?;
        writeln!(w, "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">").map_err(&e)?;
        writeln!(w, "  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"{np}\" NumberOfCells=\"{nc}\">")
            .map_err(&e)?;
        let mut offset = 0usize;
        for (tag, arrays) in sections {
            writeln!(w, "      <{tag}>").map_err(&e)?;
            for a in arrays.iter() {
                writeln!(
                    w,
                    "        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"appended\" offset=\"{offset}\"/>",
                    a.values.vtk_type(),
                    a.name,
                    a.components
                )
                .map_err(&e)?;
                offset += 8 + a.values.bytes();
            }
            writeln!(w, "      </{tag}>").map_err(&e)?;
        }
        writeln!(w, "    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">").map_err(&e)?;
        // The data start after the underscore (VTK's marker).
        w.write_all(b"   _").map_err(&e)?;
        for (_, arrays) in sections {
            for a in arrays.iter() {
                a.values.write(w).map_err(&e)?;
            }
        }
        writeln!(w, "\n  </AppendedData>\n</VTKFile>").map_err(&e)
    })
}

/// A `.pvd` collection: one data set per (time or load-case number, `.vtu` path). Paths are
/// written relative to the `.pvd` file's directory when they lie below it.
pub fn write_pvd(path: &Path, entries: &[(f64, &Path)]) -> Result<()> {
    if let Some((t, p)) = entries.iter().find(|(t, _)| !t.is_finite()) {
        return Err(Error::input("pvd entry", format!("time {t} of '{}' is not finite", p.display())));
    }
    let dir = path.parent().unwrap_or(Path::new(""));
    write_atomic(path, |w| {
        let e = io_err(path);
        writeln!(w, "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\">\n  <Collection>").map_err(&e)?;
        for (t, p) in entries {
            let rel = p.strip_prefix(dir).unwrap_or(p);
            writeln!(
                w,
                "    <DataSet timestep=\"{t:e}\" group=\"\" part=\"0\" file=\"{}\"/>",
                xml_escape(&rel.to_string_lossy())
            )
            .map_err(&e)?;
        }
        writeln!(w, "  </Collection>\n</VTKFile>").map_err(&e)
    })
}

fn xml_escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c => out.push(c),
        }
    }
    out
}
