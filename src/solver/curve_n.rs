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
//! one crossing when each one's enclosure lies in the other's uniqueness region. With a
//! tolerance, a bound on the second derivative of the curve's graph (implicit differentiation
//! in interval arithmetic) bounds the distance between each arc and its chord. The guarantees
//! are in `proofs/space-curves.md`; what is not decided within the budgets (singular points,
//! the curve along a box edge or tangent to a face on a grid hyperplane) is reported unresolved
//! with its box.

use super::curve2::TIME_LIMIT_REASON;
use super::dyadic::Dyadic;
use super::system::{inverse, solve_system, DyadicBoxN, SystemOptions};
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
    /// Budgets of the square systems solved on box faces (their `refine_width` is the width
    /// of the crossings' enclosures).
    pub face: SystemOptions,
    /// Per variable, the largest allowed distance between an arc and its chord in that
    /// coordinate (`f64::INFINITY` where it does not matter); `None`: topology only.
    pub tolerance: Option<Vec<f64>>,
    /// A wall-clock time after which no box is subdivided any more.
    pub deadline: Option<std::time::Instant>,
}

impl Default for SpaceCurveOptions {
    fn default() -> Self {
        SpaceCurveOptions {
            max_depth: 16,
            max_boxes: 200_000,
            face: SystemOptions {
                max_depth: 20,
                max_boxes: 4_000,
                refine_width: 1e-12,
            },
            tolerance: None,
            deadline: None,
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
}

impl SpaceCrossing {
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
    /// The variable the arc is a graph over (strictly monotone along it).
    pub monotone_in: usize,
    /// With a tolerance: per variable, a proven bound on the distance in that coordinate
    /// between the arc and the chord between its crossings' centres (at equal `monotone_in`).
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
}

/// A crossing as one box found it.
struct RawCrossing {
    axis: usize,
    at: Dyadic,
    enclosure: Vec<[f64; 2]>,
    /// Where it is the only root of the face system (face coordinates: `axis` left out).
    unique_in: Vec<[f64; 2]>,
    on_boundary: bool,
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
    /// and whether every arc is within the tolerance.
    Arcs {
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

/// `p` with variable `axis` fixed at the dyadic `c = k / 2^e`, times `2^(e·d)` (d its degree in
/// that variable): integer de Casteljau steps `x ← (2^e − k) x_i + k x_{i+1}` on every fibre,
/// exact, a positive multiple of the restriction (the same zeros and signs).
pub(crate) fn fix_variable(p: &Bernstein<Rational>, axis: usize, c: Dyadic) -> Bernstein<Rational> {
    let q = c.to_rational();
    let den = Rational::from(q.denom().clone());
    let num = Rational::from(q.numer().clone());
    let rest = Rational::from(&den - &num);
    let n = p.nvars();
    let d = p.degrees()[axis];
    let stride = p.stride(axis);
    let degrees: Vec<usize> = (0..n)
        .filter(|&k| k != axis)
        .map(|k| p.degrees()[k])
        .collect();
    let mut coeffs = Vec::with_capacity(p.coeffs().len() / (d + 1));
    for flat in 0..p.coeffs().len() {
        if p.multi_index(flat)[axis] != 0 {
            continue;
        }
        let mut fibre: Vec<Rational> = (0..=d)
            .map(|i| p.coeffs()[flat + i * stride].clone())
            .collect();
        for len in (1..=d).rev() {
            for i in 0..len {
                fibre[i] = Rational::from(&rest * &fibre[i]) + Rational::from(&num * &fibre[i + 1]);
            }
        }
        coeffs.push(fibre.swap_remove(0));
    }
    if degrees.is_empty() {
        return Bernstein::constant(1, coeffs.swap_remove(0));
    }
    Bernstein::new(&degrees, coeffs).expect("the remaining degrees fit the coefficients")
}

/// The hull of a polynomial's coefficients: an enclosure of its range on its box.
fn range(p: &Bernstein<Interval>) -> Interval {
    let c = p.coeffs();
    c[1..].iter().fold(c[0], |a, b| a.hull(b))
}

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

struct Solver<'a> {
    eqs: &'a [Bernstein<Rational>],
    n: usize,
    opts: &'a SpaceCurveOptions,
    faces: HashMap<(usize, Dyadic), Vec<Bernstein<Rational>>>,
}

impl Solver<'_> {
    /// The square system on the hyperplane `x_axis = at` (cached).
    fn face_system(&mut self, axis: usize, at: Dyadic) -> &[Bernstein<Rational>] {
        let eqs = self.eqs;
        self.faces
            .entry((axis, at))
            .or_insert_with(|| eqs.iter().map(|p| fix_variable(p, axis, at)).collect())
    }

    /// Decides one box from its polynomials (local coordinates).
    fn settle(&mut self, cell: &DyadicBoxN, polys: &[Bernstein<Interval>]) -> Settled {
        let n = self.n;
        let jac: Vec<Vec<Interval>> = polys
            .iter()
            .map(|f| (0..n).map(|k| range(&f.deriv(k))).collect())
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
            return Settled::Open(
                "no Jacobian minor is proven regular (near a singular point of the curve, or \
                 where its equations are nearly dependent)",
            );
        };
        let mut crossings = Vec::new();
        for axis in 0..n {
            for at in [cell[axis].0, cell[axis].1] {
                let domain: DyadicBoxN = (0..n).filter(|&k| k != axis).map(|k| cell[k]).collect();
                let opts = self.opts.face.clone();
                let system = self.face_system(axis, at).to_vec();
                let roots = solve_system(&system, &[], &domain, &opts);
                if !roots.unresolved.is_empty() {
                    return Settled::Open(
                        "a face crossing was not isolated (the curve touches a face of the box)",
                    );
                }
                for r in roots.roots {
                    let strictly_inside = r
                        .enclosure
                        .iter()
                        .zip(&domain)
                        .all(|(e, d)| d.0.to_f64() < e[0] && e[1] < d.1.to_f64());
                    if !strictly_inside {
                        return Settled::Open(
                            "the curve passes through or near an edge of the box",
                        );
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
                    });
                }
            }
        }
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
        let (deviations, accurate) = self.deviations(cell, polys, &jac, i, &c, beta, &crossings);
        Settled::Arcs {
            monotone_in: i,
            crossings,
            deviations,
            accurate,
        }
    }

    /// Per arc (consecutive pairs of crossings) and variable, a bound on the distance between
    /// the arc and its chord (`proofs/space-curves.md`, Claim 3), and whether all are within
    /// the tolerance.
    #[allow(clippy::too_many_arguments)]
    fn deviations(
        &self,
        cell: &DyadicBoxN,
        polys: &[Bernstein<Interval>],
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
        // r_j = D²F_j(t, t) over the box.
        let r: Vec<Interval> = polys
            .iter()
            .map(|f| {
                let mut s = Interval::point(0.0);
                for a in 0..n {
                    let fa = f.deriv(a);
                    for (b, tb) in t.iter().enumerate() {
                        s = s.add(&range(&fa.deriv(b)).mul(&t[a]).mul(tb));
                    }
                }
                s
            })
            .collect();
        let curvature = over_one_minus(times_norm(c, &r), beta);
        let refine = self.opts.face.refine_width;
        let mut accurate = true;
        let devs = crossings
            .chunks_exact(2)
            .map(|pair| {
                let span = (pair[1].enclosure[i][1] - pair[0].enclosure[i][0]) / width[i];
                let dev: Vec<f64> = (0..n)
                    .map(|k| {
                        if k == i {
                            return 0.0;
                        }
                        // In local coordinates the arc deviates from its chord by at most
                        // span² |η''| / 8; back to global: times the width.
                        let local = Interval::point(span * span / 8.0)
                            .mul(&Interval::point(curvature))
                            .hi();
                        let global = Interval::point(local).mul(&Interval::point(width[k])).hi();
                        global.min(width[k]) + refine
                    })
                    .collect();
                accurate &= dev.iter().zip(tol).all(|(d, t)| d <= t);
                Some(dev)
            })
            .collect();
        (devs, accurate)
    }
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
    let n = eqs.first().map_or(0, |p| p.nvars());
    assert!(
        n >= 2 && eqs.len() == n - 1 && eqs.iter().all(|p| p.nvars() == n),
        "n − 1 polynomials in n ≥ 2 variables"
    );
    let eqs: Vec<Bernstein<Rational>> = eqs.iter().map(integral).collect();
    let mut solver = Solver {
        eqs: &eqs,
        n,
        opts,
        faces: HashMap::new(),
    };
    let mut out = SpaceCurve {
        nvars: n,
        within_tolerance: true,
        ..SpaceCurve::default()
    };
    let mut raw: Vec<RawCrossing> = Vec::new();
    let mut arcs: Vec<RawArc> = Vec::new();
    let mut stack = vec![Item {
        cell: vec![(Dyadic::ZERO, Dyadic::ONE); n],
        depth: 0,
        polys: eqs.iter().map(|p| p.convert(Precision::F64)).collect(),
        exact: false,
    }];
    while let Some(item) = stack.pop() {
        out.boxes += 1;
        if item.polys.iter().any(excludes) {
            continue;
        }
        let (reason, accurate_enough) = match solver.settle(&item.cell, &item.polys) {
            Settled::Arcs {
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
                    let first = raw.len();
                    raw.extend(crossings);
                    for (k, deviation) in deviations.into_iter().enumerate() {
                        arcs.push(RawArc {
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
        if accurate_enough && !item.exact && item.depth >= 3 && slack(&item.polys) > 1e-9 {
            out.escalations += 1;
            let lo: Vec<Rational> = item.cell.iter().map(|d| d.0.to_rational()).collect();
            let hi: Vec<Rational> = item.cell.iter().map(|d| d.1.to_rational()).collect();
            let polys = eqs
                .iter()
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
        let mut children = vec![(item.cell.clone(), item.polys)];
        for axis in 0..n {
            let mut next = Vec::with_capacity(children.len() * 2);
            for (b, ps) in children {
                let mid = b[axis]
                    .0
                    .midpoint(b[axis].1)
                    .expect("max_depth is below the dyadic limit");
                let (mut l, mut r) = (b.clone(), b);
                l[axis].1 = mid;
                r[axis].0 = mid;
                let (pl, pr): (Vec<_>, Vec<_>) = ps.iter().map(|p| p.subdivide_half(axis)).unzip();
                next.push((l, pl));
                next.push((r, pr));
            }
            children = next;
        }
        for (cell, polys) in children.into_iter().rev() {
            stack.push(Item {
                cell,
                depth: item.depth + 1,
                polys,
                exact: false,
            });
        }
    }
    assemble(&mut out, raw, arcs);
    out
}

/// Names each crossing once (two raw crossings on one hyperplane are the same point when one's
/// enclosure lies in the other's uniqueness region), and chains the arcs into branches.
fn assemble(out: &mut SpaceCurve, raw: Vec<RawCrossing>, arcs: Vec<RawArc>) {
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
        if !c.on_boundary {
            by_plane.entry((c.axis, c.at)).or_default().push(k);
        }
    }
    let face = |c: &RawCrossing| -> Vec<[f64; 2]> {
        c.enclosure
            .iter()
            .enumerate()
            .filter(|&(k, _)| k != c.axis)
            .map(|(_, e)| *e)
            .collect()
    };
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
            });
        }
    }
    let mut ends = |k: usize| id[&find(&mut parent, k)];
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
    let boundary: Vec<bool> = out.crossings.iter().map(|c| c.on_boundary).collect();
    out.branches = super::chain::chain(&edges, out.crossings.len(), &|v| boundary[v])
        .into_iter()
        .map(|c| SpaceBranch {
            crossings: c.vertices,
            closed: c.closed,
            complete: c.complete,
        })
        .collect();
}
