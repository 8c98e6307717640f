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
//! `F` on the box faces, isolated by Krawczyk's test ([`crate::solver::system`]), and two boxes name
//! one crossing when the enclosure of one lies in the uniqueness region of the other. With a
//! tolerance, a bound on the second derivative of the curve's graph (implicit differentiation
//! in interval arithmetic) bounds the distance between each arc and its chord. The guarantees
//! are in `proofs/space-curves.md`; what is not decided within the budgets (singular points,
//! the curve along a box edge or tangent to a face on a grid hyperplane) is reported unresolved
//! with its box.

mod assemble;
mod faces;
mod regular_minor;
pub mod singular_branches;
mod singular_search;
mod subdivision;
pub mod topology;
pub mod warp;

pub use topology::{
    SpaceArc, SpaceBranch, SpaceCrossing, SpaceCurve, SpaceSingularPoint, SpaceUnresolved,
};
pub use warp::{unwarp, unwarp_exact, unwarp_interval, warp, PAIR_WARP};

use crate::bernstein::Bernstein;
use crate::number::Rational;
use crate::reason::Reason;
use crate::solver::precision::Ladder;
use crate::solver::space_curve::assemble::assemble;
use crate::solver::space_curve::singular_branches::HigherPartials;
use crate::solver::space_curve::singular_search::{singular_points_near, star_around, Leaves};
use crate::solver::space_curve::subdivision::{subdivide, Solver};
use crate::solver::space_curve::warp::integral;
use crate::solver::system::SystemOptions;
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
    /// The precision in which a box's polynomials are recomputed from the exact input where
    /// their enclosures have spread: its tightest level ([`Ladder::tightest`]).
    pub ladder: Ladder,
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
                ..SystemOptions::default()
            },
            tolerance: None,
            max_chord: None,
            deadline: None,
            accept: None,
            ladder: Ladder::default(),
        }
    }
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
/// use limn::solver::space_curve::{solve_space_curve, SpaceCurveOptions};
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
#[derive(Clone, Debug, PartialEq)]
pub enum BoxVerdict {
    /// Examine it as usual.
    Solve,
    /// The caller has proven that the box holds no point of the curve it wants (a spurious
    /// component, or a mirror image of another box): it is dropped. The crossings of the
    /// curve on the faces it shares with kept boxes stay, as ends of their branches.
    Drop,
    /// The caller gives up on the box: it is reported unresolved with this reason.
    Unresolved(Reason),
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

/// The star test is tried on boxes around a singular point from this depth on.
pub(crate) const STAR_MIN_DEPTH: u32 = 2;
