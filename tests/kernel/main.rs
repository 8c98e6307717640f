//! The number, Bernstein, surface and solver layers, and the readers under fuzzing.
//!
//! One test binary per group (each links GMP and MPFR): the modules below were separate
//! binaries before.

mod curve_topology;
mod fuzz;
mod reader_fuzz;
mod separable;
mod space_curve;
mod surface;
mod system;
mod trims;
