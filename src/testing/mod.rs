//! Generators for property tests, public so that users' fuzzing can use them.
//!
//! - [`shapes`]: exact rational models with known closed forms (quarter circles with rational
//!   weights, spheres, tori, cylinders, planes), and exact rational rotations.
//! - [`strategies`]: proptest strategies for random and degenerate patches and polynomials.
//! - [`ArbitraryPatch`]: a quickcheck `Arbitrary` wrapper over the same generators.
//! - [`fuzz`]: a mutational fuzzer of the model readers and of the `limn` command line, on the
//!   stable toolchain (`examples/fuzz.rs`, `docs/testing.md`).
//!
//! Enabled by the `testing` feature (on by default).

mod arbitrary;
pub mod fuzz;
pub mod shapes;
pub mod strategies;

pub use arbitrary::ArbitraryPatch;

/// The Newell teapot (32 bicubic patches, the embedded copy of
/// `fixtures/bezier/teapot.bpt`), the model most tests and benches run on.
///
/// # Examples
/// ```
/// let teapot = limn::testing::teapot();
/// assert_eq!(teapot.patches.len(), 32);
/// ```
pub fn teapot() -> crate::model::Model {
    crate::io::read_model_bytes(
        "teapot",
        crate::TEAPOT.as_bytes(),
        Some(crate::model::Format::Bpt),
    )
    .expect("the embedded teapot parses")
}
