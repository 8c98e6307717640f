//! Polygon meshes (triangles, quads, polygons) with exact vertex coordinates.

use super::Point3;

/// A polygon mesh: vertices with exact coordinates and faces as vertex index lists
/// (zero-based, counter-clockwise seen from outside for an oriented closed mesh).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Mesh {
    /// Vertex positions.
    pub vertices: Vec<Point3>,
    /// Faces, each at least 3 vertex indices in range.
    pub faces: Vec<Vec<usize>>,
}

impl Mesh {
    /// Whether every face is a triangle.
    pub fn is_triangle_mesh(&self) -> bool {
        self.faces.iter().all(|f| f.len() == 3)
    }
}
