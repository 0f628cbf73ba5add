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
use std::path::Path;

/// Reads a Gmsh `.msh` file.
pub fn read(path: &Path) -> Result<Mesh> {
    let bytes = std::fs::read(path).map_err(|e| Error::read(path, e))?;
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

/// Reads ASCII tokens and binary values from the file, and turns positions into messages.
struct Cursor<'a> {
    buf: &'a [u8],
    pos: usize,
    file: &'a Path,
    binary: bool,
    big_endian: bool,
    /// Bytes of a binary `size_t` (MSH 4.1 data-size).
    size_t: usize,
}

impl Default for Cursor<'_> {
    fn default() -> Self {
        Cursor { buf: &[], pos: 0, file: Path::new(""), binary: false, big_endian: false, size_t: 8 }
    }
}

impl<'a> Cursor<'a> {
    fn err(&self, at: usize, msg: impl Into<String>) -> Error {
        let at = at.min(self.buf.len());
        let at = if self.binary {
            format!("byte {at}")
        } else {
            format!("line {}", self.buf[..at].iter().filter(|&&c| c == b'\n').count() + 1)
        };
        Error::Parse { file: self.file.to_path_buf(), at, msg: msg.into() }
    }

    fn remaining(&self) -> usize {
        self.buf.len() - self.pos
    }

    /// Capacity to reserve for `count` items of at least `min_bytes` each: never more than the
    /// rest of the input could hold, whatever the file claims.
    fn cap(&self, count: u64, min_bytes: usize) -> usize {
        (self.remaining() / min_bytes.max(1)).min(usize::try_from(count).unwrap_or(usize::MAX))
    }

    fn skip_ws(&mut self) {
        while self.pos < self.buf.len() && self.buf[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
    }

    /// Next whitespace-separated token and its position.
    fn token(&mut self, what: &str) -> Result<(usize, &'a [u8])> {
        self.skip_ws();
        let start = self.pos;
        while self.pos < self.buf.len() && !self.buf[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
        if start == self.pos {
            return Err(self.err(start, format!("unexpected end of file, expected {what}")));
        }
        Ok((start, &self.buf[start..self.pos]))
    }

    fn ascii<T: std::str::FromStr>(&mut self, what: &str) -> Result<T> {
        let (at, tok) = self.token(what)?;
        std::str::from_utf8(tok).ok().and_then(|s| s.parse().ok()).ok_or_else(|| {
            self.err(
                at,
                format!("expected {what}, found '{}'", String::from_utf8_lossy(&tok[..tok.len().min(40)])),
            )
        })
    }

    /// Ends the current text line: only blanks may remain before the newline. Binary data
    /// starts right after it, so no further whitespace may be skipped.
    fn end_line(&mut self) -> Result<()> {
        while self.pos < self.buf.len() && matches!(self.buf[self.pos], b' ' | b'\t' | b'\r') {
            self.pos += 1;
        }
        match self.buf.get(self.pos) {
            Some(b'\n') => {
                self.pos += 1;
                Ok(())
            }
            None => Err(self.err(self.pos, "unexpected end of file, expected the end of the line")),
            Some(_) => Err(self.err(self.pos, "unexpected data at the end of the line")),
        }
    }

    fn expect(&mut self, word: &str) -> Result<()> {
        let (at, tok) = self.token(word)?;
        if tok != word.as_bytes() {
            return Err(self.err(
                at,
                format!("expected {word}, found '{}'", String::from_utf8_lossy(&tok[..tok.len().min(40)])),
            ));
        }
        Ok(())
    }

    fn bytes<const N: usize>(&mut self, what: &str) -> Result<[u8; N]> {
        let Some(b) = self.buf.get(self.pos..self.pos + N) else {
            return Err(self.err(self.pos, format!("unexpected end of file, expected {what} ({N} bytes)")));
        };
        self.pos += N;
        let mut a: [u8; N] = b.try_into().expect("slice of length N");
        if self.big_endian {
            a.reverse();
        }
        Ok(a)
    }

    fn bin_i32(&mut self, what: &str) -> Result<i64> {
        Ok(i32::from_le_bytes(self.bytes(what)?) as i64)
    }

    fn bin_f64(&mut self, what: &str) -> Result<f64> {
        let at = self.pos;
        let x = f64::from_le_bytes(self.bytes(what)?);
        self.finite(at, x, what)
    }

    fn finite(&self, at: usize, x: f64, what: &str) -> Result<f64> {
        if x.is_finite() {
            Ok(x)
        } else {
            Err(self.err(at, format!("{what} is {x}")))
        }
    }

    // Mode-independent readers for MSH 4.1, whose binary layout mirrors its text layout.

    fn int(&mut self, what: &str) -> Result<i64> {
        if self.binary {
            self.bin_i32(what)
        } else {
            self.ascii(what)
        }
    }

    fn size(&mut self, what: &str) -> Result<u64> {
        if !self.binary {
            return self.ascii(what);
        }
        Ok(if self.size_t == 4 {
            u32::from_le_bytes(self.bytes(what)?) as u64
        } else {
            u64::from_le_bytes(self.bytes(what)?)
        })
    }

    fn real(&mut self, what: &str) -> Result<f64> {
        if self.binary {
            return self.bin_f64(what);
        }
        let at = self.pos;
        let x = self.ascii(what)?;
        self.finite(at, x, what)
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

    fn mesh_format(&mut self) -> Result<()> {
        let (at, v) = self.r.token("the format version")?;
        self.version = match v {
            b"4.1" => 4,
            b"2.2" | b"2.1" | b"2" | b"2.0" => 2,
            _ => {
                return Err(self.r.err(
                    at,
                    format!(
                        "MSH version '{}' is not supported; save as MSH 4.1 or 2.2",
                        String::from_utf8_lossy(&v[..v.len().min(20)])
                    ),
                ));
            }
        };
        let at = self.r.pos;
        let file_type: i64 = self.r.ascii("the file type (0 ASCII, 1 binary)")?;
        let data_size: i64 = self.r.ascii("the data size")?;
        match file_type {
            0 => {}
            1 => {
                let ok = if self.version == 4 { data_size == 4 || data_size == 8 } else { data_size == 8 };
                if !ok {
                    return Err(self.r.err(at, format!("unsupported binary data size {data_size}")));
                }
                self.r.size_t = data_size as usize;
                self.r.end_line()?;
                self.r.binary = true;
                let at = self.r.pos;
                // The int 1 written by Gmsh tells the byte order.
                self.r.big_endian = match self.r.bytes::<4>("the endianness marker (int 1)")? {
                    [1, 0, 0, 0] => false,
                    [0, 0, 0, 1] => true,
                    _ => {
                        return Err(self
                            .r
                            .err(at, "bad endianness marker: expected the int 1 after the $MeshFormat line"))
                    }
                };
            }
            _ => {
                return Err(self
                    .r
                    .err(at, format!("file type {file_type} is neither 0 (ASCII) nor 1 (binary)")))
            }
        }
        self.r.expect("$EndMeshFormat")
    }

    fn physical_names(&mut self) -> Result<()> {
        let n: u64 = self.r.ascii("the number of physical names")?;
        for _ in 0..n {
            let dim: i64 = self.r.ascii("a physical group dimension")?;
            let tag: i64 = self.r.ascii("a physical group tag")?;
            self.r.skip_ws();
            let at = self.r.pos;
            let rest = &self.r.buf[at..];
            let name = (rest.first() == Some(&b'"'))
                .then(|| rest[1..].iter().position(|&c| c == b'"' || c == b'\n'))
                .flatten()
                .filter(|&i| rest[1 + i] == b'"')
                .ok_or_else(|| self.r.err(at, "expected a physical name in double quotes"))?;
            if !(0..=3).contains(&dim) {
                return Err(self.r.err(at, format!("physical group dimension {dim} is not 0 to 3")));
            }
            self.names.insert((dim, tag), String::from_utf8_lossy(&rest[1..1 + name]).into_owned());
            self.r.pos += name + 2;
        }
        Ok(())
    }

    fn entities(&mut self) -> Result<()> {
        let mut counts = [0u64; 4];
        for (d, c) in counts.iter_mut().enumerate() {
            *c = self.r.size(
                [
                    "the number of points",
                    "the number of curves",
                    "the number of surfaces",
                    "the number of volumes",
                ][d],
            )?;
        }
        for (dim, &count) in counts.iter().enumerate() {
            for _ in 0..count {
                let tag = self.r.int("an entity tag")?;
                // A point has its coordinates, the others a bounding box.
                for _ in 0..if dim == 0 { 3 } else { 6 } {
                    self.r.real("an entity coordinate")?;
                }
                let n = self.r.size("the number of physical tags")?;
                let mut phys = Vec::with_capacity(self.r.cap(n, 2));
                for _ in 0..n {
                    phys.push(self.r.int("a physical tag")?);
                }
                if dim > 0 {
                    let n = self.r.size("the number of bounding entities")?;
                    for _ in 0..n {
                        self.r.int("a bounding entity tag")?;
                    }
                }
                self.entity_groups.insert((dim as i64, tag), phys);
            }
        }
        Ok(())
    }

    fn add_node(&mut self, at: usize, tag: u64, x: f64, y: f64) -> Result<()> {
        if self.node_index.insert(tag, self.nodes.len()).is_some() {
            return Err(self.r.err(at, format!("node tag {tag} is defined twice")));
        }
        self.nodes.push([x, y]);
        self.node_tags.push(tag);
        Ok(())
    }

    fn nodes_41(&mut self) -> Result<()> {
        let at = self.r.pos;
        let n_blocks = self.r.size("the number of node blocks")?;
        let n_nodes = self.r.size("the number of nodes")?;
        self.r.size("the smallest node tag")?;
        self.r.size("the largest node tag")?;
        let cap = self.r.cap(n_nodes, 8);
        self.nodes.reserve(cap);
        self.node_tags.reserve(cap);
        let mut read = 0u64;
        for _ in 0..n_blocks {
            let dim_at = self.r.pos;
            let dim = self.r.int("the entity dimension")?;
            self.r.int("the entity tag")?;
            let parametric = self.r.int("the parametric flag")?;
            if !(0..=3).contains(&dim) || !(0..=1).contains(&parametric) {
                return Err(self.r.err(
                    dim_at,
                    format!("bad node block header: dimension {dim}, parametric flag {parametric}"),
                ));
            }
            let n = self.r.size("the number of nodes in the block")?;
            let mut tags = Vec::with_capacity(self.r.cap(n, 8));
            for _ in 0..n {
                tags.push((self.r.pos, self.r.size("a node tag")?));
            }
            for (at, tag) in tags {
                let x = self.r.real("x")?;
                let y = self.r.real("y")?;
                self.r.real("z")?;
                // Parametric coordinates (u, v, w as far as the entity's dimension) follow.
                for _ in 0..parametric * dim {
                    self.r.real("a parametric coordinate")?;
                }
                self.add_node(at, tag, x, y)?;
            }
            read = read.saturating_add(n);
        }
        if read != n_nodes {
            return Err(self
                .r
                .err(at, format!("the header announces {n_nodes} nodes but the blocks hold {read}")));
        }
        Ok(())
    }

    /// MSH 2 `$Nodes`, or `$ParametricNodes` whose nodes are followed by the entity dimension
    /// and tag and then u (curves) or u, v (surfaces).
    fn nodes_22(&mut self, parametric: bool) -> Result<()> {
        let n: u64 = self.r.ascii("the number of nodes")?;
        let cap = self.r.cap(n, 8);
        self.nodes.reserve(cap);
        self.node_tags.reserve(cap);
        if self.r.binary {
            self.r.end_line()?;
        }
        for _ in 0..n {
            let at = self.r.pos;
            let tag = if self.r.binary {
                let tag = self.r.bin_i32("a node tag")?;
                u64::try_from(tag).map_err(|_| self.r.err(at, format!("negative node tag {tag}")))?
            } else {
                self.r.ascii("a node tag")?
            };
            let (x, y) = (self.r.real("x")?, self.r.real("y")?);
            self.r.real("z")?;
            if parametric {
                let dim = self.r.int("the entity dimension")?;
                self.r.int("the entity tag")?;
                for _ in 0..if (1..=2).contains(&dim) { dim } else { 0 } {
                    self.r.real("a parametric coordinate")?;
                }
            }
            self.add_node(at, tag, x, y)?;
        }
        Ok(())
    }

    fn shape(&self, at: usize, t: i64) -> Result<Shape> {
        Shape::from_gmsh(t).ok_or_else(|| {
            self.r.err(at, format!("Gmsh element type {t} is not supported; supported types: {SUPPORTED}"))
        })
    }

    fn node(&self, at: usize, tag: u64) -> Result<usize> {
        self.node_index.get(&tag).copied().ok_or_else(|| {
            self.r.err(at, format!("node tag {tag} is used by an element but not defined in $Nodes"))
        })
    }

    fn elements_41(&mut self) -> Result<()> {
        let at = self.r.pos;
        let n_blocks = self.r.size("the number of element blocks")?;
        let n_elems = self.r.size("the number of elements")?;
        self.r.size("the smallest element tag")?;
        self.r.size("the largest element tag")?;
        let mut read = 0u64;
        let mut nodes = Vec::with_capacity(9);
        for _ in 0..n_blocks {
            let block_at = self.r.pos;
            let dim = self.r.int("the entity dimension")?;
            let entity = self.r.int("the entity tag")?;
            let type_at = self.r.pos;
            let t = self.r.int("the element type")?;
            let shape = self.shape(type_at, t)?;
            if shape.dim() != dim {
                return Err(self.r.err(
                    block_at,
                    format!(
                        "element type {t} is {}D but its block is on an entity of dimension {dim}",
                        shape.dim()
                    ),
                ));
            }
            let groups = self.entity_groups.get(&(dim, entity)).cloned().unwrap_or_default();
            let n = self.r.size("the number of elements in the block")?;
            for _ in 0..n {
                let at = self.r.pos;
                let tag = self.r.size("an element tag")?;
                nodes.clear();
                for _ in 0..shape.n_nodes() {
                    let at = self.r.pos;
                    let t = self.r.size("a node tag")?;
                    nodes.push(self.node(at, t)?);
                }
                self.add_element(at, shape, tag, &nodes, &groups);
            }
            read = read.saturating_add(n);
        }
        if read != n_elems {
            return Err(self
                .r
                .err(at, format!("the header announces {n_elems} elements but the blocks hold {read}")));
        }
        Ok(())
    }

    fn elements_22(&mut self) -> Result<()> {
        let n: u64 = self.r.ascii("the number of elements")?;
        let mut nodes = Vec::with_capacity(9);
        let mut tags = Vec::new();
        if !self.r.binary {
            for _ in 0..n {
                let at = self.r.pos;
                let tag = self.r.ascii("an element tag")?;
                let type_at = self.r.pos;
                let t = self.r.ascii("the element type")?;
                let shape = self.shape(type_at, t)?;
                let n_tags: u64 = self.r.ascii("the number of tags")?;
                tags.clear();
                for _ in 0..n_tags {
                    tags.push(self.r.ascii::<i64>("a physical or entity tag")?);
                }
                nodes.clear();
                for _ in 0..shape.n_nodes() {
                    let at = self.r.pos;
                    let t = self.r.ascii("a node tag")?;
                    nodes.push(self.node(at, t)?);
                }
                self.add_element_22(at, shape, tag, &nodes, &tags);
            }
            return Ok(());
        }
        // Binary: blocks of (type, count, number of tags) headers, each followed by all-int records.
        self.r.end_line()?;
        let mut read = 0u64;
        while read < n {
            let type_at = self.r.pos;
            let t = self.r.bin_i32("the element type")?;
            let shape = self.shape(type_at, t)?;
            let count_at = self.r.pos;
            let count = self.r.bin_i32("the number of elements in the block")?;
            let n_tags = self.r.bin_i32("the number of tags")?;
            if count < 0 || n_tags < 0 || read + count as u64 > n {
                return Err(self.r.err(count_at, format!("bad element block: {count} elements with {n_tags} tags each ({read} of {n} read so far)")));
            }
            for _ in 0..count {
                let at = self.r.pos;
                let tag = self.r.bin_i32("an element tag")?;
                tags.clear();
                for _ in 0..n_tags {
                    tags.push(self.r.bin_i32("a physical or entity tag")?);
                }
                nodes.clear();
                for _ in 0..shape.n_nodes() {
                    let at = self.r.pos;
                    let t = self.r.bin_i32("a node tag")?;
                    nodes.push(self.node(at, t as u64)?);
                }
                let tag =
                    u64::try_from(tag).map_err(|_| self.r.err(at, format!("negative element tag {tag}")))?;
                self.add_element_22(at, shape, tag, &nodes, &tags);
            }
            read += count as u64;
        }
        Ok(())
    }

    /// MSH 2.2: the first tag is the physical group (0 = none).
    fn add_element_22(&mut self, at: usize, shape: Shape, tag: u64, nodes: &[usize], tags: &[i64]) {
        let groups: &[i64] = match tags.first() {
            Some(&p) if p != 0 => &tags[..1],
            _ => &[],
        };
        self.add_element(at, shape, tag, nodes, groups)
    }

    /// Records a 2D element (once) and the sets the element adds to; `at` locates it for messages.
    fn add_element(&mut self, at: usize, shape: Shape, tag: u64, nodes: &[usize], groups: &[i64]) {
        let dim = shape.dim();
        match shape {
            Shape::Surface(kind) => {
                // MSH 2.2 repeats an element, under a new tag, once per physical group it belongs
                // to: the same kind and nodes mean the same element.
                let mut key = [usize::MAX; 9];
                key[..nodes.len()].copy_from_slice(nodes);
                let e = *self.elem_index.entry((kind, key)).or_insert(self.kinds.len());
                if e == self.kinds.len() {
                    self.kinds.push(kind);
                    self.conn.extend_from_slice(&key);
                    self.elem_tags.push(tag);
                }
                for &g in groups {
                    self.element_groups.entry((dim, g)).or_default().push(e);
                }
            }
            Shape::Line { .. } => {
                let edge = [nodes[0], nodes[1], nodes.get(2).copied().unwrap_or(usize::MAX)];
                for &g in groups {
                    self.edge_groups.entry((dim, g)).or_default().push((edge, at));
                }
            }
            Shape::Point => {
                for &g in groups {
                    self.node_groups.entry((dim, g)).or_default().push((nodes[0], at));
                }
            }
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
