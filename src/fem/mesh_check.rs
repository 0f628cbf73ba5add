//! Consistency of a block mesh read from a file (issue 31): one connected piece, no two
//! nodes at the same point (an unmerged seam is a crack the solver would happily open), and
//! each boundary group made of element edges that cover its side. Each of these gave wrong
//! numbers with exit 0 before: a crack at x = 0 doubled tau(0), an interface given as one
//! corner-to-corner line held 2 of the base's nodes.
//!
//! And the block's shape (issue 45): no hanging node (a node on another element's side,
//! the two not joined: a slit the solver opens), no boundary inside the block (a hole: tau(0)
//! ~ 0 instead of 0.409) unless the geometry is declared the file's own, no overlap. All from one
//! hash of the element sides: O(n) in the elements.

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

/// Each element side (corner pair, smaller node first): how many elements have it and the
/// first of them. A side of one element lies on the mesh's boundary, of two inside it.
pub type Sides = HashMap<(usize, usize), (usize, usize)>;

/// The [`Sides`] of `m`, one hash of every element side: O(n).
pub fn sides(m: &Mesh) -> Sides {
    let mut s = Sides::with_capacity(2 * m.n_elements() + 4);
    for (e, [a, b]) in element_sides(m) {
        s.entry(key(a, b)).and_modify(|c| c.0 += 1).or_insert((1, e));
    }
    s
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
                            "the block '{}' has two nodes at the same point: {} and {} (closer than {tol:.1e} m, {COINCIDENT_FRACTION:e} of the shortest element side): an unmerged seam is a crack (inside the block: a slit, a delamination); merge them (Gmsh: Coherence, or one surface instead of two)",
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
pub fn check_group_edges(m: &Mesh, sides: &Sides, group: &str, y: f64, tol: f64) -> Result<()> {
    let edges = m.edges(group)?;
    let mut given = HashSet::new();
    for e in edges {
        let [a, b] = e.ends;
        match sides.get(&key(a, b)).map(|c| c.0) {
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
    for (&(a, b), &(c, _)) in sides {
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

/// Fraction of a side's length within which a node lies on it (hangs). Only the mesh's
/// boundary sides inside the block are searched, never those of a conforming mesh: generous,
/// for coordinates written with few digits.
pub const ON_SIDE_FRACTION: f64 = 1e-3;

/// The first node, in the order of `inner` (sides as (element, a, b)), lying on one of these
/// sides without being one of its ends: (node, element, a, b). Only the ends of these sides
/// can hang (a hanging node's own sides are boundary sides inside the block too), binned in
/// cells of the sides' mean length: O(n) for any grading.
fn hanging(m: &Mesh, inner: &[(usize, usize, usize)]) -> Option<(usize, usize, usize, usize)> {
    let len = |a: usize, b: usize| {
        let (p, q) = (m.nodes[a], m.nodes[b]);
        (q[0] - p[0]).hypot(q[1] - p[1])
    };
    let c = inner.iter().map(|&(_, a, b)| len(a, b)).sum::<f64>() / inner.len().max(1) as f64;
    if !(c > 0.0 && c.is_finite()) {
        return None; // degenerate elements are refused by Mesh::validate
    }
    let cell = |p: [f64; 2]| ((p[0] / c).floor() as i64, (p[1] / c).floor() as i64);
    let mut grid: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
    let mut binned = HashSet::new();
    for &(_, a, b) in inner {
        for n in [a, b] {
            if binned.insert(n) {
                grid.entry(cell(m.nodes[n])).or_default().push(n);
            }
        }
    }
    for &(e, a, b) in inner {
        let (p, q, l) = (m.nodes[a], m.nodes[b], len(a, b));
        let d = [q[0] - p[0], q[1] - p[1]];
        let tol = (ON_SIDE_FRACTION * l).min(c / 4.0);
        // Samples at most c/2 apart: a point within tol of the side is in a cell next to one's.
        let steps = (2.0 * l / c).ceil().max(1.0) as usize;
        for k in 0..=steps {
            let s = k as f64 / steps as f64;
            let (cx, cy) = cell([p[0] + s * d[0], p[1] + s * d[1]]);
            for dx in -1..=1 {
                for dy in -1..=1 {
                    for &n in grid.get(&(cx + dx, cy + dy)).map_or(&[][..], |v| v.as_slice()) {
                        let r = [m.nodes[n][0] - p[0], m.nodes[n][1] - p[1]];
                        let along = (r[0] * d[0] + r[1] * d[1]) / l;
                        let off = (r[0] * d[1] - r[1] * d[0]).abs() / l;
                        if n != a && n != b && off <= tol && along > -tol && along < l + tol {
                            return Some((n, e, a, b));
                        }
                    }
                }
            }
        }
    }
    None
}

/// The block's shape against the rectangle x in [x_min, x_max] (its nodes' extent), y in
/// [0, t], its sides within `tol`. Refuses always: a side of three elements (an overlap), a
/// node on another element's side (hanging: the two are not joined), elements covering more
/// than the rectangle, a boundary inside the block enclosing no area (a slit). Refuses unless
/// `file_shape`: a boundary inside the block enclosing area, or less area than the rectangle
/// (a hole or notch). Run after [`check_coincident`]: a slit whose faces have their nodes at
/// the same points is refused there.
pub fn check_shape(m: &Mesh, sides: &Sides, block: &str, t: f64, tol: f64, file_shape: bool) -> Result<()> {
    let node = |n: usize| at(m, n);
    let (x0, x1) =
        m.nodes.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| (a.min(p[0]), b.max(p[0])));
    let on = |u: f64, v: f64| (u - v).abs() <= tol;
    let outer = |a: [f64; 2], b: [f64; 2]| {
        (on(a[0], x0) && on(b[0], x0))
            || (on(a[0], x1) && on(b[0], x1))
            || (on(a[1], 0.0) && on(b[1], 0.0))
            || (on(a[1], t) && on(b[1], t))
    };
    let mut inner = Vec::new();
    let mut overlap: Option<(usize, usize, usize, usize)> = None;
    for (&(a, b), &(count, e)) in sides {
        if count > 2 && overlap.is_none_or(|o| e < o.0) {
            overlap = Some((e, count, a, b));
        } else if count == 1 && !outer(m.nodes[a], m.nodes[b]) {
            inner.push((e, a, b));
        }
    }
    if let Some((e, count, a, b)) = overlap {
        return Err(Error::Mesh(format!(
            "the block '{}' has elements that overlap: the side from {} to {} belongs to {count} elements, {} among them, where a side is shared by two at most; mesh the block as one surface",
            quote(block),
            node(a),
            node(b),
            m.describe_element(e)
        )));
    }
    inner.sort_unstable(); // the first in element order, whatever the hash's order
    if let Some((n, e, a, b)) = hanging(m, &inner) {
        return Err(Error::Mesh(format!(
            "the block '{}' is not conforming: {} lies on the side from {} to {} of {} without being one of its nodes (a hanging node: the elements either side are not joined there, a slit the solver would open); mesh the block so that neighbouring elements share whole sides (Gmsh: one surface, matching transfinite counts, Coherence)",
            quote(block),
            node(n),
            node(a),
            node(b),
            m.describe_element(e)
        )));
    }
    let full = (x1 - x0) * t;
    let area = m.total_area();
    // The sides may lie tol off (as the extent check accepts), plus the sum's round-off.
    let area_tol = 2.0 * (x1 - x0 + t) * tol + 1e-9 * full;
    if area > full + area_tol {
        return Err(Error::Mesh(format!(
            "the block '{}' has elements that overlap: they cover {area:.6e} m^2, more than its rectangle L x t = {full:.6e} m^2; mesh the block as one surface",
            quote(block)
        )));
    }
    let missing = full - area;
    if inner.is_empty() && missing <= area_tol {
        return Ok(());
    }
    let place = inner.first().map_or(String::new(), |&(e, a, b)| {
        format!(
            ": the side from {} to {} of {} lies inside the block, on none of its four sides",
            node(a),
            node(b),
            m.describe_element(e)
        )
    });
    if missing <= area_tol {
        return Err(Error::Mesh(format!(
            "the block '{}' has a boundary inside it that encloses no area measurable against L t (less than {area_tol:.1e} m^2), a slit (crack, delamination) or a hole too small to tell from one{place}; a slit opens under load and the code models none: mesh the block as one conforming surface",
            quote(block)
        )));
    }
    if file_shape {
        return Ok(());
    }
    Err(Error::Mesh(format!(
        "the block '{}' is not the scene's L x t rectangle: its elements cover {area:.6e} m^2, {:.4} % less than L t = {full:.6e} m^2, a hole or notch{place}; if this geometry is intended, give --geometry file (scene key [mesh] geometry = \"file\"): the results are then those of the mesh, which the paper's model does not describe",
        quote(block),
        100.0 * missing / full
    )))
}

/// All of the above for a block read from a file, with its interface (y = 0) and top (y = t)
/// groups; `file_shape` accepts holes and notches ([`check_shape`]).
pub fn check_block(
    m: &Mesh,
    block: &str,
    interface: &str,
    top: &str,
    t: f64,
    file_shape: bool,
) -> Result<()> {
    check_connected(m, block)?;
    check_coincident(m, block)?;
    let tol = 1e-6 * t;
    let sides = sides(m);
    check_shape(m, &sides, block, t, tol, file_shape)?;
    check_group_edges(m, &sides, interface, 0.0, tol)?;
    check_group_edges(m, &sides, top, t, tol)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::element::ElementKind;

    /// The nx x ny unit-square QUA4 grid on [0, nx] x [0, ny], node (i, j) = j (nx + 1) + i,
    /// without the elements `skip` names.
    fn grid(nx: usize, ny: usize, skip: &[(usize, usize)]) -> Mesh {
        let nodes = (0..=ny).flat_map(|j| (0..=nx).map(move |i| [i as f64, j as f64])).collect();
        let mut m = Mesh::new(nodes);
        let n = |i: usize, j: usize| j * (nx + 1) + i;
        for j in 0..ny {
            for i in (0..nx).filter(|&i| !skip.contains(&(i, j))) {
                m.push_element(ElementKind::Qua4, &[n(i, j), n(i + 1, j), n(i + 1, j + 1), n(i, j + 1)]);
            }
        }
        m
    }

    fn shape(m: &Mesh, file_shape: bool) -> Result<()> {
        let t = m.nodes.iter().fold(0.0f64, |a, p| a.max(p[1]));
        check_shape(m, &sides(m), "block", t, 1e-6 * t, file_shape)
    }

    #[test]
    fn sides_count_each_element_side_once_per_element() {
        let m = grid(2, 1, &[]);
        let s = sides(&m);
        assert_eq!(s.len(), 7);
        assert_eq!(s[&(1, 4)], (2, 0), "the shared side, first met in element 0");
        assert_eq!(s.values().filter(|c| c.0 == 1).count(), 6);
        shape(&m, false).unwrap();
    }

    #[test]
    fn a_hole_is_refused_unless_the_shape_is_the_files() {
        let m = grid(3, 3, &[(1, 1)]);
        let e = shape(&m, false).unwrap_err().to_string();
        for s in
            ["8.000000e0 m^2", "11.1111 % less", "9.000000e0 m^2", "lies inside the block", "--geometry file"]
        {
            assert!(e.contains(s), "{s}: {e}");
        }
        shape(&m, true).unwrap();
        // A notch from the top is a boundary inside the rectangle too.
        assert!(shape(&grid(3, 3, &[(1, 2)]), false).unwrap_err().to_string().contains("a hole or notch"));
    }

    #[test]
    fn a_hanging_node_is_refused_naming_it() {
        // Two unit squares left of x = 1, one 1 x 2 element right of it: node 3 at (1, 1) hangs.
        let nodes = vec![
            [0.0, 0.0],
            [1.0, 0.0],
            [0.0, 1.0],
            [1.0, 1.0],
            [0.0, 2.0],
            [1.0, 2.0],
            [2.0, 0.0],
            [2.0, 2.0],
        ];
        let mut m = Mesh::new(nodes);
        m.push_element(ElementKind::Qua4, &[0, 1, 3, 2]);
        m.push_element(ElementKind::Qua4, &[2, 3, 5, 4]);
        m.push_element(ElementKind::Qua4, &[1, 6, 7, 5]);
        for file_shape in [false, true] {
            let e = shape(&m, file_shape).unwrap_err().to_string();
            assert!(
                e.contains("not conforming") && e.contains("node 4 at (1.000000e0, 1.000000e0) m"),
                "{e}"
            );
            assert!(e.contains("element 3 (qua4, nodes 2, 7, 8, 6)"), "{e}");
        }
    }

    #[test]
    fn a_slit_is_refused_whatever_the_shape() {
        // A 2 x 2 grid cut along y = 1 between x = 0.5 and 1.5 with matching faces: the upper
        // face's middle node 9 copies node 4 (1, 1). check_coincident names the pair first;
        // check_shape alone still refuses it.
        let mut m = grid(4, 2, &[]);
        m.nodes.iter_mut().for_each(|p| p[0] /= 2.0);
        m.nodes.push([1.0, 1.0]);
        let copy = m.nodes.len() - 1;
        for e in 4..8 {
            m.element_nodes_mut(e).iter_mut().filter(|n| **n == 7).for_each(|n| *n = copy);
        }
        let e = check_coincident(&m, "block").unwrap_err().to_string();
        assert!(e.contains("two nodes at the same point") && e.contains("slit"), "{e}");
        for file_shape in [false, true] {
            let e = shape(&m, file_shape).unwrap_err().to_string();
            assert!(e.contains("(1.000000e0, 1.000000e0) m"), "{e}");
        }
    }

    #[test]
    fn overlapping_elements_are_refused_whatever_the_shape() {
        let mut m = grid(2, 1, &[]);
        m.push_element(ElementKind::Qua4, &[1, 2, 5, 4]); // element 1 again
        for file_shape in [false, true] {
            let e = shape(&m, file_shape).unwrap_err().to_string();
            assert!(e.contains("overlap"), "{e}");
        }
    }
}
