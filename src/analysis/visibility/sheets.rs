//! Boxes of a patch that are one sheet in the image, so that a ray meets them at most once
//! near a point: injective boxes (the image map is one-to-one there) and fold boxes (the fold
//! lemma at an outline point), `proofs/ray-count.md`.

use crate::analysis::chords::plane_curve::jet_on;
use crate::analysis::visibility::ray::dy;
use crate::analysis::visibility::scene::Scene;
use crate::bernstein::Bernstein;
use crate::bernstein::Poly;
use crate::number::{Interval, Number, Precision, Rational};
use crate::solver::system::DyadicBoxN;

/// The interval range of a polynomial on a box given by f64 bounds.
pub(crate) fn range_on(p: &Bernstein<Interval>, lo: &[f64], hi: &[f64]) -> Interval {
    p.restrict_box_f64(lo, hi).hull()
}
/// The box `[lo − 2^-k, hi + 2^-k] ∩ [0, 1]²` around a parameter box, its corners rounded
/// outwards to the grid `2^-(k+8)` when they are not dyadic (a point of a trimming curve):
/// it holds `[lo, hi]` with a margin of at least `2^-k − 2^-(k+8)`.
fn box_around(lo: &[Rational; 2], hi: &[Rational; 2], k: u32) -> Option<DyadicBoxN> {
    let mut r = Rational::from(1);
    r >>= k;
    let clamp = |x: Rational| -> Rational {
        if x < 0 {
            Rational::new()
        } else if x > 1 {
            Rational::from(1)
        } else {
            x
        }
    };
    (0..2)
        .map(|a| {
            let grid = |x: Rational, up: bool| -> Rational {
                if dy(&x).is_some() {
                    return x;
                }
                let mut y = Rational::from(&x << (k + 8));
                y = if up {
                    Rational::from(y.ceil_ref())
                } else {
                    Rational::from(y.floor_ref())
                };
                y >>= k + 8;
                y
            };
            let l = clamp(grid(Rational::from(&lo[a] - &r), false));
            let h = clamp(grid(Rational::from(&hi[a] + &r), true));
            Some((dy(&l)?, dy(&h)?))
        })
        .collect()
}

/// The margins `2^-k` tried around a point, coarse to fine.
const MARGINS: std::ops::RangeInclusive<u32> = 3..=22;

/// How many of the coarsest margins are tried one by one before the finest is tried.
const COARSE_TRIES: u32 = 3;

/// A box `[lo − 2^-k, hi + 2^-k] ∩ [0, 1]²` (k in [`MARGINS`]) on which `holds` is true, or
/// `None` ([`first_margin`]).
pub(crate) fn first_box_around(
    lo: &[Rational; 2],
    hi: &[Rational; 2],
    holds: impl FnMut(&DyadicBoxN) -> bool,
) -> Option<DyadicBoxN> {
    first_margin(|k| box_around(lo, hi, k), holds)
}
/// The box built at the first margin `2^-k` (k in [`MARGINS`]) on which `holds` is true, or
/// `None`. The coarsest few are tried in turn; then the finest, and if it does not hold
/// either, none is tried further (a test on a box rarely holds where it fails on a box
/// inside it); otherwise the margin is bisected between the last failure and the finest.
/// Any box returned is one on which `holds` was evaluated true: which one it is is a matter
/// of cost and reach, never of soundness.
fn first_margin<B>(
    build: impl Fn(u32) -> Option<B>,
    mut holds: impl FnMut(&B) -> bool,
) -> Option<B> {
    let (first, last) = (*MARGINS.start(), *MARGINS.end());
    let mut test = |k: u32| build(k).filter(|b| holds(b));
    for k in first..first + COARSE_TRIES {
        if let Some(b) = test(k) {
            return Some(b);
        }
    }
    // Bisection: the margin at `fail` failed, the one at `ok` holds.
    let mut best = test(last)?;
    let (mut fail, mut ok) = (first + COARSE_TRIES - 1, last);
    while ok - fail > 1 {
        let mid = fail + (ok - fail) / 2;
        match test(mid) {
            Some(b) => {
                best = b;
                ok = mid;
            }
            None => fail = mid,
        }
    }
    Some(best)
}
pub(crate) fn f64_box(b: &DyadicBoxN) -> (Vec<f64>, Vec<f64>) {
    (
        b.iter().map(|d| d.0.to_f64()).collect(),
        b.iter().map(|d| d.1.to_f64()).collect(),
    )
}
/// A box around `c` on which the image map of patch `j` is injective (its interval Jacobian
/// is regular: by the mean value theorem, `F(w₁) − F(w₂) = M (w₁ − w₂)` with the rows of M
/// gradients of the image coordinates at points of the segment, and each row a positive
/// multiple of a row of the numerator Jacobian), or `None`.
pub fn injective_box(scene: &Scene, j: usize, c: &[Rational; 2]) -> Option<DyadicBoxN> {
    injective_box_around(scene, j, c, c)
}
/// [`injective_box`] around a parameter box `[lo, hi]` (dyadic corners).
pub fn injective_box_around(
    scene: &Scene,
    j: usize,
    lo: &[Rational; 2],
    hi: &[Rational; 2],
) -> Option<DyadicBoxN> {
    let jac: Vec<Bernstein<Interval>> = scene.jacobians[j]
        .iter()
        .flatten()
        .map(|p| p.convert(Precision::F64))
        .collect();
    first_box_around(lo, hi, |b| {
        let (lo, hi) = f64_box(b);
        let r: Vec<Interval> = jac.iter().map(|p| range_on(p, &lo, &hi)).collect();
        let det = r[0].mul(&r[3]).sub(&r[1].mul(&r[2]));
        det.lo() > 0.0 || det.hi() < 0.0
    })
}
/// A box of f64 corners (`[[u_lo, u_hi], [v_lo, v_hi]]`) around the parameter box `[lo, hi]`
/// with margins `2^-k`, **not** cut to the unit square, on which the image map of patch `j` —
/// its polynomials, which extend past their square — is injective: the denominator `q` has no
/// zero on it and the interval Jacobian is regular (`proofs/ray-count.md`, "Injective box";
/// past the square `q > 0` is not known, so `q ≠ 0` is proven on the box). A vertex on a side
/// of the square then lies inside the box, with room on every side for the lines that meet
/// there (`proofs/hidden-lines.md`, lemma I). `None` if no margin does.
pub fn injective_box_past(
    scene: &Scene,
    j: usize,
    lo: &[Rational; 2],
    hi: &[Rational; 2],
) -> Option<[[f64; 2]; 2]> {
    let jac: Vec<Bernstein<Interval>> = scene.jacobians[j]
        .iter()
        .flatten()
        .map(|p| p.convert(Precision::F64))
        .collect();
    let q: Bernstein<Interval> = scene.images[j].q.convert(Precision::F64);
    let lo = lo
        .clone()
        .map(|x| Interval::from_rational(&x, Precision::F64).lo());
    let hi = hi
        .clone()
        .map(|x| Interval::from_rational(&x, Precision::F64).hi());
    let build = |k: u32| -> Option<[[f64; 2]; 2]> {
        let m = (2f64).powi(-(k as i32));
        let b = [[lo[0] - m, hi[0] + m], [lo[1] - m, hi[1] + m]];
        b.iter().flatten().all(|x| x.is_finite()).then_some(b)
    };
    first_margin(build, |b| {
        let (lo, hi) = ([b[0][0], b[1][0]], [b[0][1], b[1][1]]);
        if !strict(&range_on(&q, &lo, &hi)) {
            return false;
        }
        let r: Vec<Interval> = jac.iter().map(|p| range_on(p, &lo, &hi)).collect();
        strict(&r[0].mul(&r[3]).sub(&r[1].mul(&r[2])))
    })
}
/// The jet of `k / q` from the jets of `k` and `q` (q > 0), by differentiating `k = f q`.
pub(crate) fn quotient_jet(k: &[Interval; 6], q: &[Interval; 6]) -> Option<[Interval; 6]> {
    let iq = q[0].recip()?;
    let f = k[0].mul(&iq);
    let fu = k[1].sub(&f.mul(&q[1])).mul(&iq);
    let fv = k[2].sub(&f.mul(&q[2])).mul(&iq);
    let two = Interval::point(2.0);
    let fuu = k[3]
        .sub(&two.mul(&fu).mul(&q[1]))
        .sub(&f.mul(&q[3]))
        .mul(&iq);
    let fuv = k[4]
        .sub(&fu.mul(&q[2]))
        .sub(&fv.mul(&q[1]))
        .sub(&f.mul(&q[4]))
        .mul(&iq);
    let fvv = k[5]
        .sub(&two.mul(&fv).mul(&q[2]))
        .sub(&f.mul(&q[5]))
        .mul(&iq);
    Some([f, fu, fv, fuu, fuv, fvv])
}
pub(crate) fn strict(i: &Interval) -> bool {
    i.lo() > 0.0 || i.hi() < 0.0
}
/// A box around the silhouette point of patch `j` on the line `axis = at` (free parameter in
/// `interval`) on which the fold lemma holds (`proofs/ray-count.md`), or `None`.
pub fn fold_box(
    scene: &Scene,
    j: usize,
    axis: usize,
    at: &Rational,
    interval: &[Rational; 2],
) -> Option<DyadicBoxN> {
    let mut lo = [at.clone(), at.clone()];
    let mut hi = [at.clone(), at.clone()];
    lo[1 - axis] = interval[0].clone();
    hi[1 - axis] = interval[1].clone();
    fold_box_around(scene, j, &lo, &hi)
}
/// A box around the parameter box `[lo, hi]` (dyadic corners) of patch `j` on which the fold
/// lemma holds (`proofs/ray-count.md`): the fibre of every fold point in it is that point
/// alone. `None` if not proven.
pub fn fold_box_around(
    scene: &Scene,
    j: usize,
    lo: &[Rational; 2],
    hi: &[Rational; 2],
) -> Option<DyadicBoxN> {
    let mid: Vec<Rational> = (0..2)
        .map(|a| {
            let mut m = Rational::from(&lo[a] + &hi[a]);
            m >>= 1u32;
            m
        })
        .collect();
    let polys = FoldPolys::at(scene, j, &mid)?;
    first_box_around(lo, hi, |b| {
        let (blo, bhi) = f64_box(b);
        polys.holds(&blo, &bhi)
    })
}
/// The image direction along which the outline of patch `j` runs near the parameter point
/// `mid`, approximately: a nonzero column of the Jacobian there (at a fold both columns are
/// parallel to the outline tangent). `None` if the Jacobian vanishes there.
pub(crate) fn outline_direction(scene: &Scene, j: usize, mid: &[Rational]) -> Option<[f64; 2]> {
    let jac = &scene.jacobians[j];
    let g = |p: &Poly| p.eval(mid).to_f64();
    let cu = [g(&jac[0][0]), g(&jac[1][0])];
    let cv = [g(&jac[0][1]), g(&jac[1][1])];
    let t = if cu[0].hypot(cu[1]) >= cv[0].hypot(cv[1]) {
        cu
    } else {
        cv
    };
    let norm = t[0].hypot(t[1]);
    (norm.is_finite() && norm > 0.0).then_some(t)
}
/// κ, η, q and their first and second partial derivatives, in interval form: what the fold
/// lemma is checked on (`proofs/ray-count.md`).
pub(crate) struct FoldPolys {
    kappa: [Bernstein<Interval>; 6],
    eta: [Bernstein<Interval>; 6],
    q: [Bernstein<Interval>; 6],
}
impl FoldPolys {
    /// The polynomials of patch `j`, with the image rotated so that κ runs along the
    /// outline's direction at the parameter point `mid` (approximately: a nonzero column of
    /// the Jacobian there, which at a fold is parallel to the outline tangent). The lemma is
    /// proven for whatever rotation is chosen; a good one only makes it succeed. `None` if
    /// the Jacobian vanishes there.
    pub(crate) fn at(scene: &Scene, j: usize, mid: &[Rational]) -> Option<FoldPolys> {
        FoldPolys::along(scene, j, outline_direction(scene, j, mid)?)
    }

    /// The polynomials of patch `j` with κ along the image direction `t` (rounded to a
    /// rational direction on a grid of 1/1024), or `None` if that rounds to zero.
    pub(crate) fn along(scene: &Scene, j: usize, t: [f64; 2]) -> Option<FoldPolys> {
        let im = &scene.images[j];
        let norm = t[0].hypot(t[1]);
        if norm.is_nan() || norm <= 0.0 {
            return None;
        }
        let r =
            |x: f64| Rational::from_f64((x / norm * 1024.0).round() / 1024.0).unwrap_or_default();
        let (tx, ty) = (r(t[0]), r(t[1]));
        if tx == 0 && ty == 0 {
            return None;
        }
        // κ along the outline, η across it.
        let kappa = &im.x.scale(&tx) + &im.y.scale(&ty);
        let eta = &im.y.scale(&tx) - &im.x.scale(&ty);
        Some(FoldPolys::new(&kappa, &eta, &im.q))
    }

    /// Whether the fold lemma holds on the box: then the fibre, within the box, of every
    /// fold point in it is that point alone.
    pub(crate) fn holds(&self, lo: &[f64], hi: &[f64]) -> bool {
        self.holds_within(lo, hi, 3)
    }

    /// [`FoldPolys::holds`], with the box halved at most `depth` times to prove it.
    pub(crate) fn holds_within(&self, lo: &[f64], hi: &[f64], depth: u32) -> bool {
        !signs_differ_at_corners(self, lo, hi) && fold_signs(self, lo, hi, depth).is_some()
    }

    fn new(kappa: &Poly, eta: &Poly, q: &Poly) -> FoldPolys {
        let all = |p: &Poly| -> [Bernstein<Interval>; 6] {
            let (pu, pv) = (p.deriv(0), p.deriv(1));
            [
                p.clone(),
                pu.clone(),
                pv.clone(),
                pu.deriv(0),
                pu.deriv(1),
                pv.deriv(1),
            ]
            .map(|x| x.convert(Precision::F64))
        };
        FoldPolys {
            kappa: all(kappa),
            eta: all(eta),
            q: all(q),
        }
    }
}
/// The strict signs of `(κ_u, κ_v, C)` on a box, where `C = κ_v³ · (second derivative of η
/// along the level curves of κ)`, proven on the box or on a cover of it by sub-boxes
/// (halved up to `depth` times) that all agree; `None` if not proven.
pub(crate) fn fold_signs(p: &FoldPolys, lo: &[f64], hi: &[f64], depth: u32) -> Option<[bool; 3]> {
    let jet = |f: &[Bernstein<Interval>; 6]| jet_on(f, lo, hi);
    let here = fold_quantities(&jet(&p.kappa), &jet(&p.eta), &jet(&p.q)).and_then(|q| {
        q.iter()
            .all(strict)
            .then(|| [q[0].lo() > 0.0, q[1].lo() > 0.0, q[2].lo() > 0.0])
    });
    if here.is_some() || depth == 0 {
        return here;
    }
    let mid = [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])];
    let mut common: Option<[bool; 3]> = None;
    for (u0, u1) in [(lo[0], mid[0]), (mid[0], hi[0])] {
        for (v0, v1) in [(lo[1], mid[1]), (mid[1], hi[1])] {
            let s = fold_signs(p, &[u0, v0], &[u1, v1], depth - 1)?;
            if common.is_some_and(|c| c != s) {
                return None;
            }
            common = Some(s);
        }
    }
    common
}

/// `(κ_u, κ_v, C)` from the jets of κ, η and q (on a box or at a point), `None` where q's
/// enclosure contains zero.
fn fold_quantities(
    kappa: &[Interval; 6],
    eta: &[Interval; 6],
    q: &[Interval; 6],
) -> Option<[Interval; 3]> {
    let k = quotient_jet(kappa, q)?;
    let h = quotient_jet(eta, q)?;
    let (ku, kv) = (k[1], k[2]);
    let two = Interval::point(2.0);
    let form = |f: &[Interval; 6]| {
        f[3].mul(&kv.mul(&kv))
            .sub(&two.mul(&f[4]).mul(&ku).mul(&kv))
            .add(&f[5].mul(&ku.mul(&ku)))
    };
    let c = kv.mul(&form(&h)).sub(&h[2].mul(&form(&k)));
    Some([ku, kv, c])
}

/// Whether one of `(κ_u, κ_v, C)` is proven to take both strict signs at the corners of the
/// box: then none of them can keep a strict sign on it, nor agree on a cover of it, and
/// [`fold_signs`] fails there. A filter: point enclosures cost a fraction of box enclosures.
fn signs_differ_at_corners(p: &FoldPolys, lo: &[f64], hi: &[f64]) -> bool {
    let at = |u: f64, v: f64| {
        let x = [Interval::point(u), Interval::point(v)];
        let jet = |f: &[Bernstein<Interval>; 6]| f.each_ref().map(|g| g.eval(&x));
        fold_quantities(&jet(&p.kappa), &jet(&p.eta), &jet(&p.q))
    };
    let mut seen = [[false; 2]; 3];
    for (u, v) in [
        (lo[0], lo[1]),
        (hi[0], lo[1]),
        (lo[0], hi[1]),
        (hi[0], hi[1]),
    ] {
        let Some(q) = at(u, v) else { continue };
        for (s, x) in seen.iter_mut().zip(q) {
            s[0] |= x.lo() > 0.0;
            s[1] |= x.hi() < 0.0;
        }
    }
    seen.iter().any(|s| s[0] && s[1])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::view::View;
    use crate::analysis::visibility::scene::tests::torus_scene;

    /// The corner filter rejects only boxes the fold lemma's test rejects too, and the box
    /// search returns only boxes on which its test holds: on every patch of a torus seen from
    /// a generic direction, over boxes of a grid at three scales.
    #[test]
    fn the_corner_filter_and_the_box_search_are_sound() {
        let (model, scene) = torus_scene(&View::Direction([7, 2, 4].map(Rational::from)));
        let (mut rejected, mut held) = (0, 0);
        for j in 0..model.patches.len() {
            let Some(p) = FoldPolys::along(&scene, j, [1.0, 0.3]) else {
                continue;
            };
            for n in [2, 5, 12] {
                for a in 0..n {
                    for b in 0..n {
                        let w = 1.0 / n as f64;
                        let lo = [a as f64 * w, b as f64 * w];
                        let hi = [lo[0] + w, lo[1] + w];
                        if signs_differ_at_corners(&p, &lo, &hi) {
                            rejected += 1;
                            assert!(fold_signs(&p, &lo, &hi, 3).is_none(), "{j} {lo:?} {hi:?}");
                        } else if fold_signs(&p, &lo, &hi, 3).is_some() {
                            held += 1;
                        }
                    }
                }
            }
            // The box search: every box it returns holds.
            let c = [Rational::from(1) >> 1u32, Rational::from(1) >> 2u32];
            let found = first_box_around(&c, &c, |b| {
                let (lo, hi) = f64_box(b);
                p.holds(&lo, &hi)
            });
            if let Some(b) = found {
                let (lo, hi) = f64_box(&b);
                assert!(fold_signs(&p, &lo, &hi, 3).is_some());
            }
        }
        // Both branches are exercised.
        assert!(rejected > 0 && held > 0, "{rejected} {held}");
    }
}
