//! Certified topology of a curve in n variables: the common zeros of `n − 1` polynomials
//! `F = (F₁, …, F_{n−1})` on the unit box `[0, 1]ⁿ` (flecnodal curves in `(u, v, s)`,
//! bitangents in `(u, v, s, t)`).
//!
//! Subdivision into dyadic boxes with exclusion (some `F_j` has Bernstein coefficients of one
//! strict sign), and a certified test that a box holds only smooth pieces of the curve that are
//! graphs over one variable `x_i`: the `(n−1)×(n−1)` minor of the interval Jacobian without
//! column `i` is a regular interval matrix (`‖I − C J‖∞ < 1`), so every slice `x_i = c` meets
//! the curve at most once in the box. The box's pieces are then the arcs between its face
//! crossings taken in order of `x_i`; the crossings are the roots of the square systems of
//! `F` on the box faces, isolated by Krawczyk's test ([`super::system`]), and two boxes name
//! one crossing when the enclosure of one lies in the uniqueness region of the other. With a
//! tolerance, a bound on the second derivative of the curve's graph (implicit differentiation
//! in interval arithmetic) bounds the distance between each arc and its chord. The guarantees
//! are in `proofs/space-curves.md`; what is not decided within the budgets (singular points,
//! the curve along a box edge or tangent to a face on a grid hyperplane) is reported unresolved
//! with its box.

use super::curve2::TIME_LIMIT_REASON;
use super::dyadic::Dyadic;
use super::star::{
    exact_singular_point, simple_points_near, star_branches, ExactPartials, HigherPartials,
    SingularPoint, StarBranch,
};
use super::system::{
    inverse, krawczyk, krawczyk_in_box, krawczyk_verdict, newton, split_box, DyadicBoxN,
    KrawczykVerdict, SystemOptions,
};
use crate::bernstein::Bernstein;
use crate::number::{Interval, Number, Precision, Rational};
use std::collections::HashMap;

/// Budgets and accuracy of the n-variable curve solver.
#[derive(Clone, Debug)]
pub struct SpaceCurveOptions {
    /// The deepest subdivision (box sides 2^-depth).
    pub max_depth: u32,
    /// The most boxes examined.
    pub max_boxes: usize,
    /// Budgets of the square systems solved on box faces (their `refine_width` is the target
    /// width of the crossings' enclosures relative to the face's).
    pub face: SystemOptions,
    /// Per variable, the largest allowed distance between an arc and its chord in that
    /// coordinate (`f64::INFINITY` where it does not matter); `None`: topology only.
    pub tolerance: Option<Vec<f64>>,
    /// Per variable, the largest allowed extent of an arc (the difference of its ends'
    /// coordinates), so that a caller can bound what depends on the chords' lengths (the
    /// bulge of a chord's image on a surface); `None`: no limit. Applied with `tolerance`.
    pub max_chord: Option<Vec<f64>>,
    /// A wall-clock time after which no box is subdivided any more.
    pub deadline: Option<std::time::Instant>,
    /// The caller's own test of an arc's accuracy, in place of the comparisons with
    /// `tolerance` and `max_chord` (which must still be set, to have deviations computed).
    pub accept: Option<ArcAccept>,
}

/// A test of an arc's accuracy from its two crossings' enclosures and its deviation per
/// variable ([`SpaceArc::deviation`]): a box whose arcs all pass is not subdivided for
/// accuracy. With it a caller subdivides until its own a-posteriori bound (the distance in
/// space, say) meets its tolerance, rather than until a priori per-variable targets do.
#[derive(Clone)]
pub struct ArcAccept(pub std::sync::Arc<AcceptFn>);

/// The function of an [`ArcAccept`]: `(from enclosure, to enclosure, deviation) -> accurate`.
pub type AcceptFn = dyn Fn(&[[f64; 2]], &[[f64; 2]], &[f64]) -> bool + Send + Sync;

impl std::fmt::Debug for ArcAccept {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("ArcAccept(..)")
    }
}

impl Default for SpaceCurveOptions {
    fn default() -> Self {
        SpaceCurveOptions {
            max_depth: 16,
            max_boxes: 200_000,
            face: SystemOptions {
                max_depth: 5,
                max_boxes: 64,
                refine_width: 1e-5,
            },
            tolerance: None,
            max_chord: None,
            deadline: None,
            accept: None,
        }
    }
}

/// A point where the curve crosses a face of a box, named once for all boxes that share it.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SpaceCrossing {
    /// The variable that is constant on the face.
    pub axis: usize,
    /// Its exact value there.
    pub at: Dyadic,
    /// A box that contains the point, `[lo, hi]` per variable (`[at, at]` on `axis`).
    pub enclosure: Vec<[f64; 2]>,
    /// On the boundary of the unit box (an end of the curve in the domain).
    pub on_boundary: bool,
    /// The region of the face hyperplane (coordinates without `axis`) where the point is the
    /// only zero of the face system: another solve of a system with the same zeros on that
    /// hyperplane names the same point when its enclosure lies here.
    pub unique_in: Vec<[f64; 2]>,
    /// An exact singular point of the curve (index into [`SpaceCurve::singular_points`]), the
    /// centre of the arcs of one box: it lies on no face of a box (`axis` is then `nvars` and
    /// `at` 0), and its arcs are the curve's branches through it (`proofs/space-curves.md` §6).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub singular: Option<usize>,
}

impl SpaceCrossing {
    /// The enclosure without the coordinate `axis` (coordinates on the face hyperplane).
    pub fn on_face(&self) -> Vec<[f64; 2]> {
        without(&self.enclosure, self.axis)
    }

    /// Whether `other`, a crossing of a system with the same zeros on the same hyperplane, is
    /// the same point (one's enclosure lies in the other's uniqueness region).
    pub fn same_point(&self, other: &SpaceCrossing) -> bool {
        self.axis == other.axis
            && self.at == other.at
            && (within(&self.on_face(), &other.unique_in)
                || within(&other.on_face(), &self.unique_in))
    }

    /// The centre of the enclosure.
    pub fn point(&self) -> Vec<f64> {
        self.enclosure.iter().map(|e| 0.5 * (e[0] + e[1])).collect()
    }
}

/// A smooth piece of the curve inside one box, between two crossings.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SpaceArc {
    /// One end (index into [`SpaceCurve::crossings`]).
    pub from: usize,
    /// The other end.
    pub to: usize,
    /// The box that contains it, `[lo, hi]` per variable.
    #[serde(rename = "box")]
    pub cell: Vec<[f64; 2]>,
    /// The variable the arc is a graph over (strictly monotone along it); `nvars` for an arc
    /// from a singular point, which is a graph over the distance from it (radially, in the
    /// box's own scale).
    pub monotone_in: usize,
    /// With a tolerance: per variable, a proven bound on the difference in that coordinate
    /// between corresponding points of the arc and of the segment between its crossings'
    /// centres, under a correspondence onto both (so the Hausdorff distance in the max norm
    /// is at most the largest entry).
    pub deviation: Option<Vec<f64>>,
}

/// A connected piece of the curve: a chain of crossings joined by arcs.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SpaceBranch {
    /// The crossings in order along the curve.
    pub crossings: Vec<usize>,
    /// A closed loop.
    pub closed: bool,
    /// Both ends lie on the boundary of the unit box (or it is closed), not at an unresolved box.
    pub complete: bool,
}

/// A box whose part of the curve was not decided.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SpaceUnresolved {
    /// The box.
    #[serde(rename = "box")]
    pub cell: Vec<[f64; 2]>,
    /// Why.
    pub reason: String,
}

/// An exact rational singular point of the curve: `F(p) = 0` and `DF(p)` of rank below `n − 1`,
/// both checked in exact arithmetic.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SpaceSingularPoint {
    /// Its exact coordinates, `"a/b"`.
    pub exact: Vec<String>,
    /// The same as rationals.
    #[serde(skip)]
    pub values: Vec<Rational>,
    /// The same in f64 (nearest).
    pub point: Vec<f64>,
    /// Its crossing (the centre of its arcs) when the star test decided a box around it;
    /// `None`: its branches are not resolved (the boxes around it are unresolved).
    pub crossing: Option<usize>,
    /// The number of branches from it (arcs of the curve ending there), when decided.
    pub branches: Option<usize>,
}

impl SpaceSingularPoint {
    /// Its exact coordinates before the solver's [`warp`] with the factors `lambda`.
    pub fn unwarped(&self, lambda: &[Rational]) -> Vec<Rational> {
        self.values
            .iter()
            .zip(lambda)
            .map(|(t, l)| unwarp_exact(t, l))
            .collect()
    }
}

/// What the n-variable curve solver found.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct SpaceCurve {
    /// The number of variables.
    pub nvars: usize,
    /// The crossings, each point once.
    pub crossings: Vec<SpaceCrossing>,
    /// The arcs.
    pub arcs: Vec<SpaceArc>,
    /// The arcs chained into branches.
    pub branches: Vec<SpaceBranch>,
    /// Boxes left undecided.
    pub unresolved: Vec<SpaceUnresolved>,
    /// The exact singular points found near undecided boxes, with their branches where the
    /// star test decided them.
    pub singular_points: Vec<SpaceSingularPoint>,
    /// Boxes examined.
    pub boxes: usize,
    /// Boxes whose polynomials were recomputed exactly (their f64 enclosures were too wide).
    pub escalations: usize,
    /// With a tolerance: every arc's deviation is within it.
    pub within_tolerance: bool,
}

impl SpaceCurve {
    /// Topology proven everywhere: no unresolved box, and every branch complete.
    pub fn is_certified(&self) -> bool {
        self.unresolved.is_empty() && self.branches.iter().all(|b| b.complete)
    }

    /// A box, `[lo, hi]` per variable, that holds the arc and the drawn segment between its
    /// crossings' centres: the arc's box, narrowed (with a tolerance) to the hull of the two
    /// centres grown by the arc's deviation (`proofs/space-curves.md` §5: every point of the
    /// arc is within `deviation_k` in coordinate `k` of a point of the segment).
    pub fn arc_tube(&self, arc: &SpaceArc) -> Vec<[f64; 2]> {
        let (a, b) = (
            self.crossings[arc.from].point(),
            self.crossings[arc.to].point(),
        );
        (0..arc.cell.len())
            .map(|k| {
                let [lo, hi] = arc.cell[k];
                match &arc.deviation {
                    Some(dev) => {
                        let (l, h) = (a[k].min(b[k]), a[k].max(b[k]));
                        let grown = [
                            Interval::point(l).sub(&Interval::point(dev[k])).lo(),
                            Interval::point(h).add(&Interval::point(dev[k])).hi(),
                        ];
                        [grown[0].max(lo), grown[1].min(hi)]
                    }
                    None => [lo, hi],
                }
            })
            .collect()
    }
}

/// A crossing as one box found it.
struct RawCrossing {
    axis: usize,
    at: Dyadic,
    enclosure: Vec<[f64; 2]>,
    /// Where it is the only root of the face system (face coordinates: `axis` left out).
    unique_in: Vec<[f64; 2]>,
    on_boundary: bool,
    /// The centre of a star: this singular point (index into the solver's list).
    singular: Option<usize>,
}

struct RawArc {
    from: usize,
    to: usize,
    cell: Vec<[f64; 2]>,
    monotone_in: usize,
    deviation: Option<Vec<f64>>,
}

/// How a box was decided.
enum Settled {
    /// Its crossings (sorted along the monotone variable), paired into arcs in that order,
    /// and whether every arc is within the tolerance. With a `center` (a singular point, §6),
    /// every crossing is joined to it instead.
    Arcs {
        center: Option<RawCrossing>,
        monotone_in: usize,
        crossings: Vec<RawCrossing>,
        deviations: Vec<Option<Vec<f64>>>,
        accurate: bool,
    },
    /// Not decided on this box (why).
    Open(&'static str),
}

struct Item {
    cell: DyadicBoxN,
    depth: u32,
    polys: Vec<Bernstein<Interval>>,
    exact: bool,
}

/// The polynomial times the lcm of its coefficients' denominators (a positive integer):
/// the same zeros, cheaper exact arithmetic.
fn integral(p: &Bernstein<Rational>) -> Bernstein<Rational> {
    let mut l = rug::Integer::from(1);
    for c in p.coeffs() {
        l.lcm_mut(c.denom());
    }
    p.scale(&Rational::from(l))
}

/// The polynomial whose zeros on `[0, 1]ⁿ` are those of `p` moved by the Möbius map
/// `u = λ t / (1 + (λ − 1) t)` in each variable (λ per variable, positive): the coefficient of
/// index `(i₀, …)` is multiplied by `Π λ_k^{i_k}`. The map fixes 0 and 1 and is increasing, so
/// the curve in `t` has the same topology, and its ends stay on the same sides. With λ ≠ 1 the
/// dyadic grid of the subdivision in `t` falls on points of `u` that are not simple fractions,
/// which curves with simple rational coefficients rarely pass through (a curve through an
/// edge of the grid leaves its boxes unresolved: `proofs/space-curves.md`).
pub fn warp(p: &Bernstein<Rational>, lambda: &[Rational]) -> Bernstein<Rational> {
    let mut out = p.clone();
    for flat in 0..p.coeffs().len() {
        let idx = p.multi_index(flat);
        let mut f = Rational::from(1);
        for (k, l) in lambda.iter().enumerate() {
            for _ in 0..idx[k] {
                f *= l;
            }
        }
        out.coeffs_mut()[flat] *= f;
    }
    out
}

/// The point `u` of the Möbius map of [`warp`] at a rational `t`, exactly:
/// `u = λ t / (1 + (λ − 1) t)`.
pub fn unwarp_exact(t: &Rational, lambda: &Rational) -> Rational {
    let num = Rational::from(lambda * t);
    let den = Rational::from(1) + Rational::from(lambda - 1u32) * t;
    num / den
}

/// The point `u` of the Möbius map of [`warp`] at `t` (f64, for drawing).
pub fn unwarp(t: f64, lambda: f64) -> f64 {
    lambda * t / (1.0 + (lambda - 1.0) * t)
}

/// An interval of `t` mapped to `u` by the map of [`warp`], rounded outward (the map is
/// increasing).
pub fn unwarp_interval(t: [f64; 2], lambda: f64) -> [f64; 2] {
    let map = |x: f64| {
        let l = Interval::point(lambda);
        let x = Interval::point(x);
        let den = Interval::point(1.0).add(&l.sub(&Interval::point(1.0)).mul(&x));
        den.recip().map(|r| l.mul(&x).mul(&r))
    };
    match (map(t[0]), map(t[1])) {
        (Some(a), Some(b)) => [a.lo().max(0.0), b.hi().min(1.0)],
        _ => [0.0, 1.0],
    }
}

/// A zero of a face system: an enclosure and a region where it is the only zero (face
/// coordinates: local while the face is solved, then global on the hyperplane).
#[derive(Clone)]
struct FaceRoot {
    enclosure: Vec<[f64; 2]>,
    unique_in: Vec<[f64; 2]>,
}

/// The polynomial on its face `x_axis = 0` (`side` false) or `= 1`, in the remaining
/// variables: exactly its Bernstein coefficients with that index at 0 or at the degree.
fn face_slice(p: &Bernstein<Interval>, axis: usize, side: bool) -> Bernstein<Interval> {
    let d = p.degrees()[axis];
    let want = if side { d } else { 0 };
    let coeffs: Vec<Interval> = (0..p.coeffs().len())
        .filter(|&k| p.multi_index(k)[axis] == want)
        .map(|k| p.coeffs()[k])
        .collect();
    let degrees: Vec<usize> = (0..p.nvars())
        .filter(|&k| k != axis)
        .map(|k| p.degrees()[k])
        .collect();
    if degrees.is_empty() {
        return Bernstein::constant(1, coeffs[0]);
    }
    Bernstein::new(&degrees, coeffs).expect("the face keeps the other degrees")
}

/// Local unit-box coordinates `[lo, hi]` mapped into the box `[a, b]`, rounded outward (an
/// enclosure keeps what it holds).
fn to_global(local: &[[f64; 2]], a: &[f64], b: &[f64]) -> Vec<[f64; 2]> {
    map_into(local, a, b, false)
}

/// The same map for a uniqueness region, rounded inward (a region must not claim more than
/// was tested; with dyadic ends the map is exact anyway).
fn to_global_inward(local: &[[f64; 2]], a: &[f64], b: &[f64]) -> Vec<[f64; 2]> {
    map_into(local, a, b, true)
}

fn map_into(local: &[[f64; 2]], a: &[f64], b: &[f64], inward: bool) -> Vec<[f64; 2]> {
    local
        .iter()
        .enumerate()
        .map(|(k, t)| {
            let w = Interval::point(b[k]).sub(&Interval::point(a[k]));
            let at = |x: f64| Interval::point(a[k]).add(&w.mul(&Interval::point(x)));
            let (lo, hi) = (at(t[0]), at(t[1]));
            if inward {
                [lo.hi(), hi.lo()]
            } else {
                [lo.lo(), hi.hi()]
            }
        })
        .collect()
}

/// The zeros of a square system given on a face (local unit coordinates, the box's own
/// interval polynomials): each with an enclosure and a region where it is the only zero, both
/// local; `None` if some part of the face was not decided within the budget. Krawczyk's test
/// is run first on each sub-box as it is (no restriction needed), then, for a zero on a
/// sub-box side, on the sub-box grown by an eighth (restricted by extrapolation: the interval
/// polynomials enclose the exact ones there too); a zero found twice is recognised by its
/// enclosure lying in the other's uniqueness region (`proofs/krawczyk.md`).
fn face_roots(face: Vec<Bernstein<Interval>>, opts: &SystemOptions) -> Option<Vec<FaceRoot>> {
    let m = face.len();
    let mut out: Vec<FaceRoot> = Vec::new();
    let mut stack = vec![(vec![0.0; m], vec![1.0; m], 0u32, face)];
    let mut boxes = 0usize;
    while let Some((lo, hi, depth, polys)) = stack.pop() {
        boxes += 1;
        if polys.iter().any(excludes) {
            continue;
        }
        // Krawczyk's operator: one zero (found), none (`K` misses the box), or undecided.
        let verdict = krawczyk_verdict(&polys);
        if matches!(verdict, KrawczykVerdict::NoZero) {
            continue;
        }
        if !matches!(verdict, KrawczykVerdict::Unknown { worth: false }) {
            if let KrawczykVerdict::Unique(k) = verdict {
                let unique: Vec<[f64; 2]> = lo.iter().zip(&hi).map(|(a, b)| [*a, *b]).collect();
                let enc = refine_local(&polys, k, &lo, &hi, opts.refine_width);
                record(&mut out, enc, unique);
                continue;
            }
            // A zero near the sub-box's sides: the test on the grown box (not on the whole
            // face, which is subdivided first: the grown test costs a restriction). Tried only
            // where Newton's method from the centre (f64, a guess: the test decides) ends in the
            // margin of the grown box, not deep inside the box (where growing does not help)
            // nor far away.
            if depth >= 1 && near_the_sides(&polys) {
                let grown_lo: Vec<f64> =
                    lo.iter().zip(&hi).map(|(a, b)| a - (b - a) / 8.0).collect();
                let grown_hi: Vec<f64> =
                    lo.iter().zip(&hi).map(|(a, b)| b + (b - a) / 8.0).collect();
                let grown: Vec<Bernstein<Interval>> = polys
                    .iter()
                    .map(|p| p.restrict_box_f64(&vec![-0.125; m], &vec![1.125; m]))
                    .collect();
                if let Some(k) = krawczyk(&grown) {
                    let unique: Vec<[f64; 2]> = grown_lo
                        .iter()
                        .zip(&grown_hi)
                        .map(|(a, b)| [*a, *b])
                        .collect();
                    let enc = refine_local(&grown, k, &grown_lo, &grown_hi, opts.refine_width);
                    // A zero in the margin outside the face is not a crossing of this face.
                    if enc.iter().any(|e| e[1] < 0.0 || e[0] > 1.0) {
                        continue;
                    }
                    record(&mut out, enc, unique);
                    continue;
                }
            }
        }
        if depth >= opts.max_depth || boxes + stack.len() >= opts.max_boxes {
            return None;
        }
        let mut children = vec![(lo, hi, polys)];
        for axis in 0..m {
            let mut next = Vec::with_capacity(children.len() * 2);
            for (l, h, ps) in children {
                let mid = 0.5 * (l[axis] + h[axis]);
                let (mut lh, mut rl) = (h.clone(), l.clone());
                lh[axis] = mid;
                rl[axis] = mid;
                let (pl, pr): (Vec<_>, Vec<_>) = ps.iter().map(|p| p.subdivide_half(axis)).unzip();
                next.push((l, lh, pl));
                next.push((rl, h, pr));
            }
            children = next;
        }
        for (l, h, ps) in children.into_iter().rev() {
            stack.push((l, h, depth + 1, ps));
        }
    }
    Some(out)
}

/// Adds a zero of a face system to those found, unless it is one of them (found already by a
/// grown test of a neighbouring sub-box: one's enclosure lies in the other's uniqueness region).
fn record(out: &mut Vec<FaceRoot>, enclosure: Vec<[f64; 2]>, unique_in: Vec<[f64; 2]>) {
    let seen = out
        .iter()
        .any(|r| within(&enclosure, &r.unique_in) || within(&r.enclosure, &unique_in));
    if !seen {
        out.push(FaceRoot {
            enclosure,
            unique_in,
        });
    }
}

/// Whether Newton's method (f64, from the centre of the polynomials' unit box) ends within
/// 1/8 of the box's sides, inside or out: where a grown box may isolate a zero the box itself
/// could not.
fn near_the_sides(polys: &[Bernstein<Interval>]) -> bool {
    let f: Vec<Bernstein<f64>> = polys
        .iter()
        .map(|p| p.map(|x| 0.5 * (x.lo() + x.hi())))
        .collect();
    newton(&f, vec![0.5; polys.len()], 6).is_some_and(|x| {
        x.iter().all(|&t| (-0.125..=1.125).contains(&t))
            && x.iter().any(|&t| !(0.125..=0.875).contains(&t))
    })
}

/// Narrows a zero's Krawczyk image `k` (in the polynomials' own unit coordinates; the zero
/// is the only one in that unit box): Newton's method in f64 from its centre, then Krawczyk's
/// test on small boxes around the result inside the unit box, growing until one succeeds (a
/// success proves a zero there, which is the same zero: the only one in the unit box). The result is in the face's
/// local coordinates (the polynomials' box is `[lo, hi]` there); where nothing succeeds the
/// image itself is kept, still proven.
fn refine_local(
    polys: &[Bernstein<Interval>],
    k: Vec<Interval>,
    lo: &[f64],
    hi: &[f64],
    width: f64,
) -> Vec<[f64; 2]> {
    let m = polys.len();
    let image: Vec<[f64; 2]> = k.iter().map(|x| [x.lo(), x.hi()]).collect();
    let fallback = to_global(&image, lo, hi);
    if fallback.iter().all(|e| e[1] - e[0] <= width) {
        return fallback;
    }
    let f: Vec<Bernstein<f64>> = polys
        .iter()
        .map(|p| p.map(|x| 0.5 * (x.lo() + x.hi())))
        .collect();
    let Some(x) = newton(&f, image.iter().map(|e| 0.5 * (e[0] + e[1])).collect(), 30) else {
        return fallback;
    };
    // The first box about the target width (in the face's units, mapped to the polynomials'),
    // smaller ones only if needed.
    let scale = (0..m)
        .map(|k| hi[k] - lo[k])
        .fold(0.0, f64::max)
        .max(1e-300);
    let mut r = (0.25 * width / scale).max(1e-14);
    let mut tries = 0;
    // The partial derivatives once, for Krawczyk's test on each small box.
    let derivs: Vec<Vec<Bernstein<Interval>>> = polys
        .iter()
        .map(|p| (0..m).map(|j| p.deriv(j)).collect())
        .collect();
    while r < 0.25 && tries < 12 {
        tries += 1;
        // Inside the tested box (the polynomials' unit box), where the zero is unique.
        let b: Vec<[f64; 2]> = x.iter().map(|&v| [v - r, v + r]).collect();
        if !b.iter().all(|e| 0.0 <= e[0] && e[1] <= 1.0) {
            break;
        }
        let a: Vec<f64> = b.iter().map(|e| e[0]).collect();
        let c: Vec<f64> = b.iter().map(|e| e[1]).collect();
        if let Some(kk) = krawczyk_in_box(polys, &derivs, &a, &c) {
            let own: Vec<[f64; 2]> = kk.iter().map(|x| [x.lo(), x.hi()]).collect();
            return to_global(&own, lo, hi);
        }
        r *= 8.0;
    }
    fallback
}

/// The hull of a polynomial's coefficients: an enclosure of its range on its box.
fn excludes(p: &Bernstein<Interval>) -> bool {
    let c = p.coeffs();
    c.iter().all(|x| x.lo() > 0.0) || c.iter().all(|x| x.hi() < 0.0)
}

fn magnitude(x: &Interval) -> f64 {
    x.lo().abs().max(x.hi().abs())
}

/// The largest coefficient width relative to the largest magnitude: how much the f64
/// enclosures carried down the tree have spread.
fn slack(polys: &[Bernstein<Interval>]) -> f64 {
    polys
        .iter()
        .map(|p| {
            let big = p.coeffs().iter().map(magnitude).fold(0.0, f64::max);
            let wide = p.coeffs().iter().map(|c| c.width()).fold(0.0, f64::max);
            if big > 0.0 {
                wide / big
            } else {
                f64::INFINITY
            }
        })
        .fold(0.0, f64::max)
}

/// `C` and an upper bound `β < 1` of `‖I − C M‖∞` for the interval matrix `M`, which proves
/// every real matrix in `M` invertible (`‖(C A)⁻¹‖∞ ≤ 1 / (1 − β)`); `None` if not proven.
fn regular(m: &[Vec<Interval>]) -> Option<(Vec<Vec<f64>>, f64)> {
    let k = m.len();
    let mid: Vec<Vec<f64>> = m
        .iter()
        .map(|r| r.iter().map(|x| 0.5 * (x.lo() + x.hi())).collect())
        .collect();
    let c = inverse(&mid)?;
    let mut beta = Interval::point(0.0);
    for (r, cr) in c.iter().enumerate() {
        let mut row = Interval::point(0.0);
        for col in 0..k {
            let mut e = Interval::point(if r == col { 1.0 } else { 0.0 });
            for (crl, ml) in cr.iter().zip(m) {
                e = e.sub(&Interval::point(*crl).mul(&ml[col]));
            }
            row = row.add(&Interval::point(magnitude(&e)));
        }
        if row.hi() > beta.hi() {
            beta = row;
        }
    }
    (beta.hi() < 1.0).then_some((c, beta.hi()))
}

/// The determinant of a small matrix (for choosing the best-conditioned minor only).
fn det(m: &[Vec<f64>]) -> f64 {
    let n = m.len();
    let mut a = m.to_vec();
    let mut d = 1.0;
    for col in 0..n {
        let Some(piv) = (col..n).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))
        else {
            return 0.0;
        };
        if a[piv][col] == 0.0 {
            return 0.0;
        }
        if piv != col {
            a.swap(piv, col);
            d = -d;
        }
        d *= a[col][col];
        let (top, rest) = a.split_at_mut(col + 1);
        let pivot = &top[col];
        for row in rest {
            let f = row[col] / pivot[col];
            for (x, p) in row[col..].iter_mut().zip(&pivot[col..]) {
                *x -= f * p;
            }
        }
    }
    d
}

/// An upper bound of `x / (1 − β)` for `x ≥ 0`, `β < 1`.
fn over_one_minus(x: f64, beta: f64) -> f64 {
    let den = Interval::point(1.0).sub(&Interval::point(beta));
    den.recip()
        .map_or(f64::INFINITY, |r| Interval::point(x).mul(&r).hi())
}

/// The upper bound of `‖C v‖∞` for an interval vector `v`.
fn times_norm(c: &[Vec<f64>], v: &[Interval]) -> f64 {
    c.iter()
        .map(|row| {
            let mut s = Interval::point(0.0);
            for (a, b) in row.iter().zip(v) {
                s = s.add(&Interval::point(*a).mul(b));
            }
            magnitude(&s)
        })
        .fold(0.0, f64::max)
}

/// A face of a box: the fixed variable, its value, and the other sides.
type FaceKey = (usize, Dyadic, DyadicBoxN);

struct Solver<'a> {
    /// The crossings found on each face solved so far (`None`: not decided).
    faces: HashMap<FaceKey, Option<Vec<FaceRoot>>>,
    n: usize,
    opts: &'a SpaceCurveOptions,
    /// The exact singular points known (§6), and the partials their star tests use.
    singular: Vec<SingularPoint>,
    partials: Option<HigherPartials>,
}

impl Solver<'_> {
    /// Decides one box from its polynomials (local coordinates).
    fn settle(&mut self, cell: &DyadicBoxN, polys: &[Bernstein<Interval>]) -> Settled {
        let n = self.n;
        // The first partials, kept for the accuracy bounds.
        let partials: Vec<Vec<Bernstein<Interval>>> = polys
            .iter()
            .map(|f| (0..n).map(|k| f.deriv(k)).collect())
            .collect();
        let jac: Vec<Vec<Interval>> = partials
            .iter()
            .map(|row| row.iter().map(Bernstein::hull).collect())
            .collect();
        let minor = |skip: usize| -> Vec<Vec<Interval>> {
            jac.iter()
                .map(|r| {
                    r.iter()
                        .enumerate()
                        .filter(|&(k, _)| k != skip)
                        .map(|(_, x)| *x)
                        .collect()
                })
                .collect()
        };
        let mid = |m: &[Vec<Interval>]| -> Vec<Vec<f64>> {
            m.iter()
                .map(|r| r.iter().map(|x| 0.5 * (x.lo() + x.hi())).collect())
                .collect()
        };
        let mut order: Vec<(usize, f64)> =
            (0..n).map(|i| (i, det(&mid(&minor(i))).abs())).collect();
        order.sort_by(|a, b| b.1.total_cmp(&a.1));
        let Some((i, c, beta)) = order
            .iter()
            .find_map(|&(i, _)| regular(&minor(i)).map(|(c, b)| (i, c, b)))
        else {
            return Settled::Open(NO_REGULAR_MINOR);
        };
        let mut crossings = match self.face_crossings(cell, polys, &|_, _| false) {
            Ok(c) => c,
            Err(reason) => return Settled::Open(reason),
        };
        if crossings.len() % 2 == 1 {
            return Settled::Open("an odd number of face crossings");
        }
        crossings.sort_by(|a, b| {
            (a.enclosure[i][0] + a.enclosure[i][1])
                .total_cmp(&(b.enclosure[i][0] + b.enclosure[i][1]))
        });
        if crossings
            .windows(2)
            .any(|w| w[0].enclosure[i][1] >= w[1].enclosure[i][0])
        {
            return Settled::Open(
                "two face crossings are not separated along the monotone variable",
            );
        }
        let (deviations, accurate) =
            self.deviations(cell, &partials, &jac, i, &c, beta, &crossings);
        Settled::Arcs {
            center: None,
            monotone_in: i,
            crossings,
            deviations,
            accurate,
        }
    }

    /// Decides a box around the singular point `index` by the star test (§6): its branches,
    /// each joined to the face crossing it ends at.
    fn star(
        &mut self,
        cell: &DyadicBoxN,
        polys: &dyn Fn() -> Vec<Bernstein<Interval>>,
        index: usize,
    ) -> Settled {
        let sp = &self.singular[index];
        let lo: Vec<f64> = cell.iter().map(|d| d.0.to_f64()).collect();
        let hi: Vec<f64> = cell.iter().map(|d| d.1.to_f64()).collect();
        let partials = self
            .partials
            .as_ref()
            .expect("partials with singular points");
        let branches = match star_branches(sp, partials, &lo, &hi) {
            Ok(b) => b,
            Err(reason) => return Settled::Open(reason),
        };
        // The faces through the singular point (sides of the unit box) hold no crossing but
        // it: the branches end on the other faces.
        let exact = sp.exact.clone();
        let on_side = move |axis: usize, side: bool| {
            let at = if side { cell[axis].1 } else { cell[axis].0 };
            exact[axis] == at.to_rational()
        };
        let crossings = match self.face_crossings(cell, &polys(), &on_side) {
            Ok(c) => c,
            Err(reason) => return Settled::Open(reason),
        };
        let sp = &self.singular[index];
        // Each crossing is the end of exactly one branch: its enclosure lies in the region of
        // the facet where that branch's end is the only point of the curve on the face.
        if crossings.len() != branches.len() {
            return Settled::Open(
                "the face crossings do not match the branches from the singular point",
            );
        }
        let mut used = vec![false; branches.len()];
        let mut order = Vec::with_capacity(branches.len());
        for c in &crossings {
            let upper = c.at == cell[c.axis].1;
            let matches: Vec<usize> = (0..branches.len())
                .filter(|&b| {
                    let br = &branches[b];
                    br.axis == c.axis
                        && br.upper == upper
                        && (0..self.n).filter(|&k| k != c.axis).all(|k| {
                            let region = sp.at[k].add(&br.region[k]);
                            region.lo() <= c.enclosure[k][0] && c.enclosure[k][1] <= region.hi()
                        })
                })
                .collect();
            match matches.as_slice() {
                [b] if !used[*b] => {
                    used[*b] = true;
                    order.push(*b);
                }
                _ => {
                    return Settled::Open(
                        "the face crossings do not match the branches from the singular point",
                    )
                }
            }
        }
        let center = RawCrossing {
            axis: self.n,
            at: Dyadic::ZERO,
            enclosure: sp.at.iter().map(|x| [x.lo(), x.hi()]).collect(),
            unique_in: sp.at.iter().map(|x| [x.lo(), x.hi()]).collect(),
            on_boundary: sp.exact.iter().any(|x| *x == 0 || *x == 1),
            singular: Some(index),
        };
        let (deviations, accurate) =
            self.star_deviations(sp, &center, &branches, &order, &crossings);
        Settled::Arcs {
            center: Some(center),
            monotone_in: self.n,
            crossings,
            deviations,
            accurate,
        }
    }

    /// Per branch of a star, a bound per variable on the distance between the branch and the
    /// segment from the singular point to its crossing (§6: every point `p + r w(r)` is within
    /// `|w(r) − (c − p)|` of `p + r (c − p)`, and `w(r)` lies in the branch's image).
    fn star_deviations(
        &self,
        sp: &SingularPoint,
        center: &RawCrossing,
        branches: &[StarBranch],
        order: &[usize],
        crossings: &[RawCrossing],
    ) -> (Vec<Option<Vec<f64>>>, bool) {
        if self.opts.tolerance.is_none() {
            return (vec![None; crossings.len()], true);
        }
        let mut accurate = true;
        let devs = crossings
            .iter()
            .zip(order)
            .map(|(c, &b)| {
                let br = &branches[b];
                let dev: Vec<f64> = (0..self.n)
                    .map(|k| {
                        let mid = |e: &[f64; 2]| 0.5 * (e[0] + e[1]);
                        let drawn_p = mid(&center.enclosure[k]);
                        // c̃ − p and the image of w(r) (the facet value on the face's axis).
                        let to_end = Interval::point(mid(&c.enclosure[k])).sub(&sp.at[k]);
                        let w = if k == br.axis {
                            br.region[k]
                        } else {
                            br.image[k]
                        };
                        let spread = magnitude(&w.sub(&to_end));
                        let start = magnitude(&sp.at[k].sub(&Interval::point(drawn_p)));
                        Interval::point(spread).add(&Interval::point(start)).hi()
                    })
                    .collect();
                if let Some(accept) = &self.opts.accept {
                    accurate &= (accept.0)(&center.enclosure, &c.enclosure, &dev);
                } else if let Some(tol) = &self.opts.tolerance {
                    accurate &= dev.iter().zip(tol).all(|(d, t)| d <= t);
                    if let Some(chord) = &self.opts.max_chord {
                        let (a, e) = (&center.enclosure, &c.enclosure);
                        accurate &= chord
                            .iter()
                            .enumerate()
                            .all(|(k, l)| a[k][1].max(e[k][1]) - a[k][0].min(e[k][0]) <= *l);
                    }
                }
                Some(dev)
            })
            .collect();
        (devs, accurate)
    }

    /// The crossings of the curve with the faces of the box (all faces but those `skip`
    /// names, by axis and side), each strictly inside its face (§3); `Err` if some face was
    /// not decided.
    fn face_crossings(
        &mut self,
        cell: &DyadicBoxN,
        polys: &[Bernstein<Interval>],
        skip: &dyn Fn(usize, bool) -> bool,
    ) -> Result<Vec<RawCrossing>, &'static str> {
        let n = self.n;
        let mut crossings = Vec::new();
        for axis in 0..n {
            for (side, at) in [(false, cell[axis].0), (true, cell[axis].1)] {
                if skip(axis, side) {
                    continue;
                }
                // The box's own coefficients on the face are the face polynomials' (exactly
                // the Bernstein coefficients with that index at 0 or at the degree): where
                // one equation has a strict sign there, the face holds no crossing.
                if polys.iter().any(|p| excludes(&face_slice(p, axis, side))) {
                    continue;
                }
                let domain: DyadicBoxN = (0..n).filter(|&k| k != axis).map(|k| cell[k]).collect();
                // A face shared with a neighbour of the same size is solved once: both boxes
                // enclose the same exact system on it (`proofs/space-curves.md` §4).
                let key = (axis, at, domain.clone());
                let roots = match self.faces.get(&key) {
                    Some(known) => known.clone(),
                    None => {
                        let face: Vec<Bernstein<Interval>> =
                            polys.iter().map(|p| face_slice(p, axis, side)).collect();
                        let dlo: Vec<f64> = domain.iter().map(|d| d.0.to_f64()).collect();
                        let dhi: Vec<f64> = domain.iter().map(|d| d.1.to_f64()).collect();
                        let found = face_roots(face, &self.opts.face).map(|roots| {
                            roots
                                .into_iter()
                                .map(|r| FaceRoot {
                                    enclosure: to_global(&r.enclosure, &dlo, &dhi),
                                    unique_in: to_global_inward(&r.unique_in, &dlo, &dhi),
                                })
                                .collect::<Vec<_>>()
                        });
                        self.faces.insert(key, found.clone());
                        found
                    }
                };
                let Some(roots) = roots else {
                    return Err(
                        "a face crossing was not isolated (the curve touches a face of the box)",
                    );
                };
                for r in roots {
                    let strictly_inside = r
                        .enclosure
                        .iter()
                        .zip(&domain)
                        .all(|(e, d)| d.0.to_f64() < e[0] && e[1] < d.1.to_f64());
                    if !strictly_inside {
                        return Err("the curve passes through or near an edge of the box");
                    }
                    let a = at.to_f64();
                    let mut enclosure = r.enclosure.clone();
                    enclosure.insert(axis, [a, a]);
                    crossings.push(RawCrossing {
                        axis,
                        at,
                        enclosure,
                        unique_in: r.unique_in,
                        on_boundary: at == Dyadic::ZERO || at == Dyadic::ONE,
                        singular: None,
                    });
                }
            }
        }
        Ok(crossings)
    }

    /// Per arc (consecutive pairs of crossings) and variable, a bound on the distance between
    /// the arc and its chord (`proofs/space-curves.md`, Claim 3), and whether all are within
    /// the tolerance.
    #[allow(clippy::too_many_arguments)]
    fn deviations(
        &self,
        cell: &DyadicBoxN,
        partials: &[Vec<Bernstein<Interval>>],
        jac: &[Vec<Interval>],
        i: usize,
        c: &[Vec<f64>],
        beta: f64,
        crossings: &[RawCrossing],
    ) -> (Vec<Option<Vec<f64>>>, bool) {
        let Some(tol) = &self.opts.tolerance else {
            return (vec![None; crossings.len() / 2], true);
        };
        let n = self.n;
        let width: Vec<f64> = cell.iter().map(|d| d.1.to_f64() - d.0.to_f64()).collect();
        // |η'|∞ ≤ ‖C J_x‖∞ / (1 − β) in local coordinates.
        let jx: Vec<Interval> = jac.iter().map(|r| r[i]).collect();
        let slope = over_one_minus(times_norm(c, &jx), beta);
        let t: Vec<Interval> = (0..n)
            .map(|k| {
                if k == i {
                    Interval::point(1.0)
                } else {
                    Interval::new(-slope, slope)
                }
            })
            .collect();
        // r_j = D²F_j(t, t) over the box: the Hessian is symmetric, so each mixed partial is
        // taken once and counted twice.
        let r: Vec<Interval> = partials
            .iter()
            .map(|row| {
                let mut s = Interval::point(0.0);
                for a in 0..n {
                    for b in a..n {
                        let h = row[a].deriv_hull(b);
                        let term = h.mul(&t[a]).mul(&t[b]);
                        s = s.add(&if a == b { term } else { term.add(&term) });
                    }
                }
                s
            })
            .collect();
        let curvature = over_one_minus(times_norm(c, &r), beta);
        let mut accurate = true;
        let devs = crossings
            .chunks_exact(2)
            .map(|pair| {
                // The arc's extent along x_i in box units (an upper bound).
                let span = Interval::point(pair[1].enclosure[i][1])
                    .sub(&Interval::point(pair[0].enclosure[i][0]))
                    .mul(
                        &Interval::point(width[i])
                            .recip()
                            .unwrap_or(Interval::new(0.0, f64::INFINITY)),
                    )
                    .hi()
                    .clamp(0.0, 1.0);
                let span = Interval::point(span);
                let dev: Vec<f64> = (0..n)
                    .map(|k| {
                        // In local coordinates the arc deviates from the chord between its true
                        // ends, at equal x_i, by at most span² |η''| / 8; back to global: times
                        // the width (and never more than the box's width).
                        let bulge = if k == i {
                            0.0
                        } else {
                            span.mul(&span)
                                .mul(&Interval::point(0.125))
                                .mul(&Interval::point(curvature))
                                .mul(&Interval::point(width[k]))
                                .hi()
                                .min(width[k])
                        };
                        // The drawn chord joins the enclosures' centres: moving each end by at
                        // most its half-width moves every point of the chord (at equal chord
                        // parameter) by at most the larger one, in every coordinate.
                        let half = |c: &RawCrossing| {
                            Interval::point(c.enclosure[k][1])
                                .sub(&Interval::point(c.enclosure[k][0]))
                                .mul(&Interval::point(0.5))
                                .hi()
                        };
                        let slack = half(&pair[0]).max(half(&pair[1]));
                        Interval::point(bulge).add(&Interval::point(slack)).hi()
                    })
                    .collect();
                if let Some(accept) = &self.opts.accept {
                    accurate &= (accept.0)(&pair[0].enclosure, &pair[1].enclosure, &dev);
                } else {
                    accurate &= dev.iter().zip(tol).all(|(d, t)| d <= t);
                    if let Some(chord) = &self.opts.max_chord {
                        let extent = |k: usize| {
                            let (a, b) = (&pair[0].enclosure[k], &pair[1].enclosure[k]);
                            a[1].max(b[1]) - a[0].min(b[0])
                        };
                        accurate &= chord.iter().enumerate().all(|(k, c)| extent(k) <= *c);
                    }
                }
                Some(dev)
            })
            .collect();
        (devs, accurate)
    }
}

/// A box without one coordinate (its projection on a face hyperplane).
fn without(b: &[[f64; 2]], axis: usize) -> Vec<[f64; 2]> {
    b.iter()
        .enumerate()
        .filter(|&(k, _)| k != axis)
        .map(|(_, e)| *e)
        .collect()
}

fn f64_box(cell: &DyadicBoxN) -> Vec<[f64; 2]> {
    cell.iter().map(|d| [d.0.to_f64(), d.1.to_f64()]).collect()
}

fn within(inner: &[[f64; 2]], outer: &[[f64; 2]]) -> bool {
    inner
        .iter()
        .zip(outer)
        .all(|(a, b)| b[0] <= a[0] && a[1] <= b[1])
}

/// The curve `F₁ = … = F_{n−1} = 0` on `[0, 1]ⁿ`, with certified topology where the result
/// says so (`proofs/space-curves.md`).
///
/// # Panics
/// If there are not `n − 1` polynomials in `n ≥ 2` variables.
///
/// # Examples
/// ```
/// use limn::bernstein::Bernstein;
/// use limn::number::Rational;
/// use limn::solver::curve_n::{solve_space_curve, SpaceCurveOptions};
/// // The segment F₁ = x − y/3 − 1/5 = 0, F₂ = z − 1/3 = 0.
/// let q = |a: i64, b: i64| Rational::from((a, b));
/// // Bernstein coefficients of a linear form: its values at (x, y) ∈ {0, 1}².
/// let f1 = Bernstein::new(&[1, 1, 0], vec![q(-1, 5), q(-8, 15), q(4, 5), q(7, 15)]).unwrap();
/// let f2 = Bernstein::new(&[0, 0, 1], vec![q(-1, 3), q(2, 3)]).unwrap();
/// let c = solve_space_curve(&[f1, f2], &SpaceCurveOptions::default());
/// assert!(c.is_certified());
/// assert_eq!(c.branches.len(), 1);
/// // It runs from the face y = 0 (x = 1/5) to the face y = 1 (x = 8/15).
/// let ends: Vec<usize> = c.crossings.iter().filter(|x| x.on_boundary).map(|x| x.axis).collect();
/// assert_eq!(ends, vec![1, 1]);
/// ```
pub fn solve_space_curve(eqs: &[Bernstein<Rational>], opts: &SpaceCurveOptions) -> SpaceCurve {
    solve_space_curve_where(eqs, &[], opts)
}

/// [`solve_space_curve`] restricted to where every polynomial of `nonpositive` is ≤ 0: a box
/// on which one of them is strictly positive is excluded (for example the elliptic region,
/// where no real asymptotic direction exists).
///
/// # Panics
/// As [`solve_space_curve`], and if a filter has another number of variables.
pub fn solve_space_curve_where(
    eqs: &[Bernstein<Rational>],
    nonpositive: &[Bernstein<Rational>],
    opts: &SpaceCurveOptions,
) -> SpaceCurve {
    solve_space_curve_excluding(
        eqs,
        nonpositive,
        &|_: &[[f64; 2]], _: u32| BoxVerdict::Solve,
        opts,
    )
}

/// What a caller says of a box before the solver examines it (see
/// [`solve_space_curve_excluding`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BoxVerdict {
    /// Examine it as usual.
    Solve,
    /// The caller has proven that the box holds no point of the curve it wants (a spurious
    /// component, or a mirror image of another box): it is dropped. The crossings of the
    /// curve on the faces it shares with kept boxes stay, as ends of their branches.
    Drop,
    /// The caller gives up on the box: it is reported unresolved with this reason.
    Unresolved(&'static str),
}

/// [`solve_space_curve_where`] with a caller's verdict on every box before it is examined
/// (its sides `[lo, hi]` per variable, exact dyadics, and its depth): the curve of the result
/// is the curve of `eqs` outside the dropped boxes. What a dropped box is allowed to hold is
/// the caller's claim (for bitangents: only the spurious diagonal, or the mirror image of a
/// kept box, `proofs/bitangent.md`).
///
/// # Panics
/// As [`solve_space_curve_where`].
pub fn solve_space_curve_excluding(
    eqs: &[Bernstein<Rational>],
    nonpositive: &[Bernstein<Rational>],
    verdict: &dyn Fn(&[[f64; 2]], u32) -> BoxVerdict,
    opts: &SpaceCurveOptions,
) -> SpaceCurve {
    let n = eqs.first().map_or(0, |p| p.nvars());
    assert!(
        n >= 2 && eqs.len() == n - 1 && eqs.iter().chain(nonpositive).all(|p| p.nvars() == n),
        "n − 1 polynomials in n ≥ 2 variables"
    );
    let eqs: Vec<Bernstein<Rational>> = eqs.iter().map(integral).collect();
    let filters: Vec<Bernstein<Rational>> = nonpositive.iter().map(integral).collect();
    let mut solver = Solver {
        faces: HashMap::new(),
        n,
        opts,
        singular: Vec::new(),
        partials: None,
    };
    let mut out = SpaceCurve {
        nvars: n,
        within_tolerance: true,
        ..SpaceCurve::default()
    };
    let mut leaves = Leaves::default();
    subdivide(&mut solver, &eqs, &filters, verdict, &mut out, &mut leaves);
    // Exact singular points near the boxes left undecided, and the star test around them
    // (§6): a box that it decides replaces the leaves inside it.
    solver.singular = singular_points_near(&eqs, &out.unresolved, opts);
    if !solver.singular.is_empty() {
        solver.partials = Some(HigherPartials::new(&eqs));
    }
    // Per singular point, its number of branches where its star was decided (a later star
    // moves the leaves' crossings, so centres are found by their mark after naming).
    let mut starred = vec![None; solver.singular.len()];
    for (k, star) in starred.iter_mut().enumerate() {
        *star = star_around(&mut solver, k, &eqs, &mut out, &mut leaves);
    }
    assemble(&mut out, leaves.crossings, leaves.arcs);
    out.singular_points = solver
        .singular
        .iter()
        .zip(starred)
        .enumerate()
        .map(|(k, (sp, branches))| SpaceSingularPoint {
            exact: sp.exact_strings(),
            values: sp.exact.clone(),
            point: sp.point(),
            crossing: out.crossings.iter().position(|c| c.singular == Some(k)),
            branches,
        })
        .collect();
    out
}

/// What the subdivision decided, before the crossings are named: the crossings and arcs of
/// the settled leaves, and the leaves the caller dropped or gave up on (which no star box may
/// cover).
#[derive(Default)]
struct Leaves {
    crossings: Vec<RawCrossing>,
    arcs: Vec<RawArc>,
    dropped: Vec<Vec<[f64; 2]>>,
}

/// Decides the box around the singular point `k` by the star test (§6), from the smallest
/// depth where it succeeds (and, with a tolerance, its arcs are accurate, or the box is the
/// smallest allowed) down: the leaves inside it are replaced by its arcs. The star's number of
/// branches.
fn star_around(
    solver: &mut Solver,
    k: usize,
    eqs: &[Bernstein<Rational>],
    out: &mut SpaceCurve,
    leaves: &mut Leaves,
) -> Option<usize> {
    let exact = solver.singular[k].exact.clone();
    // Exact comparisons (the leaves' sides are dyadic, exact in f64).
    let holds_p = |cell: &[[f64; 2]]| {
        cell.iter().zip(&exact).all(|(b, x)| {
            let lo = Rational::from_f64(b[0]).expect("finite");
            let hi = Rational::from_f64(b[1]).expect("finite");
            lo <= *x && *x <= hi
        })
    };
    let width = |cell: &[[f64; 2]]| cell[0][1] - cell[0][0];
    // No box of the star may be smaller than an undecided leaf that holds the point (it would
    // cut that leaf): the largest such leaf bounds the depth.
    let largest = out
        .unresolved
        .iter()
        .filter(|u| holds_p(&u.cell))
        .map(|u| width(&u.cell))
        .fold(0.0, f64::max);
    if largest == 0.0 {
        return None;
    }
    for depth in STAR_MIN_DEPTH..=solver.opts.max_depth.min(60) {
        let side = (-f64::from(depth)).exp2();
        if side < largest
            || solver
                .opts
                .deadline
                .is_some_and(|d| std::time::Instant::now() >= d)
        {
            break;
        }
        // The dyadic box of this depth around the point.
        let cell: DyadicBoxN = exact
            .iter()
            .map(|x| {
                let scale = Rational::from(rug::Integer::from(1) << depth);
                let i = Rational::from(x * &scale).floor();
                let top = rug::Integer::from(1) << depth;
                let i = i.numer().clone().min(top.clone() - 1u32);
                let lo = i.to_u64().expect("depth ≤ 60");
                (Dyadic::new(lo, depth), Dyadic::new(lo + 1, depth))
            })
            .collect();
        let lo: Vec<Rational> = cell.iter().map(|d| d.0.to_rational()).collect();
        let hi: Vec<Rational> = cell.iter().map(|d| d.1.to_rational()).collect();
        if !solver.singular[k].admissible_in(&lo, &hi) {
            continue;
        }
        let fcell = f64_box(&cell);
        if leaves.dropped.iter().any(|d| overlaps(d, &fcell)) {
            continue;
        }
        // The box's polynomials, for its face crossings (only if its boundary is decided).
        let polys = || -> Vec<Bernstein<Interval>> {
            eqs.iter()
                .map(|f| f.restrict_box_rational(&lo, &hi).convert(Precision::F64))
                .collect()
        };
        let Settled::Arcs {
            center: Some(center),
            monotone_in,
            crossings,
            deviations,
            accurate,
        } = solver.star(&cell, &polys, k)
        else {
            continue;
        };
        let deepest = 0.5 * side < largest;
        if !accurate && !deepest {
            continue;
        }
        // Replace the leaves inside the box by the star.
        leaves.retain_outside(&fcell);
        out.unresolved.retain(|u| !within(&u.cell, &fcell));
        out.within_tolerance &= accurate;
        let c = leaves.crossings.len();
        let count = crossings.len();
        leaves.crossings.push(center);
        for (j, deviation) in deviations.into_iter().enumerate() {
            leaves.arcs.push(RawArc {
                from: c,
                to: c + 1 + j,
                cell: fcell.clone(),
                monotone_in,
                deviation,
            });
        }
        leaves.crossings.extend(crossings);
        return Some(count);
    }
    // Not decided: the undecided boxes that hold the point say so.
    for u in out.unresolved.iter_mut().filter(|u| holds_p(&u.cell)) {
        u.reason = UNRESOLVED_SINGULAR.to_string();
    }
    None
}

impl Leaves {
    /// Drops the arcs (and their crossings) of the leaves inside `cell`.
    fn retain_outside(&mut self, cell: &[[f64; 2]]) {
        let mut keep_crossing = vec![true; self.crossings.len()];
        let arcs = std::mem::take(&mut self.arcs);
        let mut kept = Vec::with_capacity(arcs.len());
        for a in arcs {
            if within(&a.cell, cell) {
                keep_crossing[a.from] = false;
                keep_crossing[a.to] = false;
            } else {
                kept.push(a);
            }
        }
        let mut index = vec![usize::MAX; self.crossings.len()];
        let crossings = std::mem::take(&mut self.crossings);
        for (k, c) in crossings.into_iter().enumerate() {
            if keep_crossing[k] {
                index[k] = self.crossings.len();
                self.crossings.push(c);
            }
        }
        for a in kept.iter_mut() {
            a.from = index[a.from];
            a.to = index[a.to];
        }
        self.arcs = kept;
    }
}

/// Whether two closed boxes share interior points.
fn overlaps(a: &[[f64; 2]], b: &[[f64; 2]]) -> bool {
    a.iter().zip(b).all(|(x, y)| x[0] < y[1] && y[0] < x[1])
}

/// The reason of a box the graph test could not decide for want of a regular minor.
pub const NO_REGULAR_MINOR: &str =
    "no Jacobian minor is proven regular (near a singular point of the \
                                curve, or where its equations are nearly dependent)";

/// The reason of a box around a known singular point that the star test did not decide.
pub const UNRESOLVED_SINGULAR: &str = "holds an exact singular point of the curve (listed in \
                                   singular_points) whose branches were not resolved";

/// The star test is tried on boxes around a singular point from this depth on.
const STAR_MIN_DEPTH: u32 = 2;

/// The most undecided boxes looked at for exact singular points, and the most candidates
/// checked exactly.
const SINGULAR_BOXES: usize = 512;
const SINGULAR_CANDIDATES: usize = 24;

/// The most singular points kept per curve. On a 2-dimensional set of solutions (a plane
/// tangent along a circle, for bitangents) every point is one, and their stars all fail.
const SINGULAR_POINTS: usize = 4;

/// The exact singular points of `F = 0` at the simplest rational points near undecided boxes
/// whose reason is a Jacobian not proven regular (each checked exactly).
fn singular_points_near(
    eqs: &[Bernstein<Rational>],
    unresolved: &[SpaceUnresolved],
    opts: &SpaceCurveOptions,
) -> Vec<SingularPoint> {
    // The simplest candidates first (the sum of their denominators' sizes): where a whole
    // set of points is singular, the ones listed are the simple ones.
    let mut seen = std::collections::HashSet::new();
    let mut candidates: Vec<Vec<Rational>> = unresolved
        .iter()
        .filter(|u| u.reason == NO_REGULAR_MINOR)
        .take(SINGULAR_BOXES)
        .flat_map(|u| simple_points_near(&u.cell))
        .filter(|p| seen.insert(p.clone()))
        .collect();
    let size = |p: &Vec<Rational>| -> u32 { p.iter().map(|x| x.denom().significant_bits()).sum() };
    candidates.sort_by_cached_key(size);
    candidates.truncate(SINGULAR_CANDIDATES);
    // Interval values first: most candidates are off the curve, which they show cheaply.
    let enclosed: Vec<Bernstein<Interval>> =
        eqs.iter().map(|f| f.convert(Precision::F64)).collect();
    let maybe_zero = |p: &[Rational]| {
        let at: Vec<Interval> = p
            .iter()
            .map(|x| Interval::from_rational(x, Precision::F64))
            .collect();
        enclosed.iter().all(|f| f.eval(&at).contains(0.0))
    };
    let maybe: Vec<Vec<Rational>> = candidates.into_iter().filter(|p| maybe_zero(p)).collect();
    if maybe.is_empty() {
        return Vec::new();
    }
    let partials = ExactPartials::new(eqs);
    maybe
        .into_iter()
        .take_while(|_| opts.deadline.is_none_or(|d| std::time::Instant::now() < d))
        .filter_map(|p| exact_singular_point(eqs, &partials, p))
        .take(SINGULAR_POINTS)
        .collect()
}

/// The subdivision: every box excluded, settled (its crossings and arcs added to `leaves`),
/// dropped by the caller, or unresolved (added to `out`).
fn subdivide(
    solver: &mut Solver,
    eqs: &[Bernstein<Rational>],
    filters: &[Bernstein<Rational>],
    verdict: &dyn Fn(&[[f64; 2]], u32) -> BoxVerdict,
    out: &mut SpaceCurve,
    leaves: &mut Leaves,
) {
    let (n, opts) = (solver.n, solver.opts);
    // Each box carries the equations, then the filters.
    let mut stack = vec![Item {
        cell: vec![(Dyadic::ZERO, Dyadic::ONE); n],
        depth: 0,
        polys: eqs
            .iter()
            .chain(filters)
            .map(|p| p.convert(Precision::F64))
            .collect(),
        exact: false,
    }];
    let positive = |p: &Bernstein<Interval>| p.coeffs().iter().all(|x| x.lo() > 0.0);
    while let Some(item) = stack.pop() {
        out.boxes += 1;
        let (equations, filter_polys) = item.polys.split_at(n - 1);
        if equations.iter().any(excludes) || filter_polys.iter().any(positive) {
            continue;
        }
        match verdict(&f64_box(&item.cell), item.depth) {
            BoxVerdict::Solve => {}
            BoxVerdict::Drop => {
                leaves.dropped.push(f64_box(&item.cell));
                continue;
            }
            BoxVerdict::Unresolved(reason) => {
                // Neither may a star box cover it: the caller's reason stands.
                leaves.dropped.push(f64_box(&item.cell));
                out.unresolved.push(SpaceUnresolved {
                    cell: f64_box(&item.cell),
                    reason: reason.to_string(),
                });
                continue;
            }
        }
        let (reason, accurate_enough) = match solver.settle(&item.cell, equations) {
            Settled::Arcs {
                center: _,
                monotone_in,
                crossings,
                deviations,
                accurate,
            } => {
                let last_chance = item.depth >= opts.max_depth
                    || out.boxes + stack.len() >= opts.max_boxes
                    || opts
                        .deadline
                        .is_some_and(|d| std::time::Instant::now() >= d);
                if accurate || last_chance {
                    out.within_tolerance &= accurate;
                    let first = leaves.crossings.len();
                    leaves.crossings.extend(crossings);
                    for (k, deviation) in deviations.into_iter().enumerate() {
                        leaves.arcs.push(RawArc {
                            from: first + 2 * k,
                            to: first + 2 * k + 1,
                            cell: f64_box(&item.cell),
                            monotone_in,
                            deviation,
                        });
                    }
                    continue;
                }
                ("", false)
            }
            Settled::Open(reason) => (reason, true),
        };
        // Undecided: recompute the polynomials exactly once if the enclosures have spread.
        if accurate_enough && !item.exact && item.depth >= 3 && slack(equations) > 1e-9 {
            out.escalations += 1;
            let lo: Vec<Rational> = item.cell.iter().map(|d| d.0.to_rational()).collect();
            let hi: Vec<Rational> = item.cell.iter().map(|d| d.1.to_rational()).collect();
            let polys = eqs
                .iter()
                .chain(filters)
                .map(|p| p.restrict_box_rational(&lo, &hi).convert(Precision::F64))
                .collect();
            out.boxes -= 1;
            stack.push(Item {
                polys,
                exact: true,
                ..item
            });
            continue;
        }
        if opts
            .deadline
            .is_some_and(|d| std::time::Instant::now() >= d)
        {
            out.unresolved.push(SpaceUnresolved {
                cell: f64_box(&item.cell),
                reason: TIME_LIMIT_REASON.to_string(),
            });
            continue;
        }
        if item.depth >= opts.max_depth || out.boxes + stack.len() >= opts.max_boxes {
            out.unresolved.push(SpaceUnresolved {
                cell: f64_box(&item.cell),
                reason: reason.to_string(),
            });
            continue;
        }
        let axes: Vec<usize> = (0..n).collect();
        let Some(children) = split_box(&item.cell, item.polys, &axes) else {
            out.unresolved.push(SpaceUnresolved {
                cell: f64_box(&item.cell),
                reason: "the box is at the finest dyadic subdivision".to_string(),
            });
            continue;
        };
        for (cell, polys) in children.into_iter().rev() {
            stack.push(Item {
                cell,
                depth: item.depth + 1,
                polys,
                exact: false,
            });
        }
    }
}

/// Names each crossing once (two raw crossings on one hyperplane are the same point when one's
/// enclosure lies in the other's uniqueness region), and chains the arcs into branches; the
/// named crossing of each raw one.
fn assemble(out: &mut SpaceCurve, raw: Vec<RawCrossing>, arcs: Vec<RawArc>) -> Vec<usize> {
    let mut parent: Vec<usize> = (0..raw.len()).collect();
    fn find(parent: &mut [usize], mut x: usize) -> usize {
        while parent[x] != x {
            parent[x] = parent[parent[x]];
            x = parent[x];
        }
        x
    }
    let mut by_plane: HashMap<(usize, Dyadic), Vec<usize>> = HashMap::new();
    for (k, c) in raw.iter().enumerate() {
        if !c.on_boundary && c.singular.is_none() {
            by_plane.entry((c.axis, c.at)).or_default().push(k);
        }
    }
    let face = |c: &RawCrossing| without(&c.enclosure, c.axis);
    let mut planes: Vec<_> = by_plane.into_values().collect();
    planes.sort();
    for members in planes {
        for (x, &a) in members.iter().enumerate() {
            for &b in &members[x + 1..] {
                if within(&face(&raw[a]), &raw[b].unique_in)
                    || within(&face(&raw[b]), &raw[a].unique_in)
                {
                    let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
                    parent[ra.max(rb)] = ra.min(rb);
                }
            }
        }
    }
    let mut id: HashMap<usize, usize> = HashMap::new();
    for k in 0..raw.len() {
        let root = find(&mut parent, k);
        if let std::collections::hash_map::Entry::Vacant(e) = id.entry(root) {
            e.insert(out.crossings.len());
            let c = &raw[root];
            out.crossings.push(SpaceCrossing {
                axis: c.axis,
                at: c.at,
                enclosure: c.enclosure.clone(),
                on_boundary: c.on_boundary,
                unique_in: c.unique_in.clone(),
                singular: c.singular,
            });
        }
    }
    let named: Vec<usize> = (0..raw.len()).map(|k| id[&find(&mut parent, k)]).collect();
    let ends = |k: usize| named[k];
    out.arcs = arcs
        .into_iter()
        .map(|a| SpaceArc {
            from: ends(a.from),
            to: ends(a.to),
            cell: a.cell,
            monotone_in: a.monotone_in,
            deviation: a.deviation,
        })
        .collect();
    let edges: Vec<(usize, usize)> = out.arcs.iter().map(|a| (a.from, a.to)).collect();
    // A branch ending at a singular point whose star was decided is complete there.
    let crossings = &out.crossings;
    out.branches = super::chain::chain(
        &edges,
        crossings.len(),
        &|v| crossings[v].on_boundary,
        &|v| crossings[v].singular.is_some(),
    )
    .into_iter()
    .map(|c| SpaceBranch {
        crossings: c.vertices,
        closed: c.closed,
        complete: c.complete,
    })
    .collect();
    named
}
