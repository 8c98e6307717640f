//! Silhouettes on trimmed faces: a sphere whose patches are trimmed by loops in their
//! parameter planes (a half-plane, a disc hole), against the same silhouette untrimmed and
//! the closed forms of the loops (`proofs/trimmed-faces.md`, 6).

use crate::trim_models::{circle, polygon, q, unit, with_face};
use limn::model::{Format, Model};
use limn::number::Rational;
use limn::testing::shapes;
use limn::{silhouette, ContourOptions, View};

fn sphere() -> Model {
    let mut m = Model::from_patches(Format::Json, shapes::sphere(&q(1, 1)));
    for p in &mut m.patches {
        p.source.parameters = Some(unit());
    }
    m
}

fn view() -> View {
    View::direction([1, 2, 3])
}

fn opts() -> ContourOptions {
    let mut o = ContourOptions::default();
    o.tol = Some(1e-6);
    o
}

/// The drawn (patch, u, v) points of every curve.
fn points(s: &limn::analysis::contour::curves::Silhouette) -> Vec<(usize, f64, f64)> {
    s.curves.iter().flat_map(|c| c.points_uv.clone()).collect()
}

/// The distance in space from `x` to the drawn polylines.
fn to_drawing(s: &limn::analysis::contour::curves::Silhouette, x: [f64; 3]) -> f64 {
    let mut best = f64::INFINITY;
    for c in &s.curves {
        for w in c.points.windows(2) {
            let (a, b) = (w[0], w[1]);
            let d: [f64; 3] = std::array::from_fn(|k| b[k] - a[k]);
            let len2: f64 = d.iter().map(|z| z * z).sum();
            let t = if len2 > 0.0 {
                ((0..3).map(|k| (x[k] - a[k]) * d[k]).sum::<f64>() / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let e: f64 = (0..3).map(|k| (a[k] + t * d[k] - x[k]).powi(2)).sum();
            best = best.min(e.sqrt());
        }
    }
    best
}

/// The drawn points on patch `p`, in (u, v) and in space.
fn on_patch(
    s: &limn::analysis::contour::curves::Silhouette,
    p: usize,
) -> Vec<([f64; 2], [f64; 3])> {
    s.curves
        .iter()
        .flat_map(|c| c.points_uv.iter().zip(&c.points))
        .filter(|(uv, _)| uv.0 == p)
        .map(|(uv, x)| ([uv.1, uv.2], *x))
        .collect()
}

/// The patch that carries the most of the untrimmed silhouette, and its points there.
fn busiest(all: &[(usize, f64, f64)]) -> (usize, Vec<[f64; 2]>) {
    let mut count = std::collections::BTreeMap::new();
    for &(p, _, _) in all {
        *count.entry(p).or_insert(0usize) += 1;
    }
    let (&p, _) = count.iter().max_by_key(|(_, &n)| n).unwrap();
    let pts = all
        .iter()
        .filter(|x| x.0 == p)
        .map(|&(_, u, v)| [u, v])
        .collect();
    (p, pts)
}

#[test]
fn a_half_plane_trim_clips_the_silhouette_at_its_line() {
    let whole = silhouette(&sphere(), &view(), &opts()).unwrap();
    assert!(whole.certified());
    let all = points(&whole);
    let (p, on_p) = busiest(&all);
    // The trim: the part u < c of patch p's square, with c inside the arc's range.
    let (lo, hi) = on_p
        .iter()
        .fold((1.0f64, 0.0f64), |(a, b), x| (a.min(x[0]), b.max(x[0])));
    // Not dyadic, so that the line is no box edge of the subdivision.
    let c = q((500.0 * (lo + hi)).round() as i64, 1000) + q(1, 3000);
    let cf = c.to_f64();
    let model = with_face(
        sphere(),
        p,
        Some(polygon(&[
            [q(0, 1), q(0, 1)],
            [c.clone(), q(0, 1)],
            [c.clone(), q(1, 1)],
            [q(0, 1), q(1, 1)],
        ])),
        Vec::new(),
    );
    let cut = silhouette(&model, &view(), &opts()).unwrap();
    assert!(cut.certified(), "{:?}", cut.unresolved);
    let trims = cut.trims.clone().unwrap();
    // The untrimmed polyline crosses u = c as often as the curve does (it is within 1e-6).
    let crossings = on_p
        .windows(2)
        .filter(|w| (w[0][0] - cf) * (w[1][0] - cf) < 0.0)
        .count();
    assert!(crossings >= 1);
    assert_eq!(trims.crossings, crossings);
    // The sphere is closed: every end of a curve is on a trimming curve, at a crossing or
    // where the curve passes from an untrimmed patch into the part of p trimmed away.
    let ends = cut.curves.iter().filter(|c| !c.closed).count() * 2;
    assert_eq!(trims.trim_ends, ends);
    assert!(ends >= 2 * crossings);
    // Sound: every drawn point on patch p is in the face (to the drawing's resolution).
    let drawn = points(&cut);
    for &(q_, u, _) in &drawn {
        if q_ == p {
            assert!(u <= cf + 1e-6, "a point at u = {u} > {cf} was kept");
        }
    }
    // Complete: every untrimmed point well inside the face is near a drawn one, and the
    // other patches are drawn as before.
    for (uv, x) in on_patch(&whole, p) {
        if uv[0] < cf - 1e-3 {
            let d = to_drawing(&cut, x);
            assert!(d < 4e-6, "the point {uv:?} inside the face was lost ({d})");
        }
    }
    let others = |v: &[(usize, f64, f64)]| v.iter().filter(|x| x.0 != p).count();
    assert!(others(&drawn) >= others(&all) - 2 * crossings);
    // The curves end on the line u = c.
    for curve in cut.curves.iter().filter(|c| !c.closed) {
        for end in [curve.points_uv[0], *curve.points_uv.last().unwrap()] {
            if end.0 == p {
                assert!(
                    (end.1 - cf).abs() < 1e-6,
                    "an end at {end:?} is not on u = {cf}"
                );
            }
        }
    }
    // The error bound stays within the tolerance, the trimmed ends included.
    assert!(cut
        .curves
        .iter()
        .all(|c| c.error_bound.unwrap() <= opts().tol.unwrap() * 2.0));
}

#[test]
fn a_disc_hole_removes_the_silhouette_inside_it() {
    let whole = silhouette(&sphere(), &view(), &opts()).unwrap();
    let all = points(&whole);
    let (p, on_p) = busiest(&all);
    // A hole of radius 1/8 about a point of the arc (its middle drawn point, rounded).
    let m = on_p[on_p.len() / 2];
    let centre = [m[0], m[1]].map(|x| Rational::from_f64((x * 1024.0).round() / 1024.0).unwrap());
    let (cx, cy) = (centre[0].to_f64(), centre[1].to_f64());
    let r = q(1, 8);
    let model = with_face(sphere(), p, None, vec![circle(centre, r, true)]);
    let cut = silhouette(&model, &view(), &opts()).unwrap();
    assert!(cut.certified(), "{:?}", cut.unresolved);
    let trims = cut.trims.clone().unwrap();
    let dist = |u: f64, v: f64| ((u - cx).powi(2) + (v - cy).powi(2)).sqrt();
    let crossings = on_p
        .windows(2)
        .filter(|w| (dist(w[0][0], w[0][1]) - 0.125) * (dist(w[1][0], w[1][1]) - 0.125) < 0.0)
        .count();
    assert_eq!(
        crossings, 2,
        "the arc passes through the hole's centre region"
    );
    assert_eq!(trims.crossings, 2);
    assert_eq!(trims.trim_ends, 2);
    let drawn = points(&cut);
    for &(q_, u, v) in &drawn {
        if q_ == p {
            assert!(
                dist(u, v) >= 0.125 - 1e-6,
                "a point in the hole was kept: ({u}, {v})"
            );
        }
    }
    for (uv, x) in on_patch(&whole, p) {
        if dist(uv[0], uv[1]) > 0.125 + 1e-3 {
            let d = to_drawing(&cut, x);
            assert!(d < 4e-6, "the point {uv:?} outside the hole was lost ({d})");
        }
    }
    // One closed curve became one open curve with both ends on the circle.
    assert_eq!(whole.curves.len(), 1);
    assert_eq!(cut.curves.len(), 1);
    assert!(!cut.curves[0].closed);
}

#[test]
fn a_face_that_misses_the_silhouette_drops_it_and_a_whole_face_keeps_it() {
    let whole = silhouette(&sphere(), &view(), &opts()).unwrap();
    let (p, _) = busiest(&points(&whole));
    // A tiny square face in a corner the curve does not reach: the arcs on p are dropped.
    let corner = |x: i64, y: i64| [q(x, 1000), q(y, 1000)];
    let far = points(&whole)
        .iter()
        .filter(|x| x.0 == p)
        .all(|x| x.1 > 0.01 || x.2 > 0.01);
    assert!(far, "the curve passes the corner");
    let model = with_face(
        sphere(),
        p,
        Some(polygon(&[
            corner(1, 1),
            corner(9, 1),
            corner(9, 9),
            corner(1, 9),
        ])),
        Vec::new(),
    );
    let cut = silhouette(&model, &view(), &opts()).unwrap();
    assert!(cut.certified());
    assert!(points(&cut).iter().all(|x| x.0 != p));
    assert!(cut.trims.as_ref().unwrap().dropped_arcs > 0);
    // The face that is the whole domain keeps everything.
    let model = with_face(sphere(), p, None, Vec::new());
    let same = silhouette(&model, &view(), &opts()).unwrap();
    assert_eq!(points(&same), points(&whole));
}

/// The IGES fixtures with trimmed faces, from the axes and two generic directions: every
/// silhouette certified on the faces (the seams and span sides of the closed cone and cylinder
/// on which the curve lies along a loop, the sides of the domain off the loops); CTS17806 from
/// +x, where the curve leaves the face, has its two crossings, each a curve end.
#[test]
fn the_fixtures_silhouettes_on_their_faces_are_certified() {
    let read = |name: &str| {
        limn::read_model(std::path::Path::new(&format!(
            "{}/fixtures/iges/occt/{name}",
            env!("CARGO_MANIFEST_DIR")
        )))
        .unwrap()
    };
    for name in [
        "CTS17806-38038.igs",
        "OCC8842_cone_Ideas.igs",
        "OCC8842_cylinder_Ideas.igs",
        "bug24012_face.igs",
    ] {
        let model = read(name);
        assert!(!model.faces.is_empty());
        let mut o = ContourOptions::default();
        o.tol = Some(1e-3 * model.diagonal());
        for d in [[1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 2, 3], [-2, 1, 1]] {
            let s = silhouette(&model, &View::direction(d), &o).unwrap();
            assert!(s.certified(), "{name} from {d:?}: {:?}", s.unresolved);
            let trims = s.trims.clone().unwrap();
            // Every trim end is an end of an open curve.
            let ends = 2 * s.curves.iter().filter(|c| !c.closed).count();
            assert!(trims.trim_ends <= ends, "{name} from {d:?}");
            if name.starts_with("CTS") && d == [1, 0, 0] {
                assert_eq!(trims.crossings, 2, "{name}");
                assert!(trims.trim_ends >= 2, "{name}");
            }
        }
    }
}

/// The parabolic curves of a torus (its top and bottom circles: lines of the patches on which
/// the curvature vanishes) on a patch trimmed by a half-plane across them: clipped at the
/// line like the silhouette, through the same machinery.
#[test]
fn parabolic_lines_of_a_torus_are_clipped_at_a_trim() {
    let torus = || {
        let mut m = Model::from_patches(Format::Json, shapes::torus(&q(3, 1), &q(1, 1)));
        for p in &mut m.patches {
            p.source.parameters = Some(unit());
        }
        m
    };
    let whole = limn::parabolic(&torus(), &opts()).unwrap();
    assert!(whole.certified());
    let all = points(&whole);
    let (p, on_p) = busiest(&all);
    // Cut across the axis along which the curve on p runs.
    let span = |a: usize| {
        let (lo, hi) = on_p
            .iter()
            .fold((1.0f64, 0.0f64), |(x, y), z| (x.min(z[a]), y.max(z[a])));
        (hi - lo, lo, hi)
    };
    let axis = if span(0).0 >= span(1).0 { 0 } else { 1 };
    let (_, lo, hi) = span(axis);
    let c = q((500.0 * (lo + hi)).round() as i64, 1000) + q(1, 3000);
    let cf = c.to_f64();
    let corner = |x: Rational, y: Rational| if axis == 0 { [x, y] } else { [y, x] };
    let model = with_face(
        torus(),
        p,
        Some(polygon(&if axis == 0 {
            [
                corner(q(0, 1), q(0, 1)),
                corner(c.clone(), q(0, 1)),
                corner(c.clone(), q(1, 1)),
                corner(q(0, 1), q(1, 1)),
            ]
        } else {
            [
                corner(q(0, 1), q(0, 1)),
                corner(q(0, 1), q(1, 1)),
                corner(c.clone(), q(1, 1)),
                corner(c.clone(), q(0, 1)),
            ]
        })),
        Vec::new(),
    );
    let cut = limn::parabolic(&model, &opts()).unwrap();
    assert!(cut.certified(), "{:?}", cut.unresolved);
    let trims = cut.trims.clone().unwrap();
    let crossings = on_p
        .windows(2)
        .filter(|w| (w[0][axis] - cf) * (w[1][axis] - cf) < 0.0)
        .count();
    assert!(crossings >= 1);
    assert!(trims.trim_ends >= crossings);
    for &(q_, u, v) in &points(&cut) {
        if q_ == p {
            let x = if axis == 0 { u } else { v };
            assert!(x <= cf + 1e-6, "a point at {x} > {cf} was kept");
        }
    }
    for (uv, x) in on_patch(&whole, p) {
        if uv[axis] < cf - 1e-3 {
            let d = to_drawing(&cut, x);
            assert!(d < 4e-6, "the point {uv:?} inside the face was lost ({d})");
        }
    }
}
