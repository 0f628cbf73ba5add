//! Structured meshes of a rectangle [x0, x1] x [y0, y1], optionally graded geometrically
//! towards both ends of each direction. Named edge sets `bottom`, `right`, `top`, `left` and
//! the element set `all` come with the mesh.

use crate::error::{Error, Result};
use crate::fem::element::ElementKind;
use crate::fem::mesh::{Edge, Mesh};

/// Geometric grading symmetric about the centre: elements of size `end` at both ends,
/// growing by `ratio` per element towards the middle, capped at `max` if given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grading {
    pub end: f64,
    pub ratio: f64,
    pub max: Option<f64>,
}

/// Element sizes along one direction of length `len`: uniform with `n` elements, or graded.
pub fn spacing(len: f64, n: usize, grading: Option<Grading>) -> Result<Vec<f64>> {
    if !(len.is_finite() && len > 0.0) {
        return Err(Error::input("rectangle", format!("side length {len} m must be positive")));
    }
    let Some(g) = grading else {
        if n == 0 {
            return Err(Error::input("mesh", "need at least one element per direction"));
        }
        return Ok(vec![len / n as f64; n]);
    };
    if !(g.end > 0.0 && g.end <= len / 2.0 && g.ratio >= 1.0 && g.ratio.is_finite()) {
        return Err(Error::input(
            "grading",
            format!("end size {} m must be in (0, {}] and ratio {} >= 1", g.end, len / 2.0, g.ratio),
        ));
    }
    let cap = g.max.unwrap_or(f64::INFINITY).max(g.end);
    // Grow from one end until half the length is covered, then scale to fit exactly.
    let mut half = Vec::new();
    let (mut h, mut sum) = (g.end, 0.0);
    while sum + 0.5 * h < len / 2.0 {
        half.push(h);
        sum += h;
        h = (h * g.ratio).min(cap);
        if half.len() > 10_000_000 {
            return Err(Error::input("grading", "more than 1e7 elements; increase the end size"));
        }
    }
    let scale = (len / 2.0) / sum;
    let mut sizes: Vec<f64> = half.iter().map(|h| h * scale).collect();
    sizes.extend(half.iter().rev().map(|h| h * scale));
    Ok(sizes)
}

/// A rectangle to mesh with `kind` elements (TRI* split each cell along its rising diagonal).
#[derive(Debug, Clone)]
pub struct Rectangle {
    pub x0: f64,
    pub x1: f64,
    pub y0: f64,
    pub y1: f64,
    pub nx: usize,
    pub ny: usize,
    pub grading_x: Option<Grading>,
    pub grading_y: Option<Grading>,
    pub kind: ElementKind,
}

impl Rectangle {
    pub fn new(x0: f64, x1: f64, y0: f64, y1: f64, nx: usize, ny: usize) -> Self {
        Self { x0, x1, y0, y1, nx, ny, grading_x: None, grading_y: None, kind: ElementKind::Qua4 }
    }
    pub fn kind(mut self, kind: ElementKind) -> Self {
        self.kind = kind;
        self
    }
    pub fn graded_x(mut self, g: Grading) -> Self {
        self.grading_x = Some(g);
        self
    }
    pub fn graded_y(mut self, g: Grading) -> Self {
        self.grading_y = Some(g);
        self
    }

    pub fn build(&self) -> Result<Mesh> {
        let hx = spacing(self.x1 - self.x0, self.nx, self.grading_x)?;
        let hy = spacing(self.y1 - self.y0, self.ny, self.grading_y)?;
        let xs = refined_coords(self.x0, &hx, self.kind.order());
        let ys = refined_coords(self.y0, &hy, self.kind.order());
        let (nx, ny, p) = (hx.len(), hy.len(), self.kind.order());
        let (gx, gy) = (xs.len(), ys.len());
        // Grid points are numbered row by row; nodes no element uses (QUA8 centres) are dropped.
        let grid = |i: usize, j: usize| j * gx + i;
        let per_cell = if self.kind.is_quad() { 1 } else { 2 };
        let nn = self.kind.n_nodes();
        let mut conn: Vec<usize> = Vec::with_capacity(nx * ny * per_cell * nn);
        for cj in 0..ny {
            for ci in 0..nx {
                let (i, j) = (ci * p, cj * p);
                let c = [grid(i, j), grid(i + p, j), grid(i + p, j + p), grid(i, j + p)];
                match self.kind {
                    ElementKind::Qua4 => conn.extend_from_slice(&c),
                    ElementKind::Tri3 => conn.extend_from_slice(&[c[0], c[1], c[2], c[0], c[2], c[3]]),
                    ElementKind::Qua8 | ElementKind::Qua9 => {
                        conn.extend_from_slice(&c);
                        conn.extend_from_slice(&[
                            grid(i + 1, j),
                            grid(i + 2, j + 1),
                            grid(i + 1, j + 2),
                            grid(i, j + 1),
                        ]);
                        if self.kind == ElementKind::Qua9 {
                            conn.push(grid(i + 1, j + 1));
                        }
                    }
                    ElementKind::Tri6 => {
                        let m = grid(i + 1, j + 1);
                        conn.extend_from_slice(&[c[0], c[1], c[2], grid(i + 1, j), grid(i + 2, j + 1), m]);
                        conn.extend_from_slice(&[c[0], c[2], c[3], m, grid(i + 1, j + 2), grid(i, j + 1)]);
                    }
                }
            }
        }
        let mut new_index = vec![usize::MAX; gx * gy];
        for &g in &conn {
            new_index[g] = 0; // used
        }
        let mut nodes = Vec::with_capacity(gx * gy);
        for j in 0..gy {
            for i in 0..gx {
                if new_index[grid(i, j)] != usize::MAX {
                    new_index[grid(i, j)] = nodes.len();
                    nodes.push([xs[i], ys[j]]);
                }
            }
        }
        conn.iter_mut().for_each(|g| *g = new_index[*g]);
        let mut mesh = Mesh::with_elements(nodes, self.kind, conn);
        let edge = |a: usize, b: usize, m: usize| Edge {
            ends: [new_index[a], new_index[b]],
            mid: (p == 2).then(|| new_index[m]),
        };
        let bottom =
            (0..nx).map(|c| edge(grid(c * p, 0), grid((c + 1) * p, 0), grid(c * p + 1, 0))).collect();
        let top = (0..nx)
            .map(|c| edge(grid((c + 1) * p, gy - 1), grid(c * p, gy - 1), grid(c * p + 1, gy - 1)))
            .collect();
        let left = (0..ny).map(|c| edge(grid(0, (c + 1) * p), grid(0, c * p), grid(0, c * p + 1))).collect();
        let right = (0..ny)
            .map(|c| edge(grid(gx - 1, c * p), grid(gx - 1, (c + 1) * p), grid(gx - 1, c * p + 1)))
            .collect();
        mesh.edge_sets.insert("bottom".into(), bottom);
        mesh.edge_sets.insert("right".into(), right);
        mesh.edge_sets.insert("top".into(), top);
        mesh.edge_sets.insert("left".into(), left);
        mesh.element_sets.insert("all".into(), (0..mesh.n_elements()).collect());
        Ok(mesh)
    }
}

/// Node coordinates along one direction: element ends, plus mid points for quadratic elements.
fn refined_coords(x0: f64, sizes: &[f64], order: usize) -> Vec<f64> {
    let mut xs = vec![x0];
    let mut x = x0;
    for &h in sizes {
        if order == 2 {
            xs.push(x + 0.5 * h);
        }
        x += h;
        xs.push(x);
    }
    xs
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grading_is_symmetric_and_fits() {
        let s = spacing(0.4, 0, Some(Grading { end: 1e-4, ratio: 1.2, max: Some(5e-3) })).unwrap();
        assert!((s.iter().sum::<f64>() - 0.4).abs() < 1e-12);
        let n = s.len();
        for i in 0..n / 2 {
            assert!((s[i] - s[n - 1 - i]).abs() < 1e-15);
            assert!(s[i + 1] >= s[i] * (1.0 - 1e-12));
        }
        assert!(s[0] < 1.1e-4 && s[n / 2] <= 5e-3 * 1.01);
    }

    #[test]
    fn all_kinds_cover_the_rectangle() {
        for kind in ElementKind::ALL {
            let m = Rectangle::new(-1.0, 2.0, 0.0, 0.5, 6, 2).kind(kind).build().unwrap();
            m.validate().unwrap();
            assert!((m.total_area() - 1.5).abs() < 1e-12, "{kind:?}");
            assert_eq!(m.set_nodes("bottom").unwrap().len(), 6 * kind.order() + 1);
            // every node is used by an element
            let mut used = vec![false; m.n_nodes()];
            m.elements().for_each(|(_, v)| v.iter().for_each(|&n| used[n] = true));
            assert!(used.iter().all(|&u| u), "{kind:?}");
        }
    }
}
