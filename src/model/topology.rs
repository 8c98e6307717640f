//! Patch adjacency and topology: shared, boundary and collapsed edges, connected components,
//! Euler characteristic and genus; the same for meshes.

use super::Model;
use crate::number::Rational;
use crate::surface::{Edge, Mesh, Point3, RationalPatch};
use std::collections::HashMap;

/// How patch corners and boundary curves are matched.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
#[serde(tag = "mode", content = "value", rename_all = "lowercase")]
pub enum WeldTolerance {
    /// Equal exact rationals only (the right choice for exact models).
    Exact,
    /// Control points within this distance in every coordinate (max norm), weights
    /// proportional within this relative tolerance: for real CAD data, whose shared
    /// boundaries are written separately and rounded.
    Absolute(f64),
}

impl WeldTolerance {
    /// The weld distance, if not exact.
    pub fn distance(self) -> Option<f64> {
        match self {
            WeldTolerance::Exact => None,
            WeldTolerance::Absolute(d) => Some(d),
        }
    }
}

/// The topology of a model's patches.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct PatchTopology {
    /// Patches (faces).
    pub patches: usize,
    /// Distinct corner points after welding.
    pub vertices: usize,
    /// Distinct boundary curves that are not collapsed to a point.
    pub edges: usize,
    /// Edges bounding exactly two patch sides.
    pub shared_edges: usize,
    /// Edges bounding one patch side only (open boundary).
    pub boundary_edges: usize,
    /// Edges bounding three or more patch sides.
    pub nonmanifold_edges: usize,
    /// Patch sides collapsed to a single point (poles, the teapot's lid knob and bottom).
    pub collapsed_edges: usize,
    /// Connected components (patches joined through shared edges).
    pub components: usize,
    /// No boundary and no non-manifold edges.
    pub closed: bool,
    /// V − E + F.
    pub euler_characteristic: i64,
    /// For a closed model, Σ genus over components = (2·components − χ) / 2.
    pub genus: Option<i64>,
    /// How corners and edges were matched.
    pub weld: WeldTolerance,
    /// The largest coordinate difference between control points that were welded (0 if exact).
    pub max_weld_gap: f64,
}

/// The topology of a mesh.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct MeshTopology {
    /// Vertices used by faces.
    pub vertices: usize,
    /// Distinct undirected edges.
    pub edges: usize,
    /// Faces.
    pub faces: usize,
    /// Whether all faces are triangles.
    pub triangles: bool,
    /// Edges of one face only.
    pub boundary_edges: usize,
    /// Edges of three or more faces.
    pub nonmanifold_edges: usize,
    /// Connected components.
    pub components: usize,
    /// No boundary and no non-manifold edges.
    pub closed: bool,
    /// V − E + F.
    pub euler_characteristic: i64,
    /// For a closed mesh, Σ genus over components = (2·components − χ) / 2.
    pub genus: Option<i64>,
}

/// Union-find over `n` elements.
struct Components(Vec<usize>);

impl Components {
    fn new(n: usize) -> Self {
        Components((0..n).collect())
    }
    fn find(&mut self, mut x: usize) -> usize {
        while self.0[x] != x {
            self.0[x] = self.0[self.0[x]];
            x = self.0[x];
        }
        x
    }
    fn union(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            self.0[ra.max(rb)] = ra.min(rb);
        }
    }
    fn count(&mut self) -> usize {
        (0..self.0.len()).filter(|&i| self.find(i) == i).count()
    }
}

fn genus(closed: bool, components: usize, chi: i64) -> Option<i64> {
    let twice = 2 * components as i64 - chi;
    (closed && twice >= 0 && twice % 2 == 0).then_some(twice / 2)
}

/// Corner points welded into vertex ids.
struct Welder {
    tol: WeldTolerance,
    exact: HashMap<Point3, usize>,
    grid: HashMap<[i64; 3], Vec<usize>>,
    points: Vec<[f64; 3]>,
    max_gap: f64,
}

fn approx(p: &Point3) -> [f64; 3] {
    [p[0].to_f64(), p[1].to_f64(), p[2].to_f64()]
}

/// The max-norm distance; infinite if it cannot be computed (coordinates beyond f64).
fn gap(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    let d = (0..3).map(|k| (a[k] - b[k]).abs());
    let mut g = 0.0f64;
    for x in d {
        if x.is_nan() {
            return f64::INFINITY;
        }
        g = g.max(x);
    }
    g
}

impl Welder {
    /// The grid cell of a point; far points (|x / tol| beyond 2^62) share the extreme cells,
    /// which only costs comparisons, never correctness (points are compared exactly after).
    fn cell(&self, p: &[f64; 3], tol: f64) -> [i64; 3] {
        const LIMIT: f64 = 4.611686018427388e18; // 2^62: cell ± 1 cannot overflow
        p.map(|x| {
            let c = (x / tol).floor();
            if c.is_nan() {
                0
            } else {
                c.clamp(-LIMIT, LIMIT) as i64
            }
        })
    }

    fn vertex(&mut self, p: &Point3) -> usize {
        match self.tol {
            WeldTolerance::Exact => {
                let n = self.exact.len();
                *self.exact.entry(p.clone()).or_insert(n)
            }
            WeldTolerance::Absolute(tol) => {
                let q = approx(p);
                let c = self.cell(&q, tol);
                let mut best: Option<(f64, usize)> = None;
                for dx in -1..=1 {
                    for dy in -1..=1 {
                        for dz in -1..=1 {
                            if let Some(ids) = self.grid.get(&[c[0] + dx, c[1] + dy, c[2] + dz]) {
                                for &id in ids {
                                    let g = gap(&self.points[id], &q);
                                    if g <= tol && best.is_none_or(|(bg, _)| g < bg) {
                                        best = Some((g, id));
                                    }
                                }
                            }
                        }
                    }
                }
                if let Some((g, id)) = best {
                    self.max_gap = self.max_gap.max(g);
                    return id;
                }
                let id = self.points.len();
                self.points.push(q);
                self.grid.entry(c).or_default().push(id);
                id
            }
        }
    }
}

/// A patch side as control points and weights.
type Side<'a> = Vec<(&'a Point3, &'a Rational)>;

/// Edge classes under one key (sorted endpoint vertex ids): a representative side and the
/// patch sides that match it.
type EdgeClasses<'a> = HashMap<(usize, usize), Vec<(Side<'a>, Vec<SideUse>)>>;

fn points_match(a: &Side, b: &Side, tol: WeldTolerance, reversed: bool, max_gap: &mut f64) -> bool {
    if a.len() != b.len() {
        return false;
    }
    let n = a.len();
    let pick = |i: usize| if reversed { b[n - 1 - i] } else { b[i] };
    match tol {
        WeldTolerance::Exact => (0..n).all(|i| {
            let (p, w) = a[i];
            let (q, v) = pick(i);
            // Same point, and weights proportional: w_i v_0 = v_i w_0.
            p == q && Rational::from(w * pick(0).1) == Rational::from(v * a[0].1)
        }),
        WeldTolerance::Absolute(t) => {
            let mut g = 0.0f64;
            for i in 0..n {
                let (p, w) = a[i];
                let (q, v) = pick(i);
                g = g.max(gap(&approx(p), &approx(q)));
                let r = (w.to_f64() * pick(0).1.to_f64()) / (v.to_f64() * a[0].1.to_f64());
                if !(g <= t && (r - 1.0).abs() <= t.max(1e-12)) {
                    return false;
                }
            }
            *max_gap = max_gap.max(g);
            true
        }
    }
}

fn collapsed(side: &Side, tol: WeldTolerance) -> bool {
    let p0 = side[0].0;
    match tol {
        WeldTolerance::Exact => side.iter().all(|(p, _)| *p == p0),
        WeldTolerance::Absolute(t) => side.iter().all(|(p, _)| {
            gap(&approx(p), &approx(p0)) <= t && p.iter().all(|c| c.to_f64().is_finite())
        }),
    }
}

/// One patch side as a user of an edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SideUse {
    /// The patch index.
    pub patch: usize,
    /// Which side.
    pub edge: Edge,
    /// Whether this side runs opposite to the first user of the same edge.
    pub reversed: bool,
}

/// Which patch sides are the same edge, which are collapsed, and the welded corners.
#[derive(Clone, Debug, PartialEq)]
pub struct PatchAdjacency {
    /// Each distinct (non-collapsed) edge with the patch sides that bound it, the first user
    /// defining the direction.
    pub edges: Vec<Vec<SideUse>>,
    /// Collapsed sides: (patch, side, the vertex id of the point they collapse to).
    pub collapsed: Vec<(usize, Edge, usize)>,
    /// The number of distinct corner vertices.
    pub corner_vertices: usize,
    /// Per patch, the vertex ids of its corners S(0,0), S(1,0), S(1,1), S(0,1).
    pub corners: Vec<[usize; 4]>,
    /// The largest coordinate difference welded (0 if exact).
    pub max_weld_gap: f64,
}

impl PatchAdjacency {
    /// Whether patches `a` and `b` share a welded corner.
    pub fn shares_corner(&self, a: usize, b: usize) -> bool {
        let (ca, cb) = (&self.corners[a], &self.corners[b]);
        ca.iter().any(|x| cb.contains(x))
    }

    /// Matches corners and sides as `weld` says (see [`PatchTopology::of_patches`]).
    pub fn of_patches(patches: &[&RationalPatch], weld: WeldTolerance) -> PatchAdjacency {
        let mut welder = Welder {
            tol: weld,
            exact: HashMap::new(),
            grid: HashMap::new(),
            points: Vec::new(),
            max_gap: 0.0,
        };
        let mut used = vec![];
        let mut classes: EdgeClasses = HashMap::new();
        let mut order: Vec<((usize, usize), usize)> = Vec::new();
        let mut collapsed_sides = Vec::new();
        let mut max_gap = 0.0f64;
        let mut corners = Vec::with_capacity(patches.len());
        for (pi, patch) in patches.iter().enumerate() {
            corners.push(patch.corners().map(|c| welder.vertex(c)));
            for edge in Edge::ALL {
                let side = patch.edge(edge);
                let a = welder.vertex(side[0].0);
                let b = welder.vertex(side[side.len() - 1].0);
                used.push(a);
                used.push(b);
                if a == b && collapsed(&side, weld) {
                    collapsed_sides.push((pi, edge, a));
                    continue;
                }
                let key = (a.min(b), a.max(b));
                let bucket = classes.entry(key).or_default();
                let found = bucket.iter().enumerate().find_map(|(k, (rep, _))| {
                    if points_match(rep, &side, weld, false, &mut max_gap) {
                        Some((k, false))
                    } else if points_match(rep, &side, weld, true, &mut max_gap) {
                        Some((k, true))
                    } else {
                        None
                    }
                });
                let user = |reversed| SideUse {
                    patch: pi,
                    edge,
                    reversed,
                };
                match found {
                    Some((k, reversed)) => bucket[k].1.push(user(reversed)),
                    None => {
                        order.push((key, bucket.len()));
                        bucket.push((side, vec![user(false)]));
                    }
                }
            }
        }
        used.sort_unstable();
        used.dedup();
        // In order of first appearance, so that the result does not depend on hashing.
        let edges = order
            .into_iter()
            .map(|(key, k)| classes[&key][k].1.clone())
            .collect();
        PatchAdjacency {
            edges,
            collapsed: collapsed_sides,
            corner_vertices: used.len(),
            corners,
            max_weld_gap: max_gap.max(welder.max_gap),
        }
    }
}

impl PatchTopology {
    /// The topology of a set of patches, matching corners and boundary curves as `weld` says.
    ///
    /// Two patch sides are the same edge when their control points agree (in order or
    /// reversed) and their weights are proportional. Sides of different degrees are not
    /// matched (degree elevation to match them is left to a later version).
    pub fn of_patches(patches: &[&RationalPatch], weld: WeldTolerance) -> PatchTopology {
        let adj = PatchAdjacency::of_patches(patches, weld);
        let mut comps = Components::new(patches.len());
        let (mut shared, mut boundary, mut nonmanifold) = (0, 0, 0);
        for class in &adj.edges {
            match class.len() {
                1 => boundary += 1,
                2 => shared += 1,
                _ => nonmanifold += 1,
            }
            for w in class.windows(2) {
                comps.union(w[0].patch, w[1].patch);
            }
        }
        let (edges, collapsed_edges, max_gap) =
            (adj.edges.len(), adj.collapsed.len(), adj.max_weld_gap);
        let used = adj.corner_vertices;
        let components = comps.count();
        let chi = used as i64 - edges as i64 + patches.len() as i64;
        let closed = !patches.is_empty() && boundary == 0 && nonmanifold == 0;
        PatchTopology {
            patches: patches.len(),
            vertices: used,
            edges,
            shared_edges: shared,
            boundary_edges: boundary,
            nonmanifold_edges: nonmanifold,
            collapsed_edges,
            components,
            closed,
            euler_characteristic: chi,
            genus: genus(closed, components, chi),
            weld,
            max_weld_gap: max_gap,
        }
    }

    /// The topology of a model's patches.
    pub fn of_model(model: &Model, weld: WeldTolerance) -> PatchTopology {
        let patches: Vec<&RationalPatch> = model.patches.iter().map(|p| &p.surface).collect();
        PatchTopology::of_patches(&patches, weld)
    }
}

impl MeshTopology {
    /// The topology of a mesh (vertices matched by index, as the file gives them).
    pub fn of_mesh(mesh: &Mesh) -> MeshTopology {
        let mut edge_use: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
        let mut used = vec![false; mesh.vertices.len()];
        for (fi, f) in mesh.faces.iter().enumerate() {
            for k in 0..f.len() {
                let (a, b) = (f[k], f[(k + 1) % f.len()]);
                used[a] = true;
                edge_use.entry((a.min(b), a.max(b))).or_default().push(fi);
            }
        }
        let mut comps = Components::new(mesh.faces.len());
        let (mut boundary, mut nonmanifold) = (0, 0);
        for users in edge_use.values() {
            match users.len() {
                1 => boundary += 1,
                2 => {}
                _ => nonmanifold += 1,
            }
            for w in users.windows(2) {
                comps.union(w[0], w[1]);
            }
        }
        let vertices = used.iter().filter(|&&u| u).count();
        let chi = vertices as i64 - edge_use.len() as i64 + mesh.faces.len() as i64;
        let components = comps.count();
        let closed = !mesh.faces.is_empty() && boundary == 0 && nonmanifold == 0;
        MeshTopology {
            vertices,
            edges: edge_use.len(),
            faces: mesh.faces.len(),
            triangles: mesh.is_triangle_mesh(),
            boundary_edges: boundary,
            nonmanifold_edges: nonmanifold,
            components,
            closed,
            euler_characteristic: chi,
            genus: genus(closed, components, chi),
        }
    }
}
