//! limn: an exact/adaptive-precision geometry kernel for the certified visibility analysis of
//! free-form surfaces.
//!
//! The layers, bottom up (dependencies point downward only):
//! 1. [`number`]: `f64`, intervals, MPFR, exact rationals behind one trait, with three-valued
//!    signs.
//! 2. [`bernstein`]: tensor-product Bernstein polynomials in 1 to 4 variables, generic over
//!    the number layer.
//! 3. [`surface`] and [`model`]: rational Bézier patches, NURBS, meshes, models and their
//!    topology; [`io`] reads model files exactly.
//! 4. Front end: [`cli`], the `limn` command.
//!
//! Proofs of the guarantees the code relies on are in `proofs/` in the repository.

pub mod analysis;
pub mod bernstein;
pub mod cli;
pub mod io;
pub mod model;
pub mod number;
pub mod solver;
pub mod surface;
#[cfg(feature = "testing")]
pub mod testing;

/// The number of property-test cases: `default` unless `LIMN_PROPTEST_CASES` says otherwise
/// (and 16× more with the `heavy-tests` feature).
#[doc(hidden)]
pub fn testing_cases(default: u32) -> u32 {
    let base = std::env::var("LIMN_PROPTEST_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default);
    if cfg!(feature = "heavy-tests") {
        base * 16
    } else {
        base
    }
}
