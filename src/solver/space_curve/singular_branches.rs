//! The branches of a curve `F = 0` (`n − 1` polynomials in `n` variables) through an exact
//! singular point: the *star lemma* of `proofs/space-curves.md` §6.
//!
//! A singular point `p` (where the Jacobian `DF(p)` has rank below `n − 1`) leaves every box
//! around it undecided by the graph test of [`crate::solver::space_curve`]. When `p` is rational it is
//! found exactly ([`exact_singular_point`]: the simplest rational near an undecided box, with
//! `F(p) = 0` and the rank checked in exact arithmetic), and a box `B ∋ p` is then decided by
//! blowing `p` up: every point of `B \ {p}` is `p + r w` for one `r ∈ (0, 1]` and one `w` on
//! the boundary of `B − p`. With an exact invertible row operation `G = L F` that makes the
//! last rows of `DG(p)` vanish, `H_i(r, w) = G_i(p + r w) / r^{o_i}` (`o_i` = 1, or 2 on the
//! vanishing rows) is a polynomial in `(r, w)` whose zeros for `r > 0` are the curve's. On each
//! facet of `∂(B − p)`, Krawczyk's test in `w`, with every enclosure taken over all
//! `r ∈ [0, 1]` (a Taylor form at `p` with a Lagrange remainder over `B`), proves either that a
//! piece of the facet holds no zero for any `r`, or exactly one zero `w(r)` for every `r`: a
//! smooth arc from `p` to the boundary of `B`. If the whole boundary is decided, the curve in
//! `B` is exactly those arcs, meeting only at `p`: its branches through `p`, each ending at one
//! of the box's face crossings.

use crate::bernstein::Bernstein;
use crate::number::{Interval, Number, Precision, Rational};
use crate::reason::Reason;
use crate::solver::system::{inverse, simplest_rational};

/// An exact singular point of the curve, with what the star test needs at it.
#[derive(Clone, Debug)]
pub struct SingularPoint {
    /// Its exact coordinates.
    pub exact: Vec<Rational>,
    /// Outward-rounded enclosures of them.
    pub(crate) at: Vec<Interval>,
    /// The rows of the exact row operation `L` (enclosed), `G = L F`.
    pub(crate) rows: Vec<Vec<Interval>>,
    /// Per row of `G`, the order of its zero at `p`: 1 where `DG_i(p) ≠ 0`, else 2.
    pub(crate) orders: Vec<u32>,
    /// `DG(p)`, exact values enclosed.
    pub(crate) grad: Vec<Vec<Interval>>,
    /// `D²G(p)` of the rows of order 2 (empty for the others), exact values enclosed.
    pub(crate) hess: Vec<Vec<Vec<Interval>>>,
    /// Every row of order 2 has a nonzero Hessian at `p` (else the tangent cone is not cut
    /// out by the quadratic forms, and the star test is not tried).
    pub(crate) quadratic: bool,
    /// The tangent cone's directions are simple zeros of the leading forms (checked once):
    /// else no box passes the star test, and none is tried.
    pub(crate) transversal: bool,
}

impl SingularPoint {
    /// The coordinates in f64 (nearest).
    pub fn point(&self) -> Vec<f64> {
        self.exact.iter().map(Rational::to_f64).collect()
    }

    /// The coordinates as exact fractions, `"a/b"`.
    pub fn exact_strings(&self) -> Vec<String> {
        self.exact.iter().map(|q| q.to_string()).collect()
    }

    /// Whether the star test may be tried on the box `[lo, hi]` (exact dyadic sides): `p` is
    /// strictly inside on every axis, or on a side of the box that is a side of the unit box
    /// (a box never shares that side with a neighbour).
    pub(crate) fn admissible_in(&self, lo: &[Rational], hi: &[Rational]) -> bool {
        self.exact
            .iter()
            .zip(lo.iter().zip(hi))
            .all(|(p, (a, b))| (a < p && p < b) || (*p == 0 && *a == 0) || (*p == 1 && *b == 1))
    }
}

/// The exact partial derivatives of the equations, for the exact tests at candidate points:
/// the first ones made once, the second ones when a point of rank drop needs them.
pub struct ExactPartials {
    /// `first[j][k] = ∂F_j/∂x_k`.
    first: Vec<Vec<Bernstein<Rational>>>,
    /// `second[j]` holds `∂²F_j/∂x_a∂x_b` for `a ≤ b`, in that order.
    second: std::cell::OnceCell<Vec<Vec<Bernstein<Rational>>>>,
}

impl ExactPartials {
    /// The first partials of `eqs`.
    pub fn new(eqs: &[Bernstein<Rational>]) -> ExactPartials {
        let n = eqs.first().map_or(0, Bernstein::nvars);
        ExactPartials {
            first: eqs
                .iter()
                .map(|f| (0..n).map(|k| f.deriv(k)).collect())
                .collect(),
            second: std::cell::OnceCell::new(),
        }
    }

    /// `D²F_j(p)` per equation, full symmetric `n × n`.
    fn hessians_at(&self, p: &[Rational]) -> Vec<Vec<Vec<Rational>>> {
        let n = p.len();
        let second = self.second.get_or_init(|| {
            self.first
                .iter()
                .map(|d| {
                    (0..n)
                        .flat_map(|a| (a..n).map(move |b| (a, b)))
                        .map(|(a, b)| d[a].deriv(b))
                        .collect()
                })
                .collect()
        });
        second
            .iter()
            .map(|s| {
                let values: Vec<Rational> = s.iter().map(|d| d.eval(p)).collect();
                (0..n)
                    .map(|a| {
                        (0..n)
                            .map(|b| values[pair_index(n, a, b)].clone())
                            .collect()
                    })
                    .collect()
            })
            .collect()
    }
}

/// The position of `(min(a, b), max(a, b))` in the list of pairs `a ≤ b` of `0..n`, in order.
fn pair_index(n: usize, a: usize, b: usize) -> usize {
    let (a, b) = (a.min(b), a.max(b));
    a * n - a * (a + 1) / 2 + b
}

/// The position of the sorted triple in the list of triples `a ≤ b ≤ c` of `0..n`, in order.
fn triple_index(n: usize, a: usize, b: usize, c: usize) -> usize {
    let mut t = [a, b, c];
    t.sort_unstable();
    let mut index = 0;
    for x in 0..t[0] {
        // Triples starting with x: pairs y ≤ z of x..n.
        let k = n - x;
        index += k * (k + 1) / 2;
    }
    index + pair_index(n - t[0], t[1] - t[0], t[2] - t[0])
}

/// The exact singular point `p` of `F = 0` if `F(p) = 0` and `DF(p)` has rank below `n − 1`
/// (both decided in exact rational arithmetic), with the row operation and the derivatives
/// the star test uses; `None` otherwise. `partials` are those of `eqs`.
pub fn exact_singular_point(
    eqs: &[Bernstein<Rational>],
    partials: &ExactPartials,
    p: Vec<Rational>,
) -> Option<SingularPoint> {
    if eqs.iter().any(|f| f.eval(&p) != 0) {
        return None;
    }
    let n = p.len();
    let grad_f: Vec<Vec<Rational>> = partials
        .first
        .iter()
        .map(|row| row.iter().map(|d| d.eval(&p)).collect())
        .collect();
    // Gaussian elimination on DF(p), recording the row operations in L.
    let m = eqs.len();
    let mut a = grad_f.clone();
    let mut l: Vec<Vec<Rational>> = (0..m)
        .map(|i| (0..m).map(|j| Rational::from(i32::from(i == j))).collect())
        .collect();
    let mut rank = 0;
    for col in 0..n {
        let Some(piv) = (rank..m).find(|&r| a[r][col] != 0) else {
            continue;
        };
        a.swap(rank, piv);
        l.swap(rank, piv);
        let (pivot, pivot_l) = (a[rank].clone(), l[rank].clone());
        for (row, lrow) in a.iter_mut().zip(l.iter_mut()).skip(rank + 1) {
            if row[col] != 0 {
                let f = Rational::from(&row[col] / &pivot[col]);
                for (x, y) in row.iter_mut().zip(&pivot) {
                    *x -= Rational::from(&f * y);
                }
                for (x, y) in lrow.iter_mut().zip(&pivot_l) {
                    *x -= Rational::from(&f * y);
                }
            }
        }
        rank += 1;
        if rank == m {
            break;
        }
    }
    if rank == m {
        return None;
    }
    let enclose = |q: &Rational| Interval::from_rational(q, Precision::F64);
    let orders: Vec<u32> = (0..m).map(|i| if i < rank { 1 } else { 2 }).collect();
    // D²G_i(p) = Σ_j L_ij D²F_j(p) for the rows of order 2, exactly.
    let mut hess = vec![Vec::new(); m];
    let mut quadratic = true;
    if rank < m {
        let second = partials.hessians_at(&p);
        for (i, h) in hess.iter_mut().enumerate().skip(rank) {
            let exact: Vec<Vec<Rational>> = (0..n)
                .map(|a| {
                    (0..n)
                        .map(|b| {
                            let mut s = Rational::new();
                            for (j, sj) in second.iter().enumerate() {
                                s += Rational::from(&l[i][j] * &sj[a][b]);
                            }
                            s
                        })
                        .collect()
                })
                .collect();
            quadratic &= exact.iter().flatten().any(|x| *x != 0);
            *h = exact
                .iter()
                .map(|r| r.iter().map(enclose).collect())
                .collect();
        }
    }
    let mut sp = SingularPoint {
        at: p.iter().map(enclose).collect(),
        rows: l.iter().map(|r| r.iter().map(enclose).collect()).collect(),
        orders,
        grad: a.iter().map(|r| r.iter().map(enclose).collect()).collect(),
        hess,
        quadratic,
        transversal: false,
        exact: p,
    };
    sp.transversal = cone_is_transversal(&sp);
    Some(sp)
}

/// Rational points near a box `[lo, hi]` where an exact singular point would be, if the curve
/// has one there with small denominators: per coordinate, the simplest rational (smallest
/// denominator) in the closed side, then in the side grown by half its width and by its width
/// on both ends (within `[0, 1]`). A singular point leaves every box that holds it undecided,
/// and is the simplest rational of a small enough one.
pub fn simple_points_near(cell: &[[f64; 2]]) -> Vec<Vec<Rational>> {
    let mut out: Vec<Vec<Rational>> = Vec::new();
    for grow in [0.0, 0.5, 1.0] {
        let p: Vec<Rational> = cell
            .iter()
            .map(|&[a, b]| {
                let w = grow * (b - a);
                let lo = Rational::from_f64((a - w).max(0.0)).unwrap_or_default();
                let hi = Rational::from_f64((b + w).min(1.0)).unwrap_or_else(|| Rational::from(1));
                simplest_rational(&lo, &hi)
            })
            .collect();
        if !out.contains(&p) {
            out.push(p);
        }
    }
    out
}

/// The second and third partial derivatives of the equations (interval polynomials on the
/// unit box), for their ranges over a box.
pub(crate) struct HigherPartials {
    /// Per equation, `∂²F_j/∂x_a∂x_b` for `a ≤ b`, in that order.
    second: Vec<Vec<Bernstein<Interval>>>,
    /// Per equation, `∂³F_j/∂x_a∂x_b∂x_c` for `a ≤ b ≤ c`, in that order.
    third: Vec<Vec<Bernstein<Interval>>>,
    n: usize,
}

impl HigherPartials {
    pub(crate) fn new(eqs: &[Bernstein<Rational>]) -> HigherPartials {
        let n = eqs.first().map_or(0, Bernstein::nvars);
        let mut second = Vec::new();
        let mut third = Vec::new();
        for f in eqs {
            let f: Bernstein<Interval> = f.convert(Precision::F64);
            let (mut s, mut t) = (Vec::new(), Vec::new());
            for a in 0..n {
                let fa = f.deriv(a);
                for b in a..n {
                    let fab = fa.deriv(b);
                    for c in b..n {
                        t.push(fab.deriv(c));
                    }
                    s.push(fab);
                }
            }
            second.push(s);
            third.push(t);
        }
        HigherPartials { second, third, n }
    }

    /// The ranges over the box `[lo, hi]` of `D²F_j` (full symmetric `n × n`) and `D³F_j`
    /// (full symmetric `n × n × n`), per equation.
    #[allow(clippy::type_complexity)]
    fn ranges(
        &self,
        lo: &[f64],
        hi: &[f64],
    ) -> (Vec<Vec<Vec<Interval>>>, Vec<Vec<Vec<Vec<Interval>>>>) {
        let n = self.n;
        let hull = |p: &Bernstein<Interval>| p.restrict_box_f64(lo, hi).hull();
        let second = self
            .second
            .iter()
            .map(|s| {
                let h: Vec<Interval> = s.iter().map(hull).collect();
                (0..n)
                    .map(|a| (0..n).map(|b| h[pair_index(n, a, b)]).collect())
                    .collect()
            })
            .collect();
        let third = self
            .third
            .iter()
            .map(|t| {
                let h: Vec<Interval> = t.iter().map(hull).collect();
                (0..n)
                    .map(|a| {
                        (0..n)
                            .map(|b| (0..n).map(|c| h[triple_index(n, a, b, c)]).collect())
                            .collect()
                    })
                    .collect()
            })
            .collect();
        (second, third)
    }
}

/// One branch of the curve from the singular point to the boundary of the box.
#[derive(Clone, Debug)]
pub(crate) struct StarBranch {
    /// The axis of the box face where it ends, and whether at the upper side.
    pub axis: usize,
    pub upper: bool,
    /// The piece of the facet (`w` coordinates, `[a, a]` on `axis`) where, for every
    /// `r ∈ [0, 1]`, the branch's `w(r)` is the only zero: at `r = 1`, `p + region` holds
    /// exactly one point of the curve on the face.
    pub region: Vec<Interval>,
    /// An enclosure of `w(r)` for every `r ∈ [0, 1]` (Krawczyk's image).
    pub image: Vec<Interval>,
}

/// Why the star test failed, or its branches.
pub(crate) type StarResult = Result<Vec<StarBranch>, Reason>;

/// The most pieces of facets examined in one star test (the stars of the tests need at most
/// 50; a box too large for the test, or a point whose tangent cone is not transversal, would
/// use any budget).
const STAR_BUDGET: usize = 400;

/// The star test on the box `[lo, hi]` (global coordinates, dyadic) around the singular point
/// `sp` (admissible in it): the branches of the curve in the box, each a smooth arc from `p` to
/// a face of the box, meeting only at `p` (`proofs/space-curves.md` §6). `Err` if some piece
/// of the box's boundary was not decided within the budget.
pub(crate) fn star_branches(
    sp: &SingularPoint,
    partials: &HigherPartials,
    lo: &[f64],
    hi: &[f64],
) -> StarResult {
    if !sp.transversal {
        return Err(Reason::TangentCone);
    }
    let n = lo.len();
    // The facets below reach up to an ulp outside B − p (outward rounding), so the Lagrange
    // points may leave B by as much: the ranges are taken over B grown by a few ulps.
    let grow = |x: f64| 4.0 * f64::EPSILON * (1.0 + x.abs());
    let lo_grown: Vec<f64> = lo.iter().map(|&x| x - grow(x)).collect();
    let hi_grown: Vec<f64> = hi.iter().map(|&x| x + grow(x)).collect();
    let remainder = Remainder::over_box(sp, partials, &lo_grown, &hi_grown);
    // The facets w_axis = (side − p_axis); none where p lies on that side.
    let mut facets = Vec::new();
    for axis in 0..n {
        for upper in [false, true] {
            let side = if upper { hi[axis] } else { lo[axis] };
            let exact_side = Rational::from_f64(side).expect("finite box");
            if sp.exact[axis] == exact_side {
                continue;
            }
            let offset = |k: usize, x: f64| Interval::point(x).sub(&sp.at[k]);
            // Rounded outward (the pieces cover the facet) and inward (a branch is claimed
            // only where its image lies inside the true facet).
            let mut facet: Vec<Interval> = (0..n)
                .map(|k| Interval::new(offset(k, lo[k]).lo(), offset(k, hi[k]).hi()))
                .collect();
            let mut inner: Vec<[f64; 2]> = (0..n)
                .map(|k| [offset(k, lo[k]).hi(), offset(k, hi[k]).lo()])
                .collect();
            facet[axis] = offset(axis, side);
            inner[axis] = [f64::NEG_INFINITY, f64::INFINITY];
            facets.push(Facet {
                axis,
                upper,
                pieces: facet,
                inner,
            });
        }
    }
    facet_search(sp, &remainder, facets)
}

/// Whether the leading forms of `H` at `r = 0` (the tangent cone) have only simple zeros on
/// the facets of the cube `[−1, 1]ⁿ` of directions, each grown to `[−5/4, 21/16]` in its free
/// coordinates (so that every direction is inside one; the odd width keeps the bisection
/// planes off simple fractions such as 0 and ±1, where tangent directions tend to lie): the
/// facet search of the star test with
/// no remainder. A pre-filter only: where it fails (a double direction, as at a cusp or where
/// two branches are tangent) the box tests would fail too, since their enclosures hold those of
/// `r = 0`; a point not tried stays unresolved, so it proves nothing and costs nothing.
fn cone_is_transversal(sp: &SingularPoint) -> bool {
    if !sp.quadratic {
        return false;
    }
    let n = sp.exact.len();
    let zero = Interval::point(0.0);
    let remainder = Remainder {
        d2g: vec![vec![vec![zero; n]; n]; n - 1],
        d3g: vec![vec![vec![vec![zero; n]; n]; n]; n - 1],
        r: zero,
    };
    let facets = (0..n)
        .flat_map(|axis| {
            [false, true].map(|upper| {
                let mut w = vec![Interval::new(-1.25, 1.3125); n];
                w[axis] = Interval::point(if upper { 1.0 } else { -1.0 });
                Facet {
                    axis,
                    upper,
                    pieces: w,
                    inner: vec![[f64::NEG_INFINITY, f64::INFINITY]; n],
                }
            })
        })
        .collect();
    facet_search(sp, &remainder, facets).is_ok()
}

/// The ranges of the second and third derivatives of `G` over a box, and the range of `r`.
struct Remainder {
    d2g: Vec<Vec<Vec<Interval>>>,
    d3g: Vec<Vec<Vec<Vec<Interval>>>>,
    r: Interval,
}

impl Remainder {
    /// Over the box `[lo, hi]`, for `r ∈ [0, 1]`: `G = L F` row by row.
    fn over_box(
        sp: &SingularPoint,
        partials: &HigherPartials,
        lo: &[f64],
        hi: &[f64],
    ) -> Remainder {
        let (d2f, d3f) = partials.ranges(lo, hi);
        Remainder {
            d2g: sp.rows.iter().map(|row| combine2(row, &d2f)).collect(),
            d3g: sp.rows.iter().map(|row| combine3(row, &d3f)).collect(),
            r: Interval::new(0.0, 1.0),
        }
    }
}

/// An enclosure of `H(r, w)` for every `r` in the remainder's range and `w` in the box `w`
/// (§6: the Taylor form at `p` with the Lagrange remainder over the box).
fn h_enclosure(sp: &SingularPoint, rem: &Remainder, w: &[Interval]) -> Vec<Interval> {
    let half = Interval::point(0.5);
    let sixth = Interval::point(1.0)
        .checked_div(&Interval::point(6.0))
        .expect("1/6");
    (0..sp.rows.len())
        .map(|i| {
            if sp.orders[i] == 1 {
                dot(&sp.grad[i], w).add(&rem.r.mul(&half).mul(&quad(&rem.d2g[i], w)))
            } else {
                half.mul(&quad(&sp.hess[i], w))
                    .add(&rem.r.mul(&sixth).mul(&cubic(&rem.d3g[i], w)))
            }
        })
        .collect()
}

/// An enclosure of `∂H/∂w_k` (`k` in `free`, the columns) for every `r` in the remainder's
/// range and `w` in the box `w`.
fn jac_enclosure(
    sp: &SingularPoint,
    rem: &Remainder,
    w: &[Interval],
    free: &[usize],
) -> Vec<Vec<Interval>> {
    let half = Interval::point(0.5);
    (0..sp.rows.len())
        .map(|i| {
            free.iter()
                .map(|&k| {
                    if sp.orders[i] == 1 {
                        sp.grad[i][k].add(&rem.r.mul(&dot(&rem.d2g[i][k], w)))
                    } else {
                        dot(&sp.hess[i][k], w).add(&rem.r.mul(&half).mul(&quad(&rem.d3g[i][k], w)))
                    }
                })
                .collect()
        })
        .collect()
}

/// Decides the facet pieces by exclusion and Krawczyk's test in `w`, with `H` and its
/// Jacobian enclosed for every `r` in the remainder's range.
/// A facet `{w_axis = c}` of `B − p` to search: the box its pieces cover (rounded outward),
/// and the bounds inside which an image must lie for a branch to be claimed (rounded inward).
struct Facet {
    axis: usize,
    upper: bool,
    pieces: Vec<Interval>,
    inner: Vec<[f64; 2]>,
}

fn facet_search(sp: &SingularPoint, rem: &Remainder, facets: Vec<Facet>) -> StarResult {
    let h_of = |w: &[Interval]| h_enclosure(sp, rem, w);
    let jac_of = |w: &[Interval], free: &[usize]| jac_enclosure(sp, rem, w, free);
    let undecided = Reason::StarUndecided;
    let mut branches = Vec::new();
    let mut examined = 0usize;
    for Facet {
        axis,
        upper,
        pieces,
        inner,
    } in facets
    {
        let free: Vec<usize> = (0..pieces.len()).filter(|&k| k != axis).collect();
        let inside_facet = |image: &[Interval]| {
            free.iter()
                .all(|&k| inner[k][0] < image[k].lo() && image[k].hi() < inner[k][1])
        };
        let mut stack = vec![pieces];
        while let Some(w) = stack.pop() {
            examined += 1;
            if examined > STAR_BUDGET {
                return Err(undecided);
            }
            if h_of(&w).iter().any(|h| h.lo() > 0.0 || h.hi() < 0.0) {
                continue;
            }
            match krawczyk_facet(&w, &free, &h_of, &jac_of) {
                FacetVerdict::NoZero => continue,
                FacetVerdict::Unique(image) if inside_facet(&image) => {
                    branches.push(StarBranch {
                        axis,
                        upper,
                        region: w,
                        image,
                    });
                    continue;
                }
                FacetVerdict::Unique(_) | FacetVerdict::Unknown => {}
            }
            // Bisect the widest free coordinate.
            let k = *free
                .iter()
                .max_by(|&&a, &&b| w[a].width().total_cmp(&w[b].width()))
                .expect("n ≥ 2");
            let mid = 0.5 * (w[k].lo() + w[k].hi());
            if !(w[k].lo() < mid && mid < w[k].hi()) {
                return Err(undecided);
            }
            let (mut a, mut b) = (w.clone(), w);
            a[k] = Interval::new(a[k].lo(), mid);
            b[k] = Interval::new(mid, b[k].hi());
            stack.push(b);
            stack.push(a);
        }
    }
    Ok(branches)
}

/// An enclosure of the Jacobian of `H` in the free coordinates over a box of `w`.
type JacobianFn<'a> = dyn Fn(&[Interval], &[usize]) -> Vec<Vec<Interval>> + 'a;

enum FacetVerdict {
    NoZero,
    Unique(Vec<Interval>),
    Unknown,
}

/// Krawczyk's operator in the free coordinates of a facet piece `w`, with `H` and its
/// Jacobian enclosed over every `r ∈ [0, 1]`.
fn krawczyk_facet(
    w: &[Interval],
    free: &[usize],
    h_of: &dyn Fn(&[Interval]) -> Vec<Interval>,
    jac_of: &JacobianFn,
) -> FacetVerdict {
    let jac = jac_of(w, free);
    let mid: Vec<Vec<f64>> = jac
        .iter()
        .map(|r| r.iter().map(|x| 0.5 * (x.lo() + x.hi())).collect())
        .collect();
    let Some(c) = inverse(&mid) else {
        return FacetVerdict::Unknown;
    };
    let mut centre = w.to_vec();
    for &k in free {
        centre[k] = Interval::point(0.5 * (w[k].lo() + w[k].hi()));
    }
    let hm = h_of(&centre);
    let q = free.len();
    let mut image = w.to_vec();
    let mut inside = true;
    for (row, crow) in c.iter().enumerate() {
        let k = free[row];
        // m_k − (C H(R, m))_k + Σ_l (δ_kl − (C J)_kl)(w_l − m_l)
        let mut s = centre[k];
        for (cv, h) in crow.iter().zip(&hm) {
            s = s.sub(&Interval::point(*cv).mul(h));
        }
        for col in 0..q {
            let mut e = Interval::point(if row == col { 1.0 } else { 0.0 });
            for (cv, jr) in crow.iter().zip(&jac) {
                e = e.sub(&Interval::point(*cv).mul(&jr[col]));
            }
            let l = free[col];
            s = s.add(&e.mul(&w[l].sub(&centre[l])));
        }
        if s.hi() < w[k].lo() || s.lo() > w[k].hi() {
            return FacetVerdict::NoZero;
        }
        inside &= w[k].lo() < s.lo() && s.hi() < w[k].hi();
        image[k] = s;
    }
    if inside {
        FacetVerdict::Unique(image)
    } else {
        FacetVerdict::Unknown
    }
}

fn dot(a: &[Interval], w: &[Interval]) -> Interval {
    a.iter()
        .zip(w)
        .fold(Interval::point(0.0), |s, (x, y)| s.add(&x.mul(y)))
}

fn quad(m: &[Vec<Interval>], w: &[Interval]) -> Interval {
    m.iter().zip(w).fold(Interval::point(0.0), |s, (row, wa)| {
        s.add(&wa.mul(&dot(row, w)))
    })
}

fn cubic(t: &[Vec<Vec<Interval>>], w: &[Interval]) -> Interval {
    t.iter().zip(w).fold(Interval::point(0.0), |s, (m, wa)| {
        s.add(&wa.mul(&quad(m, w)))
    })
}

fn combine2(row: &[Interval], d2f: &[Vec<Vec<Interval>>]) -> Vec<Vec<Interval>> {
    let n = d2f[0].len();
    (0..n)
        .map(|a| {
            (0..n)
                .map(|b| {
                    row.iter()
                        .zip(d2f)
                        .fold(Interval::point(0.0), |s, (l, m)| s.add(&l.mul(&m[a][b])))
                })
                .collect()
        })
        .collect()
}

fn combine3(row: &[Interval], d3f: &[Vec<Vec<Vec<Interval>>>]) -> Vec<Vec<Vec<Interval>>> {
    let n = d3f[0].len();
    (0..n)
        .map(|a| {
            (0..n)
                .map(|b| {
                    (0..n)
                        .map(|c| {
                            row.iter()
                                .zip(d3f)
                                .fold(Interval::point(0.0), |s, (l, t)| s.add(&l.mul(&t[a][b][c])))
                        })
                        .collect()
                })
                .collect()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(a: i64, b: i64) -> Rational {
        Rational::from((a, b))
    }

    fn var(k: usize) -> Bernstein<Rational> {
        let mut d = vec![0; 3];
        d[k] = 1;
        Bernstein::new(&d, vec![q(0, 1), q(1, 1)]).unwrap()
    }

    fn konst(c: Rational) -> Bernstein<Rational> {
        Bernstein::constant(3, c)
    }

    #[test]
    fn the_taylor_forms_enclose_h_and_its_jacobian() {
        // A node at p = (2/5, 3/7, 1/3) with cubic terms in both equations:
        // F₁ = (x − y + x²)(x + y/2) + z x², F₂ = z + x y + x³ (x, y, z taken from p).
        let p = [q(2, 5), q(3, 7), q(1, 3)];
        let (x, y, z) = (
            &var(0) - &konst(p[0].clone()),
            &var(1) - &konst(p[1].clone()),
            &var(2) - &konst(p[2].clone()),
        );
        let xx = &x * &x;
        let f1 = &(&(&(&x - &y) + &xx) * &(&x + &(&y * &konst(q(1, 2))))) + &(&z * &xx);
        let f2 = &(&z + &(&x * &y)) + &(&xx * &x);
        let eqs = vec![f1, f2];
        let partials = ExactPartials::new(&eqs);
        let sp = exact_singular_point(&eqs, &partials, p.to_vec()).expect("singular");
        assert_eq!(sp.orders, vec![1, 2]);
        assert!(sp.quadratic && sp.transversal);
        // G = L F exactly: here the rows swapped (F₂ has the nonzero gradient).
        let g = [eqs[1].clone(), eqs[0].clone()];
        let (lo, hi) = ([0.375, 0.40625, 0.3125], [0.4375, 0.46875, 0.375]);
        let rem = Remainder::over_box(&sp, &HigherPartials::new(&eqs), &lo, &hi);
        // Sample (r, w) with w in B − p (dyadic, exact in f64).
        let lo_q: Vec<Rational> = lo.iter().map(|v| Rational::from_f64(*v).unwrap()).collect();
        let hi_q: Vec<Rational> = hi.iter().map(|v| Rational::from_f64(*v).unwrap()).collect();
        let mut checked = 0;
        for (a, b, c) in [(0, 0, 1), (1, 3, 2), (3, 1, 0), (2, 2, 3), (3, 0, 3)] {
            let t = |k: usize, j: i64| {
                let v = &lo_q[k] + (Rational::from(&hi_q[k] - &lo_q[k]) * q(j, 3));
                Rational::from(&v - &p[k])
            };
            let w = [t(0, a), t(1, b), t(2, c)];
            let wi: Vec<Interval> = w
                .iter()
                .map(|v| Interval::from_rational(v, Precision::F64))
                .collect();
            let h = h_enclosure(&sp, &rem, &wi);
            let jac = jac_enclosure(&sp, &rem, &wi, &[0, 1, 2]);
            for r in [q(1, 8), q(1, 2), q(1, 1)] {
                let at: Vec<Rational> =
                    (0..3).map(|k| &p[k] + Rational::from(&r * &w[k])).collect();
                for (i, gi) in g.iter().enumerate() {
                    let o = sp.orders[i] as i32;
                    let power = |e: i32| (0..e).fold(q(1, 1), |acc, _| acc * &r);
                    let exact = gi.eval(&at) / power(o);
                    assert!(
                        h[i].contains_rational(&exact),
                        "H_{i} at r = {r}: {exact} ∉ {:?}",
                        h[i]
                    );
                    for (k, j) in jac[i].iter().enumerate() {
                        let d = gi.deriv(k).eval(&at) / power(o - 1);
                        assert!(j.contains_rational(&d), "∂H_{i}/∂w_{k}: {d} ∉ {j:?}");
                        checked += 1;
                    }
                }
            }
        }
        assert_eq!(checked, 5 * 3 * 2 * 3);
    }
}
