//! Layer 4: the solver. Exact dyadic boxes, the precision ladder, certified root isolation,
//! square systems, and the certified topology of plane curves ([`plane_curve`]) and of curves
//! in n variables ([`space_curve`]); every analysis is built on these.

pub mod certificate;
pub(crate) mod chain;
pub mod checker;
pub mod dyadic;
pub mod plane_curve;
pub mod point_in_face;
pub mod precision;
pub mod space_curve;
pub mod system;
pub mod univariate;

pub use dyadic::{Dyadic, DyadicBox};
pub use plane_curve::{solve_curve, solve_curve_cut, CrossingId, CurveOptions, CurveTopology};
pub use precision::{Escalations, Ladder, Level, Policy, Question};
pub use univariate::{isolate_roots, isolate_roots_in, refine_root, Root, Roots};
