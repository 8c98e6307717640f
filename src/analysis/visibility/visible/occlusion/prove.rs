//! Certifying a walk: boxes proven around each vertex and chord (Krawczyk with the image
//! point as an interval parameter), chained from the sample, and the distance bounds.

use super::lift::IPoly;
use super::walk::{
    apart_from_square, clamp, grown, lerp, side_axes, sides_crossed, Vertex, Walk, Window,
};
use super::{Lifting, OcclusionRun};
use crate::analysis::chords::plane_curve::partials_on;
use crate::analysis::visibility::sheets::range_on;
use crate::geometry::Rect;
use crate::number::margin;
use crate::number::{Interval, Number};
use crate::reason::Reason;
use crate::solver::system::inverse;
use crate::surface::Edge;

/// A run certified: its vertices (clamped to the square) and per chord its bound before
/// rounding (`None`: not proven).
pub(super) type ProvenRun = (Vec<[f64; 2]>, Vec<Option<f64>>);

/// Where the lift is anchored: the first point behind the piece's sample.
pub(crate) struct Anchor {
    /// The patch behind and an enclosure of the point's parameters there.
    pub patch: usize,
    pub uv: Rect,
    /// An enclosure of the sample point in space.
    pub sample: ([f64; 3], [f64; 3]),
}

/// A chord proven: its box, and the tube's space box (for the anchor).
pub(super) struct Proven {
    /// The chord's index along the walk (a window's: its index, encoded, until placed).
    pub(super) chord: usize,
    /// For a window's box: 0 on the patch before the crossing, 1 after.
    pub(super) window_side: usize,
    pub(super) patch: usize,
    pub(super) w: Rect,
    pub(super) space: ([f64; 3], [f64; 3]),
}

pub(super) fn boxes_meet(a: &([f64; 3], [f64; 3]), b: &([f64; 3], [f64; 3])) -> bool {
    (0..3).all(|k| a.0[k] <= b.1[k] && b.0[k] <= a.1[k])
}

pub(super) fn point_distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt()
}

/// The deepest bisection of a chord whose box is not proven.
pub(super) const MAX_SPLITS: u32 = 6;

impl Lifting<'_> {
    /// A box around `w` holding exactly one preimage of every image point of the tube
    /// around `x` (on patch `p`), or `None`.
    pub(super) fn vertex_box(&self, p: usize, x: [f64; 3], w: [f64; 2], e: f64) -> Option<Rect> {
        let t = self.tube(&[x], e)?;
        let y = t.hull;
        let lp = &self.patches[p];
        let half = y[0].width().max(y[1].width()) * 0.5;
        // The spread of the preimages: about |J⁻¹| times the tube's half-width.
        let m: Vec<Vec<f64>> = (0..2)
            .map(|k| {
                let yc = 0.5 * (y[k].lo() + y[k].hi());
                (0..2)
                    .map(|a| lp.df[k][a].eval(&w) - yc * lp.df[2][a].eval(&w))
                    .collect()
            })
            .collect();
        let inv = inverse(&m)?;
        let norm = inv
            .iter()
            .map(|r| r[0].abs() + r[1].abs())
            .fold(0.0, f64::max);
        let r0 = norm * half + 1e-13 * (1.0 + w[0].abs().max(w[1].abs()));
        [2.0, 4.0, 16.0, 64.0].into_iter().find_map(|k| {
            let b = Rect::new(w.map(|c| c - k * r0), w.map(|c| c + k * r0));
            lp.unique_preimages(&t, &b).then_some(b)
        })
    }

    /// A box holding the vertex boxes of both ends and exactly one preimage of every image
    /// point of the chord's tube, or `None`.
    pub(super) fn chord_box(
        &self,
        p: usize,
        xs: &[[f64; 3]],
        ends: &[Rect],
        e: f64,
    ) -> Option<Rect> {
        let t = self.tube(xs, e)?;
        let h = ends.iter().skip(1).fold(ends[0], |acc, b| acc.hull(b));
        // An axis-aligned image box maps to a parallelogram in parameters: a box that holds
        // it may have to reach well past the hull of the ends.
        [0.01, 0.1, 0.5, 1.0].into_iter().find_map(|g| {
            let b = grown(&h, g, 1e-13);
            self.patches[p].unique_preimages(&t, &b).then_some(b)
        })
    }

    /// The space box of a chord's tube.
    pub(super) fn space_tube(xs: &[[f64; 3]], e: f64) -> ([f64; 3], [f64; 3]) {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for p in xs {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k] - 2.0 * e);
                hi[k] = hi[k].max(p[k] + 2.0 * e);
            }
        }
        (lo, hi)
    }

    /// A bound on the Hausdorff distance in space between the drawn chord between the points
    /// of patch `p` at `clamp(a.w)` and `clamp(b.w)` and the true curve's points on the
    /// extended patch over the chord of the piece from `a.x` to `b.x` (before the drawn
    /// points' rounding), given a box `w` proven to hold exactly one preimage of every image
    /// point of the chord's tube and the lifts of its ends (`proofs/visible-regions.md`,
    /// claim 4, "The chord bound").
    pub(super) fn chord_bound(
        &self,
        p: usize,
        w: &Rect,
        a: Vertex,
        b: Vertex,
        e: f64,
    ) -> Option<[f64; 2]> {
        let lp = &self.patches[p];
        let (lo, hi) = (w.lo, w.hi);
        let pi = Interval::point;
        let mag = |x: Interval| x.lo().abs().max(x.hi().abs());
        let y = self.tube(&[a.x, b.x], e)?.hull;
        // The inverse of the Jacobian over the box, by its adjugate.
        let j = lp.jacobian_on(y, lo, hi);
        let det = j[0][0].mul(&j[1][1]).sub(&j[0][1].mul(&j[1][0]));
        let inv = [
            [j[1][1], pi(0.0).sub(&j[0][1])],
            [pi(0.0).sub(&j[1][0]), j[0][0]],
        ]
        .map(|r| r.map(|x| x.checked_div(&det)));
        let m: [[f64; 2]; 2] = [0, 1].map(|i| [0, 1].map(|k| inv[i][k].map_or(f64::INFINITY, mag)));
        let apply = |g: [f64; 2]| -> [f64; 2] {
            [0, 1].map(|i| {
                pi(m[i][0])
                    .mul(&pi(g[0]))
                    .add(&pi(m[i][1]).mul(&pi(g[1])))
                    .hi()
            })
        };
        // The tube's image radius per coordinate, times |q|.
        let mut slo = [0.0; 3];
        let mut shi = [0.0; 3];
        for k in 0..3 {
            slo[k] = pi(a.x[k].min(b.x[k])).sub(&pi(e)).lo();
            shi[k] = pi(a.x[k].max(b.x[k])).add(&pi(e)).hi();
        }
        let grad = self.projection().image_gradient_bound(slo, shi)?;
        let q_max = mag(range_on(&lp.jets[2][0], &lo, &hi));
        let g1 = grad.map(|gk| pi(gk).mul(&pi(e)).mul(&pi(q_max)).hi());
        // G along the drawn chord in parameters: its values at the ends (Newton's residuals)
        // plus an eighth of its second derivative.
        let ya = self.projection().image_of_box(a.x, a.x)?;
        let yb = self.projection().image_of_box(b.x, b.x)?;
        let (ra, rb) = (lp.residual(a.w, ya), lp.residual(b.w, yb));
        let dw = [0, 1].map(|k| pi(b.w[k]).sub(&pi(a.w[k])));
        let second = |f: &[IPoly; 6]| -> (Interval, Interval) {
            let [fu, fv, fuu, fuv, fvv] = partials_on(f, &lo, &hi);
            let d1 = fu.mul(&dw[0]).add(&fv.mul(&dw[1]));
            let d2 = fuu
                .mul(&dw[0])
                .mul(&dw[0])
                .add(&pi(2.0).mul(&fuv).mul(&dw[0]).mul(&dw[1]))
                .add(&fvv.mul(&dw[1]).mul(&dw[1]));
            (d1, d2)
        };
        let (q1, q2) = second(&lp.jets[2]);
        let g2: [f64; 2] = std::array::from_fn(|k| {
            let (_, x2) = second(&lp.jets[k]);
            let yk = ya[k].hull(&yb[k]);
            let dy = yb[k].sub(&ya[k]);
            let phi2 = x2.sub(&yk.mul(&q2)).sub(&pi(2.0).mul(&dy).mul(&q1));
            let ends = mag(ra[k]).max(mag(rb[k]));
            pi(ends).add(&pi(mag(phi2)).mul(&pi(0.125))).hi()
        });
        let (d1, d2) = (apply(g1), apply(g2));
        // Clamping the drawn ends into the square moves them (and the chord) at most this.
        let clamp_shift = [a.w, b.w]
            .iter()
            .map(|w| (clamp(*w)[0] - w[0]).abs().max((clamp(*w)[1] - w[1]).abs()))
            .fold(0.0, f64::max);
        let delta = [0, 1].map(|k| pi(d1[k]).add(&pi(d2[k])).add(&pi(clamp_shift)).hi());
        let ([s_u, s_uu, s_uv, s_vv], s_v) = lp.surface.bounds_both(lo, hi, 0)?;
        let first = pi(s_u).mul(&pi(delta[0])).add(&pi(s_v).mul(&pi(delta[1])));
        let (ca, cb) = (clamp(a.w), clamp(b.w));
        let (du, dv) = (
            pi(cb[0])
                .sub(&pi(ca[0]))
                .hi()
                .abs()
                .max(pi(cb[0]).sub(&pi(ca[0])).lo().abs()),
            pi(cb[1])
                .sub(&pi(ca[1]))
                .hi()
                .abs()
                .max(pi(cb[1]).sub(&pi(ca[1])).lo().abs()),
        );
        let interp = pi(s_uu)
            .mul(&pi(du * du))
            .add(&pi(2.0 * s_uv).mul(&pi(du * dv)))
            .add(&pi(s_vv).mul(&pi(dv * dv)))
            .mul(&pi(0.125));
        let bound = margin::up(first.add(&interp).hi(), margin::FEW);
        // The part that shorter chords cannot reduce: the piece's own drawing error, lifted.
        let floor = pi(s_u).mul(&pi(d1[0])).add(&pi(s_v).mul(&pi(d1[1]))).hi();
        bound.is_finite().then_some([bound, floor])
    }

    /// Whether a box of patch `p` reaches past a side that is an edge continuing into one
    /// other patch (other than `allowed`).
    pub(super) fn crosses_continuing(&self, p: usize, b: &Rect, allowed: Option<Edge>) -> bool {
        sides_crossed(b)
            .into_iter()
            .any(|s| Some(s) != allowed && self.scene.twins(p, s).len() == 1)
    }

    /// Proves one chord of a run on patch `p` (bisecting it where needed): pushes the
    /// vertices after `a` (ending with `b`), each chord's bound (`None` if not proven) and the
    /// proven chords' boxes (numbered by their place in `bounds`).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn prove_chord(
        &self,
        p: usize,
        a: (Vertex, Rect),
        b: (Vertex, Rect),
        [e, target]: [f64; 2],
        depth: u32,
        out: &mut Vec<Vertex>,
        proven: &mut Vec<Proven>,
        bounds: &mut Vec<Option<f64>>,
    ) {
        let xs = [a.0.x, b.0.x];
        let ok = self
            .chord_box(p, &xs, &[a.1, b.1], e)
            .filter(|w| !self.crosses_continuing(p, w, None))
            .and_then(|w| Some((w, self.chord_bound(p, &w, a.0, b.0, e)?)))
            .filter(|(_, [d, floor])| *d <= target || *floor > 0.5 * target || depth >= MAX_SPLITS);
        if let Some((w, [bound, _])) = ok {
            proven.push(Proven {
                chord: bounds.len(),
                window_side: 0,
                patch: p,
                w,
                space: Self::space_tube(&xs, e),
            });
            bounds.push(Some(bound));
            out.push(b.0);
            return;
        }
        let xm = lerp(a.0.x, b.0.x, 0.5);
        let m = self.lift(p, xm, a.0.w).and_then(|wm| {
            let vm = self.vertex_box(p, xm, wm, e)?;
            Some((Vertex { x: xm, w: wm }, vm))
        });
        match m {
            Some(m) if depth < MAX_SPLITS => {
                let et = [e, target];
                let marks = (out.len(), proven.len(), bounds.len());
                self.prove_chord(p, a, m, et, depth + 1, out, proven, bounds);
                self.prove_chord(p, m, b, et, depth + 1, out, proven, bounds);
                // Nothing proven: one unproven chord, not the bisection's points.
                if bounds[marks.2..].iter().all(Option::is_none) {
                    out.truncate(marks.0);
                    proven.truncate(marks.1);
                    bounds.truncate(marks.2);
                    bounds.push(None);
                    out.push(b.0);
                }
            }
            _ => {
                bounds.push(None);
                out.push(b.0);
            }
        }
    }

    /// Proves a window: boxes on both patches and the conditions of claim 4 that make the
    /// true curve pass from one to the other inside them. Returns the two boxes' space
    /// diagonals.
    pub(super) fn prove_window(
        &self,
        win: &Window,
        e: f64,
        proven: &mut Vec<Proven>,
    ) -> Option<[f64; 2]> {
        let (edge_from, edge_to, rev) = win.edges;
        let boxes = |p: usize, ws: &[[f64; 2]; 3]| -> Option<([Rect; 3], Rect)> {
            let v: Vec<Rect> = (0..3)
                .map(|i| self.vertex_box(p, win.x[i], ws[i], e))
                .collect::<Option<_>>()?;
            let v = [v[0], v[1], v[2]];
            let w = self.chord_box(p, &win.x, &v, e)?;
            Some((v, w))
        };
        let (vf, mut wf) = boxes(win.from, &win.w_from)?;
        let (vt, mut wt) = boxes(win.to, &win.w_to)?;
        // The curve is on `from` before the window and on `to` after it: the lifts of x₊ on
        // `from` and of x₋ on `to` lie outside those patches.
        if !apart_from_square(&vf[2]) || !apart_from_square(&vt[0]) {
            return None;
        }
        // Within the window it can leave either patch only across the common edge.
        if self.crosses_continuing(win.from, &wf, Some(edge_from))
            || self.crosses_continuing(win.to, &wt, Some(edge_to))
        {
            return None;
        }
        // Where either box meets the edge, the same points of the edge are in the other box.
        let edge_in = |b: &Rect, edge: Edge| -> Option<[f64; 2]> {
            let (fixed, at, free) = side_axes(edge);
            (b.lo[fixed] <= at && at <= b.hi[fixed]).then_some(b.axis(free))
        };
        let map = |t: [f64; 2]| {
            if rev {
                [1.0 - t[1], 1.0 - t[0]]
            } else {
                t
            }
        };
        let (tf, tt) = (edge_in(&wf, edge_from)?, edge_in(&wt, edge_to)?);
        // Both boxes get the same stretch of the edge: the union of theirs, rounded out to
        // multiples of 2⁻⁴⁰ so that `1 − t` is exact, and are proven again.
        let grid = (2.0f64).powi(40);
        let r = [
            (tf[0].min(map(tt)[0]) * grid).floor() / grid,
            (tf[1].max(map(tt)[1]) * grid).ceil() / grid,
        ];
        let (free_f, free_t) = (side_axes(edge_from).2, side_axes(edge_to).2);
        wf.set_axis(free_f, r);
        wt.set_axis(free_t, map(r));
        let t = self.tube(&win.x, e)?;
        let unique = |p: usize, b: &Rect| self.patches[p].unique_preimages(&t, b);
        if !unique(win.from, &wf) || !unique(win.to, &wt) {
            return None;
        }
        let (tf, tt) = (edge_in(&wf, edge_from)?, edge_in(&wt, edge_to)?);
        if map(tf) != tt {
            return None;
        }
        let vertex = |i: usize, ws: &[[f64; 2]; 3]| Vertex {
            x: win.x[i],
            w: ws[i],
        };
        // On each patch, its drawn chord to or from x*, and the true points on the patch
        // over the other half of the window: within the other half's bound of its chord on
        // the extended patch, whose points are within |DS| times its length of x*.
        let half = |p: usize, b: &Rect, ws: &[[f64; 2]; 3], near: [usize; 2], far: [usize; 2]| {
            let d_near = self.chord_bound(p, b, vertex(near[0], ws), vertex(near[1], ws), e)?[0];
            let d_far = self.chord_bound(p, b, vertex(far[0], ws), vertex(far[1], ws), e)?[0];
            let (lo, hi) = (b.lo, b.hi);
            let ([s_u, ..], s_v) = self.patches[p].surface.bounds_both(lo, hi, 0)?;
            let (fa, fb) = (ws[far[0]], ws[far[1]]);
            // (The drawn end is x*'s lift clamped into the square: a shift of at most 1e-12.)
            let reach = Interval::point(s_u)
                .mul(&Interval::point((fb[0] - fa[0]).abs() + 1e-12))
                .add(&Interval::point(s_v).mul(&Interval::point((fb[1] - fa[1]).abs() + 1e-12)))
                .hi();
            // Outward-rounded interval arithmetic: `reach` is an upper bound as it is; the
            // margin (kept so as not to change reported bounds) only widens it.
            let reach = margin::up(reach, margin::FEW);
            Some(d_near.max(Interval::point(d_far).add(&Interval::point(reach)).hi()))
        };
        let df = half(win.from, &wf, &win.w_from, [0, 1], [1, 2])?;
        let dt = half(win.to, &wt, &win.w_to, [1, 2], [0, 1])?;
        let space = Self::space_tube(&win.x, e);
        proven.push(Proven {
            chord: 0,
            window_side: 0,
            patch: win.from,
            w: wf,
            space,
        });
        proven.push(Proven {
            chord: 0,
            window_side: 1,
            patch: win.to,
            w: wt,
            space,
        });
        Some([df, dt])
    }

    /// The occlusion curve of a piece: its drawn polyline `points` (each chord within `e` of
    /// its stretch of the true piece; `None`: not bounded) lifted onto the surface behind
    /// from the anchor, as runs on patches, certified where proven.
    pub(crate) fn occlusion_curve(
        &self,
        points: &[[f64; 3]],
        e: Option<f64>,
        tol: Option<f64>,
        anchor: &Anchor,
    ) -> Result<Vec<OcclusionRun>, Reason> {
        if points.len() < 2 {
            return Err(Reason::TooFewPoints);
        }
        // The drawn vertex nearest the sample, lifted from the point behind it.
        let s = anchor.sample;
        let centre: [f64; 3] = std::array::from_fn(|k| 0.5 * (s.0[k] + s.1[k]));
        let k0 = (0..points.len())
            .min_by(|&a, &b| {
                point_distance(points[a], centre).total_cmp(&point_distance(points[b], centre))
            })
            .unwrap_or(0);
        let h = anchor.uv.center();
        let w0 = self
            .lift(anchor.patch, points[k0], h)
            .ok_or(Reason::LiftFromSample)?;
        let back: Vec<[f64; 3]> = points[..=k0].iter().rev().copied().collect();
        let e0 = e.unwrap_or(0.0);
        let walk = self
            .walk(&back, anchor.patch, w0, e0)
            .reversed()
            .joined(self.walk(&points[k0..], anchor.patch, w0, e0));
        let mut runs: Vec<OcclusionRun> = walk
            .runs
            .iter()
            .map(|r| OcclusionRun {
                patch: r.patch,
                uv: r.vertices.iter().map(|v| clamp(v.w)).collect(),
                xyz: Vec::new(),
                error_bound: None,
                reason: r.reason.clone(),
            })
            .collect();
        let first_reason = walk.runs.iter().find_map(|r| r.reason.clone());
        let proof = match (e.zip(tol), first_reason) {
            (_, Some(why)) => Err(why),
            (None, None) => Err(Reason::DrawingUnbounded),
            (Some((e, tol)), None) => self.prove(&walk, [e, 0.999 * tol], anchor),
        };
        match proof {
            Ok(proved) => {
                let tol = tol.unwrap_or(f64::INFINITY);
                let mut split = Vec::new();
                for (run, (uv, bounds)) in runs.iter().zip(proved) {
                    let Some(r) = self.draws[run.patch].rounding() else {
                        split.push(OcclusionRun {
                            uv,
                            reason: Some(Reason::RoundingUnbounded),
                            ..run.clone()
                        });
                        continue;
                    };
                    let full: Vec<Option<f64>> = bounds
                        .iter()
                        .map(|b| b.map(|b| margin::up(b + r, margin::FEW)))
                        .collect();
                    // Maximal stretches of chords within the tolerance, beyond it, unproven.
                    let class = |b: Option<f64>| match b {
                        Some(b) if b <= tol => 0,
                        Some(_) => 1,
                        None => 2,
                    };
                    let mut i = 0;
                    while i < full.len() {
                        let c = class(full[i]);
                        let mut j = i;
                        while j + 1 < full.len() && class(full[j + 1]) == c {
                            j += 1;
                        }
                        let bound = full[i..=j]
                            .iter()
                            .try_fold(0.0f64, |acc, b| Some(acc.max((*b)?)));
                        let reason = match (c, bound) {
                            (0, _) => None,
                            (1, Some(b)) => Some(Reason::BoundAboveTolerance {
                                bound: b,
                                patch: run.patch,
                            }),
                            _ => Some(Reason::OcclusionStretch { patch: run.patch }),
                        };
                        split.push(OcclusionRun {
                            patch: run.patch,
                            uv: uv[i..=j + 1].to_vec(),
                            xyz: Vec::new(),
                            error_bound: bound,
                            reason,
                        });
                        i = j + 1;
                    }
                }
                runs = split;
            }
            Err(why) => {
                for run in &mut runs {
                    run.reason.get_or_insert_with(|| why.clone());
                }
            }
        }
        for run in &mut runs {
            run.xyz = run
                .uv
                .iter()
                .map(|w| self.draws[run.patch].eval(w[0], w[1]))
                .collect();
        }
        Ok(runs)
    }

    /// Certifies a walk: per run, its refined vertices (clamped to the square) and per chord
    /// a bound on its Hausdorff distance before rounding, `None` where the chord is not proven
    /// or not joined to the anchor through proven chords.
    pub(super) fn prove(
        &self,
        walk: &Walk,
        [e, target]: [f64; 2],
        anchor: &Anchor,
    ) -> Result<Vec<ProvenRun>, Reason> {
        let mut proven: Vec<Proven> = Vec::new();
        let windows: Vec<Option<[f64; 2]>> = walk
            .windows
            .iter()
            .enumerate()
            .map(|(k, win)| {
                let mut own = Vec::new();
                let b = self.prove_window(win, e, &mut own)?;
                // The window's boxes count for the chords next to it (set below).
                proven.extend(own.into_iter().map(|mut c| {
                    c.chord = usize::MAX - k;
                    c
                }));
                Some(b)
            })
            .collect();
        let mut out = Vec::new();
        // Chord indices along the whole walk, and each window's two chords.
        let mut bounds_all: Vec<Option<f64>> = Vec::new();
        let mut window_chords: Vec<[usize; 2]> = vec![[usize::MAX; 2]; walk.windows.len()];
        for run in &walk.runs {
            let p = run.patch;
            let mut bounds: Vec<Option<f64>> = Vec::new();
            let n = run.vertices.len();
            let first = usize::from(run.start.is_some());
            let last = if run.end.is_some() {
                n.saturating_sub(2)
            } else {
                n.saturating_sub(1)
            };
            let mut refined = run.vertices[..=first.min(n - 1)].to_vec();
            // The chord inside the start window.
            if let Some(k) = run.start.filter(|_| n > 1) {
                window_chords[k][1] = bounds_all.len() + bounds.len();
                bounds.push(windows[k].map(|b| b[1]));
            }
            if first < last {
                let vbox = |v: &Vertex| self.vertex_box(p, v.x, v.w, e);
                let mut a = (run.vertices[first], vbox(&run.vertices[first]));
                for v in &run.vertices[first + 1..=last] {
                    let b = (*v, vbox(v));
                    match (a.1, b.1) {
                        (Some(va), Some(vb)) => {
                            let mut local = Vec::new();
                            self.prove_chord(
                                p,
                                (a.0, va),
                                (b.0, vb),
                                [e, target],
                                0,
                                &mut refined,
                                &mut local,
                                &mut bounds,
                            );
                            // `prove_chord` numbers its chords from 0 in `bounds`' order.
                            proven.extend(local.into_iter().map(|mut c| {
                                c.chord += bounds_all.len();
                                c
                            }));
                        }
                        _ => {
                            refined.push(b.0);
                            bounds.push(None);
                        }
                    }
                    a = b;
                }
            }
            let rest = &run.vertices[(last + 1).max(first + 1).min(n)..];
            refined.extend_from_slice(rest);
            // The chord inside the end window.
            if let Some(k) = run.end.filter(|_| !rest.is_empty()) {
                window_chords[k][0] = bounds_all.len() + bounds.len();
                bounds.push(windows[k].map(|b| b[0]));
            }
            if bounds.len() + 1 != refined.len() {
                return Err(Reason::ChordsMismatch { patch: p });
            }
            bounds_all.extend(bounds.iter().copied());
            out.push((refined.iter().map(|v| clamp(v.w)).collect(), bounds));
        }
        // The windows' boxes belong to their chords: the first box to the chord before the
        // crossing, the second to the chord after it.
        for c in &mut proven {
            if c.chord > usize::MAX / 2 {
                let (k, side) = (usize::MAX - c.chord, c.window_side);
                c.chord = window_chords[k][side];
            }
        }
        // The anchor: the point behind the sample lies in the box of every proven chord
        // whose tube can hold the sample (one of them holds its stretch of the curve).
        let holders: Vec<&Proven> = proven
            .iter()
            .filter(|c| c.chord != usize::MAX && boxes_meet(&c.space, &anchor.sample))
            .collect();
        if holders.is_empty() {
            return Err(Reason::SampleOutsideDrawing);
        }
        let anchored = holders
            .iter()
            .all(|c| c.patch == anchor.patch && c.w.contains(&anchor.uv));
        if !anchored {
            return Err(Reason::NotOnLiftedSheet);
        }
        // From the anchor's chords along proven chords both ways: the rest is not joined.
        let mut joined = vec![false; bounds_all.len()];
        for h in &holders {
            for range in [
                (h.chord..bounds_all.len()).collect::<Vec<_>>(),
                (0..=h.chord).rev().collect(),
            ] {
                for i in range {
                    if bounds_all[i].is_none() {
                        break;
                    }
                    joined[i] = true;
                }
            }
        }
        let mut i = 0;
        for (_, bounds) in &mut out {
            for b in bounds.iter_mut() {
                if !joined[i] {
                    *b = None;
                }
                i += 1;
            }
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::view::View;
    use crate::analysis::visibility::scene::Scene;
    use crate::model::{Format, Model, WeldTolerance};
    use crate::number::Rational;
    use crate::testing::shapes;

    /// The parametric Krawczyk test on a chord's tube, taken term by term (the segment plus
    /// its spread, not its bounding box): every image point of the tube that Newton's method
    /// lifts from anywhere in a proven box lands inside it, at one point; and a box that misses
    /// a lift of the tube is refused (dropping the term along the segment makes this fail).
    #[test]
    fn every_point_of_a_proven_tube_lifts_into_its_box_once() {
        let patches = shapes::sphere(&Rational::from(1));
        let model = Model::from_patches(Format::Json, patches);
        let view = View::Direction([1, 2, 3].map(Rational::from));
        let scene = Scene::new(&model, &view, WeldTolerance::Exact).unwrap();
        let lifting = Lifting::new(&model, &scene);
        let (lifts, draws) = (&lifting.patches, &lifting.draws);
        let mut seed = 12345u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64) / ((1u64 << 53) as f64)
        };
        let (mut proven, mut checked, mut refused) = (0, 0, 0);
        for _ in 0..40 {
            let p = (next() * model.patches.len() as f64) as usize % model.patches.len();
            let wa = [0.2 + 0.6 * next(), 0.2 + 0.6 * next()];
            let wb = [wa[0] + 0.05 * (next() - 0.5), wa[1] + 0.05 * (next() - 0.5)];
            let (xa, xb) = (draws[p].eval(wa[0], wa[1]), draws[p].eval(wb[0], wb[1]));
            let e = 1e-5;
            let (a, b) = (Vertex { x: xa, w: wa }, Vertex { x: xb, w: wb });
            let (Some(va), Some(vb)) = (
                lifting.vertex_box(p, xa, wa, e),
                lifting.vertex_box(p, xb, wb, e),
            ) else {
                continue;
            };
            let Some(w) = lifting.chord_box(p, &[a.x, b.x], &[va, vb], e) else {
                continue;
            };
            proven += 1;
            let t = lifting.tube(&[xa, xb], e).unwrap();
            // Soundness: a box that misses a lift of the tube (the first end's box, when the
            // second end lifts outside it) must not pass the test.
            let outside = (0..2).any(|k| wb[k] < va.lo[k] || wb[k] > va.hi[k]);
            if outside {
                let accepted = lifts[p].unique_preimages(&t, &va);
                assert!(
                    !accepted,
                    "patch {p}: {va:?} accepted for the tube to {wb:?}"
                );
                refused += 1;
            }
            let mid = |i: Interval| 0.5 * (i.lo() + i.hi());
            for _ in 0..50 {
                // A point of the tube: on the segment, moved by at most r per coordinate.
                let mu = next();
                let y = [0, 1].map(|k| {
                    mid(t.a[k]) + mu * mid(t.d[k]) + (2.0 * next() - 1.0) * t.r[k] * 0.999
                });
                let starts = [w.lo, w.hi, w.center()];
                let roots: Vec<[f64; 2]> = starts
                    .iter()
                    .filter_map(|s| lifts[p].newton(y, *s))
                    .collect();
                assert!(!roots.is_empty(), "no lift of {y:?} in {w:?}");
                for r in &roots {
                    checked += 1;
                    let slack = 1e-12;
                    assert!(
                        (0..2).all(|k| w.lo[k] - slack <= r[k] && r[k] <= w.hi[k] + slack),
                        "patch {p}: the lift {r:?} of {y:?} is outside the proven box {w:?}"
                    );
                    let d = (r[0] - roots[0][0]).abs().max((r[1] - roots[0][1]).abs());
                    assert!(
                        d < 1e-9,
                        "two lifts in one proven box: {r:?}, {:?}",
                        roots[0]
                    );
                }
            }
        }
        assert!(proven >= 20, "{proven} chords proven");
        assert!(refused >= 20, "{refused} boxes refused");
        assert!(checked >= 1000, "{checked}");
    }
}
