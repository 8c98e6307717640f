//! Visibility for a view: certified ray counts ([`ray`]), the self-visible type of a patch
//! ([`facing`]), edges the surface continues across ([`fold_edges`]), the hidden-line drawing
//! ([`hlr`]) and the visible regions of each patch ([`visible`]).

pub mod facing;
pub mod fold_edges;
pub mod hlr;
pub mod ray;
pub mod scene;
pub mod sheets;
pub mod visible;
