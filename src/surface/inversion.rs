//! Inverting a model-space curve onto a surface: a curve in the surface's parameter plane
//! made of cubic pieces, each in one knot span, with a proven bound `|S(p(t)) − C(t)|∞ ≤ ε`
//! (`proofs/edge-inversion.md`). Everything that *builds* the pieces runs in f64 and need not be
//! right; the bound is computed afterwards for each piece in interval arithmetic from the exact
//! data, and a piece whose bound misses the target is split until it holds or a limit is
//! reached (then the inversion fails with what was reached, never a guess).

use super::float_eval::Evaluator;
use super::{ModelCurve, ParameterCurve, RationalPatch};
use crate::bernstein::{compose_curve, Bernstein};
use crate::number::{margin, Interval, Number, Precision, Rational};
use std::cmp::Ordering;
use std::sync::OnceLock;

/// How many times a piece may be halved (in its curve's parameter) to reach the target.
const MAX_DEPTH: usize = 24;
/// The most cubic pieces one curve may become.
const MAX_PIECES: usize = 20_000;
/// Samples per Bézier piece of the curve before any splitting.
const FIRST_SAMPLES: usize = 2;
/// A projected coordinate this close to a knot (relative to the domain's side) is moved onto
/// the knot exactly, so that a curve along a knot line or the domain's boundary stays on it.
const SNAP: f64 = 1e-9;
/// Coarse samples per side of each Bézier piece, to start the projection of a curve.
const SEED_GRID: usize = 6;

/// Why a curve was not inverted.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum InversionError {
    /// The nearest point of the surface found (f64) is farther than the target allows.
    #[error("the curve passes {distance:.3e} from the surface (the nearest point found, at parameter {at:.6} of a Bézier piece of it), more than the {allowed:.3e} allowed")]
    OffSurface {
        /// The distance found (Euclidean).
        distance: f64,
        /// Where on the curve: the parameter in its Bézier piece.
        at: f64,
        /// The largest Euclidean distance the target allows (√3 times the max-norm target).
        allowed: f64,
    },
    /// The bound did not reach the target within the splitting limits.
    #[error("its inversion onto the surface was proven only within {bound:.3e}, more than the {target:.3e} allowed")]
    NotProven {
        /// The bound reached on the piece that failed (infinite when none was computed).
        bound: f64,
        /// The target.
        target: f64,
    },
    /// The curve crosses the seam of a closed surface (its parameter jumps across the domain).
    #[error(
        "the curve crosses the seam of the closed surface, which inversion does not handle yet"
    )]
    Seam,
    /// The curve or the surface has no usable f64 values (overflow, zero weights).
    #[error("the curve or the surface cannot be evaluated in floating point")]
    NotFinite,
}

/// A curve inverted onto a surface.
#[derive(Clone, Debug, PartialEq)]
pub struct Inversion {
    /// Cubic pieces in the surface's parameter plane (its knot domain), in the curve's
    /// direction, each ending exactly where the next starts.
    pub pieces: Vec<ParameterCurve>,
    /// Per piece, the curve's Bézier piece it follows and the range `[t₀, t₁]` of that
    /// piece's parameter: the piece's parameter `s ∈ [0, 1]` is `t = t₀ + s (t₁ − t₀)`.
    pub parameters: Vec<(usize, [f64; 2])>,
    /// The proven bound: for every piece and every `s`, the surface's point over the piece's
    /// point is within this distance (max norm) of the curve's point at `t`.
    pub distance: f64,
}

/// What a Bézier piece of the surface needs for inversion, built once on first use.
struct PieceData {
    eval: Evaluator,
    /// Its homogeneous polynomials `[wx, wy, wz, w]`, enclosed in intervals.
    homogeneous: [Bernstein<Interval>; 4],
}

/// A surface split into Bézier pieces on its knot spans, ready to have curves inverted onto
/// it. Cheap to build; each piece's evaluator is built the first time a curve comes near it.
pub struct Inverter {
    spans: [Vec<[Rational; 2]>; 2],
    spans_f64: [Vec<[f64; 2]>; 2],
    /// Piece index by `iu * nv + iv`.
    grid: Vec<Option<usize>>,
    patches: Vec<RationalPatch>,
    data: Vec<OnceLock<Option<PieceData>>>,
    seeds: OnceLock<Vec<([f64; 2], [f64; 3])>>,
    /// Closed in u, in v (a jump across the whole domain is a seam crossing).
    closed: [bool; 2],
    /// The largest side of the box of the control points.
    size: f64,
}

/// One Bézier piece of a curve being inverted, and the targets.
struct Job<'a> {
    curve: &'a CurveF64,
    /// Its index in the curve.
    index: usize,
    /// The bound to reach (max norm).
    target: f64,
    /// The largest distance (Euclidean) a sample may have from the surface.
    limit: f64,
}

impl std::fmt::Debug for Inverter {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Inverter")
            .field("spans", &[self.spans[0].len(), self.spans[1].len()])
            .field("closed", &self.closed)
            .field("size", &self.size)
            .finish_non_exhaustive()
    }
}

/// A point of the curve with its inverse.
#[derive(Clone, Debug)]
struct Sample {
    /// The curve's parameter (in its Bézier piece).
    t: f64,
    /// The surface parameters, f64 and exact (snapped coordinates are knots exactly).
    uv: [f64; 2],
    exact: [Rational; 2],
    /// `dp/dt` by least squares, when the surface's Jacobian is well conditioned there.
    tangent: Option<[f64; 2]>,
}

/// A Bézier piece of the curve in f64, with its derivative.
struct CurveF64 {
    c: [Bernstein<f64>; 4],
    d: [Bernstein<f64>; 4],
    /// The exact homogeneous coordinates, enclosed.
    hom: [Bernstein<Interval>; 4],
}

impl CurveF64 {
    fn new(curve: &ModelCurve) -> CurveF64 {
        let c: [Bernstein<f64>; 4] =
            std::array::from_fn(|k| curve.coordinate(k).convert(Precision::F64));
        let d = std::array::from_fn(|k| c[k].deriv(0));
        let hom = std::array::from_fn(|k| curve.coordinate(k).convert(Precision::F64));
        CurveF64 { c, d, hom }
    }

    /// The point and its derivative at `t`.
    fn at(&self, t: f64) -> ([f64; 3], [f64; 3]) {
        let w = self.c[3].eval(&[t]);
        let dw = self.d[3].eval(&[t]);
        let mut p = [0.0; 3];
        let mut dp = [0.0; 3];
        for k in 0..3 {
            let x = self.c[k].eval(&[t]);
            let dx = self.d[k].eval(&[t]);
            p[k] = x / w;
            dp[k] = (dx - p[k] * dw) / w;
        }
        (p, dp)
    }
}

fn sub3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot3(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm3(a: [f64; 3]) -> f64 {
    dot3(a, a).sqrt()
}

/// The least-squares solution of `[su sv] d = r`, or `None` when the normal matrix is
/// singular to working precision.
fn least_squares(su: [f64; 3], sv: [f64; 3], r: [f64; 3]) -> Option<[f64; 2]> {
    let (a, b, c) = (dot3(su, su), dot3(su, sv), dot3(sv, sv));
    let (x, y) = (dot3(su, r), dot3(sv, r));
    let det = a * c - b * b;
    if det.partial_cmp(&(1e-20 * (a * c).max(f64::MIN_POSITIVE))) != Some(Ordering::Greater) {
        return None;
    }
    Some([(c * x - b * y) / det, (a * y - b * x) / det])
}

/// Bits of the grid in a span's unit coordinate that constructed coordinates are put on.
const GRID_BITS: i32 = 32;

/// The point of the span `s` (exact; `sf` in f64) nearest `x` on the grid of `2^-GRID_BITS`
/// of its width, exact: `s₀ + k 2^-GRID_BITS (s₁ − s₀)`, clamped into the span. The pieces'
/// control points, the exact data every later step computes with, then have small
/// denominators in the span's unit coordinates (a dyadic of 32 bits) rather than a 53-bit
/// f64 over a decimal knot span; the grid moves a point by at most `2^-33` of the span, and
/// the bound is proven for the points as they are.
fn on_grid(x: f64, s: &[Rational; 2], sf: [f64; 2]) -> Rational {
    let scale = 2f64.powi(GRID_BITS);
    let unit = ((x - sf[0]) / (sf[1] - sf[0])).clamp(0.0, 1.0);
    let k = (unit * scale).round();
    if !k.is_finite() {
        return s[0].clone();
    }
    let k = Rational::from_f64(k).unwrap_or_default() / Rational::from(1u64 << GRID_BITS);
    let w = Rational::from(&s[1] - &s[0]);
    clamp(Rational::from(&s[0] + &(k * w)), s)
}

/// The index of the span of `spans` containing `x`, clamped to the first or last.
fn span_of(spans: &[[f64; 2]], x: f64) -> usize {
    spans
        .iter()
        .position(|s| x < s[1])
        .unwrap_or(spans.len() - 1)
}

/// The spans (indices) of `spans` whose closed interval contains `x`, exactly.
fn spans_containing(spans: &[[Rational; 2]], x: &Rational) -> Vec<usize> {
    spans
        .iter()
        .enumerate()
        .filter(|(_, s)| s[0] <= *x && *x <= s[1])
        .map(|(i, _)| i)
        .collect()
}

fn clamp(x: Rational, s: &[Rational; 2]) -> Rational {
    if x < s[0] {
        s[0].clone()
    } else if x > s[1] {
        s[1].clone()
    } else {
        x
    }
}

impl Inverter {
    /// The inverter of the surface whose Bézier pieces are `pieces` (with their span indices
    /// into `spans`, as [`super::NurbsSurface::to_bezier`] gives them), closed in u and v as
    /// `closed` says. `None` if a span pair has no piece or the spans are empty.
    pub fn new(
        spans: [Vec<[Rational; 2]>; 2],
        pieces: &[((usize, usize), RationalPatch)],
        closed: [bool; 2],
    ) -> Option<Inverter> {
        let [nu, nv] = [spans[0].len(), spans[1].len()];
        if nu == 0 || nv == 0 {
            return None;
        }
        let mut grid = vec![None; nu * nv];
        for (i, ((iu, iv), _)) in pieces.iter().enumerate() {
            if *iu >= nu || *iv >= nv {
                return None;
            }
            grid[iu * nv + iv] = Some(i);
        }
        if grid.iter().any(Option::is_none) {
            return None;
        }
        let spans_f64 = [0, 1].map(|d| {
            spans[d]
                .iter()
                .map(|s| [s[0].to_f64(), s[1].to_f64()])
                .collect()
        });
        let size = RationalPatch::control_size(pieces.iter().map(|(_, p)| p));
        Some(Inverter {
            size,
            spans,
            spans_f64,
            grid,
            patches: pieces.iter().map(|(_, p)| p.clone()).collect(),
            data: pieces.iter().map(|_| OnceLock::new()).collect(),
            seeds: OnceLock::new(),
            closed,
        })
    }

    /// The largest side of the box of the surface's control points.
    pub fn size(&self) -> f64 {
        self.size
    }

    fn piece(&self, i: usize) -> Option<&PieceData> {
        self.data[i]
            .get_or_init(|| {
                let patch = &self.patches[i];
                let homogeneous = patch.homogeneous().map(|h| h.convert(Precision::F64));
                Some(PieceData {
                    eval: Evaluator::new(patch),
                    homogeneous,
                })
            })
            .as_ref()
    }

    fn nv(&self) -> usize {
        self.spans[1].len()
    }

    /// The domain's side lengths.
    fn sides(&self) -> [f64; 2] {
        [0, 1].map(|d| {
            let s = &self.spans_f64[d];
            s[s.len() - 1][1] - s[0][0]
        })
    }

    /// S, S_u, S_v at global `(u, v)` (clamped into the domain).
    fn eval(&self, uv: [f64; 2]) -> Option<[[f64; 3]; 3]> {
        let (iu, iv) = (
            span_of(&self.spans_f64[0], uv[0]),
            span_of(&self.spans_f64[1], uv[1]),
        );
        let i = self.grid[iu * self.nv() + iv]?;
        let (su, sv) = (self.spans_f64[0][iu], self.spans_f64[1][iv]);
        let (wu, wv) = (su[1] - su[0], sv[1] - sv[0]);
        let x = ((uv[0] - su[0]) / wu).clamp(0.0, 1.0);
        let y = ((uv[1] - sv[0]) / wv).clamp(0.0, 1.0);
        let e = self.piece(i)?.eval.eval(x, y);
        let out = [e[0], e[1].map(|c| c / wu), e[2].map(|c| c / wv)];
        out.iter().flatten().all(|c| c.is_finite()).then_some(out)
    }

    fn clamp_domain(&self, uv: [f64; 2]) -> [f64; 2] {
        [0, 1].map(|d| {
            let s = &self.spans_f64[d];
            uv[d].clamp(s[0][0], s[s.len() - 1][1])
        })
    }

    /// The coarse samples of every piece: parameters and points.
    fn seeds(&self) -> &[([f64; 2], [f64; 3])] {
        self.seeds.get_or_init(|| {
            let mut out = Vec::new();
            for su in &self.spans_f64[0] {
                for sv in &self.spans_f64[1] {
                    for a in 0..=SEED_GRID {
                        for b in 0..=SEED_GRID {
                            let f = |s: &[f64; 2], k: usize| {
                                s[0] + (s[1] - s[0]) * k as f64 / SEED_GRID as f64
                            };
                            let uv = [f(su, a), f(sv, b)];
                            if let Some(e) = self.eval(uv) {
                                out.push((uv, e[0]));
                            }
                        }
                    }
                }
            }
            out
        })
    }

    /// The nearest point of the surface to `c` found by Gauss-Newton from `start`: its
    /// parameters and distance.
    fn project_from(&self, c: [f64; 3], start: [f64; 2]) -> Option<([f64; 2], f64)> {
        let sides = self.sides();
        let mut uv = self.clamp_domain(start);
        let mut e = self.eval(uv)?;
        let mut dist = norm3(sub3(c, e[0]));
        for _ in 0..60 {
            let r = sub3(c, e[0]);
            let Some(d) = least_squares(e[1], e[2], r) else {
                break;
            };
            // Damped: halve the step until the distance does not grow.
            let mut step = 1.0;
            let mut moved = false;
            for _ in 0..30 {
                let next = self.clamp_domain([uv[0] + step * d[0], uv[1] + step * d[1]]);
                if let Some(en) = self.eval(next) {
                    let dn = norm3(sub3(c, en[0]));
                    if dn <= dist {
                        let small = (next[0] - uv[0]).abs() <= 1e-15 * sides[0]
                            && (next[1] - uv[1]).abs() <= 1e-15 * sides[1];
                        uv = next;
                        e = en;
                        dist = dn;
                        moved = !small;
                        break;
                    }
                }
                step *= 0.5;
            }
            if !moved {
                break;
            }
        }
        Some((uv, dist))
    }

    /// The nearest point to `c`: from `start` when given and good, else from the best
    /// coarse samples.
    fn project(&self, c: [f64; 3], start: Option<[f64; 2]>, near: f64) -> Option<([f64; 2], f64)> {
        if let Some(s) = start {
            if let Some(found) = self.project_from(c, s) {
                if found.1 <= near {
                    return Some(found);
                }
            }
        }
        let mut ranked: Vec<(f64, [f64; 2])> = self
            .seeds()
            .iter()
            .map(|(uv, p)| (norm3(sub3(c, *p)), *uv))
            .collect();
        ranked.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut best: Option<([f64; 2], f64)> = None;
        for (_, uv) in ranked.iter().take(4) {
            if let Some(found) = self.project_from(c, *uv) {
                if best.is_none_or(|b| found.1 < b.1) {
                    best = Some(found);
                }
            }
        }
        if let (Some(s), Some(b)) = (start, best) {
            // Keep the continuation when it is as good: it follows the curve.
            if let Some(found) = self.project_from(c, s) {
                if found.1 <= b.1 * (1.0 + 1e-9) + 1e-300 {
                    return Some(found);
                }
            }
        }
        best
    }

    /// `uv` with coordinates near a knot moved onto it exactly: within [`SNAP`] of the
    /// domain's side, or within `reach[d]` (a move of the surface's point by a small part of
    /// the target, so that an edge lying along the domain's boundary within the target is
    /// inverted onto the boundary itself).
    fn snapped(&self, uv: [f64; 2], reach: [f64; 2]) -> [Rational; 2] {
        let sides = self.sides();
        [0, 1].map(|d| {
            let near = (SNAP * sides[d]).max(reach[d]);
            let s = &self.spans[d];
            let sf = &self.spans_f64[d];
            let mut knots = sf.iter().map(|k| k[0]).chain([sf[sf.len() - 1][1]]);
            let exact = |k: usize| {
                if k < s.len() {
                    s[k][0].clone()
                } else {
                    s[s.len() - 1][1].clone()
                }
            };
            match knots.position(|k| (uv[d] - k).abs() <= near) {
                Some(k) => exact(k),
                None => on_grid(uv[d], &s[span_of(sf, uv[d])], sf[span_of(sf, uv[d])]),
            }
        })
    }

    fn sample(
        &self,
        curve: &CurveF64,
        t: f64,
        start: Option<[f64; 2]>,
        limit: f64,
    ) -> Result<Sample, InversionError> {
        let (p, dp) = curve.at(t);
        if !p.iter().chain(&dp).all(|c| c.is_finite()) {
            return Err(InversionError::NotFinite);
        }
        let (uv, dist) = self
            .project(p, start, limit)
            .ok_or(InversionError::NotFinite)?;
        if dist > limit {
            return Err(InversionError::OffSurface {
                distance: dist,
                at: t,
                allowed: limit,
            });
        }
        // A move of 1/10 of the limit along u or v moves the point by about that much.
        let reach = self.eval(uv).map_or([0.0; 2], |e| {
            [1, 2].map(|i| 0.1 * limit / norm3(e[i]).max(f64::MIN_POSITIVE))
        });
        let exact = self.snapped(uv, reach);
        let uv = [exact[0].to_f64(), exact[1].to_f64()];
        let tangent = self
            .eval(uv)
            .and_then(|e| least_squares(e[1], e[2], dp))
            .filter(|d| d.iter().all(|c| c.is_finite()));
        Ok(Sample {
            t,
            uv,
            exact,
            tangent,
        })
    }

    /// The span pairs (piece indices) both samples lie in, exactly.
    fn common_spans(&self, a: &Sample, b: &Sample) -> Vec<(usize, usize)> {
        let in_both = |d: usize| -> Vec<usize> {
            let (sa, sb) = (
                spans_containing(&self.spans[d], &a.exact[d]),
                spans_containing(&self.spans[d], &b.exact[d]),
            );
            sa.into_iter().filter(|i| sb.contains(i)).collect()
        };
        let (u, v) = (in_both(0), in_both(1));
        u.iter()
            .flat_map(|iu| v.iter().map(move |iv| (*iu, *iv)))
            .collect()
    }

    /// The bound of the cubic piece with control points `ctrl` (global parameters, inside
    /// span pair `span`) against the curve restricted to `[ta, tb]`
    /// (`proofs/edge-inversion.md`, "The bound"); `None` if a condition fails.
    fn bound(
        &self,
        span: (usize, usize),
        ctrl: &[[Rational; 2]; 4],
        curve: &CurveF64,
        ta: f64,
        tb: f64,
    ) -> Option<f64> {
        let i = self.grid[span.0 * self.nv() + span.1]?;
        let data = self.piece(i)?;
        let unit = |d: usize, s: &[Rational; 2]| -> Vec<Interval> {
            let w = Rational::from(&s[1] - &s[0]);
            ctrl.iter()
                .map(|p| {
                    let x = Rational::from(&p[d] - &s[0]) / &w;
                    Interval::from_rational(&x, Precision::F64)
                })
                .collect()
        };
        let x = unit(0, &self.spans[0][span.0]);
        let y = unit(1, &self.spans[1][span.1]);
        let on: Vec<Bernstein<Interval>> = data
            .homogeneous
            .iter()
            .map(|h| compose_curve(h, &x, &y))
            .collect::<Option<_>>()?;
        let (a, b) = (Interval::point(ta), Interval::point(tb));
        let edge: Vec<Bernstein<Interval>> =
            curve.hom.iter().map(|h| h.restrict(0, &a, &b)).collect();
        let min_lo = |p: &Bernstein<Interval>| {
            p.coeffs()
                .iter()
                .map(|c| c.lo())
                .fold(f64::INFINITY, f64::min)
        };
        let (hw, g) = (min_lo(&on[3]), min_lo(&edge[3]));
        if !(hw > 0.0 && g > 0.0) {
            return None;
        }
        let denominator = Interval::point(hw).mul(&Interval::point(g)).lo();
        if denominator.partial_cmp(&0.0) != Some(Ordering::Greater) {
            return None;
        }
        let mut bound: f64 = 0.0;
        for k in 0..3 {
            let n = on[k]
                .try_mul(&edge[3])
                .ok()?
                .try_sub(&edge[k].try_mul(&on[3]).ok()?)
                .ok()?;
            let most = n
                .coeffs()
                .iter()
                .map(|c| c.lo().abs().max(c.hi().abs()))
                .fold(0.0, f64::max);
            let q = Interval::point(most).checked_div(&Interval::point(denominator))?;
            bound = bound.max(margin::up(q.hi(), margin::FEW));
        }
        bound.is_finite().then_some(bound)
    }

    /// The cubic Hermite piece from `a` to `b`, its control points clamped into `span`.
    fn hermite(&self, a: &Sample, b: &Sample, span: (usize, usize)) -> [[Rational; 2]; 4] {
        let h = b.t - a.t;
        let secant = [(b.uv[0] - a.uv[0]) / h, (b.uv[1] - a.uv[1]) / h];
        let (ta, tb) = (a.tangent.unwrap_or(secant), b.tangent.unwrap_or(secant));
        let s = [&self.spans[0][span.0], &self.spans[1][span.1]];
        let sf = [self.spans_f64[0][span.0], self.spans_f64[1][span.1]];
        let inner = |p: [f64; 2]| -> [Rational; 2] { [0, 1].map(|d| on_grid(p[d], s[d], sf[d])) };
        let mut p1 = inner([a.uv[0] + h / 3.0 * ta[0], a.uv[1] + h / 3.0 * ta[1]]);
        let mut p2 = inner([b.uv[0] - h / 3.0 * tb[0], b.uv[1] - h / 3.0 * tb[1]]);
        // Both ends on one knot line (snapped): the whole piece runs along it.
        for d in 0..2 {
            if a.exact[d] == b.exact[d] && s[d].contains(&a.exact[d]) {
                p1[d] = a.exact[d].clone();
                p2[d] = a.exact[d].clone();
            }
        }
        [
            [
                clamp(a.exact[0].clone(), s[0]),
                clamp(a.exact[1].clone(), s[1]),
            ],
            p1,
            p2,
            [
                clamp(b.exact[0].clone(), s[0]),
                clamp(b.exact[1].clone(), s[1]),
            ],
        ]
    }

    /// The sample where the inverse crosses the knot between `a` and `b` that separates
    /// them, found by bisection on the curve's parameter, its coordinate on the knot exactly.
    fn crossing(
        &self,
        curve: &CurveF64,
        a: &Sample,
        b: &Sample,
        limit: f64,
    ) -> Result<Option<Sample>, InversionError> {
        for d in 0..2 {
            let (sa, sb) = (
                spans_containing(&self.spans[d], &a.exact[d]),
                spans_containing(&self.spans[d], &b.exact[d]),
            );
            if sa.iter().any(|i| sb.contains(i)) {
                continue;
            }
            // Samples are snapped or clamped into the domain, so each lies in a span.
            let (Some(&ia), Some(&ib), Some(&last)) = (sa.first(), sb.first(), sa.last()) else {
                return Ok(None);
            };
            // The knot between them next to a.
            let knot = if ib > ia {
                self.spans[d][last][1].clone()
            } else {
                self.spans[d][ia][0].clone()
            };
            let k = knot.to_f64();
            let side = |x: f64| (x - k).total_cmp(&0.0);
            let sa_side = side(a.uv[d]);
            let (mut lo, mut hi) = (a.t, b.t);
            let mut start = a.uv;
            let mut found: Option<Sample> = None;
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break;
                }
                let s = self.sample(curve, mid, Some(start), limit)?;
                let on = (s.uv[d] - k).abs() <= SNAP * self.sides()[d];
                if on || side(s.uv[d]) == Ordering::Equal {
                    found = Some(s);
                    break;
                }
                if side(s.uv[d]) == sa_side {
                    lo = mid;
                    start = s.uv;
                } else {
                    hi = mid;
                }
                found = Some(s);
            }
            let Some(mut s) = found else {
                return Ok(None);
            };
            s.exact[d] = knot;
            s.uv[d] = k;
            if s.t <= a.t || s.t >= b.t {
                return Ok(None);
            }
            return Ok(Some(s));
        }
        Ok(None)
    }

    /// Inverts `curve` (its exact Bézier pieces in order, each on `[0, 1]`) onto the surface
    /// within `target` (max norm, model space).
    ///
    /// # Errors
    /// [`InversionError`] when the curve leaves the surface by more than the target allows,
    /// crosses a closed surface's seam, or the bound does not reach the target.
    pub fn invert(&self, curve: &[ModelCurve], target: f64) -> Result<Inversion, InversionError> {
        let mut out = Inversion {
            pieces: Vec::new(),
            parameters: Vec::new(),
            distance: 0.0,
        };
        let mut previous: Option<(Sample, &ModelCurve)> = None;
        // Samples farther than this (Euclidean) from the surface cannot be inverted within
        // the target in the max norm.
        let limit = target * 3f64.sqrt();
        for (index, c) in curve.iter().enumerate() {
            let f = CurveF64::new(c);
            let mut samples: Vec<Sample> = Vec::with_capacity(FIRST_SAMPLES + 1);
            for k in 0..=FIRST_SAMPLES {
                let t = k as f64 / FIRST_SAMPLES as f64;
                let start = samples
                    .last()
                    .map(|s| s.uv)
                    .or(previous.as_ref().map(|p| p.0.uv));
                let s = match (&previous, k) {
                    // The previous piece's end is this one's start, when they are one point.
                    (Some((p, before)), 0) if before.end() == c.start() => Sample {
                        t: 0.0,
                        ..p.clone()
                    },
                    _ => self.sample(&f, t, start, limit)?,
                };
                if let Some(last) = samples.last() {
                    self.check_seam(last, &s)?;
                }
                samples.push(s);
            }
            // Tangents of the previous piece's end are in its parameter: recompute.
            if let Some(first) = samples.first_mut() {
                if let Some(e) = self.eval(first.uv) {
                    first.tangent = least_squares(e[1], e[2], f.at(0.0).1);
                }
            }
            for w in samples.windows(2) {
                let job = Job {
                    curve: &f,
                    index,
                    target,
                    limit,
                };
                self.build(&job, &w[0], &w[1], 0, &mut out)?;
            }
            previous = samples.pop().map(|s| (s, c));
        }
        Ok(out)
    }

    fn check_seam(&self, a: &Sample, b: &Sample) -> Result<(), InversionError> {
        let jumps = self
            .sides()
            .iter()
            .enumerate()
            .any(|(d, side)| self.closed[d] && (a.uv[d] - b.uv[d]).abs() > 0.5 * side);
        if jumps {
            return Err(InversionError::Seam);
        }
        Ok(())
    }

    /// The pieces from `a` to `b`, split at knots and halved until each bound reaches the
    /// target.
    fn build(
        &self,
        job: &Job,
        a: &Sample,
        b: &Sample,
        depth: usize,
        out: &mut Inversion,
    ) -> Result<(), InversionError> {
        let (curve, target, limit) = (job.curve, job.target, job.limit);
        let spans = self.common_spans(a, b);
        let split = |s: &Sample, out: &mut Inversion| {
            self.build(job, a, s, depth + 1, out)?;
            self.build(job, s, b, depth + 1, out)
        };
        if spans.is_empty() {
            if depth < MAX_DEPTH {
                if let Some(s) = self.crossing(curve, a, b, limit)? {
                    return split(&s, out);
                }
                let mid = 0.5 * (a.t + b.t);
                let s = self.sample(curve, mid, Some(a.uv), limit)?;
                self.check_seam(a, &s)?;
                return split(&s, out);
            }
            return Err(InversionError::NotProven {
                bound: f64::INFINITY,
                target,
            });
        }
        // Several span pairs when both ends lie on a knot line: the one the middle is in.
        let span = if spans.len() == 1 {
            spans[0]
        } else {
            let (p, _) = curve.at(0.5 * (a.t + b.t));
            let mid = self
                .project(
                    p,
                    Some([0.5 * (a.uv[0] + b.uv[0]), 0.5 * (a.uv[1] + b.uv[1])]),
                    limit,
                )
                .map(|(uv, _)| uv)
                .unwrap_or(a.uv);
            let iu = span_of(&self.spans_f64[0], mid[0]);
            let iv = span_of(&self.spans_f64[1], mid[1]);
            spans
                .iter()
                .copied()
                .find(|s| *s == (iu, iv))
                .unwrap_or(spans[0])
        };
        let ctrl = self.hermite(a, b, span);
        let bound = self.bound(span, &ctrl, curve, a.t, b.t);
        match bound {
            Some(e) if e <= target => {
                out.distance = out.distance.max(e);
                out.parameters.push((job.index, [a.t, b.t]));
                let hom = ctrl
                    .into_iter()
                    .map(|[u, v]| [u, v, Rational::from(1)])
                    .collect();
                out.pieces
                    .push(ParameterCurve::from_homogeneous(hom).expect("unit weights"));
                Ok(())
            }
            _ if depth < MAX_DEPTH && out.pieces.len() < MAX_PIECES => {
                let mid = 0.5 * (a.t + b.t);
                let s = self.sample(curve, mid, Some(a.uv), limit)?;
                self.check_seam(a, &s)?;
                split(&s, out)
            }
            e => Err(InversionError::NotProven {
                bound: e.unwrap_or(f64::INFINITY),
                target,
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bernstein::compose_homogeneous;
    use crate::surface::NurbsSurface;

    fn q(n: i64, d: i64) -> Rational {
        Rational::from((n, d))
    }

    fn p3(x: Rational, y: Rational, z: Rational) -> [Rational; 3] {
        [x, y, z]
    }

    /// A quarter cylinder of radius 1 about z: u along the circle `((1−u²)/(1+u²), 2u/(1+u²))`
    /// on `[0, 2]` in two spans (knot 1 doubled), v along z on `[0, 1]`.
    fn cylinder() -> NurbsSurface {
        // The circle's quarter on [0, 1] and, reflected, a second quarter on [1, 2].
        let circle = [
            (q(1, 1), q(0, 1), q(1, 1)),
            (q(1, 1), q(1, 1), q(1, 1)),
            (q(0, 1), q(1, 1), q(2, 1)),
            (q(-1, 1), q(1, 1), q(1, 1)),
            (q(-1, 1), q(0, 1), q(1, 1)),
        ];
        let mut points = Vec::new();
        let mut weights = Vec::new();
        for (x, y, w) in &circle {
            for z in [q(0, 1), q(1, 1)] {
                points.push(p3(x.clone(), y.clone(), z));
                weights.push(w.clone());
            }
        }
        let knots = |v: &[i64]| v.iter().map(|&k| Rational::from(k)).collect::<Vec<_>>();
        NurbsSurface::new(
            [2, 1],
            knots(&[0, 0, 0, 1, 1, 2, 2, 2]),
            knots(&[0, 0, 1, 1]),
            [5, 2],
            points,
            weights,
        )
        .unwrap()
    }

    fn inverter(s: &NurbsSurface) -> Inverter {
        Inverter::new(s.spans(), &s.to_bezier(), [false, false]).unwrap()
    }

    /// The curve `S(p(t))` for a polynomial parameter curve `p` given by its Bézier
    /// coefficients in u and v, exact.
    fn image(s: &NurbsSurface, piece: usize, u: &[Rational], v: &[Rational]) -> ModelCurve {
        let patch = &s.to_bezier()[piece].1;
        let d = u.len() - 1;
        let b = |c: &[Rational]| Bernstein::new(&[d], c.to_vec()).unwrap();
        let one = b(&vec![Rational::from(1); d + 1]);
        let h = patch.homogeneous();
        let coords: Vec<Bernstein<Rational>> = h
            .iter()
            .map(|p| compose_homogeneous(p, [&b(u), &b(v), &one]))
            .collect();
        let n = coords[0].coeffs().len();
        let hom = (0..n)
            .map(|i| std::array::from_fn(|k| coords[k].coeffs()[i].clone()))
            .collect();
        ModelCurve::from_homogeneous(hom).unwrap()
    }

    /// Checks the claim exactly at sample points of every piece: the surface over the piece's
    /// point is within the proven distance of the curve's point.
    fn check_exactly(s: &NurbsSurface, curve: &[ModelCurve], inv: &Inversion) {
        for (piece, (index, [t0, t1])) in inv.pieces.iter().zip(&inv.parameters) {
            for k in 0..=8 {
                let sp = q(k, 8);
                let uv = piece.eval(&sp);
                let t =
                    Rational::from_f64(*t0).unwrap() + Rational::from_f64(t1 - t0).unwrap() * &sp;
                let on = s.eval(&uv[0], &uv[1]);
                let c = curve[*index].eval(&t);
                for a in 0..3 {
                    let d = Rational::from(&on[a] - &c[a]).abs().to_f64();
                    assert!(d <= inv.distance, "{d} > {} at piece {index}", inv.distance);
                }
            }
        }
    }

    #[test]
    fn a_curve_on_a_cylinder_is_inverted_within_the_proven_bound() {
        let s = cylinder();
        // p(t) = (t, t²/2 + 1/4) in the first span (u in [0, 1]): exactly on the surface.
        let u = [q(0, 1), q(1, 2), q(1, 1)];
        let v = [q(1, 4), q(1, 4), q(3, 4)];
        let curve = vec![image(&s, 0, &u, &v)];
        let inv = inverter(&s).invert(&curve, 1e-9).unwrap();
        assert!(inv.distance <= 1e-9);
        assert!(!inv.pieces.is_empty());
        check_exactly(&s, &curve, &inv);
        // The pcurve is near the known one: (t, t²/2 + 1/4).
        for (piece, (_, [t0, t1])) in inv.pieces.iter().zip(&inv.parameters) {
            let mid = piece.eval(&q(1, 2));
            let t = 0.5 * (t0 + t1);
            assert!((mid[0].to_f64() - t).abs() < 1e-7, "{mid:?} {t}");
            assert!((mid[1].to_f64() - (t * t / 2.0 + 0.25)).abs() < 1e-7);
        }
        // Consecutive pieces meet exactly.
        for w in inv.pieces.windows(2) {
            assert_eq!(w[0].end(), w[1].start());
        }
    }

    #[test]
    fn a_curve_across_a_knot_is_split_on_the_knot() {
        let s = cylinder();
        // The circle at height 1/3 from u = 1/2 to u = 3/2: half in each span. It is the
        // image of a straight pcurve in each span; as one model curve, the quarter circle
        // from (0.6, 0.8) over (−0.6, 0.8), written as the images of the two halves.
        let third = [q(1, 3), q(1, 3)];
        let first = image(&s, 0, &[q(1, 2), q(1, 1)], &third);
        let second = image(&s, 1, &[q(0, 1), q(1, 2)], &third);
        let curve = vec![first, second];
        let inv = inverter(&s).invert(&curve, 1e-9).unwrap();
        check_exactly(&s, &curve, &inv);
        let on_knot = inv.pieces.iter().filter(|p| p.end()[0] == 1).count();
        assert!(on_knot >= 1, "a piece ends exactly on the knot u = 1");
        for p in &inv.pieces {
            // Every piece stays at height 1/3 (to the construction's f64 accuracy).
            for c in p.points() {
                assert!((c[1].to_f64() - 1.0 / 3.0).abs() < 1e-9);
            }
        }
    }

    #[test]
    fn a_curve_along_the_boundary_stays_on_it() {
        let s = cylinder();
        // The bottom circle, v = 0: every control point of every piece has v = 0 exactly.
        let curve = vec![image(&s, 0, &[q(0, 1), q(1, 1)], &[q(0, 1), q(0, 1)])];
        let inv = inverter(&s).invert(&curve, 1e-9).unwrap();
        check_exactly(&s, &curve, &inv);
        for p in &inv.pieces {
            for c in p.points() {
                assert_eq!(c[1], Rational::new());
            }
        }
    }

    #[test]
    fn a_curve_off_the_surface_is_refused() {
        let s = cylinder();
        // The circle of radius 1 + 1e-6 at height 1/2: 1e-6 off the surface.
        let r = q(1_000_001, 1_000_000);
        let pts = [
            (r.clone(), q(0, 1), 1),
            (r.clone(), r.clone(), 1),
            (q(0, 1), r, 2),
        ];
        let hom = pts
            .iter()
            .map(|(x, y, w)| {
                let w = Rational::from(*w);
                [
                    Rational::from(x * &w),
                    Rational::from(y * &w),
                    Rational::from(&w / 2),
                    w,
                ]
            })
            .collect();
        let curve = vec![ModelCurve::from_homogeneous(hom).unwrap()];
        let e = inverter(&s).invert(&curve, 1e-7).unwrap_err();
        assert!(matches!(e, InversionError::OffSurface { .. }), "{e}");
        // Within a target above the offset, it is inverted.
        let inv = inverter(&s).invert(&curve, 2e-6).unwrap();
        assert!(
            inv.distance >= 9e-7 && inv.distance <= 2e-6,
            "{}",
            inv.distance
        );
    }
}
