//! The self-visible type of a patch for a view (paper 000, section 2): entirely front-facing,
//! entirely back-facing, or partially front-facing, proven from the exact silhouette function.
//!
//! The paper decides the type from the control-net normals, which is a heuristic (a control
//! net can turn away while the surface does not). limn decides it from the Bernstein
//! coefficients of the exact silhouette function `g` ([`crate::analysis::contour::silhouette::silhouette_function`]),
//! subdividing where they have mixed signs: when every coefficient on every box of a cover
//! of the square has the front-facing sign, so does `g` on the whole patch (the Bernstein
//! range property, `proofs/coefficient-range.md`). Partial is proven by two exact points of
//! opposite strict signs. What neither settles within the budget is `Undecided`, never a
//! guess.

use crate::analysis::contour::silhouette::silhouette_function;

use crate::analysis::view::View;
use crate::bernstein::Bernstein;
use crate::number::{Interval, Precision, Rational, Sign};
use crate::solver::dyadic::{Dyadic, DyadicBox};
use crate::solver::plane_curve::box_signs::strict_sign;
use crate::solver::precision::Policy;
use crate::solver::univariate::PointSign;
use crate::surface::RationalPatch;

/// The self-visible type of a patch.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Facing {
    /// Front-facing at every point (proven): no silhouette inside.
    Front,
    /// Back-facing at every point (proven).
    Back,
    /// Front-facing somewhere and back-facing somewhere (proven by two exact points).
    Partial,
    /// The silhouette function vanishes identically: the patch is seen edge-on.
    EdgeOn,
    /// Neither sign everywhere nor both signs were proven within the budget (for example a
    /// patch that is front-facing except where it is seen exactly edge-on).
    Undecided,
}

/// The deepest subdivision when deciding a type.
const MAX_DEPTH: u32 = 10;

/// The self-visible type of a patch for a view, every sign decided through the caller's
/// precision ladder (its counts in `policy`).
///
/// # Examples
/// ```
/// use limn::analysis::visibility::facing::{facing, Facing};
/// use limn::analysis::view::View;
/// use limn::number::Rational;
/// use limn::solver::{Escalations, Ladder, Policy};
/// use limn::testing::shapes;
/// let torus = shapes::torus(&Rational::from(2), &Rational::from(1));
/// let tilted = View::Direction([1, 2, -20].map(Rational::from));
/// let (ladder, mut counts) = (Ladder::default(), Escalations::default());
/// let mut policy = Policy::new(&ladder, &mut counts);
/// // Seen from nearly above, the top patches face the viewer and the bottom ones away.
/// let kinds: Vec<Facing> = torus.iter().map(|p| facing(p, &tilted, &mut policy)).collect();
/// assert!(kinds.contains(&Facing::Front) && kinds.contains(&Facing::Back));
/// ```
pub fn facing(patch: &RationalPatch, view: &View, policy: &mut Policy) -> Facing {
    let g = silhouette_function(patch, view);
    facing_of_function(&g, front_sign(view), policy)
}

/// The sign of the silhouette function on the front-facing side of a view: negative for a
/// direction (`Ñ · V < 0`), positive for an eye (`Ñ · (E − S) > 0`).
pub fn front_sign(view: &View) -> Sign {
    match view {
        View::Direction(_) => Sign::Negative,
        View::Eye(_) => Sign::Positive,
    }
}

/// The type from the silhouette function and the sign of its front-facing side.
///
/// A box's coefficients are taken in f64 intervals carried down the subdivision; where they
/// show one strict sign and some undecided coefficients, the box's polynomial is recomputed
/// from the exact `g` up the ladder ([`crate::solver::plane_curve`]'s box signs); the value at
/// a box centre is decided the same way, f64 first.
pub fn facing_of_function(g: &Bernstein<Rational>, front: Sign, policy: &mut Policy) -> Facing {
    if g.is_zero() {
        return Facing::EdgeOn;
    }
    let as_facing = |s: Sign| {
        if s == front {
            Facing::Front
        } else {
            Facing::Back
        }
    };
    // Points of each strict sign, found at box centres.
    let mut seen = [false, false];
    let note = |seen: &mut [bool; 2], s: Sign| match s {
        Sign::Positive => seen[0] = true,
        Sign::Negative => seen[1] = true,
        _ => {}
    };
    let gi: Bernstein<Interval> = g.convert(Precision::F64);
    let mut common: Option<Sign> = None;
    let mut mixed = false;
    let mut stack = vec![(gi, DyadicBox::UNIT, 0u32)];
    while let Some((p, cell, depth)) = stack.pop() {
        let (s, _) = strict_sign(&p, g, cell, Some(policy.ladder), policy.counts);
        if matches!(s, Sign::Positive | Sign::Negative) {
            note(&mut seen, s);
            match common {
                None => common = Some(s),
                Some(c) if c != s => mixed = true,
                _ => {}
            }
            continue;
        }
        let halves = [0, 1].map(|a| cell.lo[a].midpoint(cell.hi[a]));
        let (Some(cu), Some(cv)) = (halves[0], halves[1]) else {
            mixed = true;
            continue;
        };
        let centre = PointSign {
            p: g,
            t: vec![cu, cv],
        };
        if let (Some(s), _) = policy.ladder.decide(&centre, policy.counts) {
            note(&mut seen, s);
        }
        if seen[0] && seen[1] {
            return Facing::Partial;
        }
        if depth >= MAX_DEPTH {
            mixed = true;
            continue;
        }
        let (l, r) = p.subdivide_half(0);
        for (q, du) in [(l, false), (r, true)] {
            let (b, t) = q.subdivide_half(1);
            for (c, dv) in [(b, false), (t, true)] {
                let pick = |a: usize, upper: bool, mid: Dyadic| {
                    if upper {
                        (mid, cell.hi[a])
                    } else {
                        (cell.lo[a], mid)
                    }
                };
                let (u0, u1) = pick(0, du, cu);
                let (v0, v1) = pick(1, dv, cv);
                let child = DyadicBox {
                    lo: [u0, v0],
                    hi: [u1, v1],
                };
                stack.push((c, child, depth + 1));
            }
        }
    }
    if seen[0] && seen[1] {
        return Facing::Partial;
    }
    match (common, mixed) {
        (Some(s), false) => as_facing(s),
        _ => Facing::Undecided,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solver::precision::{Escalations, Ladder};
    use crate::testing::shapes;

    fn facing(patch: &RationalPatch, view: &View) -> Facing {
        super::facing(
            patch,
            view,
            &mut Policy::new(&Ladder::default(), &mut Escalations::default()),
        )
    }

    #[test]
    fn torus_types_from_above_and_tilted() {
        let torus = shapes::torus(&Rational::from(2), &Rational::from(1));
        // From exactly above, every patch has a side on the silhouette (the equators are
        // patch boundaries): none is proven front or back, and none is claimed.
        let down = View::Direction([0, 0, -1].map(Rational::from));
        let kinds: Vec<Facing> = torus.iter().map(|p| facing(p, &down)).collect();
        assert!(kinds.iter().all(|k| *k == Facing::Undecided), "{kinds:?}");
        // Tilted a little: the top patches face the viewer, the bottom ones away, and the
        // equator patches straddle the silhouette.
        let tilted = View::Direction([1, 2, -20].map(Rational::from));
        let kinds: Vec<Facing> = torus.iter().map(|p| facing(p, &tilted)).collect();
        for k in [Facing::Front, Facing::Back, Facing::Partial] {
            assert!(kinds.contains(&k), "{k:?} in {kinds:?}");
        }
    }

    #[test]
    fn a_plane_seen_edge_on_is_edge_on() {
        let p = |x: i64, y: i64| [Rational::from(x), Rational::from(y), Rational::new()];
        let sq =
            RationalPatch::polynomial([1, 1], vec![p(0, 0), p(0, 1), p(1, 0), p(1, 1)]).unwrap();
        let side = View::Direction([1, 0, 0].map(Rational::from));
        assert_eq!(facing(&sq, &side), Facing::EdgeOn);
        let down = View::Direction([0, 0, -1].map(Rational::from));
        // S_u × S_v = +z: seen from above along −z, n·V = −1 < 0: front.
        assert_eq!(facing(&sq, &down), Facing::Front);
        assert_eq!(
            facing(&sq, &View::Direction([0, 0, 1].map(Rational::from))),
            Facing::Back
        );
    }

    #[test]
    fn touching_the_silhouette_at_a_corner_is_undecided_not_guessed() {
        // The paraboloid z = u² + v² over [0,1]², seen along x: n = (−2u, −2v, 1) so
        // g = n·(1,0,0) = −2u ≤ 0, zero on the side u = 0: front except on a side.
        let pts: Vec<[Rational; 3]> = (0..3)
            .flat_map(|i| {
                (0..3).map(move |j| {
                    let (u, v) = (Rational::from((i, 2)), Rational::from((j, 2)));
                    // u² has Bernstein coefficients (0, 0, 1) in degree 2.
                    let z = Rational::from(i64::from(i == 2) + i64::from(j == 2));
                    [u, v, z]
                })
            })
            .collect();
        let patch = RationalPatch::polynomial([2, 2], pts).unwrap();
        let view = View::Direction([1, 0, 0].map(Rational::from));
        assert_eq!(facing(&patch, &view), Facing::Undecided);
    }

    #[test]
    fn a_sign_below_f64_is_decided_up_the_ladder_and_counted() {
        // A flat patch in z = 0, (u, v) ↦ (u, v (a + u)) with a = 10^-400, seen along
        // (0, 0, −1): g = −(a + u), whose Bernstein coefficients −a and −(a + 1) have the one
        // sign, but no f64 interval separates −a from 0; MPFR's exponent range does. (g's
        // largest coefficient is 1: its scale is not changed, unlike that of a g that is tiny
        // everywhere, `proofs/silhouette-join.md`, "Scale".)
        let mut tiny = Rational::from(1);
        for _ in 0..400 {
            tiny /= 10;
        }
        let p = |x: Rational, y: Rational| [x, y, Rational::new()];
        let sq = RationalPatch::polynomial(
            [1, 1],
            vec![
                p(Rational::new(), Rational::new()),
                p(Rational::new(), tiny.clone()),
                p(Rational::from(1), Rational::new()),
                p(Rational::from(1), tiny + Rational::from(1)),
            ],
        )
        .unwrap();
        let view = View::Direction([0, 0, -1].map(Rational::from));
        let mut counts = Escalations::default();
        let ladder = Ladder::default();
        let f = super::facing(&sq, &view, &mut Policy::new(&ladder, &mut counts));
        assert_eq!(f, Facing::Front);
        assert!(counts.mpfr.values().sum::<u64>() >= 1, "{counts:?}");
        // Without MPFR and exact levels, nothing is decided, and nothing is guessed.
        let f64_only = Ladder {
            mpfr_start: 64,
            mpfr_cap: 0,
            exact: false,
        };
        let mut counts = Escalations::default();
        let f = super::facing(&sq, &view, &mut Policy::new(&f64_only, &mut counts));
        assert_eq!(f, Facing::Undecided, "{counts:?}");
    }
}
