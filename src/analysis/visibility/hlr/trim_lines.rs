//! Stage 1b of the drawing, for trimmed faces: the trimming curves as lines, and every other
//! line of a trimmed patch cut where it crosses them (`proofs/hidden-lines.md`, "Trimmed
//! faces").
//!
//! A loop piece `c = (U, V, W)` of a face, in a patch's parameters, is a line of the drawing
//! where it runs inside the patch's square: its crossings with the square's sides are the
//! roots of `U`, `U − W`, `V`, `V − W`, isolated exactly; between them the piece is inside or
//! outside the square as a whole, decided at one point. Each piece inside is a segment in the
//! piece's parameter `t`, with the exact image polynomials `W^{d₀+d₁} f(U/W, V/W)` of the
//! patch's ([`compose_homogeneous`]), cut at dyadic `t` until its image is monotone. Its
//! crossings with the patch's sides cut those sides, and its crossings with the patch's
//! silhouette (the roots of `g ∘ c`, and of `U − aW` for a silhouette line `u = a`) cut the
//! silhouette arcs, as shared vertices: between cuts a line of a trimmed patch meets no loop,
//! so it lies in the faces or outside them as a whole (decided per piece, `pieces.rs`).
//!
//! A piece on a B-rep edge is drawn once: as a side of a square when it runs along one on some
//! face, else from the first face that uses the edge. A piece along a side of the square is
//! that side, drawn as the side. Which faces a line is not searched against for penetrations
//! (the faces sharing an edge or vertex with its face: the B-rep assumption) is
//! [`brep_neighbours`].

use crate::analysis::contour::curves::Silhouette;
use crate::analysis::projection::ImagePolys;
use crate::analysis::visibility::hlr::crossings::Event;
use crate::analysis::visibility::hlr::lines::{
    bounds_on, class_of, find_monotone, side_uv, tangent_polys_side, Key, ParamBox, Segment, Vertex,
};
use crate::analysis::visibility::hlr::result::LineKind;
use crate::analysis::visibility::scene::Scene;
use crate::bernstein::{compose_homogeneous, Poly};
use crate::geometry::Rect;
use crate::model::Model;
use crate::number::{Interval, Number, Precision, Rational};
use crate::reason::Reason;
use crate::solver::dyadic::Dyadic;
use crate::solver::point_in_face::{self, curve_misses_box};
use crate::solver::precision::Policy;
use crate::solver::system::DyadicBoxN;
use crate::solver::univariate::{isolate_roots_in, refine_root, Root};
use crate::surface::Edge;
use std::collections::BTreeMap;

/// The trimming lines and what they found.
#[derive(Default)]
pub(super) struct TrimLines {
    /// The new segments.
    pub(super) segments: Vec<Segment>,
    /// Unresolved stretches: (segment index among all segments, event).
    pub(super) events: Vec<(usize, Event)>,
    /// Crossings of trimming curves with patch sides and silhouettes, proven.
    pub(super) crossings: usize,
}

/// How finely a crossing of a trimming curve is isolated.
const WIDTH: f64 = 1e-15;

/// The deepest bisection of a trimming segment towards monotone images.
const MONOTONE_DEPTH: u32 = 8;

/// One loop piece inside a patch, before it becomes segments.
struct Run {
    /// Its parameter interval, from the lower end's enclosure to the upper's.
    lo: (Dyadic, Dyadic),
    hi: (Dyadic, Dyadic),
}

/// The trimming curves of every trimmed patch as segments (appended after `existing`, whose
/// sides, arcs and lines get the crossings as vertices).
pub(super) fn trim_lines(
    scene: &Scene,
    model: &Model,
    sil: &Silhouette,
    existing: &mut [Segment],
    first_chain: usize,
    next_id: &mut usize,
    policy: &mut Policy,
) -> TrimLines {
    let mut out = TrimLines::default();
    if scene.faces.iter().all(Option::is_none) {
        return out;
    }
    // The faces of each B-rep edge, in order: the first draws it.
    let mut edge_faces: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for (f, face) in model.faces.iter().enumerate() {
        for l in face.loops() {
            for p in &l.pieces {
                if let Some(e) = p.edge {
                    let users = edge_faces.entry(e).or_default();
                    if !users.contains(&f) {
                        users.push(f);
                    }
                }
            }
        }
    }
    // An edge that runs along a side of a square on some face is drawn as that side, by the
    // first such face (its pieces off the side too); other edges by their first face. Drawn
    // by two faces, one edge would be two lines within the inversion bound of each other.
    let mut drawer: BTreeMap<usize, usize> = edge_faces
        .iter()
        .filter_map(|(e, users)| users.first().map(|f| (*e, *f)))
        .collect();
    let mut on_side: std::collections::BTreeSet<usize> = std::collections::BTreeSet::new();
    for trims in scene.faces.iter().flatten() {
        for piece in &trims.pieces {
            if let Some(e) = piece.edge {
                if !on_side.contains(&e) && along_side(&piece.curve) {
                    on_side.insert(e);
                    drawer.insert(e, piece.face);
                }
            }
        }
    }
    // Chains: one per loop, numbered by (face, loop).
    let mut chains: BTreeMap<(usize, usize), usize> = BTreeMap::new();
    let n_existing = existing.len();
    // By side class, the exact stretches drawn by another face's line.
    let mut elsewhere: BTreeMap<usize, Vec<(Rational, Rational)>> = BTreeMap::new();
    for p in 0..scene.faces.len() {
        let Some(Some(trims)) = scene.faces.get(p) else {
            continue;
        };
        for piece in &trims.pieces {
            let drawn = piece
                .edge
                .is_none_or(|e| drawer.get(&e) == Some(&piece.face));
            if !drawn && !along_side(&piece.curve) {
                continue;
            }
            let next_chain = first_chain + chains.len();
            let chain = *chains.entry((piece.face, piece.at.0)).or_insert(next_chain);
            let c: [Poly; 3] = piece.curve.clone();
            let sides = side_polys(&c);
            if let Some(k) = sides.iter().position(Poly::is_zero) {
                // Along a side of the square: drawn as that side, unless the edge is another
                // face's line; then that stretch of the side is not a line of the drawing.
                if !drawn {
                    let edge = [Edge::U0, Edge::U1, Edge::V0, Edge::V1][k];
                    let n = model.faces[piece.face]
                        .loops()
                        .nth(piece.at.0)
                        .map_or(1, |l| l.pieces.len());
                    let joint = |k: usize| Key::Joint {
                        face: piece.face,
                        lp: piece.at.0,
                        k,
                    };
                    let keys = [joint(piece.at.1), joint((piece.at.1 + 1) % n)];
                    let drawer_face = piece.edge.and_then(|e| drawer.get(&e).copied());
                    along_elsewhere(
                        scene,
                        model,
                        (p, edge),
                        &c,
                        keys,
                        drawer_face,
                        existing,
                        &mut elsewhere,
                    );
                }
                continue;
            }
            let enclosed = c.clone().map(|x| x.convert::<Interval>(Precision::F64));
            if curve_misses_box(&enclosed, &[[0.0, 1.0], [0.0, 1.0]]) {
                continue;
            }
            // The loop is closed: its last piece ends at joint 0.
            let in_loop = model.faces[piece.face]
                .loops()
                .nth(piece.at.0)
                .map_or(usize::MAX, |l| l.pieces.len());
            let key_of = |t: (Dyadic, Dyadic)| -> Key {
                let joint = |k: usize| Key::Joint {
                    face: piece.face,
                    lp: piece.at.0,
                    k,
                };
                if t.1 == Dyadic::ZERO {
                    joint(piece.at.1)
                } else if t.0 == Dyadic::ONE {
                    joint((piece.at.1 + 1) % in_loop)
                } else {
                    Key::Trim {
                        face: piece.face,
                        lp: piece.at.0,
                        piece: piece.at.1,
                        t: [t.0.to_f64(), t.1.to_f64()],
                    }
                }
            };
            // 1. Its crossings with the square's sides, cutting the sides.
            let mut breaks: Vec<(Dyadic, Dyadic)> = vec![(Dyadic::ZERO, Dyadic::ZERO)];
            let mut undecided = false;
            for (h, edge) in sides.iter().zip([Edge::U0, Edge::U1, Edge::V0, Edge::V1]) {
                let roots = isolate_roots_in(h, Dyadic::ZERO, Dyadic::ONE, 60, policy);
                undecided |= !roots.unresolved.is_empty();
                for r in roots.roots {
                    let r = interval(refine_root(h, r, WIDTH, policy));
                    breaks.push(r);
                    let Some(b) = curve_box(&c, r) else {
                        undecided = true;
                        continue;
                    };
                    // The crossing's place along the side (off the side's range: not on it).
                    let along = match edge {
                        Edge::U0 | Edge::U1 => b.axis(1),
                        Edge::V0 | Edge::V1 => b.axis(0),
                    };
                    if along[1] < 0.0 || along[0] > 1.0 {
                        continue;
                    }
                    let along = [along[0].max(0.0), along[1].min(1.0)];
                    if let Some((class, rev)) = class_of(scene, p, edge) {
                        let t = if rev {
                            [1.0 - along[1], 1.0 - along[0]]
                        } else {
                            along
                        };
                        let key = key_of(r);
                        let side = &mut existing[class];
                        if !side.vertices.iter().any(|v| v.key.matches(&key)) {
                            let uv = side_uv(&side.on, t);
                            side.vertices.push(Vertex { key, param: t, uv });
                            out.crossings += 1;
                        }
                    }
                }
            }
            breaks.push((Dyadic::ONE, Dyadic::ONE));
            breaks.sort_by_key(|a| a.0);
            // Overlapping enclosures are one break.
            let mut merged: Vec<(Dyadic, Dyadic)> = Vec::new();
            for b in breaks {
                match merged.last_mut() {
                    Some(last) if b.0 <= last.1 => last.1 = last.1.max(b.1),
                    _ => merged.push(b),
                }
            }
            // 2. The runs inside the square, each decided at a point between its breaks.
            let mut runs: Vec<Run> = Vec::new();
            for w in merged.windows(2) {
                let (a, b) = (w[0], w[1]);
                let Some(mid) = a.1.midpoint(b.0) else {
                    continue;
                };
                match curve_box(&c, (mid, mid)) {
                    Some(r) if (0..2).all(|k| r.axis(k)[0] > 0.0 && r.axis(k)[1] < 1.0) => {
                        runs.push(Run { lo: a, hi: b });
                    }
                    Some(r) if (0..2).any(|k| r.axis(k)[0] > 1.0 || r.axis(k)[1] < 0.0) => {}
                    _ => undecided = true,
                }
            }
            if undecided {
                runs = vec![Run {
                    lo: (Dyadic::ZERO, Dyadic::ZERO),
                    hi: (Dyadic::ONE, Dyadic::ONE),
                }];
            }
            let image = compose_image(&scene.images[p], &c);
            for run in runs {
                let domain = vec![(run.lo.0, run.hi.1)];
                let ends = [run.lo, run.hi].map(|t| Vertex {
                    key: key_of(t),
                    param: [t.0.to_f64(), t.1.to_f64()],
                    uv: curve_box(&c, t).map_or_else(Vec::new, |b| vec![uv_of(p, &b)]),
                });
                let tangent = tangent_polys_side(&image);
                let mut seg = Segment {
                    kind: LineKind::Trim,
                    patch: p,
                    edge: None,
                    chain,
                    order: piece.at.1,
                    bounds: bounds_on(&image, &domain),
                    monotone: find_monotone(&tangent, &domain),
                    image: image.clone(),
                    constraint: None,
                    tangent,
                    range: [run.lo.0.to_f64(), run.hi.1.to_f64()],
                    domain,
                    axis: 0,
                    vertices: ends.into(),
                    on: vec![(p, None, false)],
                    line: None,
                    curve: Some(c.clone()),
                    touches: Vec::new(),
                    elsewhere: Vec::new(),
                    meet: None,
                };
                // 3. Its crossings with the patch's silhouette, cutting the arcs and lines.
                let unresolved = silhouette_crossings(
                    sil,
                    p,
                    &mut seg,
                    &mut existing[..n_existing],
                    &key_of,
                    policy,
                    &mut out.crossings,
                );
                let index = n_existing + out.segments.len();
                let pieces = split_monotone(seg, MONOTONE_DEPTH, next_id);
                for (k, s) in pieces.into_iter().enumerate() {
                    if undecided || unresolved.is_some() {
                        let why = unresolved.clone().unwrap_or(Reason::TrimLine);
                        out.events
                            .push((index + k, Event::unresolved(s.range, why)));
                    }
                    out.segments.push(s);
                }
            }
        }
    }
    // The stretches drawn elsewhere, merged where they abut (exactly, at a joint), with
    // bounds rounded inwards.
    for (class, mut stretches) in elsewhere {
        stretches.sort();
        let mut merged: Vec<(Rational, Rational)> = Vec::new();
        for (lo, hi) in stretches {
            match merged.last_mut() {
                Some(last) if lo <= last.1 => {
                    if hi > last.1 {
                        last.1 = hi;
                    }
                }
                _ => merged.push((lo, hi)),
            }
        }
        for (lo, hi) in merged {
            let lo = Interval::from_rational(&lo, Precision::F64).hi();
            let hi = Interval::from_rational(&hi, Precision::F64).lo();
            if lo < hi {
                existing[class].elsewhere.push([lo, hi]);
            }
        }
    }
    // Along each loop, the segments in order of piece and parameter.
    let mut by_chain: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for (k, s) in out.segments.iter().enumerate() {
        by_chain.entry(s.chain).or_default().push(k);
    }
    for ks in by_chain.values_mut() {
        ks.sort_by(|&a, &b| {
            let (sa, sb) = (&out.segments[a], &out.segments[b]);
            (sa.order, sa.range[0])
                .partial_cmp(&(sb.order, sb.range[0]))
                .unwrap_or(std::cmp::Ordering::Equal)
        });
        for (rank, &k) in ks.iter().enumerate() {
            out.segments[k].order = rank;
        }
    }
    out
}

/// A loop piece `c` of a face that runs along side `edge` of patch `p` on a B-rep edge whose
/// line another face (`drawer`) draws: the side's stretch between the piece's ends (which the
/// piece covers, being connected) is recorded in `elsewhere` under the side's class, and each
/// end inside the side (a joint of the loop, `keys`) becomes a vertex of the side. Nothing is
/// recorded when a patch of the drawing face is itself a user of the side: then the side is
/// the drawn line.
#[allow(clippy::too_many_arguments)]
fn along_elsewhere(
    scene: &Scene,
    model: &Model,
    (p, edge): (usize, Edge),
    c: &[Poly; 3],
    keys: [Key; 2],
    drawer: Option<usize>,
    existing: &mut [Segment],
    elsewhere: &mut BTreeMap<usize, Vec<(Rational, Rational)>>,
) {
    let Some((class, rev)) = class_of(scene, p, edge) else {
        return;
    };
    let side = &mut existing[class];
    let drawn_here = side.on.iter().any(|(q, _, _)| {
        let surface = model.patches[*q].source.surface;
        model
            .faces
            .iter()
            .enumerate()
            .any(|(f, face)| face.surface == surface && Some(f) == drawer)
    });
    if drawn_here {
        return;
    }
    let free = match edge {
        Edge::U0 | Edge::U1 => 1,
        Edge::V0 | Edge::V1 => 0,
    };
    let mut ends: Vec<(Rational, Key)> = Vec::new();
    for (t, key) in [0, 1].into_iter().zip(keys) {
        let Some(x) = point_at(c, &Rational::from(t)) else {
            return;
        };
        let x = x[free].clone();
        // In the side's parameter.
        let x = if rev { Rational::from(1 - &x) } else { x };
        ends.push((x, key));
    }
    ends.sort_by(|a, b| a.0.cmp(&b.0));
    let (zero, one) = (Rational::from(0), Rational::from(1));
    let lo = ends[0].0.clone().max(zero.clone());
    let hi = ends[1].0.clone().min(one.clone());
    if lo >= hi {
        return;
    }
    for (x, key) in ends {
        if x <= zero || x >= one || side.vertices.iter().any(|v| v.key.matches(&key)) {
            continue;
        }
        let i = Interval::from_rational(&x, Precision::F64);
        let param = [i.lo(), i.hi()];
        let uv = side_uv(&side.on, param);
        side.vertices.push(Vertex { key, param, uv });
    }
    elsewhere.entry(class).or_default().push((lo, hi));
}

/// Whether a piece runs along a side of the square.
fn along_side(c: &[Poly; 3]) -> bool {
    side_polys(c).iter().any(Poly::is_zero)
}

/// `U`, `U − W`, `V`, `V − W`: their roots are the crossings with the sides `u = 0`, `u = 1`,
/// `v = 0`, `v = 1`.
fn side_polys(c: &[Poly; 3]) -> [Poly; 4] {
    let minus_w = |p: &Poly| p.try_sub(&c[2]).expect("equal degrees");
    [c[0].clone(), minus_w(&c[0]), c[1].clone(), minus_w(&c[1])]
}

/// A crossing found on a trimming segment: its parameter interval, its box in `(u, v)`, and
/// the silhouette line it lies on (`(axis, a)`), if any.
type Found = ((Dyadic, Dyadic), Rect, Option<(usize, Dyadic)>);

/// A root's interval (a point for an exact root).
fn interval(r: Root) -> (Dyadic, Dyadic) {
    (r.lo(), r.hi())
}

/// An outward enclosure in `(u, v)` of the curve over the dyadic interval `t` (`W > 0` there).
fn curve_box(c: &[Poly; 3], t: (Dyadic, Dyadic)) -> Option<Rect> {
    point_in_face::curve_box(c, &t.0.to_rational(), &t.1.to_rational())
}

/// A vertex's parameter box on patch `p` from an f64 box (exact rationals of its ends).
fn uv_of(p: usize, b: &Rect) -> (usize, [Rational; 2], [Rational; 2]) {
    let r = |x: f64| Rational::from_f64(x).unwrap_or_default();
    (
        p,
        [r(b.axis(0)[0]), r(b.axis(1)[0])],
        [r(b.axis(0)[1]), r(b.axis(1)[1])],
    )
}

/// The image polynomials of a patch along the curve, in its parameter: each composed with
/// `c` ([`compose_homogeneous`]) after the numerators and denominators are brought to common
/// degrees, so that every ratio is the patch's along the curve.
fn compose_image(im: &ImagePolys, c: &[Poly; 3]) -> ImagePolys {
    let k = [&c[0], &c[1], &c[2]];
    let all = [&im.x, &im.y, &im.q, &im.depth, &im.w];
    let mut deg = vec![0usize; 2];
    for p in all {
        for (d, e) in deg.iter_mut().zip(p.degrees()) {
            *d = (*d).max(*e);
        }
    }
    im.map(|p| compose_homogeneous(&p.elevate_to(&deg), k))
}

/// The crossings of a trimming segment with the silhouette of its patch: vertices on it and
/// on every arc or line of the patch that can hold them. `Some(reason)` if they are not all
/// isolated.
fn silhouette_crossings(
    sil: &Silhouette,
    p: usize,
    seg: &mut Segment,
    existing: &mut [Segment],
    key_of: &dyn Fn((Dyadic, Dyadic)) -> Key,
    policy: &mut Policy,
    count: &mut usize,
) -> Option<Reason> {
    let solved = sil.solved.get(p)?;
    let c = seg.curve.clone()?;
    let (lo, hi) = seg.domain[0];
    let mut found: Vec<Found> = Vec::new();
    // The arcs: g along the curve; the lines u = a (v = a): U − aW (V − aW).
    let mut polys: Vec<(Poly, Option<(usize, Dyadic)>)> = Vec::new();
    if !solved.g.is_zero() && solved.g.nvars() == 2 {
        polys.push((compose_homogeneous(&solved.g, [&c[0], &c[1], &c[2]]), None));
    }
    for zl in &solved.lines {
        let h = c[zl.axis]
            .try_sub(&c[2].scale(&zl.at.to_rational()))
            .expect("equal degrees");
        polys.push((h, Some((zl.axis, zl.at))));
    }
    let mut why = None;
    for (h, line) in polys {
        if h.is_zero() {
            why = Some(Reason::TrimAlongCurve);
            continue;
        }
        if lo >= hi {
            continue;
        }
        let roots = isolate_roots_in(&h, lo, hi, 60, policy);
        if !roots.unresolved.is_empty() {
            why = Some(Reason::TrimLine);
        }
        for r in roots.roots {
            let r = interval(refine_root(&h, r, WIDTH, policy));
            match curve_box(&c, r) {
                Some(b) => found.push((r, b, line)),
                None => why = Some(Reason::TrimLine),
            }
        }
    }
    for (t, b, line) in found {
        let key = key_of(t);
        let uv = vec![uv_of(p, &b)];
        let mut placed = false;
        for s in existing
            .iter_mut()
            .filter(|s| s.patch == p && s.kind == LineKind::Silhouette)
        {
            let param = match (s.line, line) {
                (Some((axis, at)), Some((la, lat))) if axis == la && at == lat => b.axis(1 - axis),
                (None, None) if s.constraint.is_some() => {
                    let meets = (0..2).all(|k| {
                        b.axis(k)[1] >= s.domain[k].0.to_f64()
                            && b.axis(k)[0] <= s.domain[k].1.to_f64()
                    });
                    if !meets {
                        continue;
                    }
                    b.axis(s.axis)
                }
                _ => continue,
            };
            if !s.vertices.iter().any(|v| v.key.matches(&key)) {
                s.vertices.push(Vertex {
                    key: key.clone(),
                    param,
                    uv: uv.clone(),
                });
            }
            placed = true;
        }
        if placed {
            *count += 1;
        }
        if !seg.vertices.iter().any(|v| v.key.matches(&key)) {
            seg.vertices.push(Vertex {
                key,
                param: [t.0.to_f64(), t.1.to_f64()],
                uv,
            });
        }
    }
    why
}

/// A trimming segment cut at dyadic parameters (bisection, up to `depth` times) into pieces
/// whose images are monotone; the cut points (exact points of the curve) become shared
/// vertices. Pieces never made monotone stay (their self-crossings are searched).
fn split_monotone(s: Segment, depth: u32, next_id: &mut usize) -> Vec<Segment> {
    if s.monotone.is_some() || depth == 0 {
        return vec![s];
    }
    let (lo, hi) = s.domain[0];
    let Some(mid) = lo.midpoint(hi) else {
        return vec![s];
    };
    let Some(c) = &s.curve else {
        return vec![s];
    };
    let Some(b) = curve_box(c, (mid, mid)) else {
        return vec![s];
    };
    let m = mid.to_f64();
    if m <= s.range[0] || m >= s.range[1] {
        return vec![s];
    }
    let cut = Vertex {
        key: Key::Param { id: *next_id },
        param: [m, m],
        uv: vec![uv_of(s.patch, &b)],
    };
    *next_id += 1;
    let half = |dom: (Dyadic, Dyadic), range: [f64; 2], low: bool| {
        let mut d = s.clone();
        d.domain = vec![dom];
        d.range = range;
        d.bounds = bounds_on(&d.image, &d.domain);
        d.monotone = find_monotone(&d.tangent, &d.domain);
        d.vertices = s
            .vertices
            .iter()
            .filter(|v| {
                if low {
                    v.param[0] <= m
                } else {
                    v.param[1] >= m
                }
            })
            .cloned()
            .chain([cut.clone()])
            .collect();
        d
    };
    let low = half((lo, mid), [s.range[0], m], true);
    let high = half((mid, hi), [m, s.range[1]], false);
    let mut out = split_monotone(low, depth - 1, next_id);
    out.extend(split_monotone(high, depth - 1, next_id));
    out
}

/// How finely a trimming segment's domain is halved where it straddles the boundary of a box
/// its part in the box is sought in: down to `2^-SUB_DOMAIN_DEPTH` of the domain.
const SUB_DOMAIN_DEPTH: u32 = 40;

/// How many pieces that search looks at, at most.
const SUB_DOMAIN_PIECES: usize = 4096;

/// A part of a trimming segment's domain whose points lie in the parameter box `b` of its
/// patch (which may reach past the square): a run of dyadic sub-intervals, found by
/// bisection where they straddle the box's boundary, whose curve enclosures lie in `b`. The
/// run that meets the parameter interval `near` if there is one (the vertex a lemma is
/// applied at), else the longest; `None` if there is none.
pub(super) fn curve_sub_domain(
    s: &Segment,
    c: &[Poly; 3],
    b: &ParamBox,
    near: Option<[f64; 2]>,
) -> Option<DyadicBoxN> {
    let inside = |r: &Rect| (0..2).all(|k| r.axis(k)[0] >= b[k][0] && r.axis(k)[1] <= b[k][1]);
    let misses = |r: &Rect| (0..2).any(|k| r.axis(k)[1] < b[k][0] || r.axis(k)[0] > b[k][1]);
    let mut kept: Vec<(Dyadic, Dyadic)> = Vec::new();
    let mut stack = vec![(s.domain[0], 0u32)];
    let mut looked = 0usize;
    while let Some(((lo, hi), depth)) = stack.pop() {
        looked += 1;
        if looked > SUB_DOMAIN_PIECES {
            break;
        }
        let Some(r) = curve_box(c, (lo, hi)) else {
            continue;
        };
        if inside(&r) {
            kept.push((lo, hi));
        } else if !misses(&r) && depth < SUB_DOMAIN_DEPTH {
            if let Some(mid) = lo.midpoint(hi) {
                stack.push(((lo, mid), depth + 1));
                stack.push(((mid, hi), depth + 1));
            }
        }
    }
    kept.sort();
    let mut runs: Vec<(Dyadic, Dyadic)> = Vec::new();
    for (lo, hi) in kept {
        match runs.last_mut() {
            Some(last) if last.1 == lo => last.1 = hi,
            _ => runs.push((lo, hi)),
        }
    }
    let len = |x: &(Dyadic, Dyadic)| x.1.to_f64() - x.0.to_f64();
    let meets =
        |x: &(Dyadic, Dyadic)| near.is_some_and(|n| x.0.to_f64() <= n[1] && n[0] <= x.1.to_f64());
    let longest = |it: &mut dyn Iterator<Item = (Dyadic, Dyadic)>| {
        it.max_by(|x, y| {
            len(x)
                .partial_cmp(&len(y))
                .unwrap_or(std::cmp::Ordering::Equal)
        })
    };
    longest(&mut runs.iter().copied().filter(|x| meets(x)))
        .or_else(|| longest(&mut runs.iter().copied()))
        .map(|x| vec![x])
}

/// The point of a trimming segment at an exact parameter, in its patch's parameters.
pub(super) fn point_at(c: &[Poly; 3], t: &Rational) -> Option<[Rational; 2]> {
    let at = std::slice::from_ref(t);
    let w = c[2].eval(at);
    (w > 0).then(|| {
        [
            Rational::from(&c[0].eval(at) / &w),
            Rational::from(&c[1].eval(at) / &w),
        ]
    })
}

/// Per patch, the patches of the faces that share a B-rep edge or vertex with a face on the
/// patch's surface (empty without a B-rep). By the B-rep assumption those faces meet the
/// patch's faces only along their common edges and vertices, which are drawn and decided as
/// lines and vertices: the patch's lines are not searched for penetrations of them.
pub(super) fn brep_neighbours(model: &Model) -> Vec<Vec<usize>> {
    let mut out = vec![Vec::new(); model.patches.len()];
    let Some(brep) = &model.brep else {
        return out;
    };
    // The surfaces on each edge, and at each vertex.
    let mut at_edge: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for face in &model.faces {
        for e in face.loops().flat_map(|l| &l.pieces).filter_map(|p| p.edge) {
            let s = at_edge.entry(e).or_default();
            if !s.contains(&face.surface) {
                s.push(face.surface);
            }
        }
    }
    let mut at_vertex: BTreeMap<&crate::surface::Point3, Vec<usize>> = BTreeMap::new();
    for (e, surfaces) in &at_edge {
        for v in brep.edges.get(*e).into_iter().flat_map(|b| &b.ends) {
            let s = at_vertex.entry(v).or_default();
            s.extend(
                surfaces
                    .iter()
                    .filter(|x| !s.contains(x))
                    .copied()
                    .collect::<Vec<_>>(),
            );
        }
    }
    let mut neighbours: BTreeMap<usize, std::collections::BTreeSet<usize>> = BTreeMap::new();
    for group in at_edge.values().chain(at_vertex.values()) {
        for a in group {
            for b in group.iter().filter(|b| *b != a) {
                neighbours.entry(*a).or_default().insert(*b);
            }
        }
    }
    let mut patches_of: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for (q, patch) in model.patches.iter().enumerate() {
        patches_of.entry(patch.source.surface).or_default().push(q);
    }
    for (p, patch) in model.patches.iter().enumerate() {
        if let Some(n) = neighbours.get(&patch.source.surface) {
            out[p] = n
                .iter()
                .filter_map(|s| patches_of.get(s))
                .flatten()
                .copied()
                .collect();
        }
    }
    out
}
