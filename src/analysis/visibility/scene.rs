//! The scene of a view: every patch's exact image and depth polynomials with their f64
//! bounds, the model's adjacency, and which patches can meet a given ray.

use crate::analysis::projection::{ImagePolys, Projection, ProjectionError};
use crate::analysis::view::View;
use crate::geometry::Rect;
use crate::model::{
    contact_assumption, model_contacts, Model, PatchAdjacency, SideContact, WeldTolerance,
};
use crate::number::{Number, Rational};
use crate::solver::point_in_face::{
    point_in_face, FacesOnPatch, Membership, NoParameterBox, PieceOnPatch,
};
use crate::surface::{Edge, RationalPatch};

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
    /// Sides that run along another patch's side without a common corner (measured, for a
    /// model without trimmed faces), in the order of their pairs: those pairs are adjacent
    /// too ([`Scene::adjacent`]).
    pub contacts: Vec<SideContact>,
    /// The tolerance of that measurement.
    pub contact_tolerance: f64,
    /// Per patch, the bounds of the cells of a [`LEAF_GRID`]² grid of its parameter square,
    /// made on first use ([`Scene::leaf_bounds`]).
    leaves: Vec<OnceLock<Vec<ImageBounds>>>,
    /// Per patch, its trimmed faces ([`Scene::with_faces`]; empty: every patch whole).
    pub faces: Vec<Option<PatchTrims>>,
    /// How near another face a point of a trimming curve is taken to lie on it (model
    /// units; [`Scene::with_faces`]).
    pub trim_contact: f64,
    /// The patches, for the space distances of that rule (empty without faces).
    pub surfaces: Vec<RationalPatch>,
}

/// The trimmed faces on a patch, with their loop pieces in the patch's parameters.
#[derive(Clone, Debug)]
pub struct PatchTrims {
    /// The faces and the patch's map into their parameter plane; an error if the patch has
    /// no parameter box on its surface (nothing of it is placed in the faces).
    pub on: Result<FacesOnPatch, NoParameterBox>,
    /// The loop pieces in the patch's parameters.
    pub pieces: Vec<PieceOnPatch>,
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
        let (contacts, contact_tolerance) = model_contacts(model, &adjacency, weld);
        let leaves = (0..images.len()).map(|_| OnceLock::new()).collect();
        Ok(Scene {
            projection,
            images,
            bounds,
            jacobians,
            adjacency,
            contacts,
            contact_tolerance,
            leaves,
            faces: Vec::new(),
            trim_contact: 0.0,
            surfaces: Vec::new(),
        })
    }

    /// The scene with every patch restricted to the trimmed faces of its surface (a patch
    /// whose surface has none is whole); a point of a trimming curve is taken to be the same
    /// point as any point of another face within `contact` of it.
    pub fn with_faces(mut self, model: &Model, contact: f64) -> Scene {
        self.trim_contact = contact;
        self.surfaces = model.patches.iter().map(|p| p.surface.clone()).collect();
        self.faces = (0..model.patches.len())
            .map(|p| {
                let on = FacesOnPatch::of(model, p)?;
                let pieces = match &on {
                    Ok(on) => {
                        let ids: Vec<usize> = model
                            .faces
                            .iter()
                            .enumerate()
                            .filter(|(_, f)| f.surface == model.patches[p].source.surface)
                            .map(|(i, _)| i)
                            .collect();
                        on.pieces_on(&ids)
                    }
                    Err(_) => Vec::new(),
                };
                Some(PatchTrims { on, pieces })
            })
            .collect();
        self
    }

    /// Whether two patches are neighbours: they share a welded corner, or a side of one runs
    /// along a side of the other ([`Scene::contacts`]). Neighbours are taken not to cross
    /// each other away from their common points (the adjacency assumption).
    pub fn adjacent(&self, a: usize, b: usize) -> bool {
        self.adjacency.shares_corner(a, b)
            || self
                .contacts
                .binary_search_by(|c| c.patches.cmp(&[a.min(b), a.max(b)]))
                .is_ok()
    }

    /// The assumption that [`Scene::contacts`] adds to a report, if any.
    pub fn contact_assumption(&self) -> Option<String> {
        (!self.contacts.is_empty())
            .then(|| contact_assumption(&self.contacts, self.contact_tolerance))
    }

    /// Whether patch `j` is restricted to trimmed faces.
    pub fn trimmed(&self, j: usize) -> bool {
        self.faces.get(j).is_some_and(Option::is_some)
    }

    /// Whether an exact point of patch `j`'s parameters lies on a loop piece that runs along a
    /// parameter line through it ([`on_piece_along_line`]): a point of a trimming curve.
    pub fn on_trim(&self, j: usize, uv: &[Rational; 2]) -> bool {
        let Some(Some(t)) = self.faces.get(j) else {
            return false;
        };
        t.pieces.iter().any(|p| on_piece_along_line(&p.curve, uv))
    }

    /// Whether a box of patch `j`'s parameters lies in its faces ([`crate::solver::point_in_face::box_in_faces`]; inside
    /// for a patch used whole).
    pub fn membership(&self, j: usize, r: &Rect) -> Membership {
        match self.faces.get(j) {
            Some(Some(t)) => match &t.on {
                Ok(on) => on.membership(r),
                Err(_) => Membership::Undecided,
            },
            _ => Membership::Inside,
        }
    }

    /// Whether an exact point of patch `j`'s parameters lies in its closed faces: on a loop
    /// piece that runs along a parameter line through it (between the piece's ends) it does;
    /// otherwise as [`Scene::membership`] of the point.
    pub fn point_membership(&self, j: usize, uv: &[Rational; 2]) -> Membership {
        if self.on_trim(j, uv) {
            return Membership::Inside;
        }
        let Some(Some(t)) = self.faces.get(j) else {
            return Membership::Inside;
        };
        let Ok(on) = &t.on else {
            return Membership::Undecided;
        };
        let p: [Rational; 2] =
            std::array::from_fn(|a| &on.origin[a] + Rational::from(&on.size[a] * &uv[a]));
        let mut out = Membership::Outside;
        for face in &on.faces {
            let d = &face.domain;
            let outside = (0..2).any(|a| p[a] < d[a][0] || p[a] > d[a][1]);
            let on_side = (0..2).any(|a| p[a] == d[a][0] || p[a] == d[a][1]);
            let m = if outside {
                Membership::Outside
            } else if on_side {
                // Off the loops: the region inside an outer loop lies in the open domain (the
                // loop lies in the closed, convex domain); without one, the domain's boundary
                // bounds the face.
                if face.outer.is_some() {
                    Membership::Outside
                } else {
                    Membership::Inside
                }
            } else {
                point_in_face(face, &p)
            };
            match m {
                Membership::Inside => return Membership::Inside,
                Membership::Undecided => out = Membership::Undecided,
                Membership::Outside => {}
            }
        }
        out
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

/// Whether `uv` lies on the curve `(U/W, V/W)`, `t ∈ [0, 1]`, where the curve runs along the
/// parameter line through `uv` (`U − u W ≡ 0` or `V − v W ≡ 0`) and the other coordinate of
/// `uv` lies between the curve's ends (the curve is connected, so it passes there).
pub fn on_piece_along_line(c: &[Bernstein<Rational>; 3], uv: &[Rational; 2]) -> bool {
    let (zero, one) = (Rational::new(), Rational::from(1));
    (0..2).any(|a| {
        let along = c[a].try_sub(&c[2].scale(&uv[a])).is_ok_and(|d| d.is_zero());
        if !along {
            return false;
        }
        let o = 1 - a;
        let end = |t: &Rational| {
            let at = std::slice::from_ref(t);
            let w = c[2].eval(at);
            (w > 0).then(|| Rational::from(&c[o].eval(at) / &w))
        };
        let (Some(e0), Some(e1)) = (end(&zero), end(&one)) else {
            return false;
        };
        let (lo, hi) = if e0 <= e1 { (e0, e1) } else { (e1, e0) };
        lo <= uv[o] && uv[o] <= hi
    })
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
