#![doc = include_str!("../README.md")]
//!
//! # The library's front door
//!
//! The entry points and their results are re-exported here; each takes a model, a view where
//! the analysis depends on one, and its options, and returns `Result<_, `[`Error`]`>`:
//! [`silhouette`], [`parabolic`] ([`ContourOptions`] → [`Silhouette`]), [`hidden_lines`],
//! [`visible_regions`], [`flecnodal_curves`], [`bitangent_curves`], [`events`], and
//! [`check_silhouette`] for certificates. Models come from [`read_model`] and
//! [`read_model_bytes`].
//!
//! The layers, bottom up (dependencies point downward only):
//! 1. [`number`]: `f64`, intervals, MPFR, exact rationals behind one trait, with three-valued
//!    signs.
//! 2. [`bernstein`]: tensor-product Bernstein polynomials in 1 to 6 variables, generic over
//!    the number layer; [`geometry`]: small shared primitives.
//! 3. [`surface`] and [`model`]: rational Bézier patches, NURBS, meshes, models and their
//!    topology; [`io`] reads model files exactly.
//! 4. [`solver`]: boxes, the precision ladder, root isolation, square systems, plane and
//!    space curves, certificates and their checker.
//! 5. [`analysis`]: one folder per capability.
//! 6. [`report`]: the documents (JSON, text, SVG, OBJ); `cli` (feature `cli`): the `limn`
//!    command.
//!
//! Proofs of the guarantees the code relies on are in `proofs/` in the repository.

#![warn(missing_docs)]

pub mod analysis;
pub mod bernstein;
#[cfg(feature = "cli")]
pub mod cli;
pub mod error;
pub mod geometry;
pub mod io;
pub mod model;
pub mod number;
pub mod reason;
pub mod report;
pub mod solver;
pub mod surface;
#[cfg(feature = "testing")]
pub mod testing;

pub use analysis::bitangent::curves::{bitangent_curves, BitangentCurves, BitangentOptions};
pub use analysis::contour::certificate::{check_silhouette, SilhouetteCertificate};
pub use analysis::contour::curves::{Silhouette, SilhouetteCurve};
pub use analysis::contour::family::ContourOptions;
pub use analysis::contour::parabolic::parabolic;
pub use analysis::contour::silhouette::silhouette;
pub use analysis::events::{events, EventOptions, Events};
pub use analysis::flecnodal::curves::{flecnodal_curves, FlecnodalCurves, FlecnodalOptions};
pub use analysis::view::View;
pub use analysis::visibility::hlr::{hidden_lines, HiddenLines, HlrOptions};
pub use analysis::visibility::visible::{visible_regions, VisibleOptions, VisibleRegions};
pub use error::Error;
pub use io::{read_model, read_model_bytes, write_model};
pub use model::Model;
pub use reason::Reason;

/// The options of [`silhouette`].
pub type SilhouetteOptions = ContourOptions;
/// The options of [`parabolic`].
pub type ParabolicOptions = ContourOptions;

/// The Newell teapot (32 bicubic patches, `.bpt`), embedded so that `limn demo` and the
/// examples need no files.
pub const TEAPOT: &str = include_str!("../fixtures/bezier/teapot.bpt");

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
