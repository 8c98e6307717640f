//! Layer 4: the solver. Exact dyadic boxes, the precision controller, certified root
//! isolation; every analysis is built on these.

pub mod certificate;
pub(crate) mod chain;
pub mod checker;
pub mod curve2;
pub mod curve_n;
pub mod dyadic;
pub mod lines;
pub mod precision;
pub mod singular;
pub mod star;
pub mod system;
pub mod univariate;

pub use curve2::{solve_curve, solve_curve_cut, CrossingId, CurveOptions, CurveTopology};
pub use dyadic::{Dyadic, DyadicBox};
pub use precision::{Escalations, Ladder, Level, Question};
pub use univariate::{isolate_roots, isolate_roots_in, refine_root, Root, Roots};
