//! Stage 3 of the drawing: where the QI along each line can change. Every pair of segments
//! whose image boxes meet is solved as a square system for its image crossings, every side
//! that is outline for its self-crossings, every segment against every patch that shares no
//! corner with its own for penetrations ([`super::systems`]), by the certified system solver.
//! The boxes around shared vertices, and around a silhouette arc where the fold lemma holds,
//! are excluded with a proof that they hold no other crossing ([`super::lemmas`],
//! `proofs/hidden-lines.md`). Every isolated root cuts the segments whose QI it can change;
//! every unresolved box marks the stretches it covers as unresolved.

use crate::analysis::contour::curves::Silhouette;
use crate::analysis::visibility::hlr::cusps::cusp_runs;
use crate::analysis::visibility::hlr::lemmas::{
    arc_fold_exclusion, common_monotone, fold_cover, vertex_exclusion,
};
use crate::analysis::visibility::hlr::lines::{bounds_on, Segment};
use crate::analysis::visibility::hlr::result::HlrStats;
use crate::analysis::visibility::hlr::roles::Roles;
use crate::analysis::visibility::hlr::systems::{
    crossing_system, penetration_system, self_crossing_system,
};
use crate::analysis::visibility::hlr::HlrOptions;
use crate::analysis::visibility::scene::Scene;
use crate::geometry::Rect;
use crate::reason::Reason;
use crate::solver::dyadic::Dyadic;
use crate::solver::point_in_face::Membership;
use crate::solver::system::separable::solve_separable;
use crate::solver::system::{solve_system, DyadicBoxN, SystemOptions, SystemRoots};
use rayon::prelude::*;
use std::collections::BTreeSet;

/// How many times the crossing systems' box budget a pair with an intersection segment has.
const MEET_BUDGET: usize = 8;

/// The cuts and unresolved stretches of every segment, and the pairs of patches found to pass
/// through each other.
pub(super) struct Crossings {
    /// By segment: its events, in no order.
    pub(super) events: Vec<Vec<Event>>,
    /// Pairs `[p, q]` (p < q) with a proven penetration.
    pub(super) intersecting: BTreeSet<[usize; 2]>,
}

/// The crossings, self-crossings and penetrations of the segments, as events on them.
pub(super) fn crossings(
    scene: &Scene,
    sil: &Silhouette,
    segments: &[Segment],
    roles: &Roles,
    opts: &HlrOptions,
    stats: &mut HlrStats,
) -> Crossings {
    // Pairs of segments (with the boxes around shared vertices proven to hold no other
    // crossing), self-crossings of sides, and segment-patch penetrations.
    let mut events: Vec<Vec<Event>> = vec![Vec::new(); segments.len()];
    // The silhouette regions the curve solver left unresolved are not segments: their
    // crossings with the other lines are not searched, so every segment whose image can meet
    // theirs is unresolved along its whole length.
    for (p, cell, _) in &sil.unresolved {
        if opts.curve.past_deadline() {
            // Past the deadline the rest is not searched: every segment is left unresolved.
            for (k, sg) in segments.iter().enumerate() {
                events[k].push(Event::unresolved(sg.range, Reason::TimeLimit));
            }
            break;
        }
        let b = vec![(cell.lo[0], cell.hi[0]), (cell.lo[1], cell.hi[1])];
        // A region outside the patch's faces holds nothing drawn.
        if scene.membership(*p, &cell.to_f64()) == Membership::Outside {
            continue;
        }
        let bounds = bounds_on(&scene.images[*p], &b);
        for (k, sg) in segments.iter().enumerate() {
            if sg.bounds.meets_image(&bounds) {
                let why = Reason::SilhouetteUnresolved { patch: *p };
                events[k].push(Event::unresolved(sg.range, why));
            }
        }
    }
    // Lemma C around the arcs whose images are not monotone: a run of segments with an
    // injective image, cut where its image tangent vanishes (a cusp: the QI may change).
    let runs = if opts.curve.past_deadline() {
        Vec::new()
    } else {
        cusp_runs(scene, segments, &opts.crossing)
    };
    // The runs each segment lies in (two runs grown from neighbouring segments may overlap
    // and share their cusp: it is cut and counted once).
    let mut run_of: Vec<Vec<usize>> = vec![Vec::new(); segments.len()];
    let mut cusps: Vec<(usize, [f64; 2])> = Vec::new();
    for (r, run) in runs.iter().enumerate() {
        for &k in &run.members {
            run_of[k].push(r);
        }
        if let Some((c, at)) = run.cusp {
            if !cusps
                .iter()
                .any(|(d, x)| *d == c && x[0] <= at[1] && at[0] <= x[1])
            {
                events[c].push(Event::cut(at));
                cusps.push((c, at));
            }
        }
    }
    stats.cusps = cusps.len();
    let same_run = |a: usize, b: usize| run_of[a].iter().any(|r| run_of[b].contains(r));
    let mut jobs: Vec<Job> = Vec::new();
    for (a, sa) in segments.iter().enumerate() {
        // A segment another line draws whole is no line of the drawing.
        if sa.drawn_elsewhere(sa.range) {
            continue;
        }
        // Past the deadline, the pairs (a', b) with a ≤ a' < b and the penetrations and
        // self-crossings of the segments from a on are not searched: those segments are
        // unresolved (every pair not searched has both members among them).
        if opts.curve.past_deadline() {
            for (k, sg) in segments.iter().enumerate().skip(a) {
                events[k].push(Event::unresolved(sg.range, Reason::TimeLimit));
            }
            break;
        }
        // Every vertex inside a segment cuts it (a junction on a side).
        for v in &sa.vertices {
            events[a].push(Event::vertex(v.param));
        }
        // With what lies behind wanted, so does every end of a stretch of decided role.
        if opts.behind {
            for r in roles.inner[a].iter().chain(&roles.folds[a]) {
                for x in r.iter().filter(|x| sa.range[0] < **x && **x < sa.range[1]) {
                    events[a].push(Event::cut([*x, *x]));
                }
            }
        }
        match (&sa.constraint, &sa.monotone) {
            // A stretch the surface continues across cannot change its own QI.
            (None, _) if !roles.outline[a] => {}
            (None, _) => jobs.push(Job::SelfCrossing(a)),
            (Some(_), Some(_)) => {}
            (Some(_), None) if !run_of[a].is_empty() => {}
            (Some(_), None) => events[a].push(Event::unresolved(sa.range, Reason::OutlineCusp)),
        }
        for (b, sb) in segments.iter().enumerate().skip(a + 1) {
            if sb.drawn_elsewhere(sb.range) {
                continue;
            }
            if !sa.bounds.meets_image(&sb.bounds) {
                stats.culled_pairs += 1;
                continue;
            }
            stats.pairs += 1;
            if !roles.outline[a] && !roles.outline[b] {
                stats.cluster_pairs += 1;
                continue;
            }
            if same_run(a, b) {
                stats.cusp_pairs += 1;
                continue;
            }
            if sa.chain == sb.chain && sa.order.abs_diff(sb.order) == 1 && common_monotone(sa, sb) {
                stats.monotone_pairs += 1;
                continue;
            }
            jobs.push(Job::Pair(a, b));
        }
        for (j, jb) in scene.bounds.iter().enumerate() {
            if sa.on.iter().any(|x| x.0 == j)
                || sa.touches.contains(&j)
                || sa.on.iter().any(|x| scene.adjacent(x.0, j))
            {
                continue;
            }
            let overlap_depth =
                jb.depth[0] <= sa.bounds.depth[1] && sa.bounds.depth[0] <= jb.depth[1];
            if jb.meets_image(&sa.bounds) && overlap_depth {
                stats.penetration_systems += 1;
                jobs.push(Job::Penetration(a, j));
            }
        }
    }
    // The fold boxes of each silhouette arc, once.
    let covers: Vec<Vec<(DyadicBoxN, DyadicBoxN)>> = segments
        .par_iter()
        .map(|s| {
            if opts.curve.past_deadline() {
                Vec::new()
            } else {
                fold_cover(scene, s)
            }
        })
        .collect();
    let results: Vec<(Job, SystemRoots, Vec<DyadicBoxN>, bool)> = jobs
        .par_iter()
        .map(|job| {
            if opts.curve.past_deadline() {
                // Not solved: every stretch the system covers is unresolved.
                let domain: Vec<[f64; 2]> = job_domain(segments, *job)
                    .iter()
                    .map(|d| [d.0.to_f64(), d.1.to_f64()])
                    .collect();
                let r = SystemRoots {
                    unresolved: vec![domain],
                    ..SystemRoots::default()
                };
                return (*job, r, Vec::new(), true);
            }
            // A pair with an intersection curve near its fold points meets the outline in a
            // near-tangency (its image touches the outline there): a larger box budget.
            let wide = SystemOptions {
                max_boxes: opts.crossing.max_boxes * MEET_BUDGET,
                ..opts.crossing.clone()
            };
            let opts = match *job {
                Job::Pair(a, b) if segments[a].meet.is_some() || segments[b].meet.is_some() => {
                    &wide
                }
                _ => &opts.crossing,
            };
            let (r, exclude) = match *job {
                Job::Pair(a, b) => {
                    let system = crossing_system(&segments[a], &segments[b]);
                    let mut exclude = arc_fold_exclusion(&segments[a], &segments[b], &covers, a, b);
                    for va in &segments[a].vertices {
                        for vb in &segments[b].vertices {
                            if va.key.matches(&vb.key) {
                                if let Some(x) =
                                    vertex_exclusion(scene, &segments[a], &segments[b], va, vb)
                                {
                                    exclude.push(x);
                                }
                            }
                        }
                    }
                    (solve_separable(&system, &exclude, opts), exclude)
                }
                Job::SelfCrossing(a) => {
                    let (eqs, domain) = self_crossing_system(&segments[a]);
                    (solve_system(&eqs, &[], &domain, opts), Vec::new())
                }
                Job::Penetration(a, j) => {
                    let unit = vec![(Dyadic::ZERO, Dyadic::ONE); 2];
                    let system = penetration_system(&segments[a], &scene.images[j], &unit);
                    (solve_separable(&system, &[], opts), Vec::new())
                }
            };
            (*job, r, exclude, false)
        })
        .collect();
    let mut intersecting = BTreeSet::new();
    for (job, r, exclude, timed_out) in &results {
        stats.boxes += r.boxes;
        stats.escalations.merge(&r.escalations);
        if let Job::Penetration(a, j) = *job {
            let na = segments[a].domain.len();
            let inside = |e: &Vec<[f64; 2]>| {
                scene.membership(j, &Rect::from_axes(e[na], e[na + 1])) != Membership::Outside
            };
            let found = r.roots.iter().any(|x| inside(&x.enclosure));
            for &(p, _, _) in segments[a].on.iter().filter(|_| found) {
                intersecting.insert([p.min(j), p.max(j)]);
            }
        }
        stats.excluded_vertices += exclude.len();
        // Which variables are each segment's parameter, and what an unresolved box means.
        let (targets, why): (Vec<(usize, usize)>, Reason) = match *job {
            Job::Pair(a, b) => {
                let na = segments[a].domain.len();
                (
                    vec![(a, segments[a].axis), (b, na + segments[b].axis)],
                    Reason::CrossingNotIsolated {
                        patches: [segments[b].patch, segments[a].patch],
                    },
                )
            }
            Job::SelfCrossing(a) => (vec![(a, 0), (a, 1)], Reason::SelfCrossingNotIsolated),
            Job::Penetration(a, j) => (
                vec![(a, segments[a].axis)],
                Reason::PenetrationNotIsolated { patch: j },
            ),
        };
        // A point of the system where a line, or the patch passed through, lies outside its
        // trimmed faces holds no crossing of what is drawn.
        let outside = |bx: &[[f64; 2]]| -> bool {
            match *job {
                Job::Pair(a, b) => {
                    let na = segments[a].domain.len();
                    outside_faces(scene, &segments[a], &bx[..na])
                        || outside_faces(scene, &segments[b], &bx[na..])
                }
                Job::SelfCrossing(a) => {
                    let na = segments[a].domain.len();
                    outside_faces(scene, &segments[a], &bx[..na])
                        || outside_faces(scene, &segments[a], &bx[na..])
                }
                Job::Penetration(a, j) => {
                    let na = segments[a].domain.len();
                    let uv = Rect::from_axes(bx[na], bx[na + 1]);
                    outside_faces(scene, &segments[a], &bx[..na])
                        || scene.membership(j, &uv) == Membership::Outside
                }
            }
        };
        // A crossing cuts a segment only if the other segment can change its QI there.
        let counts = |bx: &[[f64; 2]], s: usize| -> bool {
            if outside(bx) {
                return false;
            }
            match *job {
                Job::Pair(a, b) => {
                    let na = segments[a].domain.len();
                    let (other, k) = if s == a {
                        (b, na + segments[b].axis)
                    } else {
                        (a, segments[a].axis)
                    };
                    roles.outline_at(other, bx[k])
                }
                _ => true,
            }
        };
        for root in &r.roots {
            for &(s, k) in &targets {
                if counts(&root.enclosure, s) {
                    events[s].push(Event::cut(root.enclosure[k]));
                }
            }
        }
        let why = if *timed_out { Reason::TimeLimit } else { why };
        for bx in &r.unresolved {
            for &(s, k) in &targets {
                if counts(bx, s) {
                    events[s].push(Event::unresolved(bx[k], why.clone()));
                }
            }
        }
    }

    Crossings {
        events,
        intersecting,
    }
}

/// A system to solve.
#[derive(Clone, Copy, Debug)]
enum Job {
    /// Two segments' image crossings.
    Pair(usize, usize),
    /// A side's image crossing itself.
    SelfCrossing(usize),
    /// A segment passing through a patch.
    Penetration(usize, usize),
}

/// The variables' box of a job's system.
fn job_domain(segments: &[Segment], job: Job) -> DyadicBoxN {
    let unit = (Dyadic::ZERO, Dyadic::ONE);
    match job {
        Job::Pair(a, b) => segments[a]
            .domain
            .iter()
            .chain(&segments[b].domain)
            .copied()
            .collect(),
        Job::SelfCrossing(a) => segments[a]
            .domain
            .iter()
            .chain(&segments[a].domain)
            .copied()
            .collect(),
        Job::Penetration(a, _) => segments[a]
            .domain
            .iter()
            .copied()
            .chain([unit, unit])
            .collect(),
    }
}

/// A cut or an unresolved stretch on a segment's parameter.
#[derive(Clone, Debug)]
pub(super) struct Event {
    pub(super) at: [f64; 2],
    pub(super) unresolved: Option<Reason>,
    /// The cut is one of the segment's vertices (not a root of a system).
    pub(super) vertex: bool,
}

impl Event {
    pub(super) fn cut(at: [f64; 2]) -> Event {
        Event {
            at,
            unresolved: None,
            vertex: false,
        }
    }
    /// The cut at one of the segment's vertices.
    pub(super) fn vertex(at: [f64; 2]) -> Event {
        Event {
            vertex: true,
            ..Event::cut(at)
        }
    }
    pub(super) fn unresolved(at: [f64; 2], why: Reason) -> Event {
        Event {
            at,
            unresolved: Some(why),
            vertex: false,
        }
    }
}

/// Whether the points of a segment over a box of its variables are proven outside its
/// patch's trimmed faces (never for a trimming curve, which bounds them).
fn outside_faces(scene: &Scene, s: &Segment, bx: &[[f64; 2]]) -> bool {
    // A stretch another line draws is not a line here either.
    if let [t] = bx {
        if s.drawn_elsewhere(*t) {
            return true;
        }
    }
    if s.curve.is_some() || !scene.trimmed(s.patch) {
        return false;
    }
    let uv = match (s.line, s.edge, bx) {
        (Some((axis, at)), _, [t]) => {
            let mut r = Rect::from_axes(*t, *t);
            let c = at.to_f64();
            r.set_axis(axis, [c, c]);
            r
        }
        (None, Some(edge), [t]) if s.constraint.is_none() => {
            let (a, b) = (side_point_f64(edge, t[0]), side_point_f64(edge, t[1]));
            Rect::point(a).hull(&Rect::point(b))
        }
        (None, _, [u, v]) => Rect::from_axes(*u, *v),
        _ => return false,
    };
    scene.membership(s.patch, &uv) == Membership::Outside
}

/// The point of a side at parameter `t`, in f64 (exact: the side's coordinates are 0, 1, t).
fn side_point_f64(edge: crate::surface::Edge, t: f64) -> [f64; 2] {
    use crate::surface::Edge;
    match edge {
        Edge::V0 => [t, 0.0],
        Edge::V1 => [t, 1.0],
        Edge::U0 => [0.0, t],
        Edge::U1 => [1.0, t],
    }
}
