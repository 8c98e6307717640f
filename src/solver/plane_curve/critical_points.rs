//! Singular-point candidates of a plane curve `g = 0`: the zeros of `(∂g/∂u, ∂g/∂v)`, isolated
//! by the square-system solver ([`solve_system`], Krawczyk's test, `proofs/krawczyk.md`) inside
//! the boxes the curve solver could not decide, with `g` as a filter.
//!
//! Each isolated critical point of g is then classified: off the curve (g has a strict sign on
//! its enclosure), an exact singular point (a rational point in the enclosure where g and both
//! partial derivatives vanish, checked exactly: it is the unique critical point there), or
//! undecided (an irrational critical point where g's enclosure contains zero).

use crate::bernstein::Bernstein;
use crate::geometry::Rect;
use crate::number::{Interval, Precision, Rational};
use crate::reason::Reason;
use crate::solver::dyadic::{Dyadic, DyadicBox};
use crate::solver::precision::Policy;
use crate::solver::system::{simplest_rational, solve_system, SystemOptions};

/// An isolated critical point of g, with what is known of g there.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct CriticalPoint {
    /// A box in (u, v) that contains it.
    pub enclosure: Rect,
    /// The box where it is the only zero of the gradient (Krawczyk's test).
    pub unique_in: Rect,
    /// Its exact rational coordinates, when it is an exact singular point of the curve.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub exact: Option<[String; 2]>,
    /// `Some(true)`: on the curve (a singular point, proven exactly); `Some(false)`: off the
    /// curve (g has a strict sign on the enclosure); `None`: not decided.
    pub on_curve: Option<bool>,
}

impl CriticalPoint {
    /// Whether it lies in the closed box.
    pub fn in_box(&self, b: &DyadicBox) -> bool {
        b.to_f64().meets(&self.enclosure)
    }

    /// Why an undecided box near it is undecided, in words. The box is said to hold the only
    /// critical point of g in it only when the point's enclosure lies inside the box and the
    /// box inside the region where the point is the gradient's only zero.
    pub fn reason(&self, cell: &DyadicBox) -> Reason {
        let cell = cell.to_f64();
        let sole = cell.contains(&self.enclosure) && self.unique_in.contains(&cell);
        match (&self.on_curve, &self.exact) {
            (Some(true), Some(uv)) => Reason::SingularPointAt { uv: uv.clone() },
            (Some(false), _) => Reason::CriticalPointOffCurve {
                sole,
                at: self.enclosure.center(),
            },
            _ => Reason::CriticalPointUndecided {
                sole,
                enclosure: self.enclosure,
            },
        }
    }
}

fn rational(x: f64) -> Option<Rational> {
    Rational::from_f64(x)
}

/// At most this many clusters of undecided boxes are searched for critical points.
const MAX_CLUSTERS: usize = 32;

/// Groups boxes that touch (share an edge or a corner) and returns each group's bounding box.
fn clusters(boxes: &[DyadicBox]) -> Vec<DyadicBox> {
    let touch =
        |a: &DyadicBox, b: &DyadicBox| (0..2).all(|k| a.lo[k] <= b.hi[k] && b.lo[k] <= a.hi[k]);
    let mut groups: Vec<DyadicBox> = Vec::new();
    for b in boxes {
        let mut hull = *b;
        // Merge every group this box (grown by merging) touches, until none does.
        while let Some(i) = groups.iter().position(|g| touch(g, &hull)) {
            let g = groups.swap_remove(i);
            for k in 0..2 {
                hull.lo[k] = hull.lo[k].min(g.lo[k]);
                hull.hi[k] = hull.hi[k].max(g.hi[k]);
            }
        }
        groups.push(hull);
    }
    groups.sort_by_key(|a| (a.lo, a.hi));
    groups
}

/// The critical points of g inside the given boxes (each found once), classified. The boxes
/// are searched by clusters (the bounding box of each group of touching boxes), at most
/// `MAX_CLUSTERS` (32) of them, each within the system solver's budget, its refinement up
/// `ladder` (counted into `counts`).
pub fn critical_points(
    g: &Bernstein<Rational>,
    boxes: &[DyadicBox],
    policy: &mut Policy,
) -> Vec<CriticalPoint> {
    let (gu, gv) = (g.deriv(0), g.deriv(1));
    let opts = SystemOptions {
        max_depth: 12,
        max_boxes: 500,
        refine_width: 1e-13,
        ladder: *policy.ladder,
    };
    let mut out: Vec<CriticalPoint> = Vec::new();
    for b in clusters(boxes).iter().take(MAX_CLUSTERS) {
        let domain = vec![(b.lo[0], b.hi[0]), (b.lo[1], b.hi[1])];
        let roots = solve_system(
            &[gu.clone(), gv.clone()],
            std::slice::from_ref(g),
            &domain,
            &opts,
        );
        policy.counts.merge(&roots.escalations);
        for r in roots.roots {
            let e = Rect::from_axes(r.enclosure[0], r.enclosure[1]);
            let u = Rect::from_axes(r.unique_in[0], r.unique_in[1]);
            let same = |c: &CriticalPoint| c.unique_in.contains(&e) || u.contains(&c.enclosure);
            if out.iter().any(same) {
                continue;
            }
            out.push(classify(g, &gu, &gv, e, u));
        }
    }
    out
}

fn classify(
    g: &Bernstein<Rational>,
    gu: &Bernstein<Rational>,
    gv: &Bernstein<Rational>,
    enclosure: Rect,
    unique_in: Rect,
) -> CriticalPoint {
    let mut cp = CriticalPoint {
        enclosure,
        unique_in,
        exact: None,
        on_curve: None,
    };
    let (Some(lo), Some(hi)) = (
        enclosure
            .lo
            .iter()
            .map(|&x| rational(x))
            .collect::<Option<Vec<_>>>(),
        enclosure
            .hi
            .iter()
            .map(|&x| rational(x))
            .collect::<Option<Vec<_>>>(),
    ) else {
        return cp;
    };
    // g on the enclosure: a strict sign puts the critical point off the curve.
    let range: Bernstein<Interval> = g.restrict_box_rational(&lo, &hi).convert(Precision::F64);
    let c = range.coeffs();
    if c.iter().all(|x| x.lo() > 0.0) || c.iter().all(|x| x.hi() < 0.0) {
        cp.on_curve = Some(false);
        return cp;
    }
    // The simplest rational point of the enclosure: if g and its gradient vanish there
    // exactly, it is the critical point (the only one in `unique_in`), on the curve.
    let nonneg = |x: &Rational| x.clone().max(Rational::new());
    let p: Vec<Rational> = (0..2)
        .map(|k| simplest_rational(&nonneg(&lo[k]), &nonneg(&hi[k])))
        .collect();
    if (0..2).all(|k| p[k] >= lo[k] && p[k] <= hi[k])
        && [g, gu, gv]
            .iter()
            .all(|f| f.eval(&p).cmp0() == std::cmp::Ordering::Equal)
    {
        cp.exact = Some([p[0].to_string(), p[1].to_string()]);
        cp.on_curve = Some(true);
    }
    cp
}

/// The dyadic point of a singular point's exact coordinates, if both are dyadic.
pub fn dyadic_point(cp: &CriticalPoint) -> Option<(Dyadic, Dyadic)> {
    let [u, v] = cp.exact.as_ref()?;
    Some((parse_dyadic(u)?, parse_dyadic(v)?))
}

fn parse_dyadic(s: &str) -> Option<Dyadic> {
    let (num, den) = match s.split_once('/') {
        Some((n, d)) => (n.parse::<u64>().ok()?, d.parse::<u64>().ok()?),
        None => (s.parse::<u64>().ok()?, 1),
    };
    if !den.is_power_of_two() {
        return None;
    }
    let exp = den.trailing_zeros();
    (exp <= crate::solver::dyadic::MAX_DEPTH && num <= den).then(|| Dyadic::new(num, exp))
}
