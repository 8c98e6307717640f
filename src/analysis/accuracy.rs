//! Certified chord accuracy: vertices on each arc such that every drawn segment is within a
//! world-space tolerance of the true curve (`proofs/chord-accuracy.md`).

use crate::bernstein::Bernstein;
use crate::number::{Interval, Number, Precision, Rational, Sign};
use crate::solver::curve2::Arc;
use crate::surface::RationalPatch;

/// The most vertices placed on one arc before giving up on the tolerance.
const MAX_ARC_POINTS: usize = 1 << 14;

/// `x / w` for an interval `w` of strict sign, outward rounded (one ulp each way covers the
/// round-to-nearest error of each candidate quotient).
fn div(x: Interval, w: Interval) -> Option<Interval> {
    if !w.sign().is_nonzero() {
        return None;
    }
    let c = [
        x.lo() / w.lo(),
        x.lo() / w.hi(),
        x.hi() / w.lo(),
        x.hi() / w.hi(),
    ];
    if c.iter().any(|v| v.is_nan()) {
        return None;
    }
    let lo = c.iter().copied().fold(f64::INFINITY, f64::min).next_down();
    let hi = c
        .iter()
        .copied()
        .fold(f64::NEG_INFINITY, f64::max)
        .next_up();
    Interval::try_new(lo, hi)
}

/// An upper bound of |x| over the interval.
fn mag(x: Interval) -> f64 {
    x.lo().abs().max(x.hi().abs())
}

/// An upper bound of the Euclidean norm of a vector of intervals.
fn norm(v: &[Interval; 3]) -> f64 {
    let s: f64 = v.iter().map(|x| mag(*x) * mag(*x)).sum();
    // sqrt and the sum are rounded to nearest: a relative margin covers them.
    s.sqrt() * (1.0 + 1e-12)
}

/// Interval data of one patch and its silhouette function, for accuracy bounds.
pub struct PatchAccuracy {
    /// g, then ∂g/∂u, ∂g/∂v, then ∂²g/∂u², ∂²g/∂u∂v, ∂²g/∂v².
    g: Vec<Bernstein<Interval>>,
    /// For X, Y, Z, W: f, f_u, f_v, f_uu, f_uv, f_vv.
    h: Vec<[Bernstein<Interval>; 6]>,
    /// g in f64, for root estimates (certified afterwards).
    g_f64: Bernstein<f64>,
}

fn derivs(p: &Bernstein<Rational>) -> [Bernstein<Interval>; 6] {
    let (pu, pv) = (p.deriv(0), p.deriv(1));
    let (puu, puv, pvv) = (pu.deriv(0), pu.deriv(1), pv.deriv(1));
    [p, &pu, &pv, &puu, &puv, &pvv].map(|q| q.convert(Precision::F64))
}

/// Index in the 6-element derivative arrays of ∂/∂a (a = 0, 1) and ∂²/∂a∂b.
fn d1(a: usize) -> usize {
    1 + a
}
fn d2(a: usize, b: usize) -> usize {
    match (a.min(b), a.max(b)) {
        (0, 0) => 3,
        (0, 1) => 4,
        _ => 5,
    }
}

impl PatchAccuracy {
    /// Converts (once) the exact polynomials a patch's bounds are computed from.
    pub fn new(patch: &RationalPatch, g: &Bernstein<Rational>) -> PatchAccuracy {
        PatchAccuracy {
            g: derivs(g).to_vec(),
            h: patch.homogeneous().iter().map(derivs).collect(),
            g_f64: g.convert(Precision::F64),
        }
    }

    /// The range of a polynomial over a box, enclosed.
    fn range(p: &Bernstein<Interval>, lo: [f64; 2], hi: [f64; 2]) -> Interval {
        let q = |x: f64| Rational::from_f64(x).unwrap_or_default();
        let r = p.restrict_box_rational(&lo.map(q), &hi.map(q));
        let (a, b) = r.range_f64();
        Interval::try_new(a, b).unwrap_or(Interval::new(f64::NEG_INFINITY, f64::INFINITY))
    }

    /// Bounds over a box of |∂S/∂m| and of the norms of S_mm, S_mo, S_oo.
    fn surface_bounds(&self, lo: [f64; 2], hi: [f64; 2], m: usize) -> Option<[f64; 4]> {
        let o = 1 - m;
        let r = |k: usize, i: usize| PatchAccuracy::range(&self.h[k][i], lo, hi);
        let w: [Interval; 6] = std::array::from_fn(|i| r(3, i));
        if !w[0].sign().is_positive() {
            return None;
        }
        let mut s_m = [Interval::point(0.0); 3];
        let mut s_mm = s_m;
        let mut s_mo = s_m;
        let mut s_oo = s_m;
        for k in 0..3 {
            let p: [Interval; 6] = std::array::from_fn(|i| r(k, i));
            let s = div(p[0], w[0])?;
            let sx = |a: usize| -> Option<Interval> { div(p[d1(a)].sub(&s.mul(&w[d1(a)])), w[0]) };
            let (sm, so) = (sx(m)?, sx(o)?);
            let sxy = |a: usize, b: usize, sa: Interval, sb: Interval| -> Option<Interval> {
                let num = p[d2(a, b)]
                    .sub(&sa.mul(&w[d1(b)]))
                    .sub(&sb.mul(&w[d1(a)]))
                    .sub(&s.mul(&w[d2(a, b)]));
                div(num, w[0])
            };
            s_m[k] = sm;
            s_mm[k] = sxy(m, m, sm, sm)?;
            s_mo[k] = sxy(m, o, sm, so)?;
            s_oo[k] = sxy(o, o, so, so)?;
        }
        Some([norm(&s_m), norm(&s_mm), norm(&s_mo), norm(&s_oo)])
    }

    /// Bounds of |φ'| and |φ''| over a box where ∂g/∂m has a strict sign.
    fn phi_bounds(&self, lo: [f64; 2], hi: [f64; 2], m: usize) -> Option<(f64, f64)> {
        let o = 1 - m;
        let r = |i: usize| PatchAccuracy::range(&self.g[i], lo, hi);
        let (gm, go) = (r(d1(m)), r(d1(o)));
        let (gmm, gmo, goo) = (r(d2(m, m)), r(d2(m, o)), r(d2(o, o)));
        let p1 = div(go, gm)?.neg();
        let two = Interval::point(2.0);
        let num = goo.add(&two.mul(&gmo).mul(&p1)).add(&gmm.mul(&p1).mul(&p1));
        let p2 = div(num, gm)?.neg();
        Some((mag(p1), mag(p2)))
    }

    /// The sign of g at a point, enclosed.
    fn sign_at(&self, m: usize, x: f64, level: f64) -> Sign {
        let mut pt = [Interval::point(0.0); 2];
        pt[m] = Interval::point(x);
        pt[1 - m] = Interval::point(level);
        self.g[0].eval(&pt).sign()
    }

    /// A bracket `[x, y]` of the arc's point on the line o = level within [m0, m1]: a secant
    /// estimate in f64, then certified by opposite enclosed signs of g at the bracket's ends
    /// (g is strictly monotone in m on the box, so the one root between them is the arc's).
    fn point_on_line(&self, m: usize, m0: f64, m1: f64, level: f64) -> Option<(f64, f64)> {
        let s0 = self.sign_at(m, m0, level);
        let s1 = self.sign_at(m, m1, level);
        if !s0.is_nonzero() || !s1.is_nonzero() || s0 == s1 {
            return None;
        }
        let f = |x: f64| {
            let mut pt = [0.0; 2];
            pt[m] = x;
            pt[1 - m] = level;
            self.g_f64.eval(&pt)
        };
        let (mut x0, mut x1) = (m0, m1);
        let (mut f0, mut f1) = (f(x0), f(x1));
        let mut side = 0;
        for _ in 0..40 {
            if f0 * f1 >= 0.0 || f0.is_nan() || f1.is_nan() || (x1 - x0) <= 1e-15 * (1.0 + x0.abs())
            {
                break;
            }
            let x = (x0 * f1 - x1 * f0) / (f1 - f0);
            let fx = f(x);
            if fx == 0.0 {
                (x0, x1) = (x, x);
                break;
            }
            if (fx > 0.0) == (f1 > 0.0) {
                (x1, f1) = (x, fx);
                if side == 1 {
                    f0 *= 0.5;
                }
                side = 1;
            } else {
                (x0, f0) = (x, fx);
                if side == -1 {
                    f1 *= 0.5;
                }
                side = -1;
            }
        }
        // Certify a bracket around the estimate, widening until the enclosed signs differ.
        let est = 0.5 * (x0 + x1);
        let mut eps = 1e-13 * (1.0 + est.abs());
        for _ in 0..40 {
            let (a, b) = ((est - eps).max(m0), (est + eps).min(m1));
            let (sa, sb) = (self.sign_at(m, a, level), self.sign_at(m, b, level));
            if sa == s0 && sb == s1 {
                return Some((a, b));
            }
            if (a, b) == (m0, m1) {
                break;
            }
            eps *= 16.0;
        }
        Some((m0, m1))
    }

    /// Vertices along an arc, in (u, v), from its `from` end to its `to` end, with the largest
    /// chord bound `E` (`proofs/chord-accuracy.md`); `None` for the bound if `tol` was not met
    /// within the budget or a bound could not be computed.
    pub fn trace(
        &self,
        arc: &Arc,
        from: [[f64; 2]; 2],
        to: [[f64; 2]; 2],
        tol: f64,
    ) -> (Vec<[f64; 2]>, Option<f64>) {
        let center = |b: [[f64; 2]; 2]| [0.5 * (b[0][0] + b[1][0]), 0.5 * (b[0][1] + b[1][1])];
        let half = |b: [[f64; 2]; 2], k: usize| 0.5 * (b[1][k] - b[0][k]);
        let (p0, p1) = (center(from), center(to));
        let (m, on_edge) = match arc.reason {
            "graph over v" => (0, false),
            "graph over u" => (1, false),
            // On an edge: the varying coordinate is the one the ends differ in.
            _ => (
                if (p1[0] - p0[0]).abs() >= (p1[1] - p0[1]).abs() {
                    1
                } else {
                    0
                },
                true,
            ),
        };
        let o = 1 - m;
        let [blo, bhi] = if on_edge {
            [
                [p0[0].min(p1[0]), p0[1].min(p1[1])],
                [p0[0].max(p1[0]), p0[1].max(p1[1])],
            ]
        } else {
            arc.cell.to_f64()
        };
        let phi1 = if on_edge {
            Some(0.0)
        } else {
            self.phi_bounds(blo, bhi, m).map(|b| b.0)
        };
        // Bounds of S's derivatives over the whole box: the h² factor does the shrinking.
        let (Some(phi1), Some([l_m, s_mm, s_mo, s_oo])) = (phi1, self.surface_bounds(blo, bhi, m))
        else {
            return (vec![p0, p1], None);
        };
        // Vertices: (o level, m value, δ = certified error of the m value at that level).
        let end_delta = |b: [[f64; 2]; 2]| half(b, m) + phi1 * half(b, o);
        let mut verts: Vec<(f64, f64, f64)> = vec![
            (p0[o], p0[m], end_delta(from)),
            (p1[o], p1[m], end_delta(to)),
        ];
        // The true arc ends anywhere in its crossing's location box, which may extend beyond
        // the end vertex's level: that end piece lies in the box grown by Φ₁ in m, within
        // L·(δ + half-extent in o) of the vertex in space, L bounding |∂S/∂m| and |∂S/∂o|.
        let Some(l_o) = self.surface_bounds(blo, bhi, o).map(|b| b[0]) else {
            return (vec![p0, p1], None);
        };
        let end_piece =
            |b: [[f64; 2]; 2]| l_m.max(l_o) * (end_delta(b) + half(b, o)) * (1.0 + 1e-9);
        let mut worst: f64 = end_piece(from).max(end_piece(to));
        if worst > tol {
            return (vec![p0, p1], None);
        }
        let mut i = 0;
        while i + 1 < verts.len() {
            let (oa, ma, da) = verts[i];
            let (ob, mb, db) = verts[i + 1];
            let h = (ob - oa).abs();
            let slope = if h > 0.0 {
                (mb - ma).abs() / h
            } else {
                f64::INFINITY
            };
            // The sub-arc over [oa, ob] stays within δ + Φ₁·h of both vertices in m: bound
            // everything on that small box, so the bound shrinks with h.
            let reach = da.max(db) + phi1 * h;
            let mut lo = blo;
            let mut hi = bhi;
            lo[o] = oa.min(ob).max(blo[o]);
            hi[o] = oa.max(ob).min(bhi[o]);
            lo[m] = (ma.min(mb) - reach).max(blo[m]);
            hi[m] = (ma.max(mb) + reach).min(bhi[m]);
            let phi2 = if on_edge {
                Some(0.0)
            } else {
                self.phi_bounds(lo, hi, m).map(|b| b.1)
            };
            let bound = phi2.map(|p2| {
                let e = l_m * (h * h / 8.0 * p2 + da.max(db))
                    + h * h / 8.0 * (s_mm * slope * slope + 2.0 * s_mo * slope + s_oo);
                e * (1.0 + 1e-9)
            });
            match bound {
                Some(e) if e.is_finite() && e <= tol => {
                    worst = worst.max(e);
                    i += 1;
                }
                _ if verts.len() >= MAX_ARC_POINTS || on_edge && h == 0.0 => {
                    return (verts.iter().map(|v| uv(m, v.1, v.0)).collect(), None);
                }
                _ => {
                    let level = 0.5 * (oa + ob);
                    let point = if on_edge {
                        Some((ma + (mb - ma) * 0.5, ma + (mb - ma) * 0.5))
                    } else {
                        self.point_on_line(m, blo[m], bhi[m], level)
                    };
                    let Some((x, y)) = point else {
                        return (verts.iter().map(|v| uv(m, v.1, v.0)).collect(), None);
                    };
                    verts.insert(i + 1, (level, 0.5 * (x + y), 0.5 * (y - x)));
                }
            }
        }
        (verts.iter().map(|v| uv(m, v.1, v.0)).collect(), Some(worst))
    }
}

fn uv(m: usize, mv: f64, ov: f64) -> [f64; 2] {
    if m == 0 {
        [mv, ov]
    } else {
        [ov, mv]
    }
}
