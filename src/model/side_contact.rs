//! Patch sides that run along another patch's side without being welded as one edge: the
//! faces of a surface model written side by side with gaps larger than its stated resolution,
//! or meeting at T-junctions (a side of one patch along part of a side of another).
//!
//! The weld ([`super::PatchAdjacency`]) matches corners and whole sides within a tolerance;
//! two patches that meet only like this share no corner, so nothing tells the analyses that
//! they are neighbours. Their untrimmed surfaces then touch or cross along the common side,
//! where no certified solver can separate them (the intersection curve runs in the domain's
//! boundary, often tangentially). A measured side contact makes such a pair adjacent, with
//! the assumption stated in every report that uses it ([`contact_assumption`]): the two
//! patches meet along that side and do not cross each other elsewhere. The measurement is in
//! floating point and proves nothing; it only decides which pairs the assumption covers.

use super::{Model, PatchAdjacency, WeldTolerance};
use crate::surface::{DrawPatch, Edge, RationalPatch};

/// Two patch sides found running along each other.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SideContact {
    /// The two patches (first < second).
    pub patches: [usize; 2],
    /// Their sides that run along each other.
    pub sides: [Edge; 2],
    /// The largest distance measured between a sampled point of the stretch and the other
    /// side (model units, floating point).
    pub gap: f64,
}

/// The side contacts of a model, as `limn info` reports them.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ContactSummary {
    /// The tolerance they were measured with ([`contact_tolerance`]).
    pub tolerance: f64,
    /// The pairs of patches in contact.
    pub pairs: Vec<[usize; 2]>,
    /// The largest gap measured.
    pub largest_gap: f64,
}

impl ContactSummary {
    /// Sums up contacts measured with `tolerance`.
    pub fn of(contacts: &[SideContact], tolerance: f64) -> ContactSummary {
        ContactSummary {
            tolerance,
            pairs: contacts.iter().map(|c| c.patches).collect(),
            largest_gap: contacts.iter().map(|c| c.gap).fold(0.0, f64::max),
        }
    }
}

/// Samples along a side, ends included (`COARSE` a multiple of `SAMPLES − 1`).
const SAMPLES: usize = 17;
/// Consecutive samples within the tolerance that make a stretch: an eighth of the side.
const STRETCH: usize = 3;
/// Coarse samples of the other side before refining the nearest parameter.
const COARSE: usize = 32;

/// The tolerance within which sides are taken to meet: the weld distance, and at least 10⁻⁵
/// of the model's diagonal (CAD files state resolutions their faces do not keep).
pub fn contact_tolerance(weld: Option<f64>, diagonal: f64) -> f64 {
    weld.unwrap_or(0.0).max(1e-5 * diagonal)
}

/// The side contacts of a model's patches that share no welded corner, with the tolerance
/// they were measured with ([`contact_tolerance`]); none for a model with trimmed faces
/// (their patches' sides are not the faces' boundaries).
pub fn model_contacts(
    model: &Model,
    adjacency: &PatchAdjacency,
    weld: WeldTolerance,
) -> (Vec<SideContact>, f64) {
    let tol = contact_tolerance(weld.distance(), model.diagonal());
    if !model.faces.is_empty() {
        return (Vec::new(), tol);
    }
    let surfaces: Vec<&RationalPatch> = model.patches.iter().map(|p| &p.surface).collect();
    let found = side_contacts(&surfaces, |a, b| adjacency.shares_corner(a, b), tol);
    (found, tol)
}

/// The side contacts of patches that share no corner (`adjacent` says which pairs already
/// do): a stretch of one side (at least 3 consecutive of 17 samples)
/// within `tol` of a side of the other.
pub fn side_contacts(
    patches: &[&RationalPatch],
    adjacent: impl Fn(usize, usize) -> bool,
    tol: f64,
) -> Vec<SideContact> {
    let draw: Vec<DrawPatch> = patches.iter().map(|p| DrawPatch::new(p)).collect();
    let boxes: Vec<[[f64; 2]; 3]> = patches
        .iter()
        .flat_map(|p| Edge::ALL.map(|e| side_box(p, e, tol)))
        .collect();
    // Each side at COARSE + 1 points, once (every other one is a sample of the stretch).
    let samples: Vec<Vec<[f64; 3]>> = draw
        .iter()
        .flat_map(|d| {
            Edge::ALL.map(|e| {
                (0..=COARSE)
                    .map(|i| {
                        let (u, v) = side_point(e, i as f64 / COARSE as f64);
                        d.eval(u, v)
                    })
                    .collect()
            })
        })
        .collect();
    let mut out = Vec::new();
    for p in 0..patches.len() {
        for q in p + 1..patches.len() {
            if adjacent(p, q) {
                continue;
            }
            'sides: for (a, ea) in Edge::ALL.into_iter().enumerate() {
                for (b, eb) in Edge::ALL.into_iter().enumerate() {
                    let (i, j) = (4 * p + a, 4 * q + b);
                    // A side collapsed to a point (a pole, an apex) touches, it runs along
                    // nothing.
                    if !boxes_meet(&boxes[i], &boxes[j])
                        || collapsed(&samples[i], tol)
                        || collapsed(&samples[j], tol)
                    {
                        continue;
                    }
                    let from_p = || {
                        may_stretch(&samples[i], &boxes[j])
                            .then(|| stretch_gap(&samples[i], &samples[j], &draw[q], eb, tol))
                            .flatten()
                    };
                    let from_q = || {
                        may_stretch(&samples[j], &boxes[i])
                            .then(|| stretch_gap(&samples[j], &samples[i], &draw[p], ea, tol))
                            .flatten()
                    };
                    if let Some(gap) = from_p().or_else(from_q) {
                        out.push(SideContact {
                            patches: [p, q],
                            sides: [ea, eb],
                            gap,
                        });
                        break 'sides;
                    }
                }
            }
        }
    }
    out
}

/// The stated assumption of a report that takes side contacts as adjacency.
pub fn contact_assumption(contacts: &[SideContact], tol: f64) -> String {
    let largest = contacts.iter().map(|c| c.gap).fold(0.0f64, f64::max);
    let pairs: Vec<String> = contacts
        .iter()
        .take(8)
        .map(|c| format!("{} and {}", c.patches[0], c.patches[1]))
        .collect();
    let more = if contacts.len() > 8 { ", …" } else { "" };
    format!(
        "{} pairs of patches whose sides run along each other within {tol:.1e} without a common corner (patches {}{more}; largest gap measured {largest:.1e}, in floating point) meet along those sides and do not cross each other elsewhere, as patches sharing an edge: their intersection is not searched",
        contacts.len(),
        pairs.join(", ")
    )
}

/// The parameter point of side `e` at `t`.
fn side_point(e: Edge, t: f64) -> (f64, f64) {
    match e {
        Edge::V0 => (t, 0.0),
        Edge::U1 => (1.0, t),
        Edge::V1 => (t, 1.0),
        Edge::U0 => (0.0, t),
    }
}

/// The box of a side's control points, grown by `tol` (it holds the side: positive weights).
fn side_box(p: &RationalPatch, e: Edge, tol: f64) -> [[f64; 2]; 3] {
    let mut b = [[f64::INFINITY, f64::NEG_INFINITY]; 3];
    for (pt, _) in p.edge(e) {
        for k in 0..3 {
            let x = pt[k].to_f64();
            b[k] = [b[k][0].min(x), b[k][1].max(x)];
        }
    }
    // The rounding to f64 is far below `tol`; grow by a little more than `tol`.
    b.map(|[lo, hi]| {
        let slack = tol + 1e-12 * lo.abs().max(hi.abs());
        [lo - slack, hi + slack]
    })
}

/// Whether a side's points all lie within `2 tol` of its first one.
fn collapsed(side: &[[f64; 3]], tol: f64) -> bool {
    side.iter().all(|x| distance(*x, side[0]) <= 2.0 * tol)
}

fn boxes_meet(a: &[[f64; 2]; 3], b: &[[f64; 2]; 3]) -> bool {
    (0..3).all(|k| a[k][0] <= b[k][1] && b[k][0] <= a[k][1])
}

fn distance(x: [f64; 3], y: [f64; 3]) -> f64 {
    ((x[0] - y[0]).powi(2) + (x[1] - y[1]).powi(2) + (x[2] - y[2]).powi(2)).sqrt()
}

/// Whether [`STRETCH`] consecutive samples of a side (every other of `side`) lie in `other`
/// (the other side's box grown by the tolerance): a stretch cannot be nearer than that.
fn may_stretch(side: &[[f64; 3]], other: &[[f64; 2]; 3]) -> bool {
    let mut run = 0;
    for x in side.iter().step_by(COARSE / (SAMPLES - 1)) {
        if (0..3).all(|k| other[k][0] <= x[k] && x[k] <= other[k][1]) {
            run += 1;
            if run >= STRETCH {
                return true;
            }
        } else {
            run = 0;
        }
    }
    false
}

/// The largest distance from the samples of a stretch of a side (`side`: its points at
/// `COARSE + 1` parameters, every other one a sample) to side `eb` of `b` (`coarse`: its
/// points), if a stretch of [`STRETCH`] consecutive samples lies within `tol` of it.
fn stretch_gap(
    side: &[[f64; 3]],
    coarse: &[[f64; 3]],
    b: &DrawPatch,
    eb: Edge,
    tol: f64,
) -> Option<f64> {
    let on_b = |t: f64| {
        let (u, v) = side_point(eb, t);
        b.eval(u, v)
    };
    // Every point of the side is within about `spacing` of a coarse point: a sample farther
    // than `tol + spacing` from all of them is not refined.
    let spacing = coarse
        .windows(2)
        .map(|w| distance(w[0], w[1]))
        .fold(0.0f64, f64::max);
    let (mut run, mut best_run, mut gap, mut best_gap) = (0, 0, 0.0f64, 0.0f64);
    for x in side.iter().step_by(COARSE / (SAMPLES - 1)) {
        let near = coarse
            .iter()
            .map(|y| distance(*x, *y))
            .fold(f64::INFINITY, f64::min);
        let d = if near > tol + spacing {
            near
        } else {
            nearest_distance(*x, coarse, &on_b)
        };
        if d <= tol {
            run += 1;
            gap = gap.max(d);
            if run > best_run {
                best_run = run;
                best_gap = gap;
            }
        } else {
            run = 0;
            gap = 0.0;
        }
    }
    (best_run >= STRETCH).then_some(best_gap)
}

/// The distance from `x` to a side: the nearest coarse sample, refined by a ternary search
/// on the two intervals beside it (the side is smooth; this is a measurement, not a bound).
fn nearest_distance(x: [f64; 3], coarse: &[[f64; 3]], on: &impl Fn(f64) -> [f64; 3]) -> f64 {
    let (mut k, mut d) = (0, f64::INFINITY);
    for (i, y) in coarse.iter().enumerate() {
        let e = distance(x, *y);
        if e < d {
            (k, d) = (i, e);
        }
    }
    if !d.is_finite() {
        return f64::INFINITY;
    }
    let n = (coarse.len() - 1) as f64;
    let (mut lo, mut hi) = ((k as f64 - 1.0).max(0.0) / n, (k as f64 + 1.0).min(n) / n);
    let f = |t: f64| distance(x, on(t));
    for _ in 0..40 {
        let (m1, m2) = (lo + (hi - lo) / 3.0, hi - (hi - lo) / 3.0);
        if f(m1) < f(m2) {
            hi = m2;
        } else {
            lo = m1;
        }
    }
    d.min(f(0.5 * (lo + hi)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::number::Rational;
    use crate::surface::Point3;

    fn plane(x0: i64, x1: i64, y0: i64, y1: i64, z: Rational) -> RationalPatch {
        let p = |x: i64, y: i64| -> Point3 { [Rational::from(x), Rational::from(y), z.clone()] };
        RationalPatch::polynomial([1, 1], vec![p(x0, y0), p(x0, y1), p(x1, y0), p(x1, y1)]).unwrap()
    }

    #[test]
    fn a_t_junction_and_a_gap_are_contacts_a_far_side_is_not() {
        let gap = Rational::from((1i64, 100_000i64));
        let big = plane(0, 2, 0, 2, Rational::new());
        // Its side x = 2 along half of the big one's side x = 2 (a T-junction), lifted by 1e-5.
        let small = plane(2, 3, 0, 1, gap.clone());
        let far = plane(5, 6, 0, 1, Rational::new());
        let patches = [&big, &small, &far];
        let found = side_contacts(&patches, |_, _| false, 1e-4);
        assert_eq!(found.len(), 1, "{found:?}");
        assert_eq!(found[0].patches, [0, 1]);
        assert!((found[0].gap - 1e-5).abs() < 1e-9, "{}", found[0].gap);
        assert_eq!(found[0].sides, [Edge::U1, Edge::U0]);
        // Within a tolerance below the gap, no contact; adjacent pairs are skipped.
        assert!(side_contacts(&patches, |_, _| false, 1e-6).is_empty());
        assert!(side_contacts(&patches, |_, _| true, 1e-4).is_empty());
    }

    #[test]
    fn a_side_collapsed_onto_another_side_is_no_contact() {
        let a = plane(0, 1, 0, 1, Rational::new());
        // A triangle whose side u = 0 is the point (1, 1/2, 0) on a's side x = 1.
        let p = |x: Rational, y: Rational| -> Point3 { [x, y, Rational::new()] };
        let (one, half) = (Rational::from(1), Rational::from((1i64, 2i64)));
        let b = RationalPatch::polynomial(
            [1, 1],
            vec![
                p(one.clone(), half.clone()),
                p(one.clone(), half),
                p(Rational::from(2), Rational::new()),
                p(Rational::from(2), one),
            ],
        )
        .unwrap();
        let found = side_contacts(&[&a, &b], |_, _| false, 1e-4);
        assert!(found.is_empty(), "{found:?}");
    }

    #[test]
    fn sides_that_cross_at_one_point_are_no_contact() {
        let a = plane(0, 1, 0, 1, Rational::new());
        // Its side y = 0 crosses a's side x = 1 at one point, transversally in space.
        let p = |x: i64, y: i64, z: i64| -> Point3 { [x, y, z].map(Rational::from) };
        let b = RationalPatch::polynomial(
            [1, 1],
            vec![p(1, 0, -1), p(1, 2, -1), p(1, 0, 1), p(1, 2, 1)],
        )
        .unwrap();
        let found = side_contacts(&[&a, &b], |_, _| false, 1e-4);
        assert!(found.is_empty(), "{found:?}");
    }
}
