//! The analyses through the library: contours, certificates, event curves, visibility.
//!
//! One test binary per group (each links GMP and MPFR): the modules below were separate
//! binaries before.

#[path = "../analytic/mod.rs"]
mod analytic;

mod bitangent_curves;
mod certificate;
mod cubics;
mod events;
mod flecnodal;
mod flecnodal_curves;
mod hlr;
mod invariance;
mod parabolic;
mod silhouette;
mod trim_models;
mod trimmed_curves;
mod trimmed_hlr;
mod visible;
