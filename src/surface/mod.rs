//! Layer 3: surfaces. Rational tensor-product Bézier patches in homogeneous coordinates,
//! NURBS surfaces split into them by exact knot insertion, and triangle/polygon meshes.
//! All coordinates are exact rationals, as the model file states them.

mod mesh;
pub(crate) mod normal;
mod nurbs;
mod patch;

pub use mesh::Mesh;
pub use nurbs::{NurbsError, NurbsSurface};
pub use patch::{Edge, PatchError, Point3, RationalPatch, MAX_PATCH_DEGREE};
