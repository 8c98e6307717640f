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

use super::accuracy::{div, restrict_enclosing};
use super::patch_curve::deflate_common;
use super::projection::lift;
use crate::bernstein::Bernstein;
use crate::number::{Interval, Number, Precision, Rational};
use crate::surface::RationalPatch;

type Poly = Bernstein<Rational>;
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
/// use limn::analysis::bitangent::bitangent_system;
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
    let (wp, wq) = (lift(&hp[3], 4, 0), lift(&hq[3], 4, 2));
    let chord: [Poly; 3] =
        std::array::from_fn(|k| &(&wp * &lift(&hq[k], 4, 2)) - &(&wq * &lift(&hp[k], 4, 0)));
    let f1 = dot(&n4, &chord);
    let f2 = dot(&n4, &ts.map(|c| lift(&c, 4, 2)));
    let f3 = dot(&n4, &tt.map(|c| lift(&c, 4, 2)));
    ([f1, f2, f3], sides)
}

fn hull(p: &IPoly) -> Interval {
    let c = p.coeffs();
    c[1..].iter().fold(c[0], |a, b| a.hull(b))
}

/// Interval data of a patch for [`DiagonalTest::excludes`]: the homogeneous coordinates and
/// their partial derivatives of orders 2 and 3, and the deflated normal and tangents.
pub struct DiagonalTest {
    /// X, Y, Z, W.
    h: Vec<IPoly>,
    /// Per coordinate: uu, uv, vv, then uuu, uuv, uvv, vvv.
    d: Vec<[IPoly; 7]>,
    normal: [IPoly; 3],
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

    /// Whether the tangents `T_u, T_v` are proven independent on the box `[lo, hi]` (some
    /// coordinate of their cross product has a strict sign): then every normal functional that
    /// vanishes on both is a multiple of the normal there.
    pub fn tangents_independent(&self, lo: [f64; 2], hi: [f64; 2]) -> bool {
        let r = |p: &IPoly| restrict_enclosing(p, lo, hi).map(|q| hull(&q));
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
            .map(|p| restrict(p).map(|q| hull(&q)))
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
            let mut acc = hull(&dw).mul(&sn).neg();
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
            sigma.lo().abs().max(sigma.hi().abs()).powi(2) * (1.0 + 1e-15),
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
