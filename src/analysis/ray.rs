//! Certified ray tests: how many surface layers lie in front of a point of a model, along the
//! viewing ray through it (its quantitative invisibility, QI).
//!
//! For a sample point `p` and each patch `j` whose image box and depth range can meet the ray,
//! the points of `j` with the image of `p` are the roots of the square system
//! `x_j q_p − x_p q_j = 0`, `y_j q_p − y_p q_j = 0` (see [`super::projection`]), isolated by
//! the certified system solver ([`crate::solver::solve_system`], `proofs/krawczyk.md`); each
//! root is in front of `p` by the certified sign of `depth_j w_p − depth_p w_j` on its
//! enclosure. The count is proven when every root is isolated, lies strictly inside its
//! domain (a ray through a patch edge would be counted on both patches), and has a strict
//! depth sign. Otherwise the sample is refused with the reason, and the caller tries another.
//!
//! The sheets that carry `p` itself (its own patch, and the patch across a shared side) have
//! `p` as a root at depth zero. That root is excluded by a box around it that provably holds
//! no other point with the same image (`proofs/ray-count.md`):
//! - where the image map is a local diffeomorphism, a box on which its interval Jacobian is
//!   regular (the map is injective there);
//! - at a silhouette point, a box on which the fold lemma holds: with rotated image
//!   coordinates `(κ, η)`, `∂κ/∂u` and `∂κ/∂v` keep their signs and `η` is strictly convex
//!   along the level curves of `κ`; then the fibre of every fold point in the box is that
//!   point alone.
//!
//! The rest of the domain is solved with those boxes excluded
//! ([`crate::solver::system::solve_system_excluding`]).

use super::accuracy::jet_on;
pub use super::projection::fix_axis;
use super::projection::{lift, side_point, ImagePolys, Projection, ProjectionError};
use super::silhouette::View;
use crate::bernstein::Bernstein;
use crate::model::{Model, PatchAdjacency, WeldTolerance};
use crate::number::{Interval, Number, Precision, Rational};
use crate::solver::dyadic::Dyadic;
use crate::solver::system::{solve_system_excluding, DyadicBoxN, SystemOptions};
use crate::surface::Edge;

type Poly = Bernstein<Rational>;

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

/// A point whose QI is wanted.
#[derive(Clone, Debug, PartialEq)]
pub enum Sample {
    /// The point of a patch at exact dyadic parameters, not on its silhouette.
    Exact {
        /// The patch.
        patch: usize,
        /// Its parameters.
        uv: [Rational; 2],
    },
    /// The silhouette point of a patch on the line `axis = at`, the other parameter being the
    /// only root of the silhouette function on that line in `[lo, hi]`.
    Silhouette {
        /// The patch.
        patch: usize,
        /// The fixed parameter (0: u, 1: v).
        axis: usize,
        /// Its value (dyadic).
        at: Rational,
        /// The isolating interval of the free parameter (dyadic ends).
        interval: [Rational; 2],
        /// The silhouette function of the patch.
        g: Poly,
    },
}

/// Budgets of a ray test.
#[derive(Clone, Debug)]
pub struct RayOptions {
    /// Budgets of each system solve.
    pub system: SystemOptions,
}

impl Default for RayOptions {
    fn default() -> Self {
        RayOptions {
            system: SystemOptions {
                max_depth: 24,
                max_boxes: 4_000,
                refine_width: 1e-12,
            },
        }
    }
}

/// The point's image polynomials in its own free variables (none for an exact point: then
/// constants), the box of those variables, and its constraints.
struct PointSystem {
    /// Number of free variables (0 or 1).
    nvars: usize,
    /// Image polynomials in the free variables (constant polynomials in 1 variable if none).
    image: ImagePolys,
    /// The free variables' box.
    domain: DyadicBoxN,
    /// Constraints on the free variables (the silhouette function on the line).
    constraints: Vec<Poly>,
}

impl Sample {
    /// An enclosure of the sample's parameters on its patch, `[lo, hi]` per parameter.
    pub fn uv_enclosure(&self) -> [[f64; 2]; 2] {
        let r = |q: &Rational| [q.lower_f64(), q.upper_f64()];
        match self {
            Sample::Exact { uv, .. } => [r(&uv[0]), r(&uv[1])],
            Sample::Silhouette {
                axis, at, interval, ..
            } => {
                let mut out = [r(at), r(at)];
                out[1 - axis] = [interval[0].lower_f64(), interval[1].upper_f64()];
                out
            }
        }
    }
}

fn dy(q: &Rational) -> Option<Dyadic> {
    Dyadic::from_rational(q)
}

impl Sample {
    /// The patch the sample lies on.
    pub fn patch(&self) -> usize {
        match self {
            Sample::Exact { patch, .. } | Sample::Silhouette { patch, .. } => *patch,
        }
    }

    fn system(&self, scene: &Scene) -> Option<PointSystem> {
        let im = &scene.images[self.patch()];
        match self {
            Sample::Exact { uv, .. } => {
                let c = |p: &Poly| Bernstein::constant(1, p.eval(uv));
                Some(PointSystem {
                    nvars: 0,
                    image: ImagePolys {
                        x: c(&im.x),
                        y: c(&im.y),
                        q: c(&im.q),
                        depth: c(&im.depth),
                        w: c(&im.w),
                    },
                    domain: Vec::new(),
                    constraints: Vec::new(),
                })
            }
            Sample::Silhouette {
                axis,
                at,
                interval,
                g,
                ..
            } => {
                let whole = im.on_line(*axis, at);
                Some(PointSystem {
                    nvars: 1,
                    image: whole,
                    domain: vec![(dy(&interval[0])?, dy(&interval[1])?)],
                    constraints: vec![fix_axis(g, *axis, at)],
                })
            }
        }
    }
}

/// The QI of a sample point, proven: the number of surface layers strictly in front of it on
/// its viewing ray.
///
/// # Errors
/// Why the count is not proven (the caller may try another sample): a ray through a patch
/// edge or tangent to a patch, a point whose own sheet could not be excluded, a budget.
pub fn layers_in_front(scene: &Scene, sample: &Sample, opts: &RayOptions) -> Result<usize, String> {
    layers(scene, sample, opts, false).map(|l| l.in_front)
}

/// A point of the model on a sample's ray, behind the sample.
#[derive(Clone, Debug, PartialEq)]
pub struct Hit {
    /// Its patch.
    pub patch: usize,
    /// An enclosure of its parameters, `[lo, hi]` per variable (the only point of the patch
    /// on the ray in it).
    pub uv: [[f64; 2]; 2],
    /// An enclosure of its depth.
    pub depth: [f64; 2],
}

/// The surface layers on a sample's ray: how many lie in front of it (proven), and, if
/// asked, the points behind it (proven complete, or why not).
#[derive(Clone, Debug, PartialEq)]
pub struct Layers {
    /// The QI of the sample.
    pub in_front: usize,
    /// Every point of the model on the ray behind the sample (each with its own enclosure),
    /// or why they are not proven; empty if not asked.
    pub behind: Result<Vec<Hit>, String>,
}

impl Layers {
    /// The nearest point behind the sample, if its depth is proven less than every other's
    /// (`Ok(None)`: nothing behind, the background).
    ///
    /// # Errors
    /// The points behind are not proven, or two of them are not proven apart in depth.
    pub fn first_behind(&self) -> Result<Option<&Hit>, String> {
        let behind = self.behind.as_ref().map_err(|e| e.clone())?;
        let Some(first) = behind
            .iter()
            .min_by(|a, b| a.depth[0].total_cmp(&b.depth[0]))
        else {
            return Ok(None);
        };
        let apart = behind
            .iter()
            .filter(|h| !std::ptr::eq(*h, first))
            .all(|h| first.depth[1] < h.depth[0]);
        if apart {
            Ok(Some(first))
        } else {
            Err("two surface points behind it are not proven apart in depth".into())
        }
    }
}

/// [`layers_in_front`], and with `behind` also every point of the model behind the sample on
/// its ray ([`Layers::behind`]).
///
/// # Errors
/// As [`layers_in_front`] (a problem behind the sample only makes [`Layers::behind`] an
/// error).
pub fn layers(
    scene: &Scene,
    sample: &Sample,
    opts: &RayOptions,
    behind: bool,
) -> Result<Layers, String> {
    let ps = sample
        .system(scene)
        .ok_or("the sample's parameters are not dyadic")?;
    let own = sample.patch();
    // The sample's depth range and image box, to skip patches that cannot be in front.
    let pb = point_bounds(&ps);
    let mut count = 0;
    let mut hits: Result<Vec<Hit>, String> = if behind {
        Ok(Vec::new())
    } else {
        Err("not asked".into())
    };
    for (j, jb) in scene.bounds.iter().enumerate() {
        if !jb.meets_image(&pb) || (!behind && jb.depth[0] > pb.depth[1]) {
            continue;
        }
        // Parameters of the sheets through the sample on this patch, each to be excluded.
        let mut exclude: Vec<DyadicBoxN> = Vec::new();
        match sample {
            Sample::Exact { uv, .. } => {
                let mut carriers: Vec<[Rational; 2]> = Vec::new();
                if j == own {
                    carriers.push(uv.clone());
                }
                if j != own {
                    for (edge, t) in sides_through(uv) {
                        for (tp, te, rev) in scene.twins(own, edge) {
                            if tp == j {
                                let t2 = if rev {
                                    Rational::from(1) - &t
                                } else {
                                    t.clone()
                                };
                                carriers.push(side_point(te, &t2));
                            }
                        }
                    }
                }
                for c in carriers {
                    let bx = injective_box(scene, j, &c).or_else(|| {
                        // A fold point (the Jacobian's determinant is exactly zero there): the
                        // fold lemma's box, whose fold points are alone in their fibres.
                        is_fold_point(scene, j, &c)
                            .then(|| fold_box_around(scene, j, &c, &c))
                            .flatten()
                    });
                    exclude.push(bx.ok_or_else(|| {
                        format!("the point's own sheet on patch {j} is not excluded (the image map is not provably injective near it)")
                    })?);
                }
            }
            Sample::Silhouette {
                axis, at, interval, ..
            } => {
                if j == own {
                    exclude.push(fold_box(scene, j, *axis, at, interval).ok_or_else(|| {
                        format!(
                            "the fold lemma does not hold near the silhouette point on patch {j}"
                        )
                    })?);
                }
            }
        }
        let (front, back) = hits_on_ray(scene, &ps, j, &exclude, opts)?;
        count += front;
        if let Ok(all) = &mut hits {
            match back {
                Ok(b) => all.extend(b),
                Err(e) => hits = Err(e),
            }
        }
    }
    Ok(Layers {
        in_front: count,
        behind: if behind { hits } else { Ok(Vec::new()) },
    })
}

/// Whether the image map of patch `j` is singular at exact parameters (its Jacobian's
/// numerator determinant is exactly zero: a point of the silhouette, a fold point).
fn is_fold_point(scene: &Scene, j: usize, uv: &[Rational; 2]) -> bool {
    let m = &scene.jacobians[j];
    let e = |p: &Poly| p.eval(uv);
    Rational::from(&e(&m[0][0]) * &e(&m[1][1])) == Rational::from(&e(&m[0][1]) * &e(&m[1][0]))
}

/// The sides of the square through a parameter point, with the side parameter.
fn sides_through(uv: &[Rational; 2]) -> Vec<(Edge, Rational)> {
    let mut out = Vec::new();
    let (zero, one) = (Rational::new(), Rational::from(1));
    if uv[1] == zero {
        out.push((Edge::V0, uv[0].clone()));
    }
    if uv[1] == one {
        out.push((Edge::V1, uv[0].clone()));
    }
    if uv[0] == zero {
        out.push((Edge::U0, uv[1].clone()));
    }
    if uv[0] == one {
        out.push((Edge::U1, uv[1].clone()));
    }
    out
}

fn point_bounds(ps: &PointSystem) -> ImageBounds {
    ImageBounds {
        x: ratio_bounds(&ps.image.x, &ps.image.q),
        y: ratio_bounds(&ps.image.y, &ps.image.q),
        depth: ratio_bounds(&ps.image.depth, &ps.image.w),
    }
}

/// The hits of patch `j` on the point's ray outside the excluded boxes: how many in front of
/// the point, and those behind it (or why they are not proven: a root behind near the
/// boundary of the patch).
fn hits_on_ray(
    scene: &Scene,
    ps: &PointSystem,
    j: usize,
    exclude: &[DyadicBoxN],
    opts: &RayOptions,
) -> Result<(usize, Result<Vec<Hit>, String>), String> {
    let n = ps.nvars + 2;
    let pim = &ps.image;
    let jim = &scene.images[j];
    let lp = |p: &Poly| {
        if ps.nvars == 0 {
            Bernstein::constant(n, p.coeffs()[0].clone())
        } else {
            lift(p, n, 0)
        }
    };
    let lj = |p: &Poly| lift(p, n, ps.nvars);
    let eq_x = &(&lj(&jim.x) * &lp(&pim.q)) - &(&lp(&pim.x) * &lj(&jim.q));
    let eq_y = &(&lj(&jim.y) * &lp(&pim.q)) - &(&lp(&pim.y) * &lj(&jim.q));
    let front = &(&lj(&jim.depth) * &lp(&pim.w)) - &(&lp(&pim.depth) * &lj(&jim.w));
    let mut square = vec![eq_x, eq_y];
    square.extend(ps.constraints.iter().map(|c| lift(c, n, 0)));
    let front_i: Bernstein<Interval> = front.convert(Precision::F64);
    let mut count = 0;
    let mut behind: Result<Vec<Hit>, String> = Ok(Vec::new());
    let mut domain = ps.domain.clone();
    domain.extend([(Dyadic::ZERO, Dyadic::ONE), (Dyadic::ZERO, Dyadic::ONE)]);
    let exclude: Vec<DyadicBoxN> = exclude
        .iter()
        .map(|b| ps.domain.iter().chain(b).copied().collect())
        .collect();
    let r = solve_system_excluding(&square, &[], &domain, &exclude, &opts.system);
    if !r.unresolved.is_empty() {
        return Err(format!(
            "the ray meets patch {j} where its intersections are not isolated (tangent to the patch, or a budget)"
        ));
    }
    for root in &r.roots {
        let inside_domain = root.inside;
        let near_excluded = exclude.iter().any(|e| {
            root.enclosure
                .iter()
                .zip(e)
                .all(|(x, d)| x[1] >= d.0.to_f64() && x[0] <= d.1.to_f64())
        });
        let lo: Vec<f64> = root.enclosure.iter().map(|e| e[0]).collect();
        let hi: Vec<f64> = root.enclosure.iter().map(|e| e[1]).collect();
        let on = front_i.restrict_box_f64(&lo, &hi);
        let c = on.coeffs();
        let is_behind = c.iter().all(|x| x.lo() > 0.0);
        let near = || {
            format!(
                "the ray passes within {:.1e} of the boundary of patch {j} (or of the box around the point's own sheet)",
                root.enclosure.iter().map(|e| e[1] - e[0]).fold(0.0, f64::max)
            )
        };
        if is_behind {
            if !inside_domain || near_excluded {
                behind = Err(near());
            } else if let Ok(b) = &mut behind {
                let uv = [root.enclosure[ps.nvars], root.enclosure[ps.nvars + 1]];
                b.push(Hit {
                    patch: j,
                    uv,
                    depth: depth_on(&jim.depth, &jim.w, uv),
                });
            }
            continue;
        }
        if !inside_domain || near_excluded {
            return Err(near());
        }
        if c.iter().all(|x| x.hi() < 0.0) {
            count += 1;
        } else {
            return Err(format!(
                "the ray meets patch {j} at the depth of the point (the point may lie on patch {j})"
            ));
        }
    }
    Ok((count, behind))
}

/// An enclosure of `depth / w` on a parameter box (`w > 0`).
fn depth_on(depth: &Poly, w: &Poly, uv: [[f64; 2]; 2]) -> [f64; 2] {
    let (lo, hi) = ([uv[0][0], uv[1][0]], [uv[0][1], uv[1][1]]);
    let on = |p: &Poly| range_on(&p.convert(Precision::F64), &lo, &hi);
    match on(depth).checked_div(&on(w)) {
        Some(d) => [d.lo(), d.hi()],
        None => [f64::NEG_INFINITY, f64::INFINITY],
    }
}

/// The interval range of a polynomial on a box given by f64 bounds.
pub(crate) fn range_on(p: &Bernstein<Interval>, lo: &[f64], hi: &[f64]) -> Interval {
    p.restrict_box_f64(lo, hi).hull()
}

/// Boxes `[c − 2^-k, c + 2^-k] ∩ [0, 1]` around a dyadic parameter point, coarse to fine.
fn boxes_around(lo: &[Rational; 2], hi: &[Rational; 2]) -> Vec<DyadicBoxN> {
    let mut out = Vec::new();
    for k in 3..=22u32 {
        let mut r = Rational::from(1);
        r >>= k;
        let clamp = |x: Rational| -> Rational {
            if x < 0 {
                Rational::new()
            } else if x > 1 {
                Rational::from(1)
            } else {
                x
            }
        };
        let b: Option<DyadicBoxN> = (0..2)
            .map(|a| {
                let l = clamp(Rational::from(&lo[a] - &r));
                let h = clamp(Rational::from(&hi[a] + &r));
                Some((dy(&l)?, dy(&h)?))
            })
            .collect();
        if let Some(b) = b {
            out.push(b);
        }
    }
    out
}

fn f64_box(b: &DyadicBoxN) -> (Vec<f64>, Vec<f64>) {
    (
        b.iter().map(|d| d.0.to_f64()).collect(),
        b.iter().map(|d| d.1.to_f64()).collect(),
    )
}

/// A box around `c` on which the image map of patch `j` is injective (its interval Jacobian
/// is regular: by the mean value theorem, `F(w₁) − F(w₂) = M (w₁ − w₂)` with the rows of M
/// gradients of the image coordinates at points of the segment, and each row a positive
/// multiple of a row of the numerator Jacobian), or `None`.
pub fn injective_box(scene: &Scene, j: usize, c: &[Rational; 2]) -> Option<DyadicBoxN> {
    injective_box_around(scene, j, c, c)
}

/// [`injective_box`] around a parameter box `[lo, hi]` (dyadic corners).
pub fn injective_box_around(
    scene: &Scene,
    j: usize,
    lo: &[Rational; 2],
    hi: &[Rational; 2],
) -> Option<DyadicBoxN> {
    let jac: Vec<Bernstein<Interval>> = scene.jacobians[j]
        .iter()
        .flatten()
        .map(|p| p.convert(Precision::F64))
        .collect();
    boxes_around(lo, hi).into_iter().find(|b| {
        let (lo, hi) = f64_box(b);
        let r: Vec<Interval> = jac.iter().map(|p| range_on(p, &lo, &hi)).collect();
        let det = r[0].mul(&r[3]).sub(&r[1].mul(&r[2]));
        det.lo() > 0.0 || det.hi() < 0.0
    })
}

/// The jet of `k / q` from the jets of `k` and `q` (q > 0), by differentiating `k = f q`.
pub(crate) fn quotient_jet(k: &[Interval; 6], q: &[Interval; 6]) -> Option<[Interval; 6]> {
    let iq = q[0].recip()?;
    let f = k[0].mul(&iq);
    let fu = k[1].sub(&f.mul(&q[1])).mul(&iq);
    let fv = k[2].sub(&f.mul(&q[2])).mul(&iq);
    let two = Interval::point(2.0);
    let fuu = k[3]
        .sub(&two.mul(&fu).mul(&q[1]))
        .sub(&f.mul(&q[3]))
        .mul(&iq);
    let fuv = k[4]
        .sub(&fu.mul(&q[2]))
        .sub(&fv.mul(&q[1]))
        .sub(&f.mul(&q[4]))
        .mul(&iq);
    let fvv = k[5]
        .sub(&two.mul(&fv).mul(&q[2]))
        .sub(&f.mul(&q[5]))
        .mul(&iq);
    Some([f, fu, fv, fuu, fuv, fvv])
}

fn strict(i: &Interval) -> bool {
    i.lo() > 0.0 || i.hi() < 0.0
}

/// A box around the silhouette point of patch `j` on the line `axis = at` (free parameter in
/// `interval`) on which the fold lemma holds (`proofs/ray-count.md`), or `None`.
pub fn fold_box(
    scene: &Scene,
    j: usize,
    axis: usize,
    at: &Rational,
    interval: &[Rational; 2],
) -> Option<DyadicBoxN> {
    let mut lo = [at.clone(), at.clone()];
    let mut hi = [at.clone(), at.clone()];
    lo[1 - axis] = interval[0].clone();
    hi[1 - axis] = interval[1].clone();
    fold_box_around(scene, j, &lo, &hi)
}

/// A box around the parameter box `[lo, hi]` (dyadic corners) of patch `j` on which the fold
/// lemma holds (`proofs/ray-count.md`): the fibre of every fold point in it is that point
/// alone. `None` if not proven.
pub fn fold_box_around(
    scene: &Scene,
    j: usize,
    lo: &[Rational; 2],
    hi: &[Rational; 2],
) -> Option<DyadicBoxN> {
    let mid: Vec<Rational> = (0..2)
        .map(|a| {
            let mut m = Rational::from(&lo[a] + &hi[a]);
            m >>= 1u32;
            m
        })
        .collect();
    let polys = FoldPolys::at(scene, j, &mid)?;
    boxes_around(lo, hi).into_iter().find(|b| {
        let (blo, bhi) = f64_box(b);
        polys.holds(&blo, &bhi)
    })
}

/// The image direction along which the outline of patch `j` runs near the parameter point
/// `mid`, approximately: a nonzero column of the Jacobian there (at a fold both columns are
/// parallel to the outline tangent). `None` if the Jacobian vanishes there.
pub(crate) fn outline_direction(scene: &Scene, j: usize, mid: &[Rational]) -> Option<[f64; 2]> {
    let jac = &scene.jacobians[j];
    let g = |p: &Poly| p.eval(mid).to_f64();
    let cu = [g(&jac[0][0]), g(&jac[1][0])];
    let cv = [g(&jac[0][1]), g(&jac[1][1])];
    let t = if cu[0].hypot(cu[1]) >= cv[0].hypot(cv[1]) {
        cu
    } else {
        cv
    };
    let norm = t[0].hypot(t[1]);
    (norm.is_finite() && norm > 0.0).then_some(t)
}

/// κ, η, q and their first and second partial derivatives, in interval form: what the fold
/// lemma is checked on (`proofs/ray-count.md`).
pub(crate) struct FoldPolys {
    kappa: [Bernstein<Interval>; 6],
    eta: [Bernstein<Interval>; 6],
    q: [Bernstein<Interval>; 6],
}

impl FoldPolys {
    /// The polynomials of patch `j`, with the image rotated so that κ runs along the
    /// outline's direction at the parameter point `mid` (approximately: a nonzero column of
    /// the Jacobian there, which at a fold is parallel to the outline tangent). The lemma is
    /// proven for whatever rotation is chosen; a good one only makes it succeed. `None` if
    /// the Jacobian vanishes there.
    pub(crate) fn at(scene: &Scene, j: usize, mid: &[Rational]) -> Option<FoldPolys> {
        FoldPolys::along(scene, j, outline_direction(scene, j, mid)?)
    }

    /// The polynomials of patch `j` with κ along the image direction `t` (rounded to a
    /// rational direction on a grid of 1/1024), or `None` if that rounds to zero.
    pub(crate) fn along(scene: &Scene, j: usize, t: [f64; 2]) -> Option<FoldPolys> {
        let im = &scene.images[j];
        let norm = t[0].hypot(t[1]);
        if norm.is_nan() || norm <= 0.0 {
            return None;
        }
        let r =
            |x: f64| Rational::from_f64((x / norm * 1024.0).round() / 1024.0).unwrap_or_default();
        let (tx, ty) = (r(t[0]), r(t[1]));
        if tx == 0 && ty == 0 {
            return None;
        }
        // κ along the outline, η across it.
        let kappa = &im.x.scale(&tx) + &im.y.scale(&ty);
        let eta = &im.y.scale(&tx) - &im.x.scale(&ty);
        Some(FoldPolys::new(&kappa, &eta, &im.q))
    }

    /// Whether the fold lemma holds on the box: then the fibre, within the box, of every
    /// fold point in it is that point alone.
    pub(crate) fn holds(&self, lo: &[f64], hi: &[f64]) -> bool {
        self.holds_within(lo, hi, 3)
    }

    /// [`FoldPolys::holds`], with the box halved at most `depth` times to prove it.
    pub(crate) fn holds_within(&self, lo: &[f64], hi: &[f64], depth: u32) -> bool {
        fold_signs(self, lo, hi, depth).is_some()
    }

    fn new(kappa: &Poly, eta: &Poly, q: &Poly) -> FoldPolys {
        let all = |p: &Poly| -> [Bernstein<Interval>; 6] {
            let (pu, pv) = (p.deriv(0), p.deriv(1));
            [
                p.clone(),
                pu.clone(),
                pv.clone(),
                pu.deriv(0),
                pu.deriv(1),
                pv.deriv(1),
            ]
            .map(|x| x.convert(Precision::F64))
        };
        FoldPolys {
            kappa: all(kappa),
            eta: all(eta),
            q: all(q),
        }
    }
}

/// The strict signs of `(κ_u, κ_v, C)` on a box, where `C = κ_v³ · (second derivative of η
/// along the level curves of κ)`, proven on the box or on a cover of it by sub-boxes
/// (halved up to `depth` times) that all agree; `None` if not proven.
fn fold_signs(p: &FoldPolys, lo: &[f64], hi: &[f64], depth: u32) -> Option<[bool; 3]> {
    let jet = |f: &[Bernstein<Interval>; 6]| jet_on(f, lo, hi);
    let q = jet(&p.q);
    let here = (|| {
        let k = quotient_jet(&jet(&p.kappa), &q)?;
        let h = quotient_jet(&jet(&p.eta), &q)?;
        let (ku, kv) = (k[1], k[2]);
        let two = Interval::point(2.0);
        let form = |f: &[Interval; 6]| {
            f[3].mul(&kv.mul(&kv))
                .sub(&two.mul(&f[4]).mul(&ku).mul(&kv))
                .add(&f[5].mul(&ku.mul(&ku)))
        };
        let c = kv.mul(&form(&h)).sub(&h[2].mul(&form(&k)));
        [ku, kv, c]
            .iter()
            .all(strict)
            .then(|| [ku.lo() > 0.0, kv.lo() > 0.0, c.lo() > 0.0])
    })();
    if here.is_some() || depth == 0 {
        return here;
    }
    let mid = [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])];
    let mut common: Option<[bool; 3]> = None;
    for (u0, u1) in [(lo[0], mid[0]), (mid[0], hi[0])] {
        for (v0, v1) in [(lo[1], mid[1]), (mid[1], hi[1])] {
            let s = fold_signs(p, &[u0, v0], &[u1, v1], depth - 1)?;
            if common.is_some_and(|c| c != s) {
                return None;
            }
            common = Some(s);
        }
    }
    common
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Format;
    use crate::solver::precision::Ladder;
    use crate::solver::univariate::{isolate_roots, refine_root, Root};
    use crate::surface::RationalPatch;
    use crate::testing::shapes;

    fn q(n: i64, d: i64) -> Rational {
        Rational::from((n, d))
    }

    fn scene_of(patches: Vec<RationalPatch>, view: [i64; 3]) -> Scene {
        let model = Model::from_patches(Format::Json, patches);
        Scene::new(
            &model,
            &View::Direction(view.map(Rational::from)),
            WeldTolerance::Exact,
        )
        .unwrap()
    }

    fn shifted(patches: Vec<RationalPatch>, by: [i64; 3]) -> Vec<RationalPatch> {
        patches
            .into_iter()
            .map(|p| p.map_points(|x| std::array::from_fn(|k| Rational::from(&x[k] + by[k]))))
            .collect()
    }

    fn exact(patch: usize, u: Rational, v: Rational) -> Sample {
        Sample::Exact { patch, uv: [u, v] }
    }

    #[test]
    fn a_sphere_seen_from_above_hides_its_lower_half() {
        let s = scene_of(shapes::sphere(&Rational::from(1)), [0, 0, -1]);
        let opts = RayOptions::default();
        for p in 0..8 {
            let n = layers_in_front(&s, &exact(p, q(1, 2), q(1, 2)), &opts).unwrap();
            // Patches 0-3 are the southern hemisphere.
            assert_eq!(n, usize::from(p < 4), "patch {p}");
        }
    }

    #[test]
    fn a_point_on_a_shared_side_does_not_count_its_neighbour() {
        let s = scene_of(shapes::sphere(&Rational::from(1)), [1, 2, -3]);
        let opts = RayOptions::default();
        // The side u = 1 of a northern patch is shared with the next one around.
        for p in 4..8 {
            let r = layers_in_front(&s, &exact(p, Rational::from(1), q(3, 8)), &opts);
            let here = layers_in_front(&s, &exact(p, q(15, 16), q(3, 8)), &opts);
            assert!(r.is_ok() && here.is_ok(), "patch {p}: {r:?} {here:?}");
        }
    }

    #[test]
    fn a_sphere_behind_another_is_hidden_twice() {
        let mut patches = shapes::sphere(&Rational::from(1));
        patches.extend(shifted(shapes::sphere(&Rational::from(1)), [0, 0, -3]));
        let s = scene_of(patches, [0, 0, -1]);
        let opts = RayOptions::default();
        // The lower sphere's northern patches (12-15) at latitude ~45°: behind both sheets of
        // the upper sphere.
        for p in 12..16 {
            assert_eq!(
                layers_in_front(&s, &exact(p, q(1, 2), q(1, 2)), &opts),
                Ok(2)
            );
        }
        // Its southern patches: three sheets in front.
        assert_eq!(
            layers_in_front(&s, &exact(9, q(1, 2), q(1, 2)), &opts),
            Ok(3)
        );
    }

    /// Silhouette samples on the lines u = k/8 of every patch.
    fn silhouette_samples(s: &Scene, model: &Model) -> Vec<Sample> {
        let mut out = Vec::new();
        for (i, p) in model.patches.iter().enumerate() {
            let g = super::super::silhouette::silhouette_function(&p.surface, &s.projection.view);
            for k in 1..8 {
                let at = q(k, 8);
                let line = fix_axis(&g, 0, &at);
                let roots = isolate_roots(&line, &Ladder::default(), 40, &mut Default::default());
                for r in roots.roots {
                    let r =
                        refine_root(&line, r, 1e-12, &Ladder::default(), &mut Default::default());
                    if let Root::Between { lo, hi } = r {
                        let interval = [lo.to_rational(), hi.to_rational()];
                        out.push(Sample::Silhouette {
                            patch: i,
                            axis: 0,
                            at: at.clone(),
                            interval,
                            g: g.clone(),
                        });
                    }
                }
            }
        }
        out
    }

    #[test]
    fn the_silhouette_of_a_sphere_is_visible() {
        let model = Model::from_patches(Format::Json, shapes::sphere(&Rational::from(1)));
        let s = Scene::new(
            &model,
            &View::Direction([1, 2, 3].map(Rational::from)),
            WeldTolerance::Exact,
        )
        .unwrap();
        let samples = silhouette_samples(&s, &model);
        assert!(samples.len() >= 4, "{}", samples.len());
        for smp in &samples {
            assert_eq!(
                layers_in_front(&s, smp, &RayOptions::default()),
                Ok(0),
                "{smp:?}"
            );
        }
    }

    #[test]
    fn the_silhouette_of_a_sphere_behind_another_is_hidden_where_it_passes_behind() {
        // A second unit sphere behind the first and shifted sideways: its outline passes
        // behind the first sphere's disc over part of its length.
        let mut patches = shapes::sphere(&Rational::from(1));
        patches.extend(shifted(shapes::sphere(&Rational::from(1)), [1, 0, -4]));
        let model = Model::from_patches(Format::Json, patches);
        let dir = [1, 2, -6];
        let view = View::Direction(dir.map(Rational::from));
        let s = Scene::new(&model, &view, WeldTolerance::Exact).unwrap();
        let d = super::super::vec3::normalize(dir.map(|x| x as f64));
        let mut seen = [0, 0, 0];
        let samples = silhouette_samples(&s, &model);
        for smp in samples.iter().filter(|x| x.patch() >= 8) {
            let Sample::Silhouette {
                patch,
                at,
                interval,
                ..
            } = smp
            else {
                unreachable!()
            };
            let mut mid = Rational::from(&interval[0] + &interval[1]);
            mid >>= 1u32;
            let pt = model.patches[*patch]
                .surface
                .eval(at, &mid)
                .map(|c| c.to_f64());
            // Analytic: the ray P − t d (t > 0, toward the viewer) meets the unit sphere at
            // the origin iff |P − t d|² = 1 has a positive root; then it crosses two sheets.
            let pd = super::super::vec3::dot(pt, d);
            let disc = pd * pd - (super::super::vec3::dot(pt, pt) - 1.0);
            let hidden = disc > 0.0 && pd > 0.0;
            // Samples within 1e-6 of the first sphere's outline are not asserted.
            if disc.abs() < 1e-6 {
                continue;
            }
            let n = layers_in_front(&s, smp, &RayOptions::default())
                .unwrap_or_else(|e| panic!("{e}: {patch} {at} {mid}"));
            assert_eq!(n, if hidden { 2 } else { 0 }, "{smp:?} at {pt:?}");
            seen[n] += 1;
        }
        assert!(seen[0] > 0 && seen[2] > 0, "{seen:?}");
    }
}
