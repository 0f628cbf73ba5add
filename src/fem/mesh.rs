//! The mesh: node coordinates, elements of mixed kinds stored flat, and named sets of
//! nodes, edges and elements that boundary conditions and outputs refer to.

use crate::error::{Error, Result};
use crate::fem::element::{shape, ElementKind};
use std::collections::BTreeMap;

/// A boundary edge: its two end nodes and, for quadratic elements, the mid node.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Edge {
    pub ends: [usize; 2],
    pub mid: Option<usize>,
}

impl Edge {
    pub fn nodes(&self) -> impl Iterator<Item = usize> + '_ {
        self.ends.iter().copied().chain(self.mid)
    }
}

#[derive(Debug, Clone, Default)]
pub struct Mesh {
    /// Node coordinates (x, y), m.
    pub nodes: Vec<[f64; 2]>,
    kinds: Vec<ElementKind>,
    offsets: Vec<usize>,
    conn: Vec<usize>,
    pub node_sets: BTreeMap<String, Vec<usize>>,
    pub edge_sets: BTreeMap<String, Vec<Edge>>,
    pub element_sets: BTreeMap<String, Vec<usize>>,
    /// Node and element numbers as the user knows them (e.g. Gmsh tags), for messages.
    pub node_tags: Option<Vec<u64>>,
    pub element_tags: Option<Vec<u64>>,
}

impl Mesh {
    pub fn new(nodes: Vec<[f64; 2]>) -> Self {
        Self { nodes, offsets: vec![0], ..Default::default() }
    }

    /// A mesh of elements of one kind from their flat connectivity (`kind.n_nodes()` node
    /// indices each, checked by [`Mesh::validate`]): no per-element growth of the arrays.
    pub fn with_elements(nodes: Vec<[f64; 2]>, kind: ElementKind, conn: Vec<usize>) -> Self {
        let nn = kind.n_nodes();
        assert_eq!(conn.len() % nn, 0, "connectivity of whole elements");
        let ne = conn.len() / nn;
        Self {
            nodes,
            kinds: vec![kind; ne],
            offsets: (0..=ne).map(|e| e * nn).collect(),
            conn,
            ..Default::default()
        }
    }

    /// Appends an element; returns its index. Node indices are checked by [`Mesh::validate`].
    pub fn push_element(&mut self, kind: ElementKind, nodes: &[usize]) -> usize {
        debug_assert_eq!(nodes.len(), kind.n_nodes());
        self.kinds.push(kind);
        self.conn.extend_from_slice(nodes);
        self.offsets.push(self.conn.len());
        self.kinds.len() - 1
    }

    pub fn n_nodes(&self) -> usize {
        self.nodes.len()
    }
    pub fn n_elements(&self) -> usize {
        self.kinds.len()
    }
    pub fn kind(&self, e: usize) -> ElementKind {
        self.kinds[e]
    }
    pub fn element_nodes(&self, e: usize) -> &[usize] {
        &self.conn[self.offsets[e]..self.offsets[e + 1]]
    }
    pub fn element_nodes_mut(&mut self, e: usize) -> &mut [usize] {
        &mut self.conn[self.offsets[e]..self.offsets[e + 1]]
    }
    pub fn elements(&self) -> impl Iterator<Item = (ElementKind, &[usize])> + '_ {
        (0..self.n_elements()).map(|e| (self.kinds[e], self.element_nodes(e)))
    }
    /// Element kinds present, sorted.
    pub fn kinds_present(&self) -> Vec<ElementKind> {
        let mut k = self.kinds.clone();
        k.sort();
        k.dedup();
        k
    }
    pub fn element_coords(&self, e: usize) -> Vec<[f64; 2]> {
        self.element_nodes(e).iter().map(|&n| self.nodes[n]).collect()
    }

    /// "element 12 (nodes 3, 4, 9, 8)" in the user's numbering when tags are known (1-based otherwise).
    pub fn describe_element(&self, e: usize) -> String {
        let etag = self.element_tags.as_ref().map_or(e as u64 + 1, |t| t[e]);
        let nodes: Vec<String> =
            self.element_nodes(e).iter().map(|&n| self.node_tag(n).to_string()).collect();
        format!("element {etag} ({}, nodes {})", self.kinds[e].name(), nodes.join(", "))
    }
    pub fn node_tag(&self, n: usize) -> u64 {
        self.node_tags.as_ref().map_or(n as u64 + 1, |t| t[n])
    }

    /// Names of all sets, for error messages.
    pub fn set_names(&self) -> Vec<String> {
        let mut v: Vec<String> = self
            .node_sets
            .keys()
            .chain(self.edge_sets.keys())
            .chain(self.element_sets.keys())
            .cloned()
            .collect();
        v.sort();
        v.dedup();
        v
    }

    fn unknown_set(&self, name: &str, what: &str) -> Error {
        Error::Mesh(format!("no {what} set named '{name}'; the mesh has: {}", self.set_names().join(", ")))
    }

    /// Edges of a named edge set.
    pub fn edges(&self, name: &str) -> Result<&[Edge]> {
        self.edge_sets.get(name).map(|v| v.as_slice()).ok_or_else(|| self.unknown_set(name, "edge"))
    }

    /// Elements of a named element set.
    pub fn element_set(&self, name: &str) -> Result<&[usize]> {
        self.element_sets.get(name).map(|v| v.as_slice()).ok_or_else(|| self.unknown_set(name, "element"))
    }

    /// Sorted, unique nodes of a named node set, or of the edges of a named edge set.
    pub fn set_nodes(&self, name: &str) -> Result<Vec<usize>> {
        let mut v: Vec<usize> = if let Some(n) = self.node_sets.get(name) {
            n.clone()
        } else if let Some(edges) = self.edge_sets.get(name) {
            edges.iter().flat_map(|e| e.nodes().collect::<Vec<_>>()).collect()
        } else {
            return Err(self.unknown_set(name, "node or edge"));
        };
        v.sort_unstable();
        v.dedup();
        Ok(v)
    }

    /// Sorted, unique nodes of several named sets together (e.g. all four sides of a rectangle).
    pub fn nodes_of_sets(&self, names: &[&str]) -> Result<Vec<usize>> {
        let mut v = Vec::new();
        for name in names {
            v.extend(self.set_nodes(name)?);
        }
        v.sort_unstable();
        v.dedup();
        Ok(v)
    }

    /// Keeps only the elements of `set` (e.g. the solid block of a mesh that also holds other surfaces).
    pub fn restrict_to(&self, set: &str) -> Result<Mesh> {
        let keep = self.element_set(set)?;
        let mut m = Mesh::new(self.nodes.clone());
        for &e in keep {
            m.push_element(self.kind(e), self.element_nodes(e));
        }
        m.node_sets = self.node_sets.clone();
        m.edge_sets = self.edge_sets.clone();
        m.element_sets.insert(set.to_string(), (0..keep.len()).collect());
        m.node_tags = self.node_tags.clone();
        m.element_tags = self.element_tags.as_ref().map(|t| keep.iter().map(|&e| t[e]).collect());
        Ok(m)
    }

    /// Checks node indices and that every element has a positive Jacobian at its nodes and
    /// centroid (catches inverted, degenerate and badly distorted elements).
    pub fn validate(&self) -> Result<()> {
        if self.n_elements() == 0 {
            return Err(Error::Mesh("the mesh has no elements".into()));
        }
        for e in 0..self.n_elements() {
            if let Some(&n) = self.element_nodes(e).iter().find(|&&n| n >= self.n_nodes()) {
                return Err(Error::Mesh(format!(
                    "{} refers to node index {n}, but there are only {} nodes",
                    self.describe_element(e),
                    self.n_nodes()
                )));
            }
            let min = self.min_jacobian(e);
            if !(min > 0.0) {
                return Err(Error::Mesh(format!(
                    "{} is {} (Jacobian determinant {min:.3e} <= 0 at a node or the centroid)",
                    self.describe_element(e),
                    if min < 0.0 { "inverted or badly distorted" } else { "degenerate" }
                )));
            }
        }
        Ok(())
    }

    /// Smallest Jacobian determinant of an element over its mean one (area / reference area):
    /// 1 for parallelograms and triangles, smaller the more a quad is distorted.
    pub fn jacobian_quality(&self, e: usize) -> f64 {
        let mesh = self;
        let reference_area = if mesh.kind(e).is_quad() { 4.0 } else { 0.5 };
        mesh.min_jacobian(e) / (mesh.signed_area(e) / reference_area)
    }

    /// Moves every interior corner node by a random vector of length <= `amp` (deterministic in
    /// `seed`); quadratic elements get their mid nodes back on straight edges.
    pub fn distort(&mut self, amp: f64, seed: u64) -> Result<()> {
        let mesh = self;
        let (mut xmin, mut xmax, mut ymin, mut ymax) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for p in &mesh.nodes {
            xmin = xmin.min(p[0]);
            xmax = xmax.max(p[0]);
            ymin = ymin.min(p[1]);
            ymax = ymax.max(p[1]);
        }
        let tol = 1e-9 * (xmax - xmin);
        let inside =
            |p: &[f64; 2]| p[0] > xmin + tol && p[0] < xmax - tol && p[1] > ymin + tol && p[1] < ymax - tol;
        let mut corner = vec![false; mesh.n_nodes()];
        for (_, v) in mesh.elements() {
            v[..4.min(v.len())].iter().for_each(|&n| corner[n] = true);
        }
        let mut s = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
        let mut rnd = || {
            s = s.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        for k in 0..mesh.n_nodes() {
            if corner[k] && inside(&mesh.nodes[k]) {
                let (r, a) = (amp * rnd(), std::f64::consts::TAU * rnd());
                mesh.nodes[k][0] += r * a.cos();
                mesh.nodes[k][1] += r * a.sin();
            }
        }
        for e in 0..mesh.n_elements() {
            let v = mesh.element_nodes(e).to_vec();
            if v.len() >= 8 {
                let c: Vec<[f64; 2]> = v[..4].iter().map(|&n| mesh.nodes[n]).collect();
                let mid = |a: [f64; 2], b: [f64; 2]| [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
                for k in 0..4 {
                    mesh.nodes[v[4 + k]] = mid(c[k], c[(k + 1) % 4]);
                }
                if v.len() == 9 {
                    mesh.nodes[v[8]] = mid(mid(c[0], c[2]), mid(c[1], c[3]));
                }
            }
        }
        for e in 0..mesh.n_elements() {
            if !(mesh.min_jacobian(e) > 0.0) {
                return Err(Error::Mesh(format!("distortion {amp} m inverts {}", mesh.describe_element(e))));
            }
        }
        Ok(())
    }

    /// Smallest Jacobian determinant over the element's nodes and centroid.
    pub fn min_jacobian(&self, e: usize) -> f64 {
        let kind = self.kind(e);
        let x = self.element_coords(e);
        let nn = kind.n_nodes();
        let (mut n, mut dn) = ([0.0; 9], [[0.0; 2]; 9]);
        let mut min = f64::INFINITY;
        for &p in kind.reference_nodes().iter().chain(std::iter::once(&kind.reference_centroid())) {
            shape::eval(kind, p, &mut n[..nn], &mut dn[..nn]);
            let mut j = [[0.0; 2]; 2];
            for a in 0..nn {
                for r in 0..2 {
                    for c in 0..2 {
                        j[r][c] += x[a][r] * dn[a][c];
                    }
                }
            }
            min = min.min(j[0][0] * j[1][1] - j[0][1] * j[1][0]);
        }
        min
    }

    /// Reorders nodes of clockwise elements so all are counter-clockwise (signed corner area > 0).
    /// Returns how many elements were flipped.
    pub fn orient_counter_clockwise(&mut self) -> usize {
        let mut flipped = 0;
        for e in 0..self.n_elements() {
            let kind = self.kind(e);
            let nc = kind.n_corners();
            if self.signed_area(e) < 0.0 {
                // Mirror the local numbering: swap corners 1 <-> nc-1 and the matching mid nodes.
                let nodes = self.element_nodes_mut(e);
                nodes.swap(1, nc - 1);
                if kind.order() == 2 {
                    // mids: edge k between corners k, k+1 sits at nc + k; reversing maps edge k -> nc-1-k.
                    nodes[nc..2 * nc].reverse();
                }
                flipped += 1;
            }
        }
        flipped
    }

    /// Signed area of an element's corner polygon (m^2), positive when counter-clockwise; exact
    /// for straight-sided elements.
    pub fn signed_area(&self, e: usize) -> f64 {
        let nodes = self.element_nodes(e);
        let nc = self.kind(e).n_corners();
        0.5 * (0..nc)
            .map(|i| {
                let (a, b) = (self.nodes[nodes[i]], self.nodes[nodes[(i + 1) % nc]]);
                a[0] * b[1] - b[0] * a[1]
            })
            .sum::<f64>()
    }

    /// Total area of the elements (m^2).
    pub fn total_area(&self) -> f64 {
        (0..self.n_elements()).map(|e| self.signed_area(e)).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orientation_fix_and_inverted_detection() {
        let mut m = Mesh::new(vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
        m.push_element(ElementKind::Qua4, &[0, 3, 2, 1]); // clockwise
        assert!(m.validate().is_err());
        assert_eq!(m.orient_counter_clockwise(), 1);
        m.validate().unwrap();
        assert!((m.total_area() - 1.0).abs() < 1e-15);
        let mut bad = Mesh::new(vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]);
        bad.push_element(ElementKind::Tri3, &[0, 1, 2]);
        let msg = bad.validate().unwrap_err().to_string();
        assert!(msg.contains("element 1") && msg.contains("degenerate"), "{msg}");
    }

    #[test]
    fn quadratic_orientation_keeps_mid_nodes_on_their_edges() {
        // TRI6 given clockwise: corners 0, 2, 1 with mids between them.
        let nodes = vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.5, 0.0], [0.5, 0.5], [0.0, 0.5]];
        let mut m = Mesh::new(nodes);
        m.push_element(ElementKind::Tri6, &[0, 2, 1, 5, 4, 3]);
        m.orient_counter_clockwise();
        assert_eq!(m.element_nodes(0), &[0, 1, 2, 3, 4, 5]);
    }
}
