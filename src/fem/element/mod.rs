//! Element kinds: node counts, reference shapes, edges and file-format codes in one place,
//! plus the element kernels (stiffness, loads) in the submodules.
//!
//! Local node numbering follows Gmsh and VTK (identical for these kinds):
//!
//! ```text
//!  QUA4/QUA8/QUA9          TRI3/TRI6
//!  3---6---2               2
//!  |       |               | \
//!  7   8   5               5   4
//!  |       |               |     \
//!  0---4---1               0---3---1
//! ```

pub mod qua4;
pub mod quadrature;
pub mod shape;
pub mod stiffness;

/// The geometric element shapes tribofe reads and solves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum ElementKind {
    Tri3,
    Tri6,
    Qua4,
    Qua8,
    Qua9,
}

impl ElementKind {
    pub const ALL: [ElementKind; 5] = [Self::Tri3, Self::Tri6, Self::Qua4, Self::Qua8, Self::Qua9];

    pub const fn n_nodes(self) -> usize {
        match self {
            Self::Tri3 => 3,
            Self::Tri6 => 6,
            Self::Qua4 => 4,
            Self::Qua8 => 8,
            Self::Qua9 => 9,
        }
    }

    /// Number of corner (vertex) nodes; they come first in the local numbering.
    pub const fn n_corners(self) -> usize {
        match self {
            Self::Tri3 | Self::Tri6 => 3,
            _ => 4,
        }
    }

    pub const fn is_quad(self) -> bool {
        matches!(self, Self::Qua4 | Self::Qua8 | Self::Qua9)
    }

    /// Polynomial order of the interpolation (1 linear, 2 quadratic).
    pub const fn order(self) -> usize {
        match self {
            Self::Tri3 | Self::Qua4 => 1,
            _ => 2,
        }
    }

    pub const fn name(self) -> &'static str {
        match self {
            Self::Tri3 => "tri3",
            Self::Tri6 => "tri6",
            Self::Qua4 => "qua4",
            Self::Qua8 => "qua8",
            Self::Qua9 => "qua9",
        }
    }

    /// Local nodes of each edge, counter-clockwise: [start, end, mid] (mid only for order 2).
    pub fn edges(self) -> &'static [[usize; 3]] {
        const TRI: [[usize; 3]; 3] = [[0, 1, 3], [1, 2, 4], [2, 0, 5]];
        const QUA: [[usize; 3]; 4] = [[0, 1, 4], [1, 2, 5], [2, 3, 6], [3, 0, 7]];
        if self.is_quad() {
            &QUA
        } else {
            &TRI
        }
    }

    /// Reference coordinates of the local nodes.
    pub fn reference_nodes(self) -> &'static [[f64; 2]] {
        const Q: [[f64; 2]; 9] = [
            [-1.0, -1.0],
            [1.0, -1.0],
            [1.0, 1.0],
            [-1.0, 1.0],
            [0.0, -1.0],
            [1.0, 0.0],
            [0.0, 1.0],
            [-1.0, 0.0],
            [0.0, 0.0],
        ];
        const T: [[f64; 2]; 6] = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.5, 0.0], [0.5, 0.5], [0.0, 0.5]];
        match self {
            Self::Tri3 => &T[..3],
            Self::Tri6 => &T,
            Self::Qua4 => &Q[..4],
            Self::Qua8 => &Q[..8],
            Self::Qua9 => &Q,
        }
    }

    /// Reference coordinates of the centroid.
    pub const fn reference_centroid(self) -> [f64; 2] {
        if self.is_quad() {
            [0.0, 0.0]
        } else {
            [1.0 / 3.0, 1.0 / 3.0]
        }
    }

    /// VTK cell type code.
    pub const fn vtk_type(self) -> u8 {
        match self {
            Self::Tri3 => 5,
            Self::Tri6 => 22,
            Self::Qua4 => 9,
            Self::Qua8 => 23,
            Self::Qua9 => 28,
        }
    }

    /// Gmsh element type code.
    pub const fn gmsh_type(self) -> u32 {
        match self {
            Self::Tri3 => 2,
            Self::Tri6 => 9,
            Self::Qua4 => 3,
            Self::Qua8 => 16,
            Self::Qua9 => 10,
        }
    }

    pub fn from_gmsh_type(t: u32) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.gmsh_type() == t)
    }
}
