//! VTK XML output for ParaView (last stage of the pipeline: results -> file).
//!
//! [`write_vtu`] writes one `UnstructuredGrid` piece: points in 3D with z = 0, connectivity,
//! offsets and cell types (VTK 5, 22, 9, 23, 28; node order is Gmsh's, which VTK shares), the
//! given point and cell fields, and three bookkeeping arrays: `node_tag` (points),
//! `element_tag` and `element_kind` (cells; the kind as its Gmsh element type code). Arrays are
//! inline base64 of a UInt64 byte count followed by the little-endian data, uncompressed
//! (VTK file format, "XML File Formats", binary inline data).
//! [`write_pvd`] writes a `.pvd` collection, one data set per load case or time.

use super::{check_fields, check_mesh, element_tag, io_err, write_atomic, Field};
use crate::error::{Error, Result};
use crate::fem::mesh::Mesh;
use std::io::Write;
use std::path::Path;

/// Names the writer adds itself; fields may not use them.
pub const POINT_ARRAYS: [&str; 1] = ["node_tag"];
pub const CELL_ARRAYS: [&str; 2] = ["element_tag", "element_kind"];

/// Writes `mesh` with its point and cell fields as a VTK XML `.vtu` file.
pub fn write_vtu(path: &Path, mesh: &Mesh, point_data: &[Field], cell_data: &[Field]) -> Result<()> {
    check_mesh(mesh)?;
    check_fields(point_data, mesh.n_nodes(), "point", &POINT_ARRAYS)?;
    check_fields(cell_data, mesh.n_elements(), "cell", &CELL_ARRAYS)?;
    let (np, nc) = (mesh.n_nodes(), mesh.n_elements());
    write_atomic(path, |w| {
        let e = io_err(path);
        writeln!(w, "<?xml version=\"1.0\"?>").map_err(&e)?;
        writeln!(w, "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">").map_err(&e)?;
        writeln!(w, "  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"{np}\" NumberOfCells=\"{nc}\">")
            .map_err(&e)?;

        writeln!(w, "      <PointData>").map_err(&e)?;
        for f in point_data {
            array(w, &f.name, f.components, &f.values).map_err(&e)?;
        }
        let node_tags: Vec<i64> = (0..np).map(|n| mesh.node_tag(n) as i64).collect();
        array(w, "node_tag", 1, &node_tags).map_err(&e)?;
        writeln!(w, "      </PointData>\n      <CellData>").map_err(&e)?;
        for f in cell_data {
            array(w, &f.name, f.components, &f.values).map_err(&e)?;
        }
        let elem_tags: Vec<i64> = (0..nc).map(|c| element_tag(mesh, c) as i64).collect();
        array(w, "element_tag", 1, &elem_tags).map_err(&e)?;
        let kinds: Vec<i32> = (0..nc).map(|c| mesh.kind(c).gmsh_type() as i32).collect();
        array(w, "element_kind", 1, &kinds).map_err(&e)?;
        writeln!(w, "      </CellData>\n      <Points>").map_err(&e)?;

        let points: Vec<f64> = mesh.nodes.iter().flat_map(|p| [p[0], p[1], 0.0]).collect();
        array(w, "Points", 3, &points).map_err(&e)?;
        writeln!(w, "      </Points>\n      <Cells>").map_err(&e)?;
        let conn: Vec<i64> = mesh.elements().flat_map(|(_, nodes)| nodes.iter().map(|&n| n as i64)).collect();
        let mut end = 0i64;
        let offsets: Vec<i64> = mesh
            .elements()
            .map(|(k, _)| {
                end += k.n_nodes() as i64;
                end
            })
            .collect();
        let types: Vec<u8> = mesh.elements().map(|(k, _)| k.vtk_type()).collect();
        array(w, "connectivity", 1, &conn).map_err(&e)?;
        array(w, "offsets", 1, &offsets).map_err(&e)?;
        array(w, "types", 1, &types).map_err(&e)?;
        writeln!(w, "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>").map_err(&e)
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

/// Numbers a `DataArray` can hold, written little-endian.
trait Scalar: Copy {
    const VTK: &'static str;
    fn put(self, out: &mut Vec<u8>);
}
macro_rules! scalar {
    ($t:ty, $name:literal) => {
        impl Scalar for $t {
            const VTK: &'static str = $name;
            fn put(self, out: &mut Vec<u8>) {
                out.extend_from_slice(&self.to_le_bytes());
            }
        }
    };
}
scalar!(f64, "Float64");
scalar!(i64, "Int64");
scalar!(i32, "Int32");
scalar!(u8, "UInt8");

fn array<T: Scalar>(w: &mut dyn Write, name: &str, components: usize, values: &[T]) -> std::io::Result<()> {
    let bytes = std::mem::size_of_val(values);
    let mut raw = Vec::with_capacity(8 + bytes);
    raw.extend_from_slice(&(bytes as u64).to_le_bytes());
    values.iter().for_each(|v| v.put(&mut raw));
    writeln!(
        w,
        "        <DataArray type=\"{}\" Name=\"{name}\" NumberOfComponents=\"{components}\" format=\"binary\">{}</DataArray>",
        T::VTK,
        base64(&raw)
    )
}

/// Standard base64 (RFC 4648) with padding.
fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for c in bytes.chunks(3) {
        let n = (c[0] as u32) << 16 | (*c.get(1).unwrap_or(&0) as u32) << 8 | *c.get(2).unwrap_or(&0) as u32;
        for i in 0..4 {
            out.push(if i <= c.len() { A[(n >> (18 - 6 * i) & 63) as usize] as char } else { '=' });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    #[test]
    fn base64_matches_rfc4648_vectors() {
        for (plain, enc) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(super::base64(plain.as_bytes()), enc);
        }
    }
}
