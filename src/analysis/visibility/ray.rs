//! Certified ray tests: how many surface layers lie in front of a point of a model, along the
//! viewing ray through it (its quantitative invisibility, QI).
//!
//! For a sample point `p` and each patch `j` whose image box and depth range can meet the ray,
//! the points of `j` with the image of `p` are the roots of the square system
//! `x_j q_p − x_p q_j = 0`, `y_j q_p − y_p q_j = 0` (see [`crate::analysis::projection`]), isolated by
//! the certified system solver ([`solve_system`](crate::solver::system::solve_system), `proofs/krawczyk.md`); each
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

pub use crate::analysis::projection::fix_axis;
use crate::analysis::projection::{side_point, ImagePolys};
use crate::analysis::visibility::scene::{ratio_bounds, ImageBounds, Scene};
use crate::analysis::visibility::sheets::{
    fold_box, fold_box_around, injective_box, injective_box_around, range_on,
};
use crate::bernstein::lift;
use crate::bernstein::Bernstein;
use crate::bernstein::Poly;
use crate::geometry::Rect;
use crate::number::margin;
use crate::number::{Interval, Number, Precision, Rational};
use crate::reason::Reason;
use crate::solver::dyadic::Dyadic;
use crate::solver::point_in_face::Membership;
use crate::solver::system::{solve_system_excluding, DyadicBoxN, SystemOptions, SystemRoots};
use crate::surface::Edge;

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
    /// A point of a trimming curve of a patch's face at exact parameters, not on its
    /// silhouette: as [`Sample::Exact`], and a point of another face within the scene's
    /// [`Scene::trim_contact`] of it is taken to be the point itself (the faces meet there).
    Trim {
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
    /// A point where two patches meet (a point of their intersection curve,
    /// [`crate::analysis::intersection`]): in their parameters `(u, v, s, t)`, variable `axis`
    /// is `at` and the other three are the only root in `cell` of the curve's three equations.
    Meet {
        /// The two patches, `(u, v)` on the first and `(s, t)` on the second.
        patches: [usize; 2],
        /// The fixed variable (0 to 3).
        axis: usize,
        /// Its value (dyadic).
        at: Rational,
        /// The isolating box of the other three variables, in order (dyadic ends).
        cell: [[Rational; 2]; 3],
        /// The curve's equations ([`crate::analysis::intersection::intersection_system`])
        /// with variable `axis` at `at`: in the other three, in order.
        fixed: std::sync::Arc<Vec<Poly>>,
    },
}

/// Budgets of a ray test.
#[derive(Clone, Debug)]
#[non_exhaustive]
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
                ..SystemOptions::default()
            },
        }
    }
}

/// The point's image polynomials in its own free variables (none for an exact point: then
/// constants), the box of those variables, and its constraints.
struct PointSystem {
    /// Number of free variables (0, 1, or 3 for a point where two patches meet).
    nvars: usize,
    /// Image polynomials in the free variables (constant polynomials in 1 variable if none).
    image: ImagePolys,
    /// The free variables' box.
    domain: DyadicBoxN,
    /// Constraints on the free variables (the silhouette function on the line).
    constraints: Vec<Poly>,
}

impl Sample {
    /// An enclosure of the sample's parameters on its patch (rounded outwards).
    pub fn uv_enclosure(&self) -> Rect {
        let r = |q: &Rational| [q.lower_f64(), q.upper_f64()];
        match self {
            Sample::Exact { uv, .. } | Sample::Trim { uv, .. } => {
                Rect::from_axes(r(&uv[0]), r(&uv[1]))
            }
            Sample::Meet { .. } => {
                let [lo, hi] = self.meet_box(0).expect("a point of two patches");
                Rect::from_axes(
                    [lo[0].lower_f64(), hi[0].upper_f64()],
                    [lo[1].lower_f64(), hi[1].upper_f64()],
                )
            }
            Sample::Silhouette {
                axis, at, interval, ..
            } => {
                let mut out = Rect::from_axes(r(at), r(at));
                out.set_axis(1 - axis, [interval[0].lower_f64(), interval[1].upper_f64()]);
                out
            }
        }
    }
}

pub(crate) fn dy(q: &Rational) -> Option<Dyadic> {
    Dyadic::from_rational(q)
}

impl Sample {
    /// The patch the sample lies on (the first, for a point where two patches meet).
    pub fn patch(&self) -> usize {
        match self {
            Sample::Exact { patch, .. }
            | Sample::Trim { patch, .. }
            | Sample::Silhouette { patch, .. } => *patch,
            Sample::Meet { patches, .. } => patches[0],
        }
    }

    /// For a point where two patches meet: its parameter box `[lo, hi]` on the first
    /// (`side` 0) or the second (`side` 1) patch.
    pub fn meet_box(&self, side: usize) -> Option<[[Rational; 2]; 2]> {
        let Sample::Meet { axis, at, cell, .. } = self else {
            return None;
        };
        let mut others = cell.iter();
        let all: Vec<[Rational; 2]> = (0..4)
            .map(|k| {
                if k == *axis {
                    [at.clone(), at.clone()]
                } else {
                    others.next().expect("three free variables").clone()
                }
            })
            .collect();
        let (a, b) = (&all[2 * side], &all[2 * side + 1]);
        Some([[a[0].clone(), b[0].clone()], [a[1].clone(), b[1].clone()]])
    }

    fn system(&self, scene: &Scene) -> Option<PointSystem> {
        let im = &scene.images[self.patch()];
        match self {
            Sample::Exact { uv, .. } | Sample::Trim { uv, .. } => Some(PointSystem {
                nvars: 0,
                image: im.map(|p| Bernstein::constant(1, p.eval(uv))),
                domain: Vec::new(),
                constraints: Vec::new(),
            }),
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
            Sample::Meet {
                axis,
                at,
                cell,
                fixed,
                ..
            } => {
                let domain: Option<DyadicBoxN> = cell
                    .iter()
                    .map(|c| Some((dy(&c[0])?, dy(&c[1])?)))
                    .collect();
                Some(PointSystem {
                    nvars: 3,
                    // The first patch's image in the three free variables.
                    image: im.map(|p| {
                        if *axis < 2 {
                            lift(&crate::bernstein::fix_var(p, *axis, at), 3, 0)
                        } else {
                            lift(p, 3, 0)
                        }
                    }),
                    domain: domain?,
                    constraints: fixed.to_vec(),
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
pub fn layers_in_front(scene: &Scene, sample: &Sample, opts: &RayOptions) -> Result<usize, Reason> {
    layers(scene, sample, opts, false).map(|l| l.in_front)
}

/// A point of the model on a sample's ray, behind the sample.
#[derive(Clone, Debug, PartialEq)]
pub struct Hit {
    /// Its patch.
    pub patch: usize,
    /// An enclosure of its parameters (the only point of the patch on the ray in it).
    pub uv: Rect,
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
    pub behind: Result<Vec<Hit>, Reason>,
}

impl Layers {
    /// The nearest point behind the sample, if its depth is proven less than every other's
    /// (`Ok(None)`: nothing behind, the background).
    ///
    /// # Errors
    /// The points behind are not proven, or two of them are not proven apart in depth.
    pub fn first_behind(&self) -> Result<Option<&Hit>, Reason> {
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
            Err(Reason::DepthsNotApart)
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
) -> Result<Layers, Reason> {
    let ps = sample.system(scene).ok_or(Reason::SampleNotDyadic)?;
    let own = sample.patch();
    // The sample's depth range and image box, to skip patches that cannot be in front.
    let pb = point_bounds(&ps);
    let mut count = 0;
    let mut hits: Result<Vec<Hit>, Reason> = if behind {
        Ok(Vec::new())
    } else {
        Err(Reason::NotAsked)
    };
    for (j, jb) in scene.bounds.iter().enumerate() {
        if !jb.meets_image(&pb) || (!behind && jb.depth[0] > pb.depth[1]) {
            continue;
        }
        // Parameters of the sheets through the sample on this patch, each to be excluded.
        let mut exclude: Vec<DyadicBoxN> = Vec::new();
        match sample {
            Sample::Exact { uv, .. } | Sample::Trim { uv, .. } => {
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
                    exclude.push(bx.ok_or(Reason::OwnSheet { patch: j })?);
                }
            }
            Sample::Silhouette {
                axis, at, interval, ..
            } => {
                if j == own {
                    exclude.push(
                        fold_box(scene, j, *axis, at, interval)
                            .ok_or(Reason::FoldLemma { patch: j })?,
                    );
                }
            }
            Sample::Meet { patches, .. } => {
                // The point is on both patches: on each, a box around its parameters where
                // the image map is injective holds no other point with its image
                // (`proofs/ray-count.md`). A point on a side of either is also on the patch
                // across: that patch's root at depth zero refuses the sample.
                for (side, &p) in patches.iter().enumerate() {
                    if j == p {
                        let [lo, hi] = sample.meet_box(side).expect("a point of two patches");
                        exclude.push(
                            injective_box_around(scene, j, &lo, &hi)
                                .ok_or(Reason::OwnSheet { patch: j })?,
                        );
                    }
                }
            }
        }
        // No sheet of the sample on this patch, and no cell of the patch whose image can hold
        // the sample's (in front of it, when only the count is asked): no hit to count
        // (`proofs/ray-count.md`, "Cells").
        let missed = exclude.is_empty()
            && scene
                .leaf_bounds(j)
                .iter()
                .all(|c| !c.meets_image(&pb) || (!behind && c.depth[0] > pb.depth[1]));
        if missed {
            continue;
        }
        let contact = match sample {
            Sample::Trim { uv, .. } if j != own => contact_point(scene, own, uv),
            _ => None,
        };
        let (front, back) = hits_on_ray(scene, &ps, j, &exclude, contact.as_ref(), opts, behind)?;
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

/// The image box and depth range of the point: of its image polynomials on the box of its
/// free variables (the point lies in it).
fn point_bounds(ps: &PointSystem) -> ImageBounds {
    let lo: Vec<Rational> = ps.domain.iter().map(|d| d.0.to_rational()).collect();
    let hi: Vec<Rational> = ps.domain.iter().map(|d| d.1.to_rational()).collect();
    let on = |p: &Poly| {
        if ps.nvars == 0 {
            p.clone()
        } else {
            p.restrict_box_rational(&lo, &hi)
        }
    };
    ImageBounds {
        x: ratio_bounds(&on(&ps.image.x), &on(&ps.image.q)),
        y: ratio_bounds(&on(&ps.image.y), &on(&ps.image.q)),
        depth: ratio_bounds(&on(&ps.image.depth), &on(&ps.image.w)),
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
    contact: Option<&[Interval; 3]>,
    opts: &RayOptions,
    want_behind: bool,
) -> Result<(usize, Result<Vec<Hit>, Reason>), Reason> {
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
    let mut domain = ps.domain.clone();
    domain.extend([(Dyadic::ZERO, Dyadic::ONE), (Dyadic::ZERO, Dyadic::ONE)]);
    let exclude: Vec<DyadicBoxN> = exclude
        .iter()
        .map(|b| ps.domain.iter().chain(b).copied().collect())
        .collect();
    let decide = |r: &SystemRoots| ray_hits(scene, r, ps, j, &front_i, &exclude, contact);
    // Lazily refined: the roots are first refined only to a coarse width; if every decision
    // below holds on those enclosures it is proven (each enclosure holds its root), and only
    // otherwise is the system solved again with the roots refined to the full width. The
    // points behind, when asked, keep the full width (their depths are compared).
    if !want_behind {
        let coarse = SystemOptions {
            refine_width: COARSE_WIDTH.max(opts.system.refine_width),
            ..opts.system.clone()
        };
        let r = solve_system_excluding(&square, &[], &domain, &exclude, &coarse);
        if r.unresolved.is_empty() {
            if let Ok(decided) = decide(&r) {
                return Ok(decided);
            }
        }
    }
    let r = solve_system_excluding(&square, &[], &domain, &exclude, &opts.system);
    decide(&r)
}

/// The width to which a ray test first refines its roots ([`hits_on_ray`]).
const COARSE_WIDTH: f64 = 1e-6;

/// What the roots of a point's ray on patch `j` say: how many hits lie in front of the point,
/// and those behind it (or why they are not proven); an error where a root is not decided.
fn ray_hits(
    scene: &Scene,
    r: &SystemRoots,
    ps: &PointSystem,
    j: usize,
    front_i: &Bernstein<Interval>,
    exclude: &[DyadicBoxN],
    contact: Option<&[Interval; 3]>,
) -> Result<(usize, Result<Vec<Hit>, Reason>), Reason> {
    let jim = &scene.images[j];
    // On a trimmed patch, only the points in its faces are surface (`proofs/hidden-lines.md`,
    // "Trimmed faces"); an unresolved box outside them holds none.
    let uv_of = |e: &[[f64; 2]]| Rect::from_axes(e[ps.nvars], e[ps.nvars + 1]);
    if r.unresolved
        .iter()
        .any(|b| scene.membership(j, &uv_of(b)) != Membership::Outside)
    {
        return Err(Reason::RayIntersections { patch: j });
    }
    let mut count = 0;
    let mut behind: Result<Vec<Hit>, Reason> = Ok(Vec::new());
    for root in &r.roots {
        let uv = uv_of(&root.enclosure);
        // A point of another face within the contact distance of a sample on a trimming
        // curve is the sample's own point (the faces meet there).
        if let Some(p) = contact {
            match within(scene, j, &uv, p) {
                Some(true) => continue,
                Some(false) => {}
                None => return Err(Reason::HitInFace { patch: j }),
            }
        }
        match scene.membership(j, &uv) {
            Membership::Outside => continue,
            Membership::Undecided => return Err(Reason::HitInFace { patch: j }),
            Membership::Inside => {}
        }
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
        let near = || Reason::RayNearBoundary {
            patch: j,
            distance: root
                .enclosure
                .iter()
                .map(|e| e[1] - e[0])
                .fold(0.0, f64::max),
        };
        if is_behind {
            if !inside_domain || near_excluded {
                behind = Err(near());
            } else if let Ok(b) = &mut behind {
                let uv = Rect::from_axes(root.enclosure[ps.nvars], root.enclosure[ps.nvars + 1]);
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
            return Err(Reason::RayAtDepth { patch: j });
        }
    }
    Ok((count, behind))
}

/// The space point of a sample on a trimming curve, for the contact rule: `None` when the
/// scene has no faces (no rule).
fn contact_point(scene: &Scene, own: usize, uv: &[Rational; 2]) -> Option<[Interval; 3]> {
    let patch = scene.surfaces.get(own)?;
    let r = |q: &Rational| [q.lower_f64(), q.upper_f64()];
    let (a, b) = (r(&uv[0]), r(&uv[1]));
    patch.enclosure([a[0], b[0]], [a[1], b[1]])
}

/// Whether every point of patch `j` over `uv` lies within the scene's contact distance of
/// every point of the box `p` (`Some(true)`), none can (`Some(false)`: the nearest points
/// are farther), or neither is proven (`None`).
fn within(scene: &Scene, j: usize, uv: &Rect, p: &[Interval; 3]) -> Option<bool> {
    let q = scene.surfaces.get(j)?.enclosure(
        [uv.axis(0)[0], uv.axis(1)[0]],
        [uv.axis(0)[1], uv.axis(1)[1]],
    )?;
    let d = scene.trim_contact;
    let (mut far, mut near) = (0.0f64, 0.0f64);
    for k in 0..3 {
        let diff = q[k].sub(&p[k]);
        let most = diff.lo().abs().max(diff.hi().abs());
        let least = if diff.lo() > 0.0 {
            diff.lo()
        } else if diff.hi() < 0.0 {
            -diff.hi()
        } else {
            0.0
        };
        far = margin::up(far + margin::up(most * most, margin::FEW), margin::FEW);
        near = margin::down(near + margin::down(least * least, margin::FEW), margin::FEW);
    }
    if margin::up(far.sqrt(), margin::FEW) <= d {
        Some(true)
    } else if margin::down(near.sqrt(), margin::FEW) > d {
        Some(false)
    } else {
        None
    }
}

/// An enclosure of `depth / w` on a parameter box (`w > 0`).
fn depth_on(depth: &Poly, w: &Poly, uv: Rect) -> [f64; 2] {
    let on = |p: &Poly| range_on(&p.convert(Precision::F64), &uv.lo, &uv.hi);
    match on(depth).checked_div(&on(w)) {
        Some(d) => [d.lo(), d.hi()],
        None => [f64::NEG_INFINITY, f64::INFINITY],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::view::View;
    use crate::model::Format;
    use crate::model::{Model, WeldTolerance};
    use crate::solver::precision::{Ladder, Policy};
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
            let g = crate::analysis::contour::silhouette::silhouette_function(
                &p.surface,
                &s.projection.view,
            );
            for k in 1..8 {
                let at = q(k, 8);
                let line = fix_axis(&g, 0, &at);
                let (ladder, mut counts) = (Ladder::default(), Default::default());
                let mut policy = Policy::new(&ladder, &mut counts);
                let roots = isolate_roots(&line, 40, &mut policy);
                for r in roots.roots {
                    let r = refine_root(&line, r, 1e-12, &mut policy);
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
        let d = crate::geometry::vec3::normalize(dir.map(|x| x as f64));
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
            let pd = crate::geometry::vec3::dot(pt, d);
            let disc = pd * pd - (crate::geometry::vec3::dot(pt, pt) - 1.0);
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
