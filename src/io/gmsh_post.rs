//! Gmsh output (last stage of the pipeline): the mesh as MSH 4.1 ASCII with its named sets as
//! physical groups, plus one `$NodeData` / `$ElementData` view per field, so a result opens
//! in Gmsh directly and reads back with [`super::gmsh::read`].
//!
//! Gmsh views hold 1 (scalar), 3 (vector) or 9 (tensor) components: build displacements
//! with [`Field::vector_2d`] and stresses with [`Field::tensor_2d`].
//!
//! Physical groups attach to entities, so elements are written in runs sharing the same set
//! membership (one surface entity per distinct membership) and kind, in mesh order; each edge
//! set gets its own curve entity, each node of a node set its own point entity. A file with
//! element views holds the block's elements only (no edge or node sets), so that every
//! element has a value of every view, as meshio requires.

use super::{check_fields, check_mesh, element_tag, io_err, write_atomic, Field};
use crate::error::{Error, Result};
use crate::fem::mesh::Mesh;
use std::collections::{BTreeMap, HashSet};
use std::path::Path;

/// Writes `mesh` and its fields (one view each) as a Gmsh MSH 4.1 ASCII file.
pub fn write_msh(path: &Path, mesh: &Mesh, node_data: &[Field], element_data: &[Field]) -> Result<()> {
    check_mesh(mesh)?;
    check_fields(node_data, mesh.n_nodes(), "node", &[])?;
    check_fields(element_data, mesh.n_elements(), "element", &[])?;
    if let Some(f) = node_data.iter().chain(element_data).find(|f| ![1, 3, 9].contains(&f.components)) {
        return Err(Error::input(
            format!("field '{}'", f.name),
            format!(
                "Gmsh views take 1, 3 or 9 components, not {} (use Field::vector_2d or Field::tensor_2d)",
                f.components
            ),
        ));
    }
    if let Some(name) = mesh.set_names().into_iter().find(|n| n.is_empty() || n.contains(['"', '\n', '\r'])) {
        return Err(Error::input(
            "set name",
            format!("'{name}' cannot be a Gmsh physical name (empty, quote or line break)"),
        ));
    }
    // Element views must cover every element for meshio (`Incompatible cell data` otherwise),
    // and the lines and points of edge and node sets have no value of a block field: with
    // element data, only the block's elements (and their element sets) are written.
    let none = (BTreeMap::new(), BTreeMap::new());
    let (edge_sets, node_sets) =
        if element_data.is_empty() { (&mesh.edge_sets, &mesh.node_sets) } else { (&none.0, &none.1) };
    let node_tags: Vec<u64> = (0..mesh.n_nodes()).map(|n| mesh.node_tag(n)).collect();
    let elem_tags: Vec<u64> = (0..mesh.n_elements()).map(|e| element_tag(mesh, e)).collect();
    for (tags, what) in [(&node_tags, "node"), (&elem_tags, "element")] {
        let mut seen = HashSet::with_capacity(tags.len());
        if let Some(t) = tags.iter().find(|&&t| !seen.insert(t)) {
            return Err(Error::Mesh(format!("{what} tag {t} is used twice; Gmsh needs unique tags")));
        }
    }
    let out_of_range = |name: &str, i: usize, n: usize, what: &str| {
        Error::Mesh(format!("set '{name}' refers to {what} index {i}, but there are {n}"))
    };

    // Surfaces: one entity per distinct element-set membership, in order of first use.
    let mut member: Vec<Vec<usize>> = vec![Vec::new(); mesh.n_elements()];
    for (g, (name, set)) in mesh.element_sets.iter().enumerate() {
        for &e in set {
            member.get_mut(e).ok_or_else(|| out_of_range(name, e, mesh.n_elements(), "element"))?.push(g + 1);
        }
    }
    let mut surfaces: Vec<Vec<usize>> = Vec::new();
    let elem_entity: Vec<usize> = member
        .iter_mut()
        .map(|m| {
            m.sort_unstable();
            m.dedup();
            surfaces.iter().position(|s| s == m).unwrap_or_else(|| {
                surfaces.push(m.clone());
                surfaces.len() - 1
            }) + 1
        })
        .collect();
    if surfaces.is_empty() {
        surfaces.push(Vec::new()); // the nodes' entity
    }
    for (name, edges) in edge_sets {
        if let Some(n) =
            edges.iter().flat_map(|e| e.nodes().collect::<Vec<_>>()).find(|&n| n >= mesh.n_nodes())
        {
            return Err(out_of_range(name, n, mesh.n_nodes(), "node"));
        }
    }
    // Points: one entity per node of any node set, with the tags of all sets holding it.
    let mut points: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for (g, (name, set)) in node_sets.iter().enumerate() {
        for &n in set {
            if n >= mesh.n_nodes() {
                return Err(out_of_range(name, n, mesh.n_nodes(), "node"));
            }
            points.entry(n).or_default().push(g + 1);
        }
    }

    let (lo, hi) = mesh.nodes.iter().fold(([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]), |(lo, hi), p| {
        ([lo[0].min(p[0]), lo[1].min(p[1])], [hi[0].max(p[0]), hi[1].max(p[1])])
    });
    let bbox = if mesh.n_nodes() == 0 {
        String::from("0 0 0 0 0 0")
    } else {
        format!("{:e} {:e} 0 {:e} {:e} 0", lo[0], lo[1], hi[0], hi[1])
    };

    write_atomic(path, |w| {
        let e = io_err(path);
        writeln!(w, "$MeshFormat\n4.1 0 8\n$EndMeshFormat").map_err(&e)?;
        let n_names = node_sets.len() + edge_sets.len() + mesh.element_sets.len();
        writeln!(w, "$PhysicalNames\n{n_names}").map_err(&e)?;
        for (dim, names) in [
            (0, node_sets.keys().collect::<Vec<_>>()),
            (1, edge_sets.keys().collect()),
            (2, mesh.element_sets.keys().collect()),
        ] {
            for (g, name) in names.into_iter().enumerate() {
                writeln!(w, "{dim} {} \"{name}\"", g + 1).map_err(&e)?;
            }
        }
        writeln!(
            w,
            "$EndPhysicalNames\n$Entities\n{} {} {} 0",
            points.len(),
            edge_sets.len(),
            surfaces.len()
        )
        .map_err(&e)?;
        let tags = |t: &[usize]| t.iter().map(|g| format!(" {g}")).collect::<String>();
        for (i, (&n, groups)) in points.iter().enumerate() {
            let p = mesh.nodes[n];
            writeln!(w, "{} {:e} {:e} 0 {}{}", i + 1, p[0], p[1], groups.len(), tags(groups)).map_err(&e)?;
        }
        for g in 1..=edge_sets.len() {
            writeln!(w, "{g} {bbox} 1 {g} 0").map_err(&e)?;
        }
        for (i, groups) in surfaces.iter().enumerate() {
            writeln!(w, "{} {bbox} {}{} 0", i + 1, groups.len(), tags(groups)).map_err(&e)?;
        }
        writeln!(w, "$EndEntities").map_err(&e)?;

        let (tmin, tmax) = (node_tags.iter().min().unwrap_or(&0), node_tags.iter().max().unwrap_or(&0));
        writeln!(w, "$Nodes\n1 {} {tmin} {tmax}\n2 1 0 {}", mesh.n_nodes(), mesh.n_nodes()).map_err(&e)?;
        for t in &node_tags {
            writeln!(w, "{t}").map_err(&e)?;
        }
        for p in &mesh.nodes {
            writeln!(w, "{:e} {:e} 0", p[0], p[1]).map_err(&e)?;
        }
        writeln!(w, "$EndNodes").map_err(&e)?;

        // Blocks in file order: (dim, entity, Gmsh type) and rows [element tag, node tags...].
        type Key = (u8, usize, u32);
        let mut blocks: Vec<(Key, Vec<Vec<u64>>)> = Vec::new();
        let mut push = |key: Key, tag: u64, nodes: &mut dyn Iterator<Item = usize>| {
            let row = std::iter::once(tag).chain(nodes.map(|n| node_tags[n])).collect();
            match blocks.last_mut() {
                Some((k, rows)) if *k == key => rows.push(row),
                _ => blocks.push((key, vec![row])),
            }
        };
        for (el, (kind, nodes)) in mesh.elements().enumerate() {
            push((2, elem_entity[el], kind.gmsh_type()), elem_tags[el], &mut nodes.iter().copied());
        }
        let mut next_tag = elem_tags.iter().max().map_or(1, |t| t + 1);
        for (g, edges) in edge_sets.values().enumerate() {
            for edge in edges {
                push((1, g + 1, if edge.mid.is_some() { 8 } else { 1 }), next_tag, &mut edge.nodes());
                next_tag += 1;
            }
        }
        for (i, &n) in points.keys().enumerate() {
            push((0, i + 1, 15), next_tag, &mut std::iter::once(n));
            next_tag += 1;
        }
        let total: usize = blocks.iter().map(|b| b.1.len()).sum();
        let first = elem_tags.iter().min().copied().unwrap_or(1); // line and point tags follow the largest
        writeln!(w, "$Elements\n{} {total} {first} {}", blocks.len(), next_tag - 1).map_err(&e)?;
        for ((dim, entity, ty), rows) in &blocks {
            writeln!(w, "{dim} {entity} {ty} {}", rows.len()).map_err(&e)?;
            for row in rows {
                writeln!(w, "{}", row.iter().map(u64::to_string).collect::<Vec<_>>().join(" "))
                    .map_err(&e)?;
            }
        }
        writeln!(w, "$EndElements").map_err(&e)?;

        for (fields, section, tags) in
            [(node_data, "NodeData", &node_tags), (element_data, "ElementData", &elem_tags)]
        {
            for f in fields {
                // string tag: name; real tag: time; int tags: time step, components, entries
                writeln!(w, "${section}\n1\n\"{}\"\n1\n0\n3\n0\n{}\n{}", f.name, f.components, tags.len())
                    .map_err(&e)?;
                for (t, v) in tags.iter().zip(f.values.chunks(f.components)) {
                    let v: String = v.iter().map(|x| format!(" {x:e}")).collect();
                    writeln!(w, "{t}{v}").map_err(&e)?;
                }
                writeln!(w, "$End{section}").map_err(&e)?;
            }
        }
        Ok(())
    })
}
