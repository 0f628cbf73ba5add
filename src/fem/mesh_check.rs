//! Consistency of a block mesh read from a file (issue 31): one connected piece, no two
//! nodes at the same point (an unmerged seam is a crack the solver would happily open), and
//! each boundary group made of element edges that cover its side. Each of these gave wrong
//! numbers with exit 0 before: a crack at x = 0 doubled tau(0), an interface given as one
//! corner-to-corner line held 2 of the base's nodes.

use crate::error::{quote, Error, Result};
use crate::fem::mesh::Mesh;
use std::collections::{HashMap, HashSet};

/// Coincidence tolerance as a fraction of the shortest element edge: far below any element,
/// far above the round-off of coordinates written with ~10 significant digits.
pub const COINCIDENT_FRACTION: f64 = 1e-6;

fn at(m: &Mesh, n: usize) -> String {
    let [x, y] = m.nodes[n];
    format!("node {} at ({x:.6e}, {y:.6e}) m", m.node_tag(n))
}

/// Corner pairs of every element's sides (a quadratic element's mid nodes not included).
fn element_sides(m: &Mesh) -> impl Iterator<Item = (usize, [usize; 2])> + '_ {
    (0..m.n_elements()).flat_map(move |e| {
        let nodes = m.element_nodes(e);
        m.kind(e).edges().iter().map(move |s| (e, [nodes[s[0]], nodes[s[1]]]))
    })
}

fn key(a: usize, b: usize) -> (usize, usize) {
    (a.min(b), a.max(b))
}

/// Shortest element side, m.
fn shortest_side(m: &Mesh) -> f64 {
    element_sides(m)
        .map(|(_, [a, b])| {
            let (p, q) = (m.nodes[a], m.nodes[b]);
            (p[0] - q[0]).hypot(p[1] - q[1])
        })
        .fold(f64::INFINITY, f64::min)
}

/// The elements (all of `m`, the block `block`) form one piece connected through shared nodes.
pub fn check_connected(m: &Mesh, block: &str) -> Result<()> {
    let mut parent: Vec<usize> = (0..m.n_nodes()).collect();
    fn root(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    for e in 0..m.n_elements() {
        let nodes = m.element_nodes(e);
        for &n in &nodes[1..] {
            let (a, b) = (root(&mut parent, nodes[0]), root(&mut parent, n));
            parent[a] = b;
        }
    }
    let first = root(&mut parent, m.element_nodes(0)[0]);
    let mut pieces: HashMap<usize, usize> = HashMap::new();
    for e in 0..m.n_elements() {
        let r = root(&mut parent, m.element_nodes(e)[0]);
        pieces.entry(r).or_insert(e);
    }
    if pieces.len() > 1 {
        let other = pieces.iter().filter(|(r, _)| **r != first).map(|(_, &e)| e).min().unwrap_or(0);
        return Err(Error::Mesh(format!(
            "the block '{}' is {} separate pieces, not one: {} shares no node, directly or through other elements, with {}; merge the duplicate nodes (Gmsh: Coherence) or mesh the block as one surface",
            quote(block),
            pieces.len(),
            m.describe_element(other),
            m.describe_element(0)
        )));
    }
    Ok(())
}

/// No two nodes closer than [`COINCIDENT_FRACTION`] of the shortest element side.
pub fn check_coincident(m: &Mesh, block: &str) -> Result<()> {
    let tol = COINCIDENT_FRACTION * shortest_side(m);
    if !(tol > 0.0 && tol.is_finite()) {
        return Ok(()); // degenerate elements are refused by Mesh::validate
    }
    // Cells of side tol: two nodes within tol lie in the same or adjacent cells.
    let cell = |p: [f64; 2]| ((p[0] / tol).floor() as i64, (p[1] / tol).floor() as i64);
    let mut grid: HashMap<(i64, i64), Vec<usize>> = HashMap::with_capacity(m.n_nodes());
    for (n, p) in m.nodes.iter().enumerate() {
        let (cx, cy) = cell(*p);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for &k in grid.get(&(cx + dx, cy + dy)).map_or(&[][..], |v| v.as_slice()) {
                    let q = m.nodes[k];
                    if (p[0] - q[0]).hypot(p[1] - q[1]) <= tol {
                        return Err(Error::Mesh(format!(
                            "the block '{}' has two nodes at the same point: {} and {} (closer than {tol:.1e} m, {COINCIDENT_FRACTION:e} of the shortest element side): an unmerged seam is a crack; merge them (Gmsh: Coherence, or one surface instead of two)",
                            quote(block),
                            at(m, k),
                            at(m, n)
                        )));
                    }
                }
            }
        }
        grid.entry((cx, cy)).or_default().push(n);
    }
    Ok(())
}

/// Every line of edge group `group` is a side of a block element, and the group holds every
/// element side on the block's boundary at y = `y` (within `tol`): it covers that side edge
/// by edge, as the interface's nodes and their tributary lengths assume.
pub fn check_group_edges(m: &Mesh, group: &str, y: f64, tol: f64) -> Result<()> {
    let mut count: HashMap<(usize, usize), usize> = HashMap::new();
    for (_, [a, b]) in element_sides(m) {
        *count.entry(key(a, b)).or_default() += 1;
    }
    let edges = m.edges(group)?;
    let mut given = HashSet::new();
    for e in edges {
        let [a, b] = e.ends;
        match count.get(&key(a, b)) {
            Some(1) => {}
            Some(_) => {
                return Err(Error::Mesh(format!(
                    "group '{}': the line from {} to {} is a side shared by two elements, inside the block, not on its boundary",
                    quote(group),
                    at(m, a),
                    at(m, b)
                )))
            }
            None => {
                return Err(Error::Mesh(format!(
                    "group '{}': the line from {} to {} is not the side of any block element; each line of the group must be one element side (mesh the line with the block so that they share nodes, e.g. a Physical Line on the surface's boundary curve)",
                    quote(group),
                    at(m, a),
                    at(m, b)
                )))
            }
        }
        given.insert(key(a, b));
    }
    let on_side = |n: usize| (m.nodes[n][1] - y).abs() <= tol;
    for (&(a, b), &c) in &count {
        if c == 1 && on_side(a) && on_side(b) && !given.contains(&(a, b)) {
            return Err(Error::Mesh(format!(
                "group '{}' does not cover the block's side y = {y} m: the element side from {} to {} is missing from it",
                quote(group),
                at(m, a),
                at(m, b)
            )));
        }
    }
    Ok(())
}

/// All of the above for a block read from a file, with its interface (y = 0) and top (y = t)
/// groups.
pub fn check_block(m: &Mesh, block: &str, interface: &str, top: &str, t: f64) -> Result<()> {
    check_connected(m, block)?;
    check_coincident(m, block)?;
    let tol = 1e-6 * t;
    check_group_edges(m, interface, 0.0, tol)?;
    check_group_edges(m, top, t, tol)
}
