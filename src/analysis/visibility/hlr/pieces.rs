//! The last stages of the drawing: each segment cut at its events into pieces, each piece's
//! QI from a certified ray test at a sample point (`proofs/ray-count.md`), and the piece drawn
//! (within the tolerance, with a bound, `proofs/hidden-lines.md`).

use crate::analysis::visibility::hlr::drawing::*;
use crate::analysis::visibility::hlr::lines::*;

use crate::analysis::chords::plane_curve::PatchAccuracy;
use crate::analysis::contour::curves::Silhouette;
use crate::analysis::projection::side_point;
use crate::analysis::visibility::hlr::crossings::Event;
use crate::analysis::visibility::hlr::intersection_lines::meet_sample;
use crate::analysis::visibility::hlr::result::HlrStats;
use crate::analysis::visibility::hlr::result::{Behind, HlrPiece, LineKind};
use crate::analysis::visibility::hlr::roles::Roles;
use crate::analysis::visibility::hlr::trim_lines::point_at;
use crate::analysis::visibility::hlr::HlrOptions;
use crate::analysis::visibility::ray::{fix_axis, layers, Sample};
use crate::analysis::visibility::scene::Scene;
use crate::geometry::Rect;
use crate::model::Model;
use crate::number::Rational;
use crate::reason::Reason;
use crate::solver::point_in_face::Membership;
use crate::solver::precision::{Escalations, Policy};
use crate::solver::univariate::{isolate_roots_in, refine_root, Root};
use crate::surface::{DrawPatch, RationalPatch};
use rayon::prelude::*;

/// The dyadic with the smallest denominator in the open interval `(lo, hi)` (lo < hi).
pub(crate) fn dyadic_between(lo: f64, hi: f64) -> Option<Rational> {
    for k in 1..=50u32 {
        let scale = (1u64 << k) as f64;
        let n = (lo * scale).floor() + 1.0;
        if n / scale < hi {
            let q = Rational::from((n as i64, 1i64 << k));
            if q > 0 && q < 1 {
                return Some(q);
            }
        }
    }
    None
}
/// Stage 4: every segment cut at its events into pieces, each with its QI and drawn.
#[allow(clippy::too_many_arguments)]
pub(super) fn all_pieces(
    model: &Model,
    scene: &Scene,
    sil: &Silhouette,
    segments: &[Segment],
    events: &[Vec<Event>],
    roles: &Roles,
    opts: &HlrOptions,
    stats: &mut HlrStats,
) -> Vec<HlrPiece> {
    let draws: Vec<DrawPatch> = model
        .patches
        .iter()
        .map(|p| DrawPatch::new(&p.surface))
        .collect();
    // The accuracy bounds of each patch with a line, for drawing to a tolerance.
    let accuracy: Vec<Option<PatchAccuracy>> = (0..model.patches.len())
        .into_par_iter()
        .map(|i| {
            let used = segments.iter().any(|s| s.patch == i);
            let surface = &model.patches[i].surface;
            opts.tol.filter(|_| used).map(|_| match sil.solved.get(i) {
                Some(solved) => PatchAccuracy::new(surface, &solved.g),
                None => PatchAccuracy::lines_only(surface),
            })
        })
        .collect();
    let per_segment: Vec<(Vec<HlrPiece>, SampleTally)> = segments
        .par_iter()
        .zip(events.par_iter())
        .zip(roles.inner.par_iter().zip(roles.folds.par_iter()))
        .map(|((s, ev), (inner, folds))| {
            let acc = accuracy[s.patch].as_ref();
            let surface = &model.patches[s.patch].surface;
            pieces_of(
                scene,
                s,
                surface,
                ev,
                &draws[s.patch],
                acc,
                [inner, folds],
                opts,
            )
        })
        .collect();
    let mut per_segment = per_segment;
    stats.qi_across_splits = qi_across_split_points(segments, events, &mut per_segment, opts);
    let mut pieces = Vec::new();
    for (p, tally) in per_segment {
        pieces.extend(p);
        stats.samples += tally.samples;
        stats.refused_samples += tally.refused;
        stats.outside_faces += tally.outside;
        stats.escalations.merge(&tally.escalations);
    }
    pieces
}

/// Claim 3's split points (`proofs/hidden-lines.md`): a point where a line was cut into
/// segments to make their images monotone (a [`Key::Param`] vertex) is no event, so where no
/// root of a system holds it, the piece that ends there and the piece that starts there on
/// the other segment have one QI. A piece whose ray tests were all refused (a sliver beside a
/// cusp) and which holds no event takes the QI of the one across. Returns how many did.
fn qi_across_split_points(
    segments: &[Segment],
    events: &[Vec<Event>],
    pieces: &mut [(Vec<HlrPiece>, SampleTally)],
    opts: &HlrOptions,
) -> usize {
    // Each split point: (segment it ends, segment it starts, its parameter).
    let mut ends: std::collections::HashMap<usize, (Option<usize>, Option<usize>, f64)> =
        std::collections::HashMap::new();
    for (k, sg) in segments.iter().enumerate() {
        for v in &sg.vertices {
            let Key::Param { id } = v.key else { continue };
            let e = ends.entry(id).or_insert((None, None, v.param[0]));
            if v.param[0] >= sg.range[1] {
                e.0 = Some(k);
            } else if v.param[1] <= sg.range[0] {
                e.1 = Some(k);
            }
        }
    }
    // No root of a system (any event but the vertices' own cuts) holds x on segment k.
    let free_at = |k: usize, x: f64| {
        events[k]
            .iter()
            .all(|e| e.vertex || !(e.at[0] <= x && x <= e.at[1]))
    };
    // No event (a vertex's cut included) meets the inside of [p0, p1] on segment k.
    let free_inside =
        |k: usize, [p0, p1]: [f64; 2]| events[k].iter().all(|e| e.at[1] <= p0 || e.at[0] >= p1);
    let mut done = 0;
    loop {
        let mut changed = false;
        for &(first, second, c) in ends.values() {
            let (Some(a), Some(b)) = (first, second) else {
                continue;
            };
            if !free_at(a, c) || !free_at(b, c) {
                continue;
            }
            let (Some(ia), Some(ib)) = (
                pieces[a].0.iter().position(|p| p.param[1] >= c),
                pieces[b].0.iter().position(|p| p.param[0] <= c),
            ) else {
                continue;
            };
            let (pa, pb) = (&pieces[a].0[ia], &pieces[b].0[ib]);
            if pa.param[1] != c || pb.param[0] != c {
                continue;
            }
            let (to, qi) = match (pa.qi, pb.qi) {
                (None, Some(q)) if free_inside(a, pa.param) => ((a, ia), q),
                (Some(q), None) if free_inside(b, pb.param) => ((b, ib), q),
                _ => continue,
            };
            let piece = &mut pieces[to.0].0[to.1];
            piece.qi = Some(qi);
            piece.reason = drawing_shortfall(opts, piece.error_bound);
            piece.certified = piece.reason.is_none();
            done += 1;
            changed = true;
        }
        if !changed {
            return done;
        }
    }
}

/// Why a piece whose QI is proven is still not certified: a tolerance was asked and its
/// drawing is not bounded within it (the time limit, if it had run out).
fn drawing_shortfall(opts: &HlrOptions, error_bound: Option<f64>) -> Option<Reason> {
    match (opts.tol, error_bound) {
        (Some(_), None) if opts.curve.past_deadline() => Some(Reason::TimeLimit),
        (Some(tol), None) => Some(Reason::DrawingTolerance { tol }),
        _ => None,
    }
}

/// A stretch of a segment between its events, before it is drawn.
pub(crate) struct Stretch {
    pub(crate) param: [f64; 2],
    pub(crate) from: PieceEnd,
    pub(crate) to: PieceEnd,
    pub(crate) qi: Result<usize, Reason>,
    pub(crate) behind: Option<Behind>,
}
/// The pieces of a segment between its events, with their QI, drawn (to `opts.tol` with
/// `acc`, the bounds of the segment's patch).
#[allow(clippy::too_many_arguments)]
pub(crate) fn pieces_of(
    scene: &Scene,
    s: &Segment,
    surface: &RationalPatch,
    events: &[Event],
    draw: &DrawPatch,
    acc: Option<&PatchAccuracy>,
    [inner, folds]: [&[[f64; 2]]; 2],
    opts: &HlrOptions,
) -> (Vec<HlrPiece>, SampleTally) {
    // Whether a stretch is proven outline (a silhouette, a free side, a fold edge), proven
    // not (inside a cluster), or neither.
    let within = |rs: &[[f64; 2]], p0: f64, p1: f64| rs.iter().any(|r| r[0] <= p0 && p1 <= r[1]);
    let outline = |p0: f64, p1: f64| -> Option<bool> {
        if s.kind == LineKind::Silhouette || s.on.len() == 1 {
            Some(true)
        } else if within(inner, p0, p1) {
            Some(false)
        } else if s.on.len() == 2 && within(folds, p0, p1) {
            Some(true)
        } else {
            None
        }
    };
    let mut ev: Vec<&Event> = events
        .iter()
        .filter(|e| e.at[1] > s.range[0] && e.at[0] < s.range[1])
        .collect();
    ev.sort_by(|a, b| a.at[0].total_cmp(&b.at[0]));
    let clip = |x: f64| x.clamp(s.range[0], s.range[1]);
    // Where the true end of a stretch that stops at `x` lies: the union of the cut
    // enclosures that hold x (a stretch bounded by an unresolved event ends exactly there).
    let around = |x: f64| -> PieceEnd {
        let mut at = [x, x];
        for e in ev.iter().filter(|e| e.unresolved.is_none()) {
            let (a, b) = (clip(e.at[0]), clip(e.at[1]));
            if a <= x && x <= b {
                at = [at[0].min(a), at[1].max(b)];
            }
        }
        PieceEnd {
            at,
            segment_end: at[0] <= s.range[0] || at[1] >= s.range[1],
        }
    };
    let exact = |x: f64| PieceEnd {
        at: [x, x],
        segment_end: x <= s.range[0] || x >= s.range[1],
    };
    let mut stretches: Vec<Stretch> = Vec::new();
    let mut tally = SampleTally::default();
    let mut push = |st: Stretch| {
        // Consecutive unresolved stretches are reported as one piece (the first reason).
        if let (Err(_), Some(last)) = (&st.qi, stretches.last_mut()) {
            if last.qi.is_err() && last.param[1] >= st.param[0] {
                last.param[1] = st.param[1];
                last.to = st.to;
                return;
            }
        }
        stretches.push(st);
    };
    let mut cursor = s.range[0];
    let mut from = around(cursor);
    let mut i = 0;
    while cursor < s.range[1] {
        // The next event at or after the cursor.
        let next = ev
            .get(i)
            .map_or(s.range[1], |e| e.at[0].max(cursor))
            .min(s.range[1]);
        if next > cursor {
            let want_behind = opts.behind && outline(cursor, next) == Some(true);
            let found = qi_of(scene, s, [cursor, next], want_behind, opts, &mut tally);
            let outside = matches!(found, Ok(None));
            let (qi, behind) = match found {
                Ok(Some((n, b))) => (Ok(n), b),
                Ok(None) => {
                    tally.outside += 1;
                    (Err(Reason::Unknown), None)
                }
                Err(e) => (Err(e), None),
            };
            let to = match ev.get(i) {
                Some(e) if e.unresolved.is_some() => exact(next),
                _ => around(next),
            };
            if !outside {
                push(Stretch {
                    param: [cursor, next],
                    from,
                    to,
                    qi,
                    behind,
                });
            }
        }
        let Some(e) = ev.get(i) else { break };
        let end = e.at[1].min(s.range[1]).max(cursor);
        if let Some(why) = &e.unresolved {
            // An unresolved stretch proven outside the faces is not drawn.
            if end > next && !stretch_outside(scene, s, [next, end]) {
                push(Stretch {
                    param: [next, end],
                    from: exact(next),
                    to: exact(end),
                    qi: Err(why.clone()),
                    behind: None,
                });
            }
        }
        if end > cursor {
            from = if e.unresolved.is_some() {
                exact(end)
            } else {
                around(end)
            };
        }
        cursor = cursor.max(end);
        i += 1;
    }
    let pieces = stretches
        .into_iter()
        .map(|st| {
            let out = outline(st.param[0], st.param[1]);
            draw_piece(s, surface, draw, acc, opts, out, st)
        })
        .collect();
    (pieces, tally)
}
/// Whether every point of a segment over `[p0, p1]` of its parameter is proven outside its
/// patch's trimmed faces (never for a trimming curve).
fn stretch_outside(scene: &Scene, s: &Segment, [p0, p1]: [f64; 2]) -> bool {
    if s.drawn_elsewhere([p0, p1]) {
        return true;
    }
    if s.curve.is_some() || !scene.trimmed(s.patch) {
        return false;
    }
    let mut r = match (s.line, s.edge) {
        (Some((axis, at)), _) => {
            let mut r = Rect::from_axes([0.0, 0.0], [0.0, 0.0]);
            let c = at.to_f64();
            r.set_axis(axis, [c, c]);
            r
        }
        (None, Some(edge)) if s.constraint.is_none() => {
            let (a, b) = (side_point(edge, &rat(p0)), side_point(edge, &rat(p1)));
            let f = |x: &[Rational; 2]| [x[0].to_f64(), x[1].to_f64()];
            return scene.membership(s.patch, &Rect::point(f(&a)).hull(&Rect::point(f(&b))))
                == Membership::Outside;
        }
        _ => Rect::from_axes(
            [s.domain[0].0.to_f64(), s.domain[0].1.to_f64()],
            [
                s.domain.get(1).map_or(0.0, |d| d.0.to_f64()),
                s.domain.get(1).map_or(0.0, |d| d.1.to_f64()),
            ],
        ),
    };
    let free = match s.line {
        Some((axis, _)) => 1 - axis,
        None => s.axis,
    };
    r.set_axis(free, [p0, p1]);
    scene.membership(s.patch, &r) == Membership::Outside
}

/// A stretch drawn: traced to the tolerance if one is asked (a piece whose drawing is not
/// certified within it is not certified), else at evenly spaced parameters.
pub(crate) fn draw_piece(
    s: &Segment,
    surface: &RationalPatch,
    draw: &DrawPatch,
    acc: Option<&PatchAccuracy>,
    opts: &HlrOptions,
    outline: Option<bool>,
    st: Stretch,
) -> HlrPiece {
    let [p0, p1] = st.param;
    let traced = match (opts.tol, acc) {
        // An intersection curve is drawn without a bound (not traced to a tolerance yet).
        _ if s.meet.is_some() => None,
        (Some(tol), _) if s.curve.is_some() && !opts.curve.past_deadline() => {
            traced_curve(s, surface, st.from, st.to, tol)
        }
        (Some(tol), Some(acc)) if !opts.curve.past_deadline() => {
            traced_points(s, draw, acc, st.from, st.to, tol)
        }
        _ => None,
    };
    let (error_bound, (points_uv, points)) = match traced {
        Some((drawn, bound)) => (Some(bound), drawn),
        None => (None, draw_points(s, draw, p0, p1, opts.draw_steps)),
    };
    let (qi, mut reason) = match st.qi {
        Ok(n) => (Some(n), None),
        Err(e) => (None, Some(e)),
    };
    if reason.is_none() {
        reason = drawing_shortfall(opts, error_bound);
    }
    HlrPiece {
        kind: s.kind,
        patch: s.patch,
        edge: s.edge,
        meets: s.meet.as_ref().map(|m| m.other),
        param: [p0, p1],
        certified: reason.is_none(),
        qi,
        reason,
        error_bound,
        points,
        points_uv,
        outline,
        behind: st.behind,
    }
}
/// What the ray tests of a segment's pieces counted.
#[derive(Debug, Default)]
pub(crate) struct SampleTally {
    /// Sample points tried.
    pub(crate) samples: usize,
    /// Samples whose ray test was refused.
    pub(crate) refused: usize,
    /// The sign questions that placed the samples.
    pub(crate) escalations: Escalations,
    /// Stretches left out as outside their patch's trimmed faces.
    pub(crate) outside: usize,
}
/// The QI of a segment's stretch `[p0, p1]`, from the first proven sample, and with `behind`,
/// if it is 0, what lies right behind that sample; `Ok(None)` if the stretch lies outside its
/// patch's trimmed faces (proven).
pub(crate) fn qi_of(
    scene: &Scene,
    s: &Segment,
    [p0, p1]: [f64; 2],
    behind: bool,
    opts: &HlrOptions,
    tally: &mut SampleTally,
) -> Result<Option<(usize, Option<Behind>)>, Reason> {
    if opts.curve.past_deadline() {
        return Err(Reason::TimeLimit);
    }
    // A stretch along a B-rep edge another face's line draws is not drawn here.
    if s.drawn_elsewhere([p0, p1]) {
        return Ok(None);
    }
    let w = p1 - p0;
    let mut last = Reason::NoSample;
    for (a, b) in [(0.25, 0.75), (0.1, 0.3), (0.7, 0.9)] {
        let Some(c) = dyadic_between(p0 + a * w, p0 + b * w) else {
            continue;
        };
        let Some(sample) = sample_at(
            s,
            &c,
            &mut Policy::new(&opts.curve.ladder, &mut tally.escalations),
        ) else {
            continue;
        };
        tally.samples += 1;
        // A point of a side or line along a trimming curve is a point of that curve.
        let sample = match sample {
            Sample::Exact { patch, uv } if scene.on_trim(patch, &uv) => Sample::Trim { patch, uv },
            other => other,
        };
        // Between its cuts a line of a trimmed patch meets no loop: in or out of the faces
        // as a whole, decided at the sample (a trimming curve bounds them: in).
        if s.curve.is_none() {
            let m = match &sample {
                Sample::Exact { uv, .. } | Sample::Trim { uv, .. } => {
                    scene.point_membership(s.patch, uv)
                }
                _ => scene.membership(s.patch, &sample.uv_enclosure()),
            };
            match m {
                Membership::Outside => return Ok(None),
                Membership::Undecided => {
                    tally.refused += 1;
                    last = Reason::PieceInFace;
                    continue;
                }
                Membership::Inside => {}
            }
        }
        match layers(scene, &sample, &opts.ray, behind) {
            Ok(l) => {
                let b = (behind && l.in_front == 0).then(|| Behind {
                    patch: s.patch,
                    uv: sample.uv_enclosure(),
                    first: l.first_behind().map(|h| h.cloned()),
                });
                return Ok(Some((l.in_front, b)));
            }
            Err(e) => {
                tally.refused += 1;
                last = e;
            }
        }
    }
    Err(last)
}
/// The sample point of a segment at parameter `c`.
pub(crate) fn sample_at(s: &Segment, c: &Rational, policy: &mut Policy) -> Option<Sample> {
    if s.meet.is_some() {
        return meet_sample(s, c);
    }
    if let Some(curve) = &s.curve {
        return Some(Sample::Trim {
            patch: s.patch,
            uv: point_at(curve, c)?,
        });
    }
    if let Some((axis, at)) = s.line {
        let mut uv = [at.to_rational(), at.to_rational()];
        uv[1 - axis] = c.clone();
        return Some(Sample::Exact { patch: s.patch, uv });
    }
    match (&s.constraint, s.edge) {
        (None, Some(edge)) => Some(Sample::Exact {
            patch: s.patch,
            uv: side_point(edge, c),
        }),
        (Some(g), _) => {
            let m = 1 - s.axis;
            let line = fix_axis(g, s.axis, c);
            let (lo, hi) = s.domain[m];
            let roots = isolate_roots_in(&line, lo, hi, 40, policy);
            if roots.roots.len() != 1 || !roots.unresolved.is_empty() {
                return None;
            }
            let r = refine_root(&line, roots.roots[0], 1e-12, policy);
            let Root::Between { lo, hi } = r else {
                return None;
            };
            Some(Sample::Silhouette {
                patch: s.patch,
                axis: s.axis,
                at: c.clone(),
                interval: [lo.to_rational(), hi.to_rational()],
                g: g.clone(),
            })
        }
        (None, None) => None,
    }
}
