//! The scene of a view: every patch's exact image and depth polynomials with their f64
//! bounds, the model's adjacency, and which patches can meet a given ray.

use crate::analysis::projection::{ImagePolys, Projection, ProjectionError};
use crate::analysis::view::View;
use crate::model::{Model, PatchAdjacency, WeldTolerance};
use crate::number::{Number, Rational};
use crate::surface::Edge;

use crate::bernstein::{Bernstein, Poly};
use crate::number::{Interval, Precision};
use std::sync::OnceLock;

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
/// [`ratio_bounds`] of interval polynomials of equal degrees; unbounded unless every
/// coefficient of `den` is proven positive.
fn interval_ratio_bounds(num: &Bernstein<Interval>, den: &Bernstein<Interval>) -> [f64; 2] {
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for (n, d) in num.coeffs().iter().zip(den.coeffs()) {
        match n.checked_div(d).filter(|_| d.lo() > 0.0) {
            Some(r) => {
                lo = lo.min(r.lo());
                hi = hi.max(r.hi());
            }
            None => return [f64::NEG_INFINITY, f64::INFINITY],
        }
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
    /// Per patch, the bounds of the cells of a [`LEAF_GRID`]² grid of its parameter square,
    /// made on first use ([`Scene::leaf_bounds`]).
    leaves: Vec<OnceLock<Vec<ImageBounds>>>,
}

/// Cells per side of the grid of [`Scene::leaf_bounds`].
pub const LEAF_GRID: usize = 4;
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
        let leaves = (0..images.len()).map(|_| OnceLock::new()).collect();
        Ok(Scene {
            projection,
            images,
            bounds,
            jacobians,
            adjacency,
            leaves,
        })
    }

    /// Outward image and depth bounds of patch `j` on each cell `[a/n, (a+1)/n] × [b/n,
    /// (b+1)/n]` (n = [`LEAF_GRID`]) of its parameter square: every point of the patch lies
    /// in the bounds of a cell that holds its parameters. A cell whose denominators are not
    /// proven positive there gets unbounded ranges. Interval restrictions (the cells' ends
    /// are exact in f64) and the rational convex-hull property; computed once per patch.
    pub fn leaf_bounds(&self, j: usize) -> &[ImageBounds] {
        self.leaves[j].get_or_init(|| {
            let im = &self.images[j];
            let pair = |n: &Poly, d: &Poly| {
                let (n, d) = same_degrees(n, d);
                let c = |p: &Poly| -> Bernstein<Interval> { p.convert(Precision::F64) };
                (c(&n), c(&d))
            };
            let xs = pair(&im.x, &im.q);
            let ys = pair(&im.y, &im.q);
            let ds = pair(&im.depth, &im.w);
            let n = LEAF_GRID;
            let mut out = Vec::with_capacity(n * n);
            for a in 0..n {
                for b in 0..n {
                    let lo = [a as f64 / n as f64, b as f64 / n as f64];
                    let hi = [(a + 1) as f64 / n as f64, (b + 1) as f64 / n as f64];
                    let on = |(num, den): &(Bernstein<Interval>, Bernstein<Interval>)| {
                        interval_ratio_bounds(
                            &num.restrict_box_f64(&lo, &hi),
                            &den.restrict_box_f64(&lo, &hi),
                        )
                    };
                    out.push(ImageBounds {
                        x: on(&xs),
                        y: on(&ys),
                        depth: on(&ds),
                    });
                }
            }
            out
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

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::model::Format;
    use crate::testing::shapes;

    /// The torus of radii 2 and 1 and its scene in a view (exact weld).
    pub(crate) fn torus_scene(view: &View) -> (Model, Scene) {
        let torus = shapes::torus(&Rational::from(2), &Rational::from(1));
        let model = Model::from_patches(Format::Json, torus);
        let scene = Scene::new(&model, view, WeldTolerance::Exact).unwrap();
        (model, scene)
    }

    /// Every point of every patch (sampled exactly on a grid finer than the cells, cell
    /// sides included) lies in the bounds of each cell that holds its parameters; a
    /// perspective eye and a parallel view, on a torus.
    #[test]
    fn every_point_lies_in_its_cells_bounds() {
        let views = [
            View::Direction([7, 2, 4].map(Rational::from)),
            View::Eye([9, -5, 11].map(Rational::from)),
        ];
        for view in &views {
            let (model, scene) = torus_scene(view);
            for j in 0..model.patches.len() {
                let cells = scene.leaf_bounds(j);
                let im = &scene.images[j];
                let k = 3 * LEAF_GRID as i64;
                for a in 0..=k {
                    for b in 0..=k {
                        let uv = [Rational::from((a, k)), Rational::from((b, k))];
                        let r = |n: &Poly, d: &Poly| Rational::from(&n.eval(&uv) / &d.eval(&uv));
                        let (x, y, d) = (r(&im.x, &im.q), r(&im.y, &im.q), r(&im.depth, &im.w));
                        let inside = |v: &Rational, range: [f64; 2]| {
                            *v >= Rational::from_f64(range[0]).unwrap()
                                && *v <= Rational::from_f64(range[1]).unwrap()
                        };
                        let g = LEAF_GRID as i64;
                        let mut holding = 0;
                        for ca in 0..g {
                            for cb in 0..g {
                                let holds = |i: i64, c: i64| i * g >= c * k && i * g <= (c + 1) * k;
                                if !(holds(a, ca) && holds(b, cb)) {
                                    continue;
                                }
                                holding += 1;
                                let c = cells[(ca * g + cb) as usize];
                                assert!(
                                    inside(&x, c.x) && inside(&y, c.y) && inside(&d, c.depth),
                                    "patch {j} at {a}/{k}, {b}/{k}: cell ({ca}, {cb}) {c:?}"
                                );
                            }
                        }
                        assert!(holding >= 1);
                    }
                }
            }
        }
    }
}
