//! Curves on a model given by one exact polynomial per patch: silhouettes (contour
//! generators, [`silhouette`]) and parabolic curves ([`parabolic`]), solved by one model-level
//! machinery ([`family`]: per patch, then joined across shared edges and chained), with the
//! silhouette's certificate ([`certificate`]) and the float baselines of paper 002
//! ([`baseline`]).
//!
//! The stages of [`family::model_curves`]: each patch's polynomial with its side factors
//! divided out ([`sides`]), solved by the plane-curve solver; crossings joined across shared
//! edges where the join is proven ([`joins`]); arcs chained into model curves ([`chaining`]);
//! drawn, and with a tolerance traced within it ([`drawing`]); the result ([`curves`]).

pub mod baseline;
pub mod certificate;
pub mod chaining;
pub mod curves;
pub mod drawing;
pub mod family;
pub mod joins;
pub mod parabolic;
pub mod sides;
pub mod silhouette;
mod trims;
