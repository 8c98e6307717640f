//! Generators for property tests, public so that users' fuzzing can use them.
//!
//! - [`shapes`]: exact rational models with known closed forms (quarter circles with rational
//!   weights, spheres, tori, cylinders, planes), and exact rational rotations.
//! - [`strategies`]: proptest strategies for random and degenerate patches and polynomials.
//! - [`ArbitraryPatch`]: a quickcheck `Arbitrary` wrapper over the same generators.
//!
//! Enabled by the `testing` feature (on by default).

mod arbitrary;
pub mod shapes;
pub mod strategies;

pub use arbitrary::ArbitraryPatch;
