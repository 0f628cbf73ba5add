//! Gmsh mesh reader (first stage of the pipeline: file -> [`Mesh`]).
//!
//! Reads MSH 4.1 and MSH 2.2 (2.x), ASCII and binary in either byte order. Physical groups
//! become named sets: 2D -> `element_sets`, 1D (line2/line3) -> `edge_sets`, 0D -> `node_sets`
//! (sorted), unnamed ones `physical_<dim>_<tag>`. Only 2D elements enter the mesh; nodes no
//! 2D element uses are dropped. Node and element tags may be sparse and start anywhere: they are
//! kept in `node_tags`/`element_tags` and mapped through a hash map, never used as indices.
//!
//! Format reference: Gmsh reference manual, section "MSH file format" (4.1) and its
//! "Legacy formats" appendix (2.2). Any input is either read or rejected with
//! [`Error::Parse`] naming the line (ASCII) or byte (binary); counts read from the file never
//! size an allocation beyond what the remaining input could hold.

use crate::error::{Error, Result};
use crate::fem::element::ElementKind;
use crate::fem::mesh::{Edge, Mesh};
use std::collections::{BTreeMap, HashMap};

mod cursor;
mod sections;
use cursor::Cursor;
use std::path::Path;

/// Reads a Gmsh `.msh` file.
pub fn read(path: &Path) -> Result<Mesh> {
    let bytes = crate::io::input::read_bounded(
        path,
        "mesh file (--mesh, mesh.file)",
        crate::io::input::MESH_MAX_BYTES,
    )?;
    parse(&bytes, path)
}

/// Parses the bytes of a Gmsh `.msh` file; `file_name` only labels error messages.
pub fn parse(bytes: &[u8], file_name: &Path) -> Result<Mesh> {
    let mut p = Parser {
        r: Cursor { buf: bytes, pos: 0, file: file_name, binary: false, big_endian: false, size_t: 8 },
        ..Default::default()
    };
    p.run()?;
    p.build()
}

const SUPPORTED: &str =
    "15 (point), 1 (line2), 8 (line3), 2 (tri3), 9 (tri6), 3 (qua4), 16 (qua8), 10 (qua9)";

/// The Gmsh element types the reader accepts.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Shape {
    Point,
    Line { mid: bool },
    Surface(ElementKind),
}

impl Shape {
    fn from_gmsh(t: i64) -> Option<Shape> {
        Some(match t {
            15 => Shape::Point,
            1 => Shape::Line { mid: false },
            8 => Shape::Line { mid: true },
            _ => Shape::Surface(ElementKind::from_gmsh_type(u32::try_from(t).ok()?)?),
        })
    }
    fn dim(self) -> i64 {
        match self {
            Shape::Point => 0,
            Shape::Line { .. } => 1,
            Shape::Surface(_) => 2,
        }
    }
    fn n_nodes(self) -> usize {
        match self {
            Shape::Point => 1,
            Shape::Line { mid } => 2 + mid as usize,
            Shape::Surface(k) => k.n_nodes(),
        }
    }
}

/// A physical group or an entity: (dimension, tag).
type Group = (i64, i64);

/// What the file holds, in file numbering, before renumbering into a [`Mesh`].
#[derive(Default)]
struct Parser<'a> {
    r: Cursor<'a>,
    version: u8,
    names: HashMap<Group, String>,
    /// MSH 4.1 entities (dim, tag) -> physical tags.
    entity_groups: HashMap<Group, Vec<i64>>,
    nodes: Vec<[f64; 2]>,
    node_tags: Vec<u64>,
    node_index: HashMap<u64, usize>,
    kinds: Vec<ElementKind>,
    /// Nodes of element e at `conn[9 * e..]`, padded with `usize::MAX`.
    conn: Vec<usize>,
    elem_tags: Vec<u64>,
    elem_index: HashMap<(ElementKind, [usize; 9]), usize>,
    /// Physical groups (dim, tag) -> elements; edges and nodes with the position of the
    /// element that added them.
    element_groups: BTreeMap<Group, Vec<usize>>,
    edge_groups: BTreeMap<Group, Vec<([usize; 3], usize)>>,
    node_groups: BTreeMap<Group, Vec<(usize, usize)>>,
    /// Where `$Elements` started, for messages about the mesh as a whole.
    elements_at: Option<usize>,
}

impl<'a> Parser<'a> {
    fn run(&mut self) -> Result<()> {
        let (at, tok) = self.r.token("$MeshFormat")?;
        if tok != b"$MeshFormat" {
            return Err(self.r.err(at, "not a Gmsh mesh: the file must start with $MeshFormat"));
        }
        self.mesh_format()?;
        loop {
            self.r.skip_ws();
            if self.r.remaining() == 0 {
                return Ok(());
            }
            let (at, tok) = self.r.token("a section")?;
            let Some(name) = tok.strip_prefix(b"$") else {
                return Err(self.r.err(
                    at,
                    format!(
                        "expected a section such as $Nodes, found '{}'",
                        String::from_utf8_lossy(&tok[..tok.len().min(40)])
                    ),
                ));
            };
            let name = String::from_utf8_lossy(name).into_owned();
            match name.as_str() {
                "PhysicalNames" => self.physical_names()?,
                "Entities" if self.version == 4 => {
                    self.r.end_line()?;
                    self.entities()?
                }
                "Nodes" => {
                    self.r.end_line()?;
                    if self.version == 4 {
                        self.nodes_41()?
                    } else {
                        self.nodes_22(false)?
                    }
                }
                // MSH 2 saved with Mesh.SaveParametric = 1.
                "ParametricNodes" if self.version == 2 => {
                    self.r.end_line()?;
                    self.nodes_22(true)?
                }
                "Elements" => {
                    if self.nodes.is_empty() {
                        return Err(self.r.err(at, "$Elements before any node was defined in $Nodes"));
                    }
                    self.elements_at = Some(at);
                    self.r.end_line()?;
                    if self.version == 4 {
                        self.elements_41()?
                    } else {
                        self.elements_22()?
                    }
                }
                "MeshFormat" => return Err(self.r.err(at, "second $MeshFormat section")),
                _ => {
                    self.skip_section(at, &name)?;
                    continue;
                }
            }
            self.r.expect(&format!("$End{name}"))?;
        }
    }

    /// Jumps past `$End<name>`; sections the reader does not use ($Periodic, $NodeData...).
    fn skip_section(&mut self, at: usize, name: &str) -> Result<()> {
        let end = format!("$End{name}");
        let rest = &self.r.buf[self.r.pos..];
        match rest.windows(end.len()).position(|w| w == end.as_bytes()) {
            Some(i) => {
                self.r.pos += i + end.len();
                Ok(())
            }
            None => Err(self.r.err(at, format!("section ${name} has no {end}"))),
        }
    }

    fn group_name(&self, key: Group) -> String {
        self.names.get(&key).cloned().unwrap_or_else(|| format!("physical_{}_{}", key.0, key.1))
    }

    /// Drops the nodes no 2D element uses, renumbers, names the sets, orients and validates.
    fn build(self) -> Result<Mesh> {
        let r = &self.r;
        let whole = self.elements_at.unwrap_or(r.buf.len());
        if self.nodes.is_empty() {
            return Err(r.err(whole, "the file defines no nodes"));
        }
        if self.kinds.is_empty() {
            return Err(r.err(whole, "the file has no 2D elements (tri3, tri6, qua4, qua8, qua9); lines and points alone make no mesh"));
        }
        let mut new = vec![usize::MAX; self.nodes.len()];
        let mut kept = Vec::new();
        for (e, kind) in self.kinds.iter().enumerate() {
            for &n in &self.conn[e * 9..e * 9 + kind.n_nodes()] {
                new[n] = 0;
            }
        }
        for (n, slot) in new.iter_mut().enumerate() {
            if *slot == 0 {
                *slot = kept.len();
                kept.push(n);
            }
        }
        let map = |n: usize, name: &str, at: usize| -> Result<usize> {
            match new[n] {
                usize::MAX => Err(r.err(
                    at,
                    format!(
                        "node tag {} in set '{name}' is not connected to any 2D element",
                        self.node_tags[n]
                    ),
                )),
                i => Ok(i),
            }
        };
        let mut mesh = Mesh::new(kept.iter().map(|&n| self.nodes[n]).collect());
        for (e, &kind) in self.kinds.iter().enumerate() {
            let nodes: Vec<usize> =
                self.conn[e * 9..e * 9 + kind.n_nodes()].iter().map(|&n| new[n]).collect();
            mesh.push_element(kind, &nodes);
        }
        for (&key, members) in &self.element_groups {
            let set = mesh.element_sets.entry(self.group_name(key)).or_default();
            set.extend(members);
            set.sort_unstable();
            set.dedup();
        }
        for (&key, members) in &self.edge_groups {
            let name = self.group_name(key);
            let mut edges = Vec::with_capacity(members.len());
            for &([a, b, m], at) in members {
                let mid = if m == usize::MAX { None } else { Some(map(m, &name, at)?) };
                edges.push(Edge { ends: [map(a, &name, at)?, map(b, &name, at)?], mid });
            }
            mesh.edge_sets.entry(name).or_default().extend(edges);
        }
        for (&key, members) in &self.node_groups {
            let name = self.group_name(key);
            let mut nodes = Vec::with_capacity(members.len());
            for &(n, at) in members {
                nodes.push(map(n, &name, at)?);
            }
            let set = mesh.node_sets.entry(name).or_default();
            set.extend(nodes);
            set.sort_unstable();
            set.dedup();
        }
        mesh.node_tags = Some(kept.iter().map(|&n| self.node_tags[n]).collect());
        mesh.element_tags = Some(self.elem_tags);
        mesh.orient_counter_clockwise();
        mesh.validate().map_err(|e| match e {
            Error::Mesh(msg) => Error::Mesh(format!("{}: {msg}", r.file.display())),
            e => e,
        })?;
        Ok(mesh)
    }
}
