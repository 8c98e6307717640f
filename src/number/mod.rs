//! Layer 1: numbers.
//!
//! Every algorithm in limn is written once against [`Number`] and runs on:
//!
//! | type | what it is | [`Exactness`] |
//! |---|---|---|
//! | `f64` | IEEE double, round to nearest | `Approximate` |
//! | [`Interval`] | `f64` interval, outward rounded | `Enclosure` |
//! | [`MpFloat`] | MPFR float at a chosen precision, round to nearest | `Approximate` |
//! | [`MpInterval`] | MPFR interval at a chosen precision, outward rounded | `Enclosure` |
//! | [`Rational`] (`rug::Rational`) | exact rational | `Exact` |
//! | [`BigRational`] (`num-rational`) | exact rational, for the independent checker | `Exact` |
//!
//! Model input is exact ([`Rational`]); every other representation is derived from it with
//! [`Number::from_rational`], so escalating precision recomputes from the exact input.
//!
//! Signs are three-valued plus unknown ([`Sign`]). For `Enclosure` and `Exact` types the sign
//! is a proof (see `proofs/outward-rounding.md`); for `Approximate` types it is the sign of the
//! computed value and proves nothing. Code that certifies must require [`Certified`].

mod bigrational;
mod float;
mod interval;
pub mod margin;
mod mpfr_float;
mod mpfr_interval;
mod parse;
mod rational;
mod sign;

pub use bigrational::to_big_rational;
pub use interval::Interval;
pub use mpfr_float::MpFloat;
pub use mpfr_interval::MpInterval;
pub use num_rational::BigRational;
pub use parse::{parse_exact, ParseNumberError};
pub use rug::Rational;
pub use sign::Sign;

use std::fmt::Debug;

/// How a number type relates to the exact value it stands for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Exactness {
    /// A rounded value; its sign is not a proof.
    Approximate,
    /// A set certainly containing the exact value; its sign is a proof when known.
    Enclosure,
    /// The exact value; its sign is always known.
    Exact,
}

/// The precision a value is made at: the number of significand bits for MPFR types.
///
/// Types with a fixed precision (`f64`, [`Interval`], the rationals) ignore it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Precision(pub u32);

impl Precision {
    /// The precision of an IEEE double (53 bits).
    pub const F64: Precision = Precision(53);
}

/// The ring operations every limn algorithm is written against.
///
/// Operations take `&self` (MPFR values are not `Copy`) and keep the precision of their
/// operands (the larger one for MPFR types). The contract of each operation depends on
/// [`Self::EXACTNESS`]:
/// - `Exact`: the result is the exact value.
/// - `Enclosure`: if the operands contain the exact values x and y, the result contains
///   x ∘ y (`proofs/outward-rounding.md`).
/// - `Approximate`: the result is x ∘ y rounded once, to nearest.
pub trait Number: Clone + Debug + Send + Sync + 'static {
    /// How the values relate to the exact numbers they stand for.
    const EXACTNESS: Exactness;

    /// A short name for reports and benches ("f64", "interval", "mpfr", ...).
    const NAME: &'static str;

    /// The value (or the tightest enclosure the type can hold) of an exact rational.
    fn from_rational(q: &Rational, prec: Precision) -> Self;

    /// An integer, exactly when the type can hold it (enclosed otherwise).
    fn from_i64(n: i64, prec: Precision) -> Self;

    /// The precision this value is held at.
    fn precision(&self) -> Precision;

    /// Zero at the precision of `self`.
    fn zero_like(&self) -> Self {
        Self::from_i64(0, self.precision())
    }

    /// `self + rhs`.
    fn add(&self, rhs: &Self) -> Self;
    /// `self - rhs`.
    fn sub(&self, rhs: &Self) -> Self;
    /// `self * rhs`.
    fn mul(&self, rhs: &Self) -> Self;
    /// `-self` (exact in every type).
    fn neg(&self) -> Self;
    /// `(self + rhs) / 2`: the de Casteljau step at t = 1/2.
    fn midpoint(&self, rhs: &Self) -> Self;

    /// `self = self + rhs`; types that allocate override it to reuse storage.
    fn add_assign(&mut self, rhs: &Self) {
        *self = self.add(rhs);
    }

    /// `self = (self + rhs) / 2`; types that allocate override it to reuse storage.
    fn midpoint_assign(&mut self, rhs: &Self) {
        *self = self.midpoint(rhs);
    }

    /// The sign. A proof for `Enclosure` and `Exact` types (`Unknown` when undecided); for
    /// `Approximate` types the sign of the rounded value.
    fn sign(&self) -> Sign;

    /// A lower bound in `f64`, rounded down (for `Approximate` types, the value rounded down).
    fn lower_f64(&self) -> f64;

    /// An upper bound in `f64`, rounded up (for `Approximate` types, the value rounded up).
    fn upper_f64(&self) -> f64;

    /// A representative value in `f64` (the midpoint for enclosures), for display and seeds.
    fn to_f64(&self) -> f64;
}

/// Number types whose [`Number::sign`] is a proof: enclosures and exact types.
///
/// Solvers that certify are bounded by this trait, so that an `f64` run can never be reported
/// as certified.
pub trait Certified: Number {}

impl Certified for Interval {}
impl Certified for MpInterval {}
impl Certified for Rational {}
impl Certified for BigRational {}

/// Converts a slice of exact rationals to another number type.
pub fn convert_all<N: Number>(values: &[Rational], prec: Precision) -> Vec<N> {
    values.iter().map(|q| N::from_rational(q, prec)).collect()
}

#[cfg(test)]
mod tests;
