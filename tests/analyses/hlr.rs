//! Hidden-line drawings against closed forms: every certified piece's QI is checked against
//! an independent analytic ray count (spheres: a quadratic; tori: the quartic, sampled and
//! bisected in f64) at its interior drawn points, from many directions.

use limn::analysis::view::View;
use limn::analysis::visibility::hlr::{hidden_lines, HiddenLines, HlrOptions, LineKind};
use limn::model::{Format, Model, WeldTolerance};
use limn::number::Rational;
use limn::reason::Reason;
use limn::surface::RationalPatch;
use limn::testing::shapes;

use crate::analytic;
use analytic::{reference_at, shifted, to_segment, Shape, Viewer};

fn q(n: i64) -> Rational {
    Rational::from(n)
}

/// Checks every certified piece against the reference at its interior drawn points; returns
/// (points checked, pieces, certified pieces).
fn check(h: &HiddenLines, shapes: &[Shape], d: [f64; 3], what: &str) -> (usize, usize, usize) {
    check_viewer(h, shapes, Viewer::Dir(d), what)
}

fn check_viewer(
    h: &HiddenLines,
    shapes: &[Shape],
    viewer: Viewer,
    what: &str,
) -> (usize, usize, usize) {
    let mut checked = 0;
    for p in &h.pieces {
        let Some(qi) = p.qi else { continue };
        let n = p.points.len();
        for pt in p.points.iter().skip(1).take(n.saturating_sub(2)) {
            if let Some(want) = reference_at(shapes, *pt, viewer) {
                assert_eq!(
                    qi, want,
                    "{what}: {:?} piece on patch {} {:?} param {:?} at {pt:?}",
                    p.kind, p.patch, p.edge, p.param
                );
                checked += 1;
            }
        }
    }
    let certified = h.pieces.iter().filter(|p| p.certified).count();
    (checked, h.pieces.len(), certified)
}

fn run(patches: Vec<RationalPatch>, dir: [i64; 3]) -> HiddenLines {
    let model = Model::from_patches(Format::Json, patches);
    let view = View::Direction(dir.map(Rational::from));
    hidden_lines(
        &model,
        &view,
        &HlrOptions::default().with_weld(WeldTolerance::Exact),
    )
    .unwrap()
}

const DIRECTIONS: [[i64; 3]; 6] = [
    [1, 2, 3],
    [-2, 1, -5],
    [3, -1, 1],
    [1, 1, -7],
    [-4, -3, 2],
    [2, 5, -1],
];

#[test]
fn two_spheres_from_many_directions() {
    let shapes_ = [
        Shape::Sphere([0.0; 3], 1.0),
        Shape::Sphere([1.0, 0.0, -3.0], 1.0),
    ];
    let mut total = 0;
    for dir in DIRECTIONS {
        let mut patches = shapes::sphere(&q(1));
        patches.extend(shifted(shapes::sphere(&q(1)), [1, 0, -3]));
        let h = run(patches, dir);
        let d = dir.map(|x| x as f64);
        let (checked, pieces, certified) = check(&h, &shapes_, d, &format!("spheres {dir:?}"));
        println!(
            "spheres {dir:?}: {pieces} pieces, {certified} certified, {checked} points checked"
        );
        total += checked;
        // Both outlines are drawn and proven.
        assert!(h
            .pieces
            .iter()
            .any(|p| p.kind == LineKind::Silhouette && p.certified));
        // Disjoint spheres: no intersection reported.
        assert!(h.intersecting_patches.is_empty());
    }
    assert!(total > 500, "{total}");
}

#[test]
fn torus_from_many_directions() {
    let shapes_ = [Shape::Torus([0.0; 3], 2.0, 1.0)];
    let mut total = 0;
    for dir in DIRECTIONS {
        let h = run(shapes::torus(&q(2), &q(1)), dir);
        let d = dir.map(|x| x as f64);
        let (checked, pieces, certified) = check(&h, &shapes_, d, &format!("torus {dir:?}"));
        println!("torus {dir:?}: {pieces} pieces, {certified} certified, {checked} points checked");
        total += checked;
    }
    assert!(total > 500, "{total}");
}

/// Lemma C (proofs/hidden-lines.md): from these directions the torus' inner outline has cusps.
/// Each is proven (a cut where the image tangent vanishes, the run around it injective), the
/// pieces on both sides get a QI, and every certified QI agrees with the analytic count. The
/// torus R = 3 turned by the rational rotation of `cubics.rs` and seen along (7, 2, 4) is
/// certified whole (12 of 111 pieces were unresolved before the lemma).
#[test]
fn tori_from_generic_directions_are_certified() {
    let shapes_ = [Shape::Torus([0.0; 3], 2.0, 1.0)];
    for dir in [[-4, -3, 2], [2, 5, -1], [3, -1, 1]] {
        let h = run(shapes::torus(&q(2), &q(1)), dir);
        let d = dir.map(|x| x as f64);
        let (checked, pieces, certified) = check(&h, &shapes_, d, &format!("torus {dir:?}"));
        println!(
            "torus {dir:?}: {pieces} pieces, {certified} certified, {} cusps",
            h.stats.cusps
        );
        // Two fish tails on the inner outline, two cusps each.
        assert_eq!(h.stats.cusps, 4, "{dir:?}");
        assert!(checked > 300);
        // No piece is left unresolved for a cusp.
        assert!(h
            .pieces
            .iter()
            .all(|p| !matches!(p.reason, Some(limn::reason::Reason::OutlineCusp))));
        if dir != [3, -1, 1] {
            // ([3, -1, 1] keeps two slivers at a patch corner, not at a cusp.)
            assert!(h.is_certified(), "{dir:?}: {certified} of {pieces}");
        }
    }
    let rot = shapes::rotation(0, 2, 1);
    let zero = [q(0), q(0), q(0)];
    let patches: Vec<RationalPatch> = shapes::torus(&q(3), &q(1))
        .iter()
        .map(|p| shapes::transform(p, &rot, &zero))
        .collect();
    let h = run(patches, [7, 2, 4]);
    assert!(h.stats.cusps >= 2);
    assert!(h.is_certified());
}

#[test]
fn a_sphere_in_front_of_a_torus() {
    let shapes_ = [
        Shape::Torus([0.0; 3], 2.0, 1.0),
        Shape::Sphere([0.0, 0.0, 3.0], 1.0),
    ];
    let mut patches = shapes::torus(&q(2), &q(1));
    patches.extend(shifted(shapes::sphere(&q(1)), [0, 0, 3]));
    let dir = [1, 2, -6];
    let h = run(patches, dir);
    let (checked, pieces, certified) = check(&h, &shapes_, dir.map(|x| x as f64), "sphere+torus");
    println!("sphere+torus: {pieces} pieces, {certified} certified, {checked} points checked");
    assert!(checked > 100);
    // The sphere hides part of the torus: some torus piece has QI 2.
    assert!(h.pieces.iter().any(|p| p.patch < 16 && p.qi == Some(2)));
    assert!(h.intersecting_patches.is_empty());
}

/// Two unit spheres whose centres are 1 apart intersect in a circle: the penetrations of one's
/// lines through the other are found, and the pairs reported (one patch of each sphere).
#[test]
fn intersecting_spheres_are_reported() {
    let mut patches = shapes::sphere(&q(1));
    let n = patches.len();
    patches.extend(shifted(shapes::sphere(&q(1)), [1, 0, 0]));
    let h = run(patches, [1, 2, 3]);
    assert!(!h.intersecting_patches.is_empty());
    for [a, b] in &h.intersecting_patches {
        assert!(*a < n && *b >= n, "{a}-{b}");
    }
}

/// Two unit spheres with centres 0 and c = (1/2, 1/3, 2/7) meet in a circle of radius
/// ρ = √(1 − |c|²/4) in the plane x·c = |c|²/2. It is drawn as intersection lines: every drawn
/// point lies on both spheres, the lines add up to the whole circle (completeness: their
/// length is the circumference, less only what chords cut short), and the QI of every certified
/// piece is the analytic ray count at its interior points (soundness), from several directions.
#[test]
fn the_intersection_circle_of_two_spheres_is_drawn_with_its_qi() {
    // (With c_z = 1/5 the circle passes within 5e-4 of both spheres' poles, where the
    // patches' parameterizations degenerate and the curve solver leaves boxes unresolved.)
    let c = [(1, 2), (1, 3), (2, 7)];
    let cf = c.map(|(a, b)| a as f64 / b as f64);
    let mut patches = shapes::sphere(&q(1));
    let shift = c.map(Rational::from);
    let id = shapes::rotation(0, 1, 0);
    patches.extend(
        shapes::sphere(&q(1))
            .iter()
            .map(|p| shapes::transform(p, &id, &shift)),
    );
    let spheres = [Shape::Sphere([0.0; 3], 1.0), Shape::Sphere(cf, 1.0)];
    let rho = (1.0 - cf.iter().map(|x| x * x).sum::<f64>() / 4.0).sqrt();
    let circumference = 2.0 * std::f64::consts::PI * rho;
    for dir in [[1, 2, 3], [-2, 1, -5], [3, -1, 1]] {
        let h = run(patches.clone(), dir);
        let what = format!("direction {dir:?}");
        check(&h, &spheres, dir.map(|x| x as f64), &what);
        let meets: Vec<_> = h
            .pieces
            .iter()
            .filter(|p| p.kind == LineKind::Intersection)
            .collect();
        assert_eq!(h.stats.intersection_unresolved, 0, "{what}");
        // Every intersection piece's crossings decided; a few ray tests are refused beside the
        // points where the circle meets a silhouette (the image map is nearly singular
        // there): measured 250 of 252 pieces certified from (1, 2, 3).
        let certified = meets.iter().filter(|p| p.certified).count();
        assert!(
            meets.iter().all(|p| p.certified
                || matches!(
                    p.reason,
                    Some(Reason::RayNearBoundary { .. }) | Some(Reason::OwnSheet { .. })
                )),
            "{what}"
        );
        assert!(
            certified * 100 >= meets.len() * 97,
            "{what}: {certified} of {}",
            meets.len()
        );
        // Each piece on one patch of each sphere.
        assert!(meets
            .iter()
            .all(|p| p.patch < 8 && p.meets.is_some_and(|m| m >= 8)));
        let mut length = 0.0;
        for p in &meets {
            for x in &p.points {
                let r1 = x.iter().map(|v| v * v).sum::<f64>();
                let r2 = (0..3).map(|i| (x[i] - cf[i]).powi(2)).sum::<f64>();
                assert!(
                    (r1 - 1.0).abs() < 1e-9 && (r2 - 1.0).abs() < 1e-9,
                    "{what}: {x:?}"
                );
            }
            for w in p.points.windows(2) {
                length += (0..3)
                    .map(|i| (w[1][i] - w[0][i]).powi(2))
                    .sum::<f64>()
                    .sqrt();
            }
        }
        assert!(
            length <= circumference && length > 0.999 * circumference,
            "{what}: drawn {length}, circumference {circumference}"
        );
        // Both visible and hidden stretches of the circle, from every one of these views.
        assert!(meets.iter().any(|p| p.qi == Some(0)) && meets.iter().any(|p| p.qi > Some(0)));
    }
}

/// Two planes whose line of intersection leaves both squares through a corner of their
/// domain at each end: z = x − 1/2 and z = y over the unit square meet on y = x − 1/2, from
/// (1/2, 0, 0), on the sides v = 0 and t = 0 at once, to (1, 1/2, 1/2), on u = 1 and s = 1.
/// The curve is solved past those sides and clipped to the squares: one straight line of
/// length √3/2, certified, every drawn point on it.
#[test]
fn an_intersection_through_corners_of_the_domain_is_clipped_to_the_squares() {
    let h = |a: i64, b: i64| Rational::from((a, b));
    let first = shapes::graph(
        &[(0, 0, h(-1, 2)), (1, 0, q(1))],
        [q(0), q(1)],
        [q(0), q(1)],
    );
    let second = shapes::graph(&[(0, 1, q(1))], [q(0), q(1)], [q(0), q(1)]);
    for dir in [[1, 2, 3], [-2, 1, -5]] {
        let d = run(vec![first.clone(), second.clone()], dir);
        let meets: Vec<_> = d
            .pieces
            .iter()
            .filter(|p| p.kind == LineKind::Intersection)
            .collect();
        assert!(
            !meets.is_empty() && meets.iter().all(|p| p.certified),
            "{dir:?}"
        );
        assert_eq!(d.stats.intersection_unresolved, 0, "{dir:?}");
        let mut length = 0.0;
        for p in &meets {
            for x in &p.points {
                assert!((x[1] - (x[0] - 0.5)).abs() < 1e-9 && (x[2] - x[1]).abs() < 1e-9);
            }
            for w in p.points.windows(2) {
                length += (0..3)
                    .map(|i| (w[1][i] - w[0][i]).powi(2))
                    .sum::<f64>()
                    .sqrt();
            }
        }
        let want = 0.75f64.sqrt();
        assert!(
            (length - want).abs() < 1e-6,
            "{dir:?}: {length} against {want}"
        );
    }
    // With clusters off an intersection curve is still no outline: the same pieces' QIs.
    let model = Model::from_patches(Format::Json, vec![first, second]);
    let view = View::Direction([1, 2, 3].map(Rational::from));
    let opts = HlrOptions {
        clusters: false,
        ..HlrOptions::default()
    };
    let off = hidden_lines(&model, &view, &opts.with_weld(WeldTolerance::Exact)).unwrap();
    let mut meets = off
        .pieces
        .iter()
        .filter(|p| p.kind == LineKind::Intersection)
        .peekable();
    assert!(meets.peek().is_some());
    assert!(meets.all(|p| p.certified && p.outline == Some(false)));
}

#[test]
fn two_spheres_in_perspective() {
    let shapes_ = [
        Shape::Sphere([0.0; 3], 1.0),
        Shape::Sphere([1.0, 0.0, -3.0], 1.0),
    ];
    let mut patches = shapes::sphere(&q(1));
    patches.extend(shifted(shapes::sphere(&q(1)), [1, 0, -3]));
    let model = Model::from_patches(Format::Json, patches);
    let eye = [-2, -3, 9];
    let view = View::Eye(eye.map(Rational::from));
    let h = hidden_lines(
        &model,
        &view,
        &HlrOptions::default().with_weld(WeldTolerance::Exact),
    )
    .unwrap();
    let (checked, pieces, certified) = check_viewer(
        &h,
        &shapes_,
        Viewer::Eye(eye.map(|x| x as f64)),
        "spheres from an eye",
    );
    println!(
        "spheres from {eye:?}: {pieces} pieces, {certified} certified, {checked} points checked"
    );
    assert!(checked > 200, "{checked}");
    // The upper sphere hides part of the lower one.
    assert!(h.pieces.iter().any(|p| p.patch >= 8 && p.qi == Some(2)));
}

/// Random directions (a seeded generator; the seed is printed): a sphere in front of a torus,
/// every certified piece against the analytic ray count. `LIMN_HLR_DIRECTIONS=N` sweeps N
/// directions (default 3), `LIMN_SEED=S` replays a run.
#[test]
fn random_directions_sweep() {
    let n: usize = std::env::var("LIMN_HLR_DIRECTIONS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(3);
    let seed: u64 = std::env::var("LIMN_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0x5eed_0001);
    println!("random_directions_sweep: LIMN_SEED={seed} LIMN_HLR_DIRECTIONS={n}");
    let mut state = seed;
    let mut next = || {
        // SplitMix64.
        state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) % 19) as i64 - 9
    };
    let shapes_ = [
        Shape::Torus([0.0; 3], 2.0, 1.0),
        Shape::Sphere([0.0, 0.0, 3.0], 1.0),
    ];
    let mut total = 0;
    let mut done = 0;
    while done < n {
        let dir = [next(), next(), next()];
        if dir == [0, 0, 0] {
            continue;
        }
        done += 1;
        let mut patches = shapes::torus(&q(2), &q(1));
        patches.extend(shifted(shapes::sphere(&q(1)), [0, 0, 3]));
        let h = run(patches, dir);
        let (checked, pieces, certified) = check(
            &h,
            &shapes_,
            dir.map(|x| x as f64),
            &format!("seed {seed}, {dir:?}"),
        );
        println!("{dir:?}: {pieces} pieces, {certified} certified, {checked} points checked");
        total += checked;
    }
    assert!(total > 100 * n, "{total}");
}

/// A regression found in review: a silhouette line inside a patch (where the silhouette
/// function vanishes identically, here the fold x = 0 of the parabolic cylinder z = x² seen
/// along x) is a line of the drawing, and the lines behind it are cut where they cross it.
/// The square behind it is checked against the analytic count: a point (10, y, z) of it is
/// behind the sheets x = ±√z that exist there (x ≤ y ≤ x + 1), behind none when z < 0.
#[test]
fn a_silhouette_line_inside_a_patch_is_a_line_of_the_drawing() {
    let p = |x: i64, y: i64, z: i64| [q(x), q(y), q(z)];
    let cylinder = RationalPatch::polynomial(
        [2, 1],
        vec![
            p(-1, -1, 1),
            p(-1, 0, 1),
            p(1, 1, -3),
            p(1, 2, -3),
            p(3, 3, 9),
            p(3, 4, 9),
        ],
    )
    .unwrap();
    let r = |n: i64, d: i64| Rational::from((n, d));
    let pt = |y: Rational, z: Rational| [q(10), y, z];
    let square = RationalPatch::polynomial(
        [1, 1],
        vec![
            pt(r(1, 2), q(-1)),
            pt(r(1, 2), r(1, 5)),
            pt(r(7, 10), q(-1)),
            pt(r(7, 10), r(1, 5)),
        ],
    )
    .unwrap();
    let h = run(vec![cylinder, square], [1, 0, 0]);
    assert!(h.is_certified());
    // The fold line is drawn, visible.
    assert!(h
        .pieces
        .iter()
        .any(|x| x.patch == 0 && x.kind == LineKind::Silhouette && x.qi == Some(0)));
    let mut checked = 0;
    for piece in h.pieces.iter().filter(|x| x.patch == 1) {
        let n = piece.points.len();
        for pt in piece.points.iter().skip(1).take(n - 2) {
            let (y, z) = (pt[1], pt[2]);
            if z.abs() < 1e-6 || (z - 0.2).abs() < 1e-6 {
                continue;
            }
            let mut want = 0;
            if z > 0.0 {
                for x in [z.sqrt(), -z.sqrt()] {
                    if (x - y).abs() > 1e-6 && (x + 1.0 - y).abs() > 1e-6 && x <= y && y <= x + 1.0
                    {
                        want += 1;
                    }
                }
            }
            assert_eq!(piece.qi, Some(want), "{piece:?} at {pt:?}");
            checked += 1;
        }
    }
    assert!(checked > 10, "{checked}");
}

/// Distance from `p` to the unit circle about the origin in the plane with unit normal `n`.
fn to_great_circle(p: [f64; 3], n: [f64; 3]) -> f64 {
    let h = p[0] * n[0] + p[1] * n[1] + p[2] * n[2];
    let perp = [p[0] - h * n[0], p[1] - h * n[1], p[2] - h * n[2]];
    let r = (perp[0] * perp[0] + perp[1] * perp[1] + perp[2] * perp[2]).sqrt();
    (h * h + (r - 1.0) * (r - 1.0)).sqrt()
}

/// Drawing to a tolerance (`proofs/hidden-lines.md`, "Drawing to a tolerance"), on the unit
/// sphere, whose lines are great circles: the silhouette (normal to the view) and the patch
/// sides (the equator and the meridians in the planes x = 0 and y = 0). Soundness: every
/// drawn point (vertices and points along each chord) is within the piece's bound of its
/// circle. Completeness: every point of each circle is within the largest bound (and the
/// 1e-12-wide cut enclosures the pieces leave out) of a drawn chord of its kind. A tenfold
/// tighter tolerance gives more points.
#[test]
fn drawing_to_a_tolerance_on_the_sphere() {
    let model = Model::from_patches(Format::Json, shapes::sphere(&q(1)));
    let dir = [1i64, 2, 3];
    let view = View::Direction(dir.map(Rational::from));
    let norm = (14f64).sqrt();
    let d = dir.map(|x| x as f64 / norm);
    let axes = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let mut points = Vec::new();
    for tol in [1e-6, 1e-9] {
        let opts = HlrOptions {
            tol: Some(tol),
            ..HlrOptions::default()
        };
        let h = hidden_lines(&model, &view, &opts.clone().with_weld(WeldTolerance::Exact)).unwrap();
        let largest = h.largest_error().expect("every piece bounded");
        assert!(largest <= tol, "{largest} > {tol}");
        let mut drawn = 0;
        for p in &h.pieces {
            let bound = p.error_bound.expect("bounded");
            assert!(bound <= tol);
            // Its circle: the silhouette's, or the side's (the plane its middle point lies in).
            let mid = p.points[p.points.len() / 2];
            let n = match p.kind {
                LineKind::Silhouette => d,
                LineKind::Boundary => *axes
                    .iter()
                    .min_by(|a, b| to_great_circle(mid, **a).total_cmp(&to_great_circle(mid, **b)))
                    .unwrap(),
                LineKind::Trim => panic!("an untrimmed sphere has no trimming lines"),
                LineKind::Intersection => panic!("one sphere has no intersection curves"),
            };
            for w in p.points.windows(2) {
                for k in 0..=8 {
                    let t = k as f64 / 8.0;
                    let x = [0, 1, 2].map(|i| w[0][i] + t * (w[1][i] - w[0][i]));
                    let e = to_great_circle(x, n);
                    assert!(
                        e <= bound,
                        "tol {tol}: {:?} piece on patch {} at {x:?}: {e} > {bound}",
                        p.kind,
                        p.patch
                    );
                }
            }
            drawn += p.points.len();
        }
        // Completeness: the four circles sampled densely.
        let circles = [
            (LineKind::Silhouette, d),
            (LineKind::Boundary, axes[0]),
            (LineKind::Boundary, axes[1]),
            (LineKind::Boundary, axes[2]),
        ];
        for (kind, n) in circles {
            // An orthonormal basis of the circle's plane.
            let a = if n[0].abs() < 0.9 {
                [1.0, 0.0, 0.0]
            } else {
                [0.0, 1.0, 0.0]
            };
            let h0 = a[0] * n[0] + a[1] * n[1] + a[2] * n[2];
            let e1 = [a[0] - h0 * n[0], a[1] - h0 * n[1], a[2] - h0 * n[2]];
            let l = (e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]).sqrt();
            let e1 = e1.map(|x| x / l);
            let e2 = [
                n[1] * e1[2] - n[2] * e1[1],
                n[2] * e1[0] - n[0] * e1[2],
                n[0] * e1[1] - n[1] * e1[0],
            ];
            // (Fewer samples at the finer tolerance: each is checked against every chord.)
            let samples = if tol > 1e-7 { 2000 } else { 150 };
            for k in 0..samples {
                let th = (k as f64 + 0.37) * std::f64::consts::TAU / samples as f64;
                let x = [0, 1, 2].map(|i| th.cos() * e1[i] + th.sin() * e2[i]);
                let near = h
                    .pieces
                    .iter()
                    .filter(|p| p.kind == kind)
                    .flat_map(|p| p.points.windows(2).map(|w| to_segment(x, w[0], w[1])))
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    near <= largest + 1e-11,
                    "tol {tol}: {kind:?} circle {n:?} at {x:?}: {near}"
                );
            }
        }
        println!(
            "sphere, tol {tol}: {} pieces, {drawn} points, largest bound {largest:.3e}",
            h.pieces.len()
        );
        points.push(drawn);
    }
    assert!(points[1] > points[0], "{points:?}");
}

/// A grid of 2,500 bilinear patches under a time limit of 50 ms (issue 26 §2): the search for
/// crossings among some 10⁴ segments stops at the deadline (it ran to the end before, about
/// 20 s on 12,100 patches with `--time-limit 1`), everything not searched is unresolved with
/// the time limit as its reason, and the run ends within a generous allowance (the per-patch
/// set-up before the search is not interrupted).
#[test]
fn a_large_grid_respects_the_time_limit() {
    let m = Model::from_patches(Format::Json, shapes::bilinear_grid(50, 50));
    let mut opts = HlrOptions::default().with_weld(WeldTolerance::Exact);
    let start = std::time::Instant::now();
    opts.curve.deadline = Some(start + std::time::Duration::from_millis(50));
    let h = hidden_lines(&m, &View::Direction([q(1), q(2), q(-3)]), &opts).unwrap();
    let took = start.elapsed();
    assert!(!h.is_certified());
    assert!(h
        .pieces
        .iter()
        .any(|p| p.reason == Some(limn::Reason::TimeLimit)));
    assert!(h.pieces.iter().all(|p| p.certified || p.reason.is_some()));
    assert!(took.as_secs_f64() < 120.0, "{took:?}");
    println!("2,500 patches under a 50 ms limit: {took:?}");
}

/// One patch whose weights span 10⁻³⁰⁰ to 10³⁰⁰ under a time limit of 0.5 s (issue 26 §2): the
/// cutting of silhouette arcs into monotone pieces stops at the deadline (it ran 13 s with
/// `--time-limit 1` before, 1.8 s after, in release), and what is left is unresolved by the
/// time limit.
#[test]
fn extreme_weights_respect_the_time_limit() {
    let w = |s: &str| limn::number::parse_exact(s).unwrap();
    let weights = [
        "1e-300", "1", "1e300", "1", "1e150", "1", "1e300", "1", "1e-300",
    ]
    .map(w);
    let points = (0..3)
        .flat_map(|i| (0..3).map(move |j| [q(i), q(j), q((i * j) % 3)]))
        .collect();
    let patch = RationalPatch::new([2, 2], points, weights.to_vec()).unwrap();
    let m = Model::from_patches(Format::Json, vec![patch]);
    let mut opts = HlrOptions::default().with_weld(WeldTolerance::Exact);
    let start = std::time::Instant::now();
    opts.curve.deadline = Some(start + std::time::Duration::from_millis(500));
    let h = hidden_lines(&m, &View::Direction([q(1), q(2), q(3)]), &opts).unwrap();
    let took = start.elapsed();
    assert!(h.pieces.iter().all(|p| p.certified || p.reason.is_some()));
    assert!(took.as_secs_f64() < 60.0, "{took:?}");
    println!("weights 1e-300..1e300 under a 0.5 s limit: {took:?}");
}

/// The length of the pieces of a drawing with QI `qi`.
fn length_with_qi(h: &HiddenLines, qi: Option<usize>) -> f64 {
    h.pieces
        .iter()
        .filter(|p| p.qi == qi)
        .flat_map(|p| p.points.windows(2))
        .map(|w| {
            (0..3)
                .map(|k| (w[1][k] - w[0][k]).powi(2))
                .sum::<f64>()
                .sqrt()
        })
        .sum()
}

/// An eye at `1e308 (1, 1, 1)` (issue 26 §2; `proofs/projection.md`): the image and depth are
/// written relative to the model, so the drawing is certified and is the drawing from
/// `1000 (1, 1, 1)` up to the perspective (before, every piece was unresolved: the image
/// polynomials overflowed f64).
#[test]
fn an_eye_very_far_away_draws_like_a_far_one() {
    let m = Model::from_patches(Format::Json, shapes::sphere(&q(1)));
    let opts = HlrOptions::default().with_weld(WeldTolerance::Exact);
    let big = limn::number::parse_exact("1e308").unwrap();
    let far = hidden_lines(&m, &View::Eye([big.clone(), big.clone(), big]), &opts).unwrap();
    let near = hidden_lines(&m, &View::Eye([q(1000), q(1000), q(1000)]), &opts).unwrap();
    for h in [&far, &near] {
        assert!(h.is_certified());
        assert!(h
            .pieces
            .iter()
            .filter(|p| p.kind == LineKind::Silhouette)
            .all(|p| p.qi == Some(0)));
    }
    for qi in [Some(0), Some(1)] {
        let (a, b) = (length_with_qi(&far, qi), length_with_qi(&near, qi));
        assert!((a - b).abs() < 0.01 * b, "QI {qi:?}: {a} against {b}");
    }
}

/// An eye written with 10,000 digits (`3 + 10⁻¹⁰⁰⁰⁰`) under a time limit of 0.5 s (issue 26 §2,
/// a fuzzer's finding: 13.6 s with `--time-limit 2` on an IGES part): the image axes carry the
/// eye's digits once, the depth axis is short (`proofs/projection.md`), and past the deadline
/// the segments are set up without their tangents (unresolved by the time limit).
#[test]
fn a_long_exact_eye_respects_the_time_limit() {
    let m = Model::from_patches(Format::Json, shapes::sphere(&q(1)));
    let e = Rational::from(3) + limn::number::parse_exact("1e-10000").unwrap();
    let view = View::Eye([e, Rational::from((1, 3)), q(0)]);
    let mut opts = HlrOptions::default().with_weld(WeldTolerance::Exact);
    let start = std::time::Instant::now();
    opts.curve.deadline = Some(start + std::time::Duration::from_millis(500));
    let h = hidden_lines(&m, &view, &opts).unwrap();
    let took = start.elapsed();
    assert!(h.pieces.iter().all(|p| p.certified || p.reason.is_some()));
    assert!(took.as_secs_f64() < 60.0, "{took:?}");
    println!("an eye of 10,000 digits under a 0.5 s limit: {took:?}");
}
