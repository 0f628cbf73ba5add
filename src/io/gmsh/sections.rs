//! The sections of a Gmsh file, one reader each: $MeshFormat, $PhysicalNames, $Entities,
//! $Nodes and $Elements in the 4.1 and 2.2 layouts.

use super::{Parser, Shape, SUPPORTED};
use crate::error::Result;

impl Parser<'_> {
    pub(super) fn mesh_format(&mut self) -> Result<()> {
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

    pub(super) fn physical_names(&mut self) -> Result<()> {
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

    pub(super) fn entities(&mut self) -> Result<()> {
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

    pub(super) fn add_node(&mut self, at: usize, tag: u64, x: f64, y: f64) -> Result<()> {
        if self.node_index.insert(tag, self.nodes.len()).is_some() {
            return Err(self.r.err(at, format!("node tag {tag} is defined twice")));
        }
        self.nodes.push([x, y]);
        self.node_tags.push(tag);
        Ok(())
    }

    pub(super) fn nodes_41(&mut self) -> Result<()> {
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
    pub(super) fn nodes_22(&mut self, parametric: bool) -> Result<()> {
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

    pub(super) fn shape(&self, at: usize, t: i64) -> Result<Shape> {
        Shape::from_gmsh(t).ok_or_else(|| {
            self.r.err(at, format!("Gmsh element type {t} is not supported; supported types: {SUPPORTED}"))
        })
    }

    pub(super) fn node(&self, at: usize, tag: u64) -> Result<usize> {
        self.node_index.get(&tag).copied().ok_or_else(|| {
            self.r.err(at, format!("node tag {tag} is used by an element but not defined in $Nodes"))
        })
    }

    pub(super) fn elements_41(&mut self) -> Result<()> {
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

    pub(super) fn elements_22(&mut self) -> Result<()> {
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
    pub(super) fn add_element_22(
        &mut self,
        at: usize,
        shape: Shape,
        tag: u64,
        nodes: &[usize],
        tags: &[i64],
    ) {
        let groups: &[i64] = match tags.first() {
            Some(&p) if p != 0 => &tags[..1],
            _ => &[],
        };
        self.add_element(at, shape, tag, nodes, groups)
    }

    /// Records a 2D element (once) and the sets the element adds to; `at` locates it for messages.
    pub(super) fn add_element(&mut self, at: usize, shape: Shape, tag: u64, nodes: &[usize], groups: &[i64]) {
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
}
