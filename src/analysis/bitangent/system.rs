//! The bitangent system of a pair of patches (paper 003) and the lemmas that keep a subdivision
//! solver out of its spurious solutions (`proofs/bitangent.md`).
//!
//! For points `p = S(u, v)` of a patch and `q = R(s, t)` of another (or the same) patch, with
//! `ν` the normal of the first, `T_s, T_t` the tangents of the second, and `X, W` homogeneous
//! coordinates:
//!
//! - `f₁ = ν(u, v) · (W_S(u, v) X_R(s, t) − W_R(s, t) X_S(u, v))`: the chord `q − p` lies in the
//!   tangent plane at `p` (times `W_S W_R > 0`);
//! - `f₂ = ν(u, v) · T_s(s, t)`, `f₃ = ν(u, v) · T_t(s, t)`: the tangent plane at `q` is the
//!   plane of `ν(u, v)`, so the normals are parallel.
//!
//! Their common zeros with `p ≠ q` are the bitangent pairs. The factors of collapsed sides are
//! divided out of `ν` and of `T_s`, `T_t` (where all three coordinates vanish on a side), so a
//! pole has its limit normal and tangent. For a patch with itself, the whole diagonal
//! `(u, v) = (s, t)` is a spurious surface of solutions: [`DiagonalTest`] proves that a box
//! pair around it holds no genuine pair, and [`mirror_dropped`] keeps one of the two orders of
//! every pair.

use crate::analysis::chords::plane_curve::{div, range_enclosing, restrict_enclosing};
use crate::analysis::chords::space_curve::deflate_common;
use crate::analysis::intersection::homogeneous_difference;
use crate::bernstein::lift;
use crate::bernstein::Bernstein;
use crate::geometry::Rect;
use crate::number::margin;
use crate::number::{Interval, Number, Precision, Rational};
use crate::surface::RationalPatch;

use crate::bernstein::Poly;
type IPoly = Bernstein<Interval>;

/// The deflated normal `ν` of a patch and the sides divided out of it.
pub fn deflated_normal(patch: &RationalPatch) -> ([Poly; 3], Vec<&'static str>) {
    let mut n = patch.normal();
    let sides = deflate_common(&mut n);
    (n, sides)
}

/// The deflated tangents `T_u, T_v` of a patch (each with the factors of the sides where it
/// vanishes divided out).
pub fn deflated_tangents(patch: &RationalPatch) -> ([Poly; 3], [Poly; 3]) {
    let (mut tu, mut tv) = patch.tangents();
    deflate_common(&mut tu);
    deflate_common(&mut tv);
    (tu, tv)
}

fn dot(a: &[Poly; 3], b: &[Poly; 3]) -> Poly {
    &(&(&a[0] * &b[0]) + &(&a[1] * &b[1])) + &(&a[2] * &b[2])
}

/// The bitangent system of a pair, in `(u, v, s, t)`: `[f₁, f₂, f₃]` of the module
/// documentation, and the sides of the first patch divided out of its normal.
///
/// # Examples
/// ```
/// use limn::analysis::bitangent::system::bitangent_system;
/// use limn::number::Rational;
/// use limn::testing::shapes;
/// let q = |n: i64| Rational::from(n);
/// // z = x² over the unit square with itself: the diagonal solves the system.
/// let p = shapes::graph(&[(2, 0, q(1))], [q(0), q(1)], [q(0), q(1)]);
/// let (f, _) = bitangent_system(&p, &p);
/// let half = Rational::from((1, 2));
/// let at = [half.clone(), Rational::from((1, 3)), half, Rational::from((1, 3))];
/// assert!(f.iter().all(|f| f.eval(&at) == q(0)));
/// ```
pub fn bitangent_system(
    first: &RationalPatch,
    second: &RationalPatch,
) -> ([Poly; 3], Vec<&'static str>) {
    let (n, sides) = deflated_normal(first);
    let (ts, tt) = deflated_tangents(second);
    let hp = first.homogeneous();
    let hq = second.homogeneous();
    let n4 = n.map(|c| lift(&c, 4, 0));
    let chord = homogeneous_difference(&hp, &hq);
    let f1 = dot(&n4, &chord);
    let f2 = dot(&n4, &ts.map(|c| lift(&c, 4, 2)));
    let f3 = dot(&n4, &tt.map(|c| lift(&c, 4, 2)));
    ([f1, f2, f3], sides)
}

/// Interval data of a patch for [`DiagonalTest::excludes`]: the homogeneous coordinates and
/// their partial derivatives of orders 2 and 3, and the deflated normal and tangents.
pub struct DiagonalTest {
    /// X, Y, Z, W.
    h: Vec<IPoly>,
    /// Per coordinate: uu, uv, vv, then uuu, uuv, uvv, vvv.
    d: Vec<[IPoly; 7]>,
    normal: [IPoly; 3],
    /// ν_u and ν_v.
    normal_d: [[IPoly; 3]; 2],
    tangents: [[IPoly; 3]; 2],
}

/// Sectors of directions tried before a region is given up, per chart: `2^MAX_SECTOR_DEPTH`.
const MAX_SECTOR_DEPTH: u32 = 7;

impl DiagonalTest {
    /// Converts (once) the patch's exact polynomials.
    pub fn new(patch: &RationalPatch) -> DiagonalTest {
        let f = |p: &Poly| p.convert::<Interval>(Precision::F64);
        let hom = patch.homogeneous();
        let d = hom
            .iter()
            .map(|p| {
                let (pu, pv) = (p.deriv(0), p.deriv(1));
                let (puu, puv, pvv) = (pu.deriv(0), pu.deriv(1), pv.deriv(1));
                [
                    f(&puu),
                    f(&puv),
                    f(&pvv),
                    f(&puu.deriv(0)),
                    f(&puu.deriv(1)),
                    f(&puv.deriv(1)),
                    f(&pvv.deriv(1)),
                ]
            })
            .collect();
        let (n, _) = deflated_normal(patch);
        let (tu, tv) = deflated_tangents(patch);
        DiagonalTest {
            h: hom.iter().map(f).collect(),
            d,
            normal_d: [0, 1].map(|a| n.clone().map(|p| f(&p.deriv(a)))),
            normal: n.map(|p| f(&p)),
            tangents: [tu.map(|p| f(&p)), tv.map(|p| f(&p))],
        }
    }

    /// An enclosure of the surface over the box `[lo, hi]` of the square (the hull of the
    /// restricted control points' quotients, `W > 0`).
    pub fn image(&self, lo: [f64; 2], hi: [f64; 2]) -> Option<[Interval; 3]> {
        let h: Vec<IPoly> = self
            .h
            .iter()
            .map(|p| restrict_enclosing(p, lo, hi))
            .collect::<Option<_>>()?;
        image_of(&h)
    }

    /// The ranges of the normal `ν` over the box `[lo, hi]`.
    pub fn normal_range(&self, lo: [f64; 2], hi: [f64; 2]) -> Option<[Interval; 3]> {
        let r: Vec<Interval> = self
            .normal
            .iter()
            .map(|p| range_enclosing(p, lo, hi))
            .collect::<Option<_>>()?;
        Some([r[0], r[1], r[2]])
    }

    /// An interval matrix that contains the Jacobian (rows: the chart's two coordinates;
    /// columns: u, v) of the Gauss chart `g = (ν·e₁, ν·e₂) / (ν·a)` over the box `[lo, hi]`,
    /// for the orthonormal frame `[a, e₁, e₂]`; `None` where `ν·a` may vanish.
    pub fn gauss_jacobian(
        &self,
        lo: [f64; 2],
        hi: [f64; 2],
        frame: &[[f64; 3]; 3],
    ) -> Option<[[Interval; 2]; 2]> {
        let n = self.normal_range(lo, hi)?;
        let along = |v: &[Interval; 3], e: &[f64; 3]| {
            (0..3).fold(Interval::point(0.0), |acc, k| {
                acc.add(&v[k].mul(&Interval::point(e[k])))
            })
        };
        let na = along(&n, &frame[0]);
        let na2 = na.mul(&na);
        if na.contains(0.0) {
            return None;
        }
        let mut jac = [[Interval::point(0.0); 2]; 2];
        for (k, dk) in self.normal_d.iter().enumerate() {
            let d: Vec<Interval> = dk
                .iter()
                .map(|p| range_enclosing(p, lo, hi))
                .collect::<Option<_>>()?;
            let d = [d[0], d[1], d[2]];
            let da = along(&d, &frame[0]);
            for i in 0..2 {
                let ni = along(&n, &frame[i + 1]);
                let di = along(&d, &frame[i + 1]);
                jac[i][k] = div(di.mul(&na).sub(&ni.mul(&da)), na2)?;
            }
        }
        Some(jac)
    }

    /// Whether the tangents `T_u, T_v` are proven independent on the box `[lo, hi]` (some
    /// coordinate of their cross product has a strict sign): then every normal functional that
    /// vanishes on both is a multiple of the normal there.
    pub fn tangents_independent(&self, lo: [f64; 2], hi: [f64; 2]) -> bool {
        let r = |p: &IPoly| range_enclosing(p, lo, hi);
        let t: Option<Vec<Interval>> = self.tangents.iter().flatten().map(r).collect();
        let Some(t) = t else { return false };
        let (a, b) = (&t[0..3], &t[3..6]);
        (0..3).any(|k| {
            let (i, j) = ((k + 1) % 3, (k + 2) % 3);
            !a[i].mul(&b[j]).sub(&a[j].mul(&b[i])).contains(0.0)
        })
    }

    /// Whether the region `[lo, hi]` of the parameter square (a convex set) is proven to hold no
    /// bitangent pair `(p, q)` with `p ≠ q` (`proofs/bitangent.md`, Lemma 1): for every
    /// direction `δ` of `q − p`, either the interval Hessian of the height over the tangent
    /// plane at `p` is regular on `δ`, or its third derivative along `δ` has a strict sign.
    pub fn excludes(&self, lo: [f64; 2], hi: [f64; 2]) -> bool {
        let restrict = |p: &IPoly| restrict_enclosing(p, lo, hi);
        let Some(h): Option<Vec<IPoly>> = self.h.iter().map(restrict).collect() else {
            return false;
        };
        let Some(n): Option<Vec<Interval>> = self
            .normal
            .iter()
            .map(|p| restrict(p).map(|q| q.hull()))
            .collect()
        else {
            return false;
        };
        if n.iter().all(|x| x.contains(0.0)) {
            return false;
        }
        // S over the region: within the hull of the control points' quotients (W > 0).
        let Some(s) = image_of(&h) else {
            return false;
        };
        // Heights from c0, a point near the region's image: Y = X − c0 W, and the part of
        // S(p) − c0 along the normal.
        let c0: [f64; 3] = s.map(|x| 0.5 * (x.lo() + x.hi()));
        let sn = (0..3).fold(Interval::point(0.0), |acc, k| {
            acc.add(&s[k].sub(&Interval::point(c0[k])).mul(&n[k]))
        });
        // D^α g = Σ_k D^α Y_k n_k − D^α W ((S(p) − c0)·n), for the 7 partials α.
        let mut g = [Interval::point(0.0); 7];
        for (a, ga) in g.iter_mut().enumerate() {
            let Some(dw) = restrict(&self.d[3][a]) else {
                return false;
            };
            let mut acc = dw.hull().mul(&sn).neg();
            for k in 0..3 {
                let Some(dx) = restrict(&self.d[k][a]) else {
                    return false;
                };
                let c = Interval::point(c0[k]);
                let y = dx
                    .coeffs()
                    .iter()
                    .zip(dw.coeffs())
                    .map(|(x, w)| x.sub(&c.mul(w)))
                    .fold(None, |a: Option<Interval>, b| {
                        Some(a.map_or(b, |a| a.hull(&b)))
                    });
                let Some(y) = y else { return false };
                acc = acc.add(&y.mul(&n[k]));
            }
            *ga = acc;
        }
        [false, true]
            .iter()
            .all(|&along_v| sectors_excluded(&g, along_v))
    }
}

/// The hull of the control points' quotients `X / W` of restricted homogeneous coordinates
/// (all weights positive): it contains the surface over the box.
fn image_of(h: &[IPoly]) -> Option<[Interval; 3]> {
    let w = &h[3];
    if w.coeffs().iter().any(|c| c.lo() <= 0.0) {
        return None;
    }
    let mut s = [Interval::point(0.0); 3];
    for (k, sk) in s.iter_mut().enumerate() {
        let q: Vec<Interval> = h[k]
            .coeffs()
            .iter()
            .zip(w.coeffs())
            .map(|(x, w)| div(*x, *w))
            .collect::<Option<_>>()?;
        *sk = q[1..].iter().fold(q[0], |a, b| a.hull(b));
    }
    Some(s)
}

/// Whether every direction of one chart (`δ = (1, σ)`, or `(σ, 1)` with `along_v`, `σ ∈ [−1, 1]`)
/// is excluded, by bisection of `σ` into sectors.
fn sectors_excluded(g: &[Interval; 7], along_v: bool) -> bool {
    let mut stack = vec![(Interval::new(-1.0, 1.0), 0u32)];
    while let Some((sigma, depth)) = stack.pop() {
        if sector_excluded(g, along_v, sigma) {
            continue;
        }
        if depth >= MAX_SECTOR_DEPTH {
            return false;
        }
        let m = 0.5 * (sigma.lo() + sigma.hi());
        stack.push((Interval::new(sigma.lo(), m), depth + 1));
        stack.push((Interval::new(m, sigma.hi()), depth + 1));
    }
    true
}

/// One sector: `H δ` has a coordinate of strict sign, or `D³g(δ, δ, δ)` has a strict sign.
fn sector_excluded(g: &[Interval; 7], along_v: bool, sigma: Interval) -> bool {
    let [huu, huv, hvv, cuuu, cuuv, cuvv, cvvv] = *g;
    let three = Interval::point(3.0);
    let s2 = if sigma.lo() >= 0.0 || sigma.hi() <= 0.0 {
        sigma.mul(&sigma)
    } else {
        Interval::new(
            0.0,
            margin::up(
                sigma.lo().abs().max(sigma.hi().abs()).powi(2),
                margin::TIGHT,
            ),
        )
    };
    let s3 = s2.mul(&sigma);
    let (h0, h1, c) = if along_v {
        // δ = (σ, 1)
        (
            sigma.mul(&huu).add(&huv),
            sigma.mul(&huv).add(&hvv),
            s3.mul(&cuuu)
                .add(&three.mul(&s2).mul(&cuuv))
                .add(&three.mul(&sigma).mul(&cuvv))
                .add(&cvvv),
        )
    } else {
        // δ = (1, σ)
        (
            huu.add(&sigma.mul(&huv)),
            huv.add(&sigma.mul(&hvv)),
            cuuu.add(&three.mul(&sigma).mul(&cuuv))
                .add(&three.mul(&s2).mul(&cuvv))
                .add(&s3.mul(&cvvv)),
        )
    };
    !h0.contains(0.0) || !h1.contains(0.0) || !c.contains(0.0)
}

/// The Morton (Z-order) code of the dyadic cell `[lo, hi]` of the square at depth `depth`.
fn morton(lo: [f64; 2], depth: u32) -> u64 {
    let scale = (1u64 << depth) as f64;
    let (i, j) = ((lo[0] * scale) as u64, (lo[1] * scale) as u64);
    let mut code = 0u64;
    for b in (0..depth).rev() {
        code = (code << 2) | (((i >> b) & 1) << 1) | ((j >> b) & 1);
    }
    code
}

/// For a patch with itself: whether the box `(u, v, s, t)` (a dyadic cube at `depth`, the same
/// grid in both pairs of variables) lies in the mirror half that is left out, its `(u, v)` cell
/// after its `(s, t)` cell in Morton order. The swap `(u, v, s, t) ↦ (s, t, u, v)` maps the
/// kept half onto the dropped one except on the cells of equal code, which are kept
/// (`proofs/bitangent.md`, Lemma 2).
pub fn mirror_dropped(cell: &[[f64; 2]], depth: u32) -> bool {
    depth <= 30 && morton([cell[0][0], cell[1][0]], depth) > morton([cell[2][0], cell[3][0]], depth)
}

/// How the square of a second patch `R` lies next to the square of a first patch `S` when they
/// share a side (the same control points and weights along it, possibly in reverse order): the
/// composite parameter plane holds `S` on `[0, 1]²` and `R` on the adjacent square across the
/// shared side, so that the composite surface is continuous (`proofs/bitangent.md`, Lemma 5).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SharedSide {
    /// The side of `S`: its axis and whether it is at 1.
    pub first: (usize, bool),
    /// The side of `R`.
    pub second: (usize, bool),
    /// `R`'s side runs against `S`'s.
    pub reversed: bool,
}

impl SharedSide {
    /// `R`'s parameter point in the composite plane.
    pub fn to_composite(&self, r: [f64; 2]) -> [f64; 2] {
        let (sa, s1) = self.first;
        let (ra, r1) = self.second;
        let along = if self.reversed {
            1.0 - r[1 - ra]
        } else {
            r[1 - ra]
        };
        let dist = if r1 { 1.0 - r[ra] } else { r[ra] };
        let mut x = [0.0; 2];
        x[1 - sa] = along;
        x[sa] = if s1 { 1.0 + dist } else { -dist };
        x
    }

    /// The inverse of [`SharedSide::to_composite`].
    pub fn from_composite(&self, x: [f64; 2]) -> [f64; 2] {
        let (sa, s1) = self.first;
        let (ra, r1) = self.second;
        let along = if self.reversed {
            1.0 - x[1 - sa]
        } else {
            x[1 - sa]
        };
        let dist = if s1 { x[sa] - 1.0 } else { -x[sa] };
        let mut r = [0.0; 2];
        r[1 - ra] = along;
        r[ra] = if r1 { 1.0 - dist } else { dist };
        r
    }

    /// A box of `R` mapped (exactly: the maps only flip and shift by 0, 1 or 2) to the
    /// composite plane (`to_composite`) or back (`from_composite`).
    fn box_to(&self, b: &Rect, f: impl Fn(&Self, [f64; 2]) -> [f64; 2]) -> Rect {
        Rect::point(f(self, b.lo)).hull(&Rect::point(f(self, b.hi)))
    }

    /// The derivative of `R`'s parameters by the composite ones: `∂r_k/∂x_j = sign` for the
    /// pair `(j, k, sign)` of each composite axis `j`.
    fn chain(&self) -> [(usize, usize, f64); 2] {
        let (sa, s1) = self.first;
        let (ra, r1) = self.second;
        let along = if self.reversed { -1.0 } else { 1.0 };
        let across = if s1 { 1.0 } else { -1.0 } * if r1 { -1.0 } else { 1.0 };
        [(1 - sa, 1 - ra, along), (sa, ra, across)]
    }
}

/// The sides that two patches share (see [`SharedSide`]), each checked exactly: equal control
/// points and weights along the side, and normals parallel along it (the cross product of the
/// two normals' restrictions, a polynomial of degree at most the sum of theirs, vanishes at more
/// points than its degree).
pub fn shared_sides(first: &RationalPatch, second: &RationalPatch) -> Vec<SharedSide> {
    use crate::surface::Edge;
    let side_of = |e: Edge| match e {
        Edge::V0 => (1, false),
        Edge::V1 => (1, true),
        Edge::U0 => (0, false),
        Edge::U1 => (0, true),
    };
    let (n1, _) = deflated_normal(first);
    let (n2, _) = deflated_normal(second);
    let mut out = Vec::new();
    for e1 in Edge::ALL {
        let row1 = first.edge(e1);
        for e2 in Edge::ALL {
            let row2 = second.edge(e2);
            if row1.len() != row2.len() {
                continue;
            }
            for reversed in [false, true] {
                let same = (0..row1.len()).all(|i| {
                    let j = if reversed { row1.len() - 1 - i } else { i };
                    row1[i] == row2[j]
                });
                if !same {
                    continue;
                }
                let side = SharedSide {
                    first: side_of(e1),
                    second: side_of(e2),
                    reversed,
                };
                if normals_parallel(&n1, &n2, &side) {
                    out.push(side);
                }
            }
        }
    }
    out
}

/// Whether the two normals are parallel at every point of the shared side, exactly.
fn normals_parallel(n1: &[Poly; 3], n2: &[Poly; 3], side: &SharedSide) -> bool {
    let deg = |n: &[Poly; 3], axis: usize| n.iter().map(|p| p.degrees()[axis]).max().unwrap_or(0);
    let k = deg(n1, 1 - side.first.0) + deg(n2, 1 - side.second.0) + 1;
    let one = Rational::from(1);
    (0..k).all(|i| {
        let t = Rational::from(((i + 1) as i64, (k + 1) as i64));
        let mut a = [Rational::new(), Rational::new()];
        a[1 - side.first.0] = t.clone();
        a[side.first.0] = if side.first.1 {
            one.clone()
        } else {
            Rational::new()
        };
        let mut b = [Rational::new(), Rational::new()];
        b[1 - side.second.0] = if side.reversed {
            Rational::from(&one - &t)
        } else {
            t.clone()
        };
        b[side.second.0] = if side.second.1 {
            one.clone()
        } else {
            Rational::new()
        };
        let x: Vec<Rational> = n1.iter().map(|p| p.eval(&a)).collect();
        let y: Vec<Rational> = n2.iter().map(|p| p.eval(&b)).collect();
        (0..3).all(|c| {
            let (i, j) = ((c + 1) % 3, (c + 2) % 3);
            Rational::from(&x[i] * &y[j]) == Rational::from(&x[j] * &y[i])
        })
    })
}

/// Lemma 5 of `proofs/bitangent.md`: whether the box pair `(B₁ of S, B₂ of R)` holds no pair of
/// distinct points of the composite surface with parallel normals, because the Gauss chart is
/// proven injective on the hull of the two boxes in the composite plane (the interval hull of
/// its Jacobians over both parts is regular). Its solutions are then the coincident points of
/// the shared side only.
pub fn seam_excludes(
    first: &DiagonalTest,
    second: &DiagonalTest,
    side: &SharedSide,
    b1: Rect,
    b2: Rect,
) -> bool {
    let c = side.box_to(&b2, SharedSide::to_composite);
    // Widened by more than the rounding of `1 − r` in the maps, so that the parts cover both
    // boxes.
    let both = b1.hull(&c).grown(1e-14);
    if both.width(0) > 0.5 || both.width(1) > 0.5 {
        return false;
    }
    // The part on S's square and the part on R's.
    let clip = |b: Rect| Rect::new(b.lo.map(|x| x.max(0.0)), b.hi.map(|x| x.min(1.0)));
    let q1 = clip(both);
    let q2 = clip(side.box_to(&both, SharedSide::from_composite));
    // A frame about the normal at the middle of the first part.
    let Some(n) = first.normal_range(q1.lo, q1.hi) else {
        return false;
    };
    let a = n.map(|x| 0.5 * (x.lo() + x.hi()));
    let la = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    if la.is_nan() || la <= 0.0 {
        return false;
    }
    let a = a.map(|x| x / la);
    let h = if a[0].abs() < 0.6 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let c = h[0] * a[0] + h[1] * a[1] + h[2] * a[2];
    let e1 = {
        let v: [f64; 3] = std::array::from_fn(|k| h[k] - c * a[k]);
        let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        v.map(|x| x / l)
    };
    let e2 = [
        a[1] * e1[2] - a[2] * e1[1],
        a[2] * e1[0] - a[0] * e1[2],
        a[0] * e1[1] - a[1] * e1[0],
    ];
    let frame = [a, e1, e2];
    let Some(j1) = first.gauss_jacobian(q1.lo, q1.hi, &frame) else {
        return false;
    };
    let Some(jr) = second.gauss_jacobian(q2.lo, q2.hi, &frame) else {
        return false;
    };
    // R's Jacobian in composite coordinates: column j is ∂/∂r_k times ∂r_k/∂x_j.
    let mut j2 = [[Interval::point(0.0); 2]; 2];
    for (j, k, sign) in side.chain() {
        for i in 0..2 {
            j2[i][j] = jr[i][k].mul(&Interval::point(sign));
        }
    }
    let m: [[Interval; 2]; 2] =
        std::array::from_fn(|i| std::array::from_fn(|j| j1[i][j].hull(&j2[i][j])));
    let det = m[0][0].mul(&m[1][1]).sub(&m[0][1].mul(&m[1][0]));
    !det.contains(0.0)
}

/// Whether no normal of `S` over the box `B₁` is parallel (or opposite) to a normal of `R`
/// over `B₂` (some coordinate of the interval cross product has a strict sign), with `R`'s
/// tangents proven independent over `B₂`: then no pair in `B₁ × B₂` solves the system
/// (`proofs/bitangent.md`, Lemma 4, per box).
pub fn normals_apart(
    first: &DiagonalTest,
    second: &DiagonalTest,
    b1: ([f64; 2], [f64; 2]),
    b2: ([f64; 2], [f64; 2]),
) -> bool {
    let (Some(a), Some(b)) = (
        first.normal_range(b1.0, b1.1),
        second.normal_range(b2.0, b2.1),
    ) else {
        return false;
    };
    let apart = (0..3).any(|k| {
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        !a[i].mul(&b[j]).sub(&a[j].mul(&b[i])).contains(0.0)
    });
    apart && second.tangents_independent(b2.0, b2.1)
}
