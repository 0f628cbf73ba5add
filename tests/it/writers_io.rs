//! Result writers: the `.vtu` file decoded back array by array, the `.pvd` collection, the
//! Gmsh MSH 4.1 output read back by our reader (mesh identical, views' values checked), and
//! the refusals (NaN, wrong length) that must leave no file behind.
//!
//! `vtu_arrays_decode_to_what_was_written` also leaves `target/tmp/io-check/` (mesh.vtu,
//! mesh.json, cases.pvd, result.msh) for the independent check with meshio:
//! `python3 validation/io/check_vtu.py target/tmp/io-check`.

use std::collections::BTreeMap;
use std::path::Path;
use tribofe::fem::element::ElementKind;
use tribofe::fem::mesh::Mesh;
use tribofe::fem::mesher::Rectangle;
use tribofe::io::{gmsh, gmsh_post, vtu, Field};

/// One small rectangle mesh of each element kind, side by side (nodes not shared).
fn all_kinds_mesh() -> Mesh {
    let mut m = Mesh::new(Vec::new());
    for (i, kind) in ElementKind::ALL.into_iter().enumerate() {
        let r = Rectangle::new(i as f64, i as f64 + 1.0, 0.0, 0.5, 2, 1).kind(kind).build().unwrap();
        let offset = m.n_nodes();
        m.nodes.extend(&r.nodes);
        for (k, v) in r.elements() {
            m.push_element(k, &v.iter().map(|n| n + offset).collect::<Vec<_>>());
        }
    }
    m
}

fn fields(m: &Mesh) -> (Vec<Field>, Vec<Field>) {
    let u: Vec<[f64; 2]> = m.nodes.iter().map(|p| [1e-6 * p[0], -2e-7 * p[0] * p[1]]).collect();
    let temp: Vec<f64> = m.nodes.iter().map(|p| 20.0 + p[1]).collect();
    let stress: Vec<[f64; 4]> = (0..m.n_elements())
        .map(|e| [-1e6 * e as f64, 2.5e5, 1e-3 * e as f64, 0.3 * (2.5e5 - 1e6 * e as f64)])
        .collect();
    (
        vec![Field::vector_2d("displacement", &u), Field::scalar("temperature", temp)],
        vec![Field::tensor_2d("stress", &stress)],
    )
}

/// Every `DataArray` of a `.vtu` written by us: name -> (type, components, raw bytes), read
/// from the raw appended block at each array's offset (after its UInt64 byte count).
fn data_arrays(bytes: &[u8]) -> BTreeMap<String, (String, usize, Vec<u8>)> {
    let marker = b"<AppendedData encoding=\"raw\">";
    let at = bytes.windows(marker.len()).position(|w| w == marker).expect("raw appended data");
    let start = at + bytes[at..].iter().position(|&b| b == b'_').unwrap() + 1;
    let xml = std::str::from_utf8(&bytes[..at]).unwrap();
    assert!(!xml.contains("format=\"binary\"") && !xml.contains("format=\"ascii\""));
    let attr = |tag: &str, name: &str| {
        tag.split(&format!(" {name}=\"")).nth(1).map(|s| s[..s.find('"').unwrap()].to_string())
    };
    let mut out = BTreeMap::new();
    for piece in xml.split("<DataArray").skip(1) {
        let tag = &piece[..piece.find("/>").unwrap()];
        assert_eq!(attr(tag, "format").unwrap(), "appended");
        let off = start + attr(tag, "offset").unwrap().parse::<usize>().unwrap();
        let n = u64::from_le_bytes(bytes[off..off + 8].try_into().unwrap()) as usize;
        let name = attr(tag, "Name").unwrap();
        out.insert(
            name,
            (
                attr(tag, "type").unwrap(),
                attr(tag, "NumberOfComponents").unwrap().parse().unwrap(),
                bytes[off + 8..off + 8 + n].to_vec(),
            ),
        );
    }
    // The arrays tile the block exactly: nothing unread between or after them.
    let total: usize = out.values().map(|a| 8 + a.2.len()).sum();
    assert_eq!(&bytes[start + total..], b"\n  </AppendedData>\n</VTKFile>\n");
    out
}

fn f64s(b: &[u8]) -> Vec<f64> {
    b.chunks(8).map(|c| f64::from_le_bytes(c.try_into().unwrap())).collect()
}
fn i64s(b: &[u8]) -> Vec<i64> {
    b.chunks(8).map(|c| i64::from_le_bytes(c.try_into().unwrap())).collect()
}

fn json_array(v: impl IntoIterator<Item = String>) -> String {
    format!("[{}]", v.into_iter().collect::<Vec<_>>().join(","))
}

/// The mesh and fields as JSON, for `validation/io/check_vtu.py`.
fn json_dump(m: &Mesh, point_data: &[Field], cell_data: &[Field]) -> String {
    let fields = |fs: &[Field]| {
        format!(
            "{{{}}}",
            fs.iter()
                .map(|f| format!(
                    "\"{}\":{{\"components\":{},\"values\":{}}}",
                    f.name,
                    f.components,
                    json_array(f.values.iter().map(|x| format!("{x:e}")))
                ))
                .collect::<Vec<_>>()
                .join(",")
        )
    };
    format!(
        "{{\"points\":{},\"cells\":{},\"point_data\":{},\"cell_data\":{}}}\n",
        json_array(m.nodes.iter().map(|p| format!("[{:e},{:e},0]", p[0], p[1]))),
        json_array(m.elements().map(|(k, v)| format!(
            "[{},{}]",
            k.vtk_type(),
            json_array(v.iter().map(|n| n.to_string()))
        ))),
        fields(point_data),
        fields(cell_data)
    )
}

#[test]
fn vtu_arrays_decode_to_what_was_written() {
    let m = all_kinds_mesh();
    m.validate().unwrap();
    let (pd, cd) = fields(&m);
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("io-check");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("mesh.vtu");
    vtu::write_vtu(&path, &m, &pd, &cd).unwrap();
    std::fs::write(dir.join("mesh.json"), json_dump(&m, &pd, &cd)).unwrap();
    vtu::write_pvd(&dir.join("cases.pvd"), &[(0.0, &path), (1.0, &path)]).unwrap();
    gmsh_post::write_msh(&dir.join("result.msh"), &m, &pd, &cd).unwrap();

    let bytes = std::fs::read(&path).unwrap();
    let xml = String::from_utf8_lossy(&bytes);
    assert!(xml.contains(&format!(
        "NumberOfPoints=\"{}\" NumberOfCells=\"{}\"",
        m.n_nodes(),
        m.n_elements()
    )));
    let a = data_arrays(&bytes);
    let names: Vec<&str> = a.keys().map(|s| s.as_str()).collect();
    assert_eq!(
        names,
        [
            "Points",
            "connectivity",
            "displacement",
            "element_kind",
            "element_tag",
            "node_tag",
            "offsets",
            "stress",
            "temperature",
            "types"
        ]
    );
    let points = f64s(&a["Points"].2);
    assert_eq!((a["Points"].1, points.len()), (3, 3 * m.n_nodes()));
    for (n, p) in m.nodes.iter().enumerate() {
        assert_eq!(points[3 * n..3 * n + 3], [p[0], p[1], 0.0]);
    }
    let conn: Vec<i64> = m.elements().flat_map(|(_, v)| v.iter().map(|&n| n as i64)).collect();
    assert_eq!(i64s(&a["connectivity"].2), conn);
    let offsets = i64s(&a["offsets"].2);
    assert_eq!(offsets.len(), m.n_elements());
    assert_eq!(*offsets.last().unwrap() as usize, conn.len());
    assert_eq!(a["types"].2, [5, 5, 5, 5, 22, 22, 22, 22, 9, 9, 23, 23, 28, 28]);
    let kinds: Vec<i32> =
        a["element_kind"].2.chunks(4).map(|c| i32::from_le_bytes(c.try_into().unwrap())).collect();
    assert_eq!(kinds, m.elements().map(|(k, _)| k.gmsh_type() as i32).collect::<Vec<_>>());
    assert_eq!(i64s(&a["node_tag"].2), (1..=m.n_nodes() as i64).collect::<Vec<_>>());
    for f in pd.iter().chain(&cd) {
        let (ty, comps, raw) = &a[&f.name];
        assert_eq!((ty.as_str(), *comps), ("Float64", f.components));
        assert_eq!(f64s(raw), f.values, "{}", f.name);
    }
    let pvd = std::fs::read_to_string(dir.join("cases.pvd")).unwrap();
    assert_eq!(pvd.matches("<DataSet ").count(), 2);
    assert!(pvd.contains("timestep=\"1e0\" group=\"\" part=\"0\" file=\"mesh.vtu\""), "{pvd}");
}

#[test]
fn refused_fields_leave_no_file() {
    let m = all_kinds_mesh();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.vtu");
    let mut values = vec![0.0; m.n_nodes()];
    values[7] = f64::NAN;
    let cases = [
        (
            Field::scalar("pressure", values),
            "field 'pressure'",
            "value NaN at point 7 component 0 is not finite",
        ),
        (Field::new("u", 2, vec![0.0; 3]), "field 'u'", "has 3 values"),
        (Field::scalar("a\"b", vec![0.0; m.n_nodes()]), "field 'a\"b'", "without quotes"),
        (Field::scalar("node_tag", vec![0.0; m.n_nodes()]), "field 'node_tag'", "used twice"),
    ];
    for (f, what, why) in cases {
        let msg = vtu::write_vtu(&path, &m, std::slice::from_ref(&f), &[]).unwrap_err().to_string();
        assert!(msg.contains(what) && msg.contains(why), "{msg}");
        // `node_tag` is reserved in .vtu only.
        assert_eq!(
            gmsh_post::write_msh(&dir.path().join("bad.msh"), &m, std::slice::from_ref(&f), &[]).is_err(),
            f.name != "node_tag"
        );
        let _ = std::fs::remove_file(dir.path().join("bad.msh"));
    }
    let msg = gmsh_post::write_msh(
        &dir.path().join("bad.msh"),
        &m,
        &[Field::new("u", 2, vec![0.0; 2 * m.n_nodes()])],
        &[],
    )
    .unwrap_err()
    .to_string();
    assert!(msg.contains("Gmsh views take 1, 3 or 9 components"), "{msg}");
    assert!(vtu::write_pvd(&dir.path().join("c.pvd"), &[(f64::INFINITY, &path)]).is_err());
    let mut moved = m.clone();
    moved.nodes[3][1] = f64::NAN;
    let msg = vtu::write_vtu(&path, &moved, &[], &[]).unwrap_err().to_string();
    assert!(msg.contains("node 4 has the non-finite coordinates"), "{msg}");
    assert!(gmsh_post::write_msh(&dir.path().join("bad.msh"), &moved, &[], &[]).is_err());
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0, "no file, no temporary left behind");
    // A directory that does not exist: an I/O error naming the temporary path, nothing written.
    let msg = vtu::write_vtu(&dir.path().join("missing/out.vtu"), &m, &[], &[]).unwrap_err().to_string();
    assert!(msg.contains("missing"), "{msg}");
}

/// `$NodeData`/`$ElementData` views of a file we wrote: name -> (components, tag -> values).
fn views(text: &str, section: &str) -> BTreeMap<String, (usize, BTreeMap<u64, Vec<f64>>)> {
    let mut out = BTreeMap::new();
    for block in text.split(&format!("${section}\n")).skip(1) {
        let block = &block[..block.find(&format!("$End{section}")).unwrap()];
        let lines: Vec<&str> = block.lines().collect();
        // 1 string tag (name), 1 real tag (time), 3 int tags (step, components, count).
        assert_eq!((lines[0], lines[2], lines[4]), ("1", "1", "3"));
        let name = lines[1].trim_matches('"').to_string();
        let (comps, count): (usize, usize) = (lines[6].parse().unwrap(), lines[7].parse().unwrap());
        let rows: BTreeMap<u64, Vec<f64>> = lines[8..]
            .iter()
            .map(|l| {
                let mut w = l.split_whitespace();
                (w.next().unwrap().parse().unwrap(), w.map(|x| x.parse().unwrap()).collect())
            })
            .collect();
        assert_eq!(rows.len(), count);
        out.insert(name, (comps, rows));
    }
    out
}

#[test]
fn gmsh_output_reads_back_identical() {
    // A Gmsh mesh (sparse sets, a node set, overlapping element sets) and a quadratic mixed one.
    let tiny = gmsh::read(&Path::new(env!("CARGO_MANIFEST_DIR")).join("meshes/tiny/tiny_mixed_v41_bin.msh"))
        .unwrap();
    let mut quad = Rectangle::new(0.0, 1.0, 0.0, 0.5, 3, 2).kind(ElementKind::Qua9).build().unwrap();
    quad.element_sets.insert("first".into(), vec![0, 2]);
    quad.node_sets.insert("pins".into(), vec![0, 5]);
    let dir = tempfile::tempdir().unwrap();
    for (what, m) in [("tiny_mixed", tiny), ("qua9", quad)] {
        let (pd, cd) = fields(&m);
        let path = dir.path().join(format!("{what}.msh"));
        // Without element views the sets are written; with them, the elements only.
        gmsh_post::write_msh(&path, &m, &pd, &[]).unwrap();
        let back = gmsh::read(&path).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(back.nodes, m.nodes, "{what}: coordinates round-trip exactly");
        assert_eq!(
            (0..back.n_nodes()).map(|n| back.node_tag(n)).collect::<Vec<_>>(),
            (0..m.n_nodes()).map(|n| m.node_tag(n)).collect::<Vec<_>>(),
            "{what}"
        );
        assert_eq!(back.elements().collect::<Vec<_>>(), m.elements().collect::<Vec<_>>(), "{what}");
        assert_eq!(
            back.element_tags.unwrap(),
            m.element_tags.clone().unwrap_or_else(|| (1..=m.n_elements() as u64).collect()),
            "{what}"
        );
        assert_eq!(back.edge_sets, m.edge_sets, "{what}");
        assert_eq!(back.node_sets, m.node_sets, "{what}");
        let sorted = |s: &BTreeMap<String, Vec<usize>>| {
            s.iter()
                .map(|(k, v)| {
                    (k.clone(), {
                        let mut v = v.clone();
                        v.sort();
                        v
                    })
                })
                .collect::<BTreeMap<_, _>>()
        };
        assert_eq!(sorted(&back.element_sets), sorted(&m.element_sets), "{what}");

        gmsh_post::write_msh(&path, &m, &pd, &cd).unwrap();
        let with_views = gmsh::read(&path).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(with_views.nodes, m.nodes, "{what}");
        assert_eq!(with_views.elements().collect::<Vec<_>>(), m.elements().collect::<Vec<_>>(), "{what}");
        assert!(with_views.edge_sets.is_empty() && with_views.node_sets.is_empty(), "{what}");
        assert_eq!(sorted(&with_views.element_sets), sorted(&m.element_sets), "{what}");
        let text = std::fs::read_to_string(&path).unwrap();
        for (section, fs, n) in [("NodeData", &pd, m.n_nodes()), ("ElementData", &cd, m.n_elements())] {
            let v = views(&text, section);
            assert_eq!(v.len(), fs.len());
            for f in fs {
                let (comps, rows) = &v[&f.name];
                assert_eq!(*comps, f.components);
                for i in 0..n {
                    let tag = if section == "NodeData" {
                        m.node_tag(i)
                    } else {
                        m.element_tags.as_ref().map_or(i as u64 + 1, |t| t[i])
                    };
                    assert_eq!(
                        rows[&tag],
                        f.values[i * comps..(i + 1) * comps],
                        "{what} {} at tag {tag}",
                        f.name
                    );
                }
            }
        }
    }
}
