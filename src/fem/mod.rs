//! The finite-element engine, one stage per module in the order data flows:
//! [`mesh`] and [`mesher`] -> [`element`] kernels with [`material`] -> [`assembly`] (pattern,
//! colouring, scatter) -> [`constraints`] (elimination u = T r + G g) -> [`ordering`] ->
//! [`problem`] (the linear pipeline over [`crate::linalg`]) -> [`recovery`] (stresses,
//! reactions). [`loads`] turns edge tractions into nodal forces. Knows nothing of scenes,
//! interface laws or reports.

pub mod assembly;
pub mod constraints;
pub mod element;
pub mod loads;
pub mod material;
pub mod mesh;
pub mod mesh_check;
pub mod mesher;
pub mod ordering;
pub mod problem;
pub mod recovery;
