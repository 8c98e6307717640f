//! The topology a B-rep file states (IGES 186/514/510/508/504/502): vertices, edges shared by
//! the loops of faces, shells. Unlike [`super::PatchTopology`], which matches the untrimmed
//! sides of patches, this is the topology of the trimmed part, as the file's author built it.

use crate::surface::Point3;

/// One edge of the B-rep: a model-space curve between two vertices, used by loops.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct BrepEdge {
    /// IGES: the directory entry of the edge list (504) and the edge's index in it (1-based).
    pub list: usize,
    /// The index in the list.
    pub index: usize,
    /// How many times loops use it (2 for an edge shared by two faces, or a seam of one).
    pub uses: usize,
    /// Its start and end vertices, exact, as the file states them.
    #[serde(skip)]
    pub ends: [Point3; 2],
}

/// A B-rep's topology.
#[derive(Clone, Debug, PartialEq, Eq, Default, serde::Serialize)]
pub struct Brep {
    /// Distinct vertices used by the edges.
    pub vertices: usize,
    /// The edges used by loops.
    pub edges: Vec<BrepEdge>,
    /// Faces.
    pub faces: usize,
    /// Loops, outer and inner.
    pub loops: usize,
    /// Inner loops (rings, holes of faces).
    pub inner_loops: usize,
    /// Shells.
    pub shells: usize,
}

/// The summary `limn info` prints of a [`Brep`].
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct BrepSummary {
    /// Distinct vertices.
    pub vertices: usize,
    /// Edges.
    pub edges: usize,
    /// Edges used twice (by two faces, or as the seam of one).
    pub shared_edges: usize,
    /// Edges used once.
    pub boundary_edges: usize,
    /// Edges used three or more times.
    pub nonmanifold_edges: usize,
    /// Faces.
    pub faces: usize,
    /// Loops.
    pub loops: usize,
    /// Inner loops.
    pub inner_loops: usize,
    /// Shells.
    pub shells: usize,
    /// Every edge used exactly twice.
    pub closed: bool,
    /// The Euler–Poincaré characteristic V − E + F − R (R the inner loops).
    pub euler_characteristic: i64,
    /// For a closed B-rep: shells − χ/2 summed (each shell a closed orientable surface of
    /// genus g has V − E + F − R = 2 − 2g), when χ is even.
    pub genus: Option<i64>,
}

impl Brep {
    /// Its summary.
    pub fn summary(&self) -> BrepSummary {
        let count = |f: &dyn Fn(usize) -> bool| self.edges.iter().filter(|e| f(e.uses)).count();
        let shared = count(&|u| u == 2);
        let boundary = count(&|u| u == 1);
        let nonmanifold = count(&|u| u >= 3);
        let closed = !self.edges.is_empty() && shared == self.edges.len();
        let chi = self.vertices as i64 - self.edges.len() as i64 + self.faces as i64
            - self.inner_loops as i64;
        let genus = (closed && chi % 2 == 0).then(|| self.shells as i64 - chi / 2);
        BrepSummary {
            vertices: self.vertices,
            edges: self.edges.len(),
            shared_edges: shared,
            boundary_edges: boundary,
            nonmanifold_edges: nonmanifold,
            faces: self.faces,
            loops: self.loops,
            inner_loops: self.inner_loops,
            shells: self.shells,
            closed,
            euler_characteristic: chi,
            genus,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn edges(uses: &[usize]) -> Vec<BrepEdge> {
        uses.iter()
            .enumerate()
            .map(|(i, &u)| BrepEdge {
                list: 1,
                index: i + 1,
                uses: u,
                ends: Default::default(),
            })
            .collect()
    }

    #[test]
    fn genus_of_closed_breps() {
        // A cube: 8 vertices, 12 edges, 6 faces: genus 0.
        let cube = Brep {
            vertices: 8,
            edges: edges(&[2; 12]),
            faces: 6,
            loops: 6,
            inner_loops: 0,
            shells: 1,
        };
        let s = cube.summary();
        assert!(s.closed);
        assert_eq!((s.euler_characteristic, s.genus), (2, Some(0)));
        // A cube with a square hole through it: 16 vertices, 24 edges, 10 faces, 2 rings:
        // χ = 0, genus 1.
        let holed = Brep {
            vertices: 16,
            edges: edges(&[2; 24]),
            faces: 10,
            loops: 12,
            inner_loops: 2,
            shells: 1,
        };
        assert_eq!(holed.summary().genus, Some(1));
        // A cylinder from IGES (side with a seam, two caps): V 2, E 3, F 3: genus 0.
        let cylinder = Brep {
            vertices: 2,
            edges: edges(&[2, 2, 2]),
            faces: 3,
            loops: 3,
            inner_loops: 0,
            shells: 1,
        };
        assert_eq!(cylinder.summary().genus, Some(0));
        // An open B-rep has no genus.
        let open = Brep {
            edges: edges(&[1, 2]),
            ..cylinder
        };
        let s = open.summary();
        assert!(!s.closed);
        assert_eq!((s.boundary_edges, s.genus), (1, None));
    }
}
