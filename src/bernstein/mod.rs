//! Layer 2: Bernstein polynomials, tensor-product in 1 to 6 variables, generic over the
//! number layer.
//!
//! A polynomial of degrees (d_0, ..., d_{k-1}) on the unit box `[0,1]^k` is
//! `p(x) = Σ_I c_I Π_a B_{d_a, I_a}(x_a)` with `B_{d,i}(t) = C(d,i) t^i (1-t)^(d-i)`.
//! The coefficients are stored row-major: the last variable varies fastest.
//!
//! Operations are written once for every [`Number`](crate::number::Number): run on
//! [`Interval`](crate::number::Interval) or [`MpInterval`](crate::number::MpInterval) they
//! enclose the exact result (`proofs/de-casteljau-enclosure.md`); on exact rationals they are
//! exact; on `f64` they are rounded. Exact polynomials (`Bernstein<Rational>`) are the source
//! from which every other precision is derived with [`Bernstein::convert`].

mod arith;
mod bounds;
mod compose;
mod deriv;
mod elevate;
mod eval;
mod poly;
mod power;
mod reduce;
mod subdivide;

pub use compose::{compose_curve, compose_curve_f64, compose_homogeneous, residual_hull};
pub use poly::{fix_var, lift, Bernstein, BernsteinError, MAX_VARS};
pub use power::antisymmetric_quotient;

/// An exact polynomial in Bernstein form: the input every analysis derives its polynomials from
/// (every other precision is computed from it).
pub type Poly = Bernstein<crate::number::Rational>;

#[cfg(test)]
mod tests;
