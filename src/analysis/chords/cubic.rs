//! Certified cubic pieces of an arc: Bézier cubics in (u, v) and in space, each with a proven
//! bound on its Hausdorff distance to the true piece of the curve, from the residual of the
//! curve's equation along it (`proofs/cubic-pieces.md`); and the drawn polyline sampled from
//! them, each chord bounded by the chord claim (`proofs/chord-accuracy.md`).
//!
//! A cubic's error shrinks like h⁴ with its length h, a chord's like h²: at a tolerance ε an arc
//! needs about ε^(−1/4) cubics against ε^(−1/2) certified vertices, and the polyline's vertices
//! are evaluations of the cubics, not certified one by one.

use super::plane_curve::{d1, on_line, PatchAccuracy, Vertex};
use crate::bernstein::{compose_curve, compose_curve_f64, residual_hull, Bernstein};
use crate::geometry::Rect;
use crate::number::{margin, Interval, Number};

/// A cubic piece of a traced arc.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Cubic {
    /// Bézier control points of a curve in the patch's parameters (u, v).
    pub uv: [[f64; 2]; 4],
    /// Bézier control points of a curve in space.
    pub space: [[f64; 3]; 4],
    /// A proven bound on the Hausdorff distance between the patch's image of the (u, v)
    /// cubic and the true piece of the curve, in model units.
    pub uv_bound: f64,
    /// A proven bound on the Hausdorff distance between the space cubic and the true piece.
    pub bound: f64,
}

/// A point of the arc estimated in f64: its level o, its m, and the slope dm/do there.
#[derive(Clone, Copy, Debug)]
struct Knot {
    o: f64,
    m: f64,
    slope: f64,
}

/// The f64 polynomials that give a cubic's Hermite data (estimates: the bounds certify
/// whatever cubic they produce).
pub(crate) struct Jets {
    /// g_u, g_v (absent for a patch without a curve function).
    g: Option<[Bernstein<f64>; 2]>,
    /// For X, Y, Z, W: the polynomial, ∂/∂u, ∂/∂v.
    p: Vec<[Bernstein<f64>; 3]>,
}

impl Jets {
    pub(crate) fn new(g: Option<&Bernstein<f64>>, homogeneous: &[Bernstein<f64>]) -> Jets {
        Jets {
            g: g.map(|g| [g.deriv(0), g.deriv(1)]),
            p: homogeneous
                .iter()
                .map(|h| [h.clone(), h.deriv(0), h.deriv(1)])
                .collect(),
        }
    }

    /// S and its two partials at a point.
    fn surface(&self, uv: [f64; 2]) -> Option<([f64; 3], [[f64; 3]; 2])> {
        let e: Vec<[f64; 3]> = self
            .p
            .iter()
            .map(|f| [f[0].eval(&uv), f[1].eval(&uv), f[2].eval(&uv)])
            .collect();
        let w = e.get(3)?;
        let mut s = [0.0; 3];
        let mut ds = [[0.0; 3]; 2];
        for k in 0..3 {
            s[k] = e[k][0] / w[0];
            for a in 0..2 {
                ds[a][k] = (e[k][1 + a] - s[k] * w[1 + a]) / w[0];
            }
        }
        (s.iter().chain(ds.iter().flatten()).all(|x| x.is_finite())).then_some((s, ds))
    }
}

/// The cubic route of one arc's trace: the arc as a graph `m = φ(o)` on the box `cell`, or a
/// line `m = const` (`on_edge`).
pub(super) struct CubicTrace<'a> {
    pub(super) acc: &'a PatchAccuracy,
    pub(super) m: usize,
    pub(super) on_edge: bool,
    pub(super) blo: [f64; 2],
    pub(super) bhi: [f64; 2],
    pub(super) tol: f64,
    /// How far past the cubic's control hull in m the box of its bounds reaches: the largest
    /// distance in m between the cubic and the arc that the bounds can prove.
    pub(super) reach: f64,
    /// A box around the arc's and enclosures of the partials of ∂g/∂m over it (u, v order),
    /// for the mean value form of ∂g/∂m ([`CubicTrace::least_gm`]).
    pub(super) grad: ([f64; 2], [f64; 2], Option<[Interval; 2]>),
    /// The arc's box with bounds of |∂S/∂m| and |∂S/∂o| over it, if they could be computed.
    pub(super) cell_bounds: Option<(Rect, f64, f64)>,
}

/// The most cubics on one arc.
const MAX_CUBICS: usize = 1 << 14;

/// The fewest chords the polyline takes on one cubic.
const MIN_CHORDS: f64 = 16.0;

/// Consecutive cubics that share one set of bounds of S's derivatives.
const TIGHTEN_RUN: usize = 8;

/// The deepest splitting of an arc's o-range into cubics.
const MAX_DEPTH: u32 = 24;

/// What a certified cubic gives its polyline: the box holding it, the arc piece and its drawn
/// vertices; the proven distance in m between cubic and arc; the bounds of S's derivatives.
#[derive(Clone)]
struct Certified {
    cubic: Cubic,
    /// The cubic's m control points (exact), and its levels.
    mu: [f64; 4],
    levels: (f64, f64),
    boxed: Rect,
    delta: f64,
    /// The rounding of the stored o control points (see `certify`) and the space residual.
    shift: f64,
    r_space: f64,
    /// Bounds of |S_m|, |S_mm|, |S_mo|, |S_oo| over a box holding `boxed`; `None` until
    /// [`CubicTrace::tighten`].
    sb: Option<[f64; 4]>,
}

/// A traced arc: its cubics, its polyline (vertices with certified errors), the boxes of the
/// polyline's pieces (one per chord, with its two vertices' indices) and the largest chord
/// bound.
pub(super) struct CubicOutcome {
    pub(super) cubics: Vec<Cubic>,
    pub(super) verts: Vec<Vertex>,
    pub(super) pieces: Vec<(Rect, usize, usize)>,
    pub(super) worst: f64,
}

impl CubicTrace<'_> {
    fn o(&self) -> usize {
        1 - self.m
    }

    fn uv(&self, o: f64, m: f64) -> [f64; 2] {
        let mut p = [0.0; 2];
        p[self.m] = m;
        p[self.o()] = o;
        p
    }

    /// The slope dm/do of the curve at a point, in f64 (`−g_o / g_m`; 0 along a line).
    fn slope(&self, o: f64, m: f64) -> Option<f64> {
        if self.on_edge {
            return Some(0.0);
        }
        let g = self.acc.jets.g.as_ref()?;
        let uv = self.uv(o, m);
        let (gm, go) = (g[self.m].eval(&uv), g[self.o()].eval(&uv));
        let s = -go / gm;
        s.is_finite().then_some(s)
    }

    /// The arc's point at level `o`, estimated by Newton's method in f64 from `guess` (kept in
    /// the arc's box).
    fn knot(&self, o: f64, guess: f64) -> Option<Knot> {
        let m = if self.on_edge {
            guess
        } else {
            let line = on_line(self.acc.g_f64.as_ref()?, self.m, o);
            let dline = line.deriv(0);
            let (lo, hi) = (self.blo[self.m], self.bhi[self.m]);
            let mut x = guess.clamp(lo, hi);
            for _ in 0..12 {
                let step = line.eval(&[x]) / dline.eval(&[x]);
                if !step.is_finite() {
                    break;
                }
                x = (x - step).clamp(lo, hi);
                if step.abs() <= 4.0 * f64::EPSILON * (1.0 + x.abs()) {
                    break;
                }
            }
            x
        };
        Some(Knot {
            o,
            m,
            slope: self.slope(o, m)?,
        })
    }

    /// The cubic from `a` to `b` (Hermite: the knots' points and slopes), with its proven
    /// bounds (`proofs/cubic-pieces.md`), if they are within the cubics' shares of the
    /// tolerance (half for the (u, v) cubic, all of it for the space cubic). Otherwise how far
    /// over they are (a ratio, to plan the split; 16 where no bound could be computed) and
    /// whether the f64 filter's rounding was a large part of a residual.
    fn certify(&self, a: Knot, b: Knot, tight: bool) -> Result<Certified, (f64, bool)> {
        const UNKNOWN: (f64, bool) = (16.0, true);
        let (m, o) = (self.m, self.o());
        let h = b.o - a.o;
        if h == 0.0 || !h.is_finite() {
            return Err((16.0, false));
        }
        let mu = [a.m, a.m + a.slope * h / 3.0, b.m - b.slope * h / 3.0, b.m];
        if mu.iter().any(|x| !x.is_finite()) {
            return Err(UNKNOWN);
        }
        // Both knots in the arc's box, so the cubic's box meets it (claim 1).
        let in_cell = |k: &Knot| {
            let p = self.uv(k.o, k.m);
            (0..2).all(|i| self.blo[i] <= p[i] && p[i] <= self.bhi[i])
        };
        if !in_cell(&a) || !in_cell(&b) {
            return Err(UNKNOWN);
        }
        let iv = Interval::point;
        // The exact o-extent of the cubic (its o is linear from a.o to b.o).
        let span = iv(b.o).sub(&iv(a.o));
        // The box: the cubic's levels in o, its control hull grown by `reach` in m.
        let (mlo, mhi) = mu
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, u), &x| {
                (l.min(x), u.max(x))
            });
        let mut lo = [0.0; 2];
        let mut hi = [0.0; 2];
        lo[o] = a.o.min(b.o);
        hi[o] = a.o.max(b.o);
        lo[m] = iv(mlo).sub(&iv(self.reach)).lo();
        hi[m] = iv(mhi).add(&iv(self.reach)).hi();
        // The curve in (u, v) and, for the tight route, in the box's local coordinates.
        let (gx, gy): (Vec<f64>, Vec<f64>) = if m == 0 {
            (mu.to_vec(), vec![a.o, b.o])
        } else {
            (vec![a.o, b.o], mu.to_vec())
        };
        let local = |x: f64, k: usize| -> Option<Interval> {
            if hi[k] == lo[k] {
                Some(iv(0.0))
            } else {
                iv(x)
                    .sub(&iv(lo[k]))
                    .checked_div(&iv(hi[k]).sub(&iv(lo[k])))
            }
        };
        let in_box =
            |z: &[f64], k: usize| z.iter().map(|&x| local(x, k)).collect::<Option<Vec<_>>>();
        let (lx, ly) = if tight {
            (
                in_box(&gx, 0).ok_or(UNKNOWN)?,
                in_box(&gy, 1).ok_or(UNKNOWN)?,
            )
        } else {
            (Vec::new(), Vec::new())
        };
        // The polynomials along the cubic: in f64 with a running error bound on the patch's
        // own coefficients, or (`tight`) restricted to the box first, in intervals (tighter
        // where a residual is near the rounding at the whole patch's scale).
        let along = |p: &Bernstein<Interval>| {
            if tight {
                compose_curve(&p.restrict_box_f64(&lo, &hi), &lx, &ly)
            } else {
                compose_curve_f64(p, &gx, &gy)
            }
            .ok_or(UNKNOWN)
        };
        let magnitude = |r: Interval| r.lo().abs().max(r.hi().abs());
        // The distance in m between the cubic and the arc: |g| along the cubic over the least
        // |g_m| on the box (`proofs/cubic-pieces.md`, claim 1).
        let mut noisy = false;
        let delta = if self.on_edge {
            0.0
        } else {
            let r = along(&self.acc.g[0])?.hull();
            let gm = self.least_gm(lo, hi);
            let least = if gm.lo() > 0.0 {
                gm.lo()
            } else if gm.hi() < 0.0 {
                -gm.hi()
            } else {
                return Err(UNKNOWN);
            };
            let big = magnitude(r);
            noisy = r.width() > 0.2 * big;
            let d = iv(big).checked_div(&iv(least)).ok_or(UNKNOWN)?.hi();
            if d.is_nan() || d > self.reach {
                return Err((
                    if d.is_finite() {
                        2.0 * d / self.reach
                    } else {
                        16.0
                    },
                    noisy,
                ));
            }
            d
        };
        // The space cubic: Hermite from S and dS/dt = h (S_m m' + S_o) at the ends.
        let ends = [a, b].map(|k| self.acc.jets.surface(self.uv(k.o, k.m)));
        let [Some((s0, d0)), Some((s3, d3))] = ends else {
            return Err(UNKNOWN);
        };
        let mut space = [[0.0; 3]; 4];
        for k in 0..3 {
            space[0][k] = s0[k];
            space[3][k] = s3[k];
            space[1][k] = s0[k] + h * (d0[m][k] * a.slope + d0[o][k]) / 3.0;
            space[2][k] = s3[k] - h * (d3[m][k] * b.slope + d3[o][k]) / 3.0;
        }
        if space.iter().flatten().any(|x| !x.is_finite()) {
            return Err(UNKNOWN);
        }
        // |S(c(t)) − σ(t)| ≤ |P(c) − σ W(c)| / W(c) (claim 2).
        let homog = &self.acc.surface.h;
        let w = along(&homog[3][0])?;
        let wmin = w.hull().lo();
        if wmin.is_nan() || wmin <= 0.0 {
            return Err(UNKNOWN);
        }
        let mut sq: f64 = 0.0;
        for (k, component) in homog.iter().take(3).enumerate() {
            let sigma: Vec<f64> = space.iter().map(|p| p[k]).collect();
            let r = residual_hull(&along(&component[0])?, &w, &sigma).ok_or(UNKNOWN)?;
            let big = magnitude(r);
            noisy |= r.width() > 0.2 * big;
            sq += big * big;
        }
        let r_space = margin::up(sq.sqrt() / wmin, margin::FEW);
        // The stored (u, v) control points: m exactly, o rounded from the exact thirds; the
        // rounding moves the curve by at most `shift` in o (convex combinations).
        let mut uv = [[0.0; 2]; 4];
        let mut shift: f64 = 0.0;
        for (k, c) in uv.iter_mut().enumerate() {
            let (exact, stored) = if k == 3 {
                (iv(b.o), b.o)
            } else {
                let third = span
                    .mul(&iv(k as f64))
                    .checked_div(&iv(3.0))
                    .ok_or(UNKNOWN)?;
                (iv(a.o).add(&third), a.o + h * (k as f64) / 3.0)
            };
            shift = shift.max((stored - exact.lo()).abs().max((exact.hi() - stored).abs()));
            *c = self.uv(stored, mu[k]);
        }
        let shift = margin::up(shift, margin::FEW);
        let mut wide = Rect::new(lo, hi);
        wide.lo[o] = iv(lo[o]).sub(&iv(shift)).lo();
        wide.hi[o] = iv(hi[o]).add(&iv(shift)).hi();
        let bounds = |l_m: f64, l_o: f64| {
            (
                margin::up(l_m * delta + l_o * shift, margin::FEW),
                margin::up(l_m * delta + r_space, margin::FEW),
            )
        };
        let over = |(uv_bound, bound): (f64, f64)| {
            let r = (uv_bound / (0.5 * self.tol)).max(bound / self.tol);
            if r.is_finite() {
                r
            } else {
                16.0
            }
        };
        // With the arc's box's bounds of |S_m|, |S_o| where the cubic's box is in it (those
        // over a smaller box, for the polyline too, come later: [`CubicTrace::tighten`]), else
        // with bounds over the cubic's box.
        let inside =
            |r: &Rect, cell: &Rect| (0..2).all(|k| cell.lo[k] <= r.lo[k] && r.hi[k] <= cell.hi[k]);
        let (sb, l_m, l_o) = match self.cell_bounds {
            Some((cell, l_m, l_o)) if inside(&wide, &cell) => (None, l_m, l_o),
            _ => {
                let (sb, l_o) = self
                    .acc
                    .surface
                    .bounds_both(wide.lo, wide.hi, m)
                    .ok_or(UNKNOWN)?;
                (Some(sb), sb[0], l_o)
            }
        };
        let (uv_bound, bound) = bounds(l_m, l_o);
        let r = over((uv_bound, bound));
        if r > 1.0 {
            return Err((r, noisy));
        }
        Ok(Certified {
            cubic: Cubic {
                uv,
                space,
                uv_bound,
                bound,
            },
            mu,
            levels: (a.o, b.o),
            boxed: wide,
            delta,
            shift,
            r_space,
            sb,
        })
    }

    /// Bounds of S's derivatives over the boxes of runs of consecutive cubics (a few at a
    /// time: one set of bounds over their boxes' hull holds for each), for the polylines, and
    /// the cubics' bounds recomputed with them where smaller. False if a bound could not be
    /// computed.
    fn tighten(&self, cubics: &mut [Certified]) -> bool {
        for run in cubics.chunks_mut(TIGHTEN_RUN) {
            if run.iter().all(|c| c.sb.is_some()) {
                continue;
            }
            let hull = run
                .iter()
                .skip(1)
                .fold(run[0].boxed, |h, c| h.hull(&c.boxed));
            let Some((sb, l_o)) = self.acc.surface.bounds_both(hull.lo, hull.hi, self.m) else {
                return false;
            };
            for c in run.iter_mut().filter(|c| c.sb.is_none()) {
                c.sb = Some(sb);
                let l_m = sb[0];
                let uv_bound = margin::up(l_m * c.delta + l_o * c.shift, margin::FEW);
                let bound = margin::up(l_m * c.delta + c.r_space, margin::FEW);
                c.cubic.uv_bound = c.cubic.uv_bound.min(uv_bound);
                c.cubic.bound = c.cubic.bound.min(bound);
            }
        }
        true
    }

    /// An enclosure of ∂g/∂m over the box: by the mean value form from its value at the
    /// centre and the bounds of its partials over the arc's box grown (`grad`), where the box
    /// lies in that; else the hull of its restriction.
    fn least_gm(&self, lo: [f64; 2], hi: [f64; 2]) -> Interval {
        let gm = &self.acc.g[d1(self.m)];
        let (glo, ghi, grad) = &self.grad;
        let inside = (0..2).all(|k| glo[k] <= lo[k] && hi[k] <= ghi[k]);
        match grad {
            Some(grad) if inside => {
                let c = [0, 1].map(|k| 0.5 * lo[k] + 0.5 * hi[k]);
                let at = gm.eval(&c.map(Interval::point));
                let mut r = Interval::point(0.0);
                for k in 0..2 {
                    let reach = Interval::point(hi[k] - c[k])
                        .hull(&Interval::point(c[k] - lo[k]))
                        .hi();
                    let reach = Interval::point(reach).mul(&Interval::point(1.0 + 1e-15));
                    r = r.add(&grad[k].mul(&Interval::new(-reach.hi(), reach.hi())));
                }
                at.add(&r)
            }
            _ => gm.restrict_box_f64(&lo, &hi).hull(),
        }
    }

    /// Covers the arc from `a` to `b` with certified cubics (appended to `out`), splitting
    /// where a cubic's bounds are over its share of the tolerance (a cubic whose residual was
    /// mostly the f64 filter's rounding is retried on its box in intervals). False if the
    /// budget ran out.
    fn cover(&self, a: Knot, b: Knot, depth: u32, out: &mut Vec<Certified>) -> bool {
        if out.len() >= MAX_CUBICS {
            return false;
        }
        let over = match self.certify(a, b, false) {
            Ok(c) => {
                out.push(c);
                return true;
            }
            // Near a pass, where the filter's rounding was much of a residual: on the box.
            Err((over, true)) if over < 8.0 => match self.certify(a, b, true) {
                Ok(c) => {
                    out.push(c);
                    return true;
                }
                Err((tight, _)) => over.min(tight),
            },
            Err((over, _)) => over,
        };
        if depth >= MAX_DEPTH {
            return false;
        }
        // The error of a cubic goes like h⁴: split into as many pieces as that asks for.
        let n = (over.powf(0.25) * 1.2).ceil().clamp(2.0, 16.0) as usize;
        let mut prev = a;
        for k in 1..=n {
            let next = if k == n {
                b
            } else {
                let t = k as f64 / n as f64;
                let level = a.o + (b.o - a.o) * t;
                let h = b.o - a.o;
                let hermite = [a.m, a.m + a.slope * h / 3.0, b.m - b.slope * h / 3.0, b.m];
                let guess = cubic_at(&hermite, t);
                match self.knot(level, guess) {
                    Some(k) => k,
                    None => return false,
                }
            };
            if !self.cover(prev, next, depth + 1, out) {
                return false;
            }
            prev = next;
        }
        true
    }

    /// The arc from the vertex `(o0, m0)` to `(o1, m1)` (the centres of its ends' boxes) as
    /// certified cubics and a polyline sampled from them; `None` if the cubics or the
    /// polyline's chords could not be certified within the budget.
    /// `d0`, `d1` are the end vertices' errors ([`Vertex`]), kept for their end pieces.
    pub(super) fn trace(
        &self,
        p0: (f64, f64),
        p1: (f64, f64),
        d0: f64,
        d1: f64,
    ) -> Option<CubicOutcome> {
        if self.on_edge && p0.1 != p1.1 {
            return None;
        }
        let a = self.knot(p0.0, p0.1)?;
        let b = self.knot(p1.0, p1.1)?;
        // The ends stay where the tracer put them (the boxes' centres).
        let a = Knot { m: p0.1, ..a };
        let b = Knot { m: p1.1, ..b };
        let mut certified = Vec::new();
        if !self.cover(a, b, 0, &mut certified) || !self.tighten(&mut certified) {
            return None;
        }

        let mut out = CubicOutcome {
            cubics: Vec::with_capacity(certified.len()),
            verts: vec![(a.o, a.m, d0)],
            pieces: Vec::with_capacity(certified.len()),
            worst: 0.0,
        };
        for c in certified {
            self.sample(&c, &mut out)?;
            out.cubics.push(c.cubic);
        }
        out.verts.last_mut()?.2 = d1;
        Some(out)
    }

    /// The polyline's vertices on one cubic (its first is already placed): at `n` uniformly
    /// spaced levels, each the centre of an interval enclosure of the cubic's m at that level,
    /// with `n` chosen so that the chord bound of `proofs/cubic-pieces.md` (claim 3),
    /// `L_m (δ + e) + Δt²/8 · K₂`, is within the tolerance; `K₂` bounds |(S∘c)''| from the
    /// bounds of S's derivatives over the cubic's box and of c's from its control points.
    fn sample(&self, c: &Certified, out: &mut CubicOutcome) -> Option<()> {
        let m = self.m;
        let (oa, ob) = c.levels;
        let iv = Interval::point;
        let span = iv(ob).sub(&iv(oa));
        let [l_m, s_mm, s_mo, s_oo] = c.sb?;
        // |μ'| ≤ 3 max |Δμ|, |μ''| ≤ 6 max |Δ²μ|, |o'| = |span| (`coefficient-range.md` on the
        // derivative's Bernstein coefficients).
        let mu = c.mu.map(iv);
        let d1 = (0..3)
            .map(|k| mu[k + 1].sub(&mu[k]).mul(&iv(3.0)))
            .fold(0.0f64, |x, d| x.max(d.lo().abs()).max(d.hi().abs()));
        let d2 = (0..2)
            .map(|k| {
                mu[k + 2]
                    .sub(&mu[k + 1].mul(&iv(2.0)))
                    .add(&mu[k])
                    .mul(&iv(6.0))
            })
            .fold(0.0f64, |x, d| x.max(d.lo().abs()).max(d.hi().abs()));
        let o1 = span.lo().abs().max(span.hi().abs());
        let k2 = margin::up(
            s_mm * d1 * d1 + 2.0 * s_mo * d1 * o1 + s_oo * o1 * o1 + l_m * d2,
            margin::MANY,
        );
        let constant = c.mu.iter().all(|&x| x == c.mu[0]);
        // The vertices' own errors are a few ulps of m; the budget keeps room for them.
        let budget = self.tol - l_m * (c.delta + 1e-15);
        if budget.is_nan() || budget <= 0.0 || !k2.is_finite() {
            return None;
        }
        // At least MIN_CHORDS chords a cubic: the pieces' boxes stay small for the bounds
        // computed over them downstream (event directions, hidden-line systems).
        let n = if k2 > 0.0 {
            (k2 / (8.0 * 0.9 * budget)).sqrt().ceil()
        } else {
            1.0
        }
        .max(MIN_CHORDS);
        if n as usize + out.verts.len() > super::plane_curve::MAX_ARC_POINTS {
            return None;
        }
        let count = n as usize;
        // The previous vertex's parameter (a lower bound) and offset from the cubic.
        let (mut prev_t, mut prev_e) = (0.0f64, 0.0f64);
        let mut worst: f64 = 0.0;
        for k in 1..=count {
            // The vertex at `level`, its parameter on c enclosed in [t_lo, t_hi], and its
            // offset from c's point there; the last is the cubic's end, exactly.
            let (vertex, t_lo, t_hi, e) = if k == count {
                ((ob, c.mu[3], c.delta), 1.0, 1.0, 0.0)
            } else {
                let level = oa + (ob - oa) * (k as f64 / n);
                let level = level.clamp(oa.min(ob), oa.max(ob));
                let t = iv(level).sub(&iv(oa)).checked_div(&span)?;
                let t = Interval::new(t.lo().max(0.0), t.hi().min(1.0));
                let (mid, err) = if constant {
                    (c.mu[0], 0.0)
                } else {
                    let e = cubic_enclosure(&c.mu, t);
                    let mid = 0.5 * e.lo() + 0.5 * e.hi();
                    let err = iv(mid)
                        .sub(&iv(e.lo()))
                        .hi()
                        .max(iv(e.hi()).sub(&iv(mid)).hi());
                    (mid, err)
                };
                // Inside the arc's box, which holds the arc: a vertex moved to its side is
                // between the cubic's point and the arc's, so within max(err, δ) of the cubic.
                let inside = mid.clamp(self.blo[m], self.bhi[m]);
                let err = if inside == mid { err } else { err.max(c.delta) };
                let vertex = (level, inside, margin::up(c.delta + err, margin::FEW));
                (vertex, t.lo(), t.hi(), err)
            };
            let dt = iv(t_hi).sub(&iv(prev_t)).hi();
            let chord = margin::up(
                l_m * (c.delta + prev_e.max(e)) + dt * dt / 8.0 * k2,
                margin::MANY,
            );
            let p = self.uv(vertex.0, vertex.1);
            let held = (0..2).all(|k| c.boxed.lo[k] <= p[k] && p[k] <= c.boxed.hi[k]);
            if chord.is_nan() || chord > self.tol || !held {
                return None;
            }
            worst = worst.max(chord);
            // The chord's box: between its levels, and within δ + e + M₁ Δt in m of both
            // vertices (the arc is within δ of μ(t), which moves at most M₁ Δt from the
            // vertices' parameters), in the cubic's box and the arc's.
            let prev_m = out.verts.last()?.1;
            let reach = margin::up(c.delta + prev_e.max(e) + d1 * dt, margin::FEW);
            let mut lo = [0.0; 2];
            let mut hi = [0.0; 2];
            let o = 1 - m;
            let prev_o = out.verts.last()?.0;
            lo[o] = prev_o.min(vertex.0);
            hi[o] = prev_o.max(vertex.0);
            lo[m] = iv(prev_m.min(vertex.1)).sub(&iv(reach)).lo();
            hi[m] = iv(prev_m.max(vertex.1)).add(&iv(reach)).hi();
            let cell = clip(
                clip(Rect::new(lo, hi), c.boxed),
                Rect::new(self.blo, self.bhi),
            );
            let first = out.verts.len() - 1;
            out.pieces.push((cell, first, first + 1));
            out.verts.push(vertex);
            prev_t = t_lo;
            prev_e = e;
        }
        out.worst = out.worst.max(worst);
        Some(())
    }
}

/// The part of `a` in `b` (degenerate if they only touch).
fn clip(a: Rect, b: Rect) -> Rect {
    let lo = [0, 1].map(|k| a.lo[k].max(b.lo[k]));
    let hi = [0, 1].map(|k| a.hi[k].min(b.hi[k]).max(lo[k]));
    Rect::new(lo, hi)
}

/// A cubic Bézier's value at t, in f64 (de Casteljau).
fn cubic_at(c: &[f64; 4], t: f64) -> f64 {
    let s = 1.0 - t;
    let l = |x: f64, y: f64| s * x + t * y;
    let (a, b, d) = (l(c[0], c[1]), l(c[1], c[2]), l(c[2], c[3]));
    let (e, f) = (l(a, b), l(b, d));
    l(e, f)
}

/// An enclosure of a cubic Bézier's values over an interval of t ⊂ [0, 1] (de Casteljau in
/// interval arithmetic: inclusion-monotone, `proofs/de-casteljau-enclosure.md`).
fn cubic_enclosure(c: &[f64; 4], t: Interval) -> Interval {
    let s = Interval::point(1.0).sub(&t);
    let l = |x: Interval, y: Interval| s.mul(&x).add(&t.mul(&y));
    let p = c.map(Interval::point);
    let (a, b, d) = (l(p[0], p[1]), l(p[1], p[2]), l(p[2], p[3]));
    let (e, f) = (l(a, b), l(b, d));
    l(e, f)
}
