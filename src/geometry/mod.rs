//! Small shared primitives in `f64`: vectors in space and rectangles in the plane.

pub mod rect;
pub mod vec3;

pub use rect::Rect;
