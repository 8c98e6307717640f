//! The scene of a view: every patch's exact image and depth polynomials with their f64
//! bounds, the model's adjacency, and which patches can meet a given ray.

use crate::analysis::projection::{ImagePolys, Projection, ProjectionError};
use crate::analysis::view::View;
use crate::model::{Model, PatchAdjacency, WeldTolerance};
use crate::number::{Number, Rational};
use crate::surface::Edge;

use crate::bernstein::Poly;
/// Image bounds of a patch, outward in `f64`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImageBounds {
    /// Range of the first image coordinate.
    pub x: [f64; 2],
    /// Range of the second image coordinate.
    pub y: [f64; 2],
    /// Range of the depth.
    pub depth: [f64; 2],
}
impl ImageBounds {
    /// Whether two bounds can overlap in the image.
    pub fn meets_image(&self, o: &ImageBounds) -> bool {
        self.x[0] <= o.x[1] && o.x[0] <= self.x[1] && self.y[0] <= o.y[1] && o.y[0] <= self.y[1]
    }
}
/// Outward bounds of `num / den` over the domain of Bernstein polynomials of equal degrees
/// with `den`'s coefficients positive (the rational convex-hull property).
pub fn ratio_bounds(num: &Poly, den: &Poly) -> [f64; 2] {
    let (num, den) = same_degrees(num, den);
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for (n, d) in num.coeffs().iter().zip(den.coeffs()) {
        let r = Rational::from(n / d);
        lo = lo.min(r.lower_f64());
        hi = hi.max(r.upper_f64());
    }
    [lo, hi]
}
/// Both polynomials at their common degrees.
pub(crate) fn same_degrees(a: &Poly, b: &Poly) -> (Poly, Poly) {
    let deg: Vec<usize> = a
        .degrees()
        .iter()
        .zip(b.degrees())
        .map(|(x, y)| *x.max(y))
        .collect();
    (a.elevate_to(&deg), b.elevate_to(&deg))
}
/// A model seen in one view: the exact image polynomials of every patch and what the ray
/// tests need of them.
#[derive(Clone, Debug)]
pub struct Scene {
    /// The image frame.
    pub projection: Projection,
    /// Per patch, its image polynomials in (u, v).
    pub images: Vec<ImagePolys>,
    /// Per patch, outward image and depth bounds.
    pub bounds: Vec<ImageBounds>,
    /// Per patch, the numerators of the rows of the image map's Jacobian:
    /// `[[x_u q − x q_u, x_v q − x q_v], [y_u q − y q_u, y_v q − y q_v]]`.
    pub jacobians: Vec<[[Poly; 2]; 2]>,
    /// Which patch sides are the same edge.
    pub adjacency: PatchAdjacency,
}
impl Scene {
    /// Sets up a model and a view.
    ///
    /// # Errors
    /// As [`Projection::new`].
    pub fn new(model: &Model, view: &View, weld: WeldTolerance) -> Result<Scene, ProjectionError> {
        let projection = Projection::new(model, view)?;
        let images: Vec<ImagePolys> = model
            .patches
            .iter()
            .map(|p| projection.image(&p.surface))
            .collect();
        let bounds = images
            .iter()
            .map(|im| ImageBounds {
                x: ratio_bounds(&im.x, &im.q),
                y: ratio_bounds(&im.y, &im.q),
                depth: ratio_bounds(&im.depth, &im.w),
            })
            .collect();
        let jacobians = images
            .iter()
            .map(|im| {
                let row = |f: &Poly| [0, 1].map(|a| &(&f.deriv(a) * &im.q) - &(f * &im.q.deriv(a)));
                [row(&im.x), row(&im.y)]
            })
            .collect();
        let surfaces: Vec<_> = model.patches.iter().map(|p| &p.surface).collect();
        let adjacency = PatchAdjacency::of_patches(&surfaces, weld);
        Ok(Scene {
            projection,
            images,
            bounds,
            jacobians,
            adjacency,
        })
    }

    /// The other patch sides that are the same edge as `(patch, edge)`, with whether each
    /// runs opposite to it.
    pub fn twins(&self, patch: usize, edge: Edge) -> Vec<(usize, Edge, bool)> {
        for users in &self.adjacency.edges {
            if let Some(me) = users.iter().find(|s| s.patch == patch && s.edge == edge) {
                return users
                    .iter()
                    .filter(|s| !(s.patch == patch && s.edge == edge))
                    .map(|s| (s.patch, s.edge, s.reversed != me.reversed))
                    .collect();
            }
        }
        Vec::new()
    }
}
