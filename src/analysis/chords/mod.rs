//! Certified drawing: vertices on the solver's arcs such that every drawn segment lies within a
//! tolerance of the true curve, one module per kind of curve.
//!
//! - [`plane_curve`]: curves `g(u, v) = 0` on a patch, traced to a world-space tolerance
//!   (`proofs/chord-accuracy.md`);
//! - [`cubic`]: certified cubic pieces of those curves, and their polylines
//!   (`proofs/cubic-pieces.md`);
//! - [`space_curve`]: curves in `(u, v, s[, t])` lifted onto a patch (`proofs/space-curves.md` §5);
//! - [`sphere_curve`]: curves of directions on the viewing sphere (`proofs/events.md`).

pub mod cubic;
pub mod plane_curve;
pub mod space_curve;
pub mod sphere_curve;
