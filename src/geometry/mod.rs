//! Small shared primitives in `f64`: vectors in space.

pub mod vec3;
