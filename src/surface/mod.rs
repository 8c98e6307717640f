//! Layer 3: surfaces. Rational tensor-product Bézier patches in homogeneous coordinates,
//! NURBS surfaces split into them by exact knot insertion, and triangle/polygon meshes.
//! All coordinates are exact rationals, as the model file states them; [`float_eval`] is the one
//! f64 evaluator of a patch, with its rounding bound.

mod curve;
pub mod float_eval;
mod inversion;
mod knots;
mod mesh;
pub(crate) mod normal;
mod nurbs;
mod patch;

pub use curve::{ModelCurve, NurbsCurve, ParameterCurve, RationalCurve};
pub use float_eval::{eval_f64, DrawPatch, Evaluator};
pub use inversion::{Inversion, InversionError, Inverter};
pub(crate) use knots::de_boor_f64;
pub use mesh::Mesh;
pub use nurbs::{FloatNurbs, NurbsError, NurbsSurface};
pub use patch::{Edge, PatchError, Point3, RationalPatch, MAX_PATCH_DEGREE};
