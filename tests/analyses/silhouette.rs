//! Silhouettes of exact closed-form models: loop counts (completeness and soundness of the
//! topology), every output crossing on the true silhouette, degenerate cases reported.

use limn::analysis::contour::silhouette::silhouette;
use limn::ContourOptions;

use limn::analysis::view::View;
use limn::model::{Format, Model, WeldTolerance};
use limn::number::Rational;
use limn::solver::{CrossingId, CurveOptions};
use limn::testing::shapes;

use crate::analytic;

fn q(a: i64, b: i64) -> Rational {
    Rational::from((a, b))
}

fn model(patches: Vec<limn::surface::RationalPatch>) -> Model {
    Model::from_patches(Format::Json, patches)
}

/// The silhouette with default options, exact welding and no tolerance.
fn solve(m: &Model, view: &View) -> limn::analysis::contour::curves::Silhouette {
    silhouette(
        m,
        view,
        &ContourOptions::new(CurveOptions::default(), WeldTolerance::Exact, None),
    )
    .expect("a valid view")
}

fn dir(x: i64, y: i64, z: i64) -> View {
    View::Direction([q(x, 1), q(y, 1), q(z, 1)])
}

/// For a sphere about the origin the normal is parallel to the position, so the silhouette
/// for direction V is S · V = 0: check every crossing's location box brackets it, exactly.
fn sphere_crossings_on_true_silhouette(
    m: &Model,
    s: &limn::analysis::contour::curves::Silhouette,
    v: &[Rational; 3],
) {
    for (p, t) in s.patches.iter().enumerate() {
        // The crossings of the arcs kept (arcs along collapsed sides are dropped).
        let kept: Vec<CrossingId> = t.arcs.iter().flat_map(|a| [a.from, a.to]).collect();
        for (id, [lo, hi]) in t
            .locations
            .iter()
            .filter(|(id, _)| kept.contains(id))
            .map(|(id, r)| (id, r.corners()))
        {
            let f = |x: [f64; 2]| {
                let pt = m.patches[p].surface.eval(
                    &Rational::from_f64(x[0]).unwrap(),
                    &Rational::from_f64(x[1]).unwrap(),
                );
                (0..3)
                    .map(|k| Rational::from(&pt[k] * &v[k]))
                    .sum::<Rational>()
            };
            let (a, b) = (f(lo), f(hi));
            match id {
                CrossingId::Exact { .. } => assert_eq!(a, 0),
                CrossingId::Segment { .. } => {
                    assert!(Rational::from(&a * &b) <= 0, "patch {p} {id:?}")
                }
            }
        }
    }
}

#[test]
fn sphere_has_one_loop_from_generic_directions() {
    let m = model(shapes::sphere(&q(3, 2)));
    for (x, y, z) in [(1, 2, 3), (-2, 1, 5), (3, -4, 1), (1, 1, -7)] {
        let s = silhouette(
            &m,
            &dir(x, y, z),
            &ContourOptions::new(CurveOptions::default(), WeldTolerance::Exact, None),
        )
        .expect("a valid view");
        assert!(s.unresolved.is_empty(), "{:?}", s.unresolved);
        assert!(s.unjoined_edges.is_empty(), "{:?}", s.unjoined_edges);
        assert_eq!(
            s.curves.len(),
            1,
            "direction ({x},{y},{z}): {:#?}",
            s.curves
                .iter()
                .map(|c| (c.closed, c.patches.clone()))
                .collect::<Vec<_>>()
        );
        assert!(s.curves[0].closed && s.curves[0].certified_topology);
        sphere_crossings_on_true_silhouette(&m, &s, &[q(x, 1), q(y, 1), q(z, 1)]);
        // The poles are collapsed sides, reported as degenerate.
        assert_eq!(
            s.degenerate
                .iter()
                .filter(|d| d.kind == "collapsed side")
                .count(),
            8
        );
        assert_eq!(
            s.escalations.escalated(),
            0,
            "generic directions need no escalation"
        );
    }
}

#[test]
fn torus_has_two_loops_from_generic_directions() {
    let m = model(shapes::torus(&q(3, 1), &q(1, 1)));
    for (x, y, z) in [(1, 2, 3), (2, -1, 4), (-3, 1, 2)] {
        let s = silhouette(
            &m,
            &dir(x, y, z),
            &ContourOptions::new(CurveOptions::default(), WeldTolerance::Exact, None),
        )
        .expect("a valid view");
        assert!(s.unresolved.is_empty(), "{:?}", s.unresolved);
        let closed = s
            .curves
            .iter()
            .filter(|c| c.closed && c.certified_topology)
            .count();
        assert_eq!(
            closed,
            2,
            "direction ({x},{y},{z}): {} curves",
            s.curves.len()
        );
        assert_eq!(s.curves.len(), 2);
    }
}

#[test]
fn perspective_sphere_is_one_loop_and_edge_on_plane_is_degenerate() {
    let m = model(shapes::sphere(&q(1, 1)));
    let s = silhouette(
        &m,
        &View::Eye([q(1, 3), q(2, 1), q(5, 1)]),
        &ContourOptions::new(CurveOptions::default(), WeldTolerance::Exact, None),
    )
    .expect("a valid view");
    assert!(s.unresolved.is_empty());
    assert_eq!(s.curves.len(), 1);
    assert!(s.curves[0].closed && s.curves[0].certified_topology);
    let plane = model(vec![shapes::plane_square(&q(1, 1))]);
    let s = silhouette(
        &plane,
        &dir(1, 2, 0),
        &ContourOptions::new(CurveOptions::default(), WeldTolerance::Exact, None),
    )
    .expect("a valid view");
    assert_eq!(s.degenerate.len(), 1);
    assert_eq!(s.degenerate[0].kind, "edge-on");
    assert!(s.curves.is_empty());
}

#[test]
fn thread_count_does_not_change_the_answer() {
    let m = model(shapes::torus(&q(3, 1), &q(1, 1)));
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            silhouette(
                &m,
                &dir(1, 2, 3),
                &ContourOptions::new(CurveOptions::default(), WeldTolerance::Exact, None),
            )
            .expect("a valid view")
        })
    };
    let (a, b) = (run(1), run(2));
    assert_eq!(a.curves, b.curves);
}

#[test]
fn axis_views_along_patch_edges_and_through_poles_are_certified() {
    // Along z the silhouette is the equator, which is exactly the shared edge between the
    // southern and northern patches; along x or y it is a great circle running along meridian
    // edges and through both poles (collapsed sides).
    let m = model(shapes::sphere(&q(1, 1)));
    for (x, y, z) in [(0, 0, 1), (1, 0, 0), (0, 1, 0), (1, 1, 0), (1, 2, 0)] {
        let s = silhouette(
            &m,
            &dir(x, y, z),
            &ContourOptions::new(CurveOptions::default(), WeldTolerance::Exact, None),
        )
        .expect("a valid view");
        assert!(
            s.unresolved.is_empty(),
            "({x},{y},{z}): {:?}",
            s.unresolved.len()
        );
        assert!(
            s.unjoined_edges.is_empty(),
            "({x},{y},{z}): {:?}",
            s.unjoined_edges
        );
        assert_eq!(s.curves.len(), 1, "({x},{y},{z})");
        assert!(
            s.curves[0].closed && s.curves[0].certified_topology,
            "({x},{y},{z})"
        );
        // Drawing points lie on the great circle.
        for p in &s.curves[0].points {
            let d = p[0] * x as f64 + p[1] * y as f64 + p[2] * z as f64;
            assert!(d.abs() < 1e-6, "({x},{y},{z}): {p:?}");
        }
        assert!(s.boxes < 200, "({x},{y},{z}): {} boxes", s.boxes);
    }
}

#[test]
fn deflation_divides_exactly() {
    use limn::analysis::contour::sides::deflate_side;
    use limn::bernstein::Bernstein;
    use limn::surface::Edge;
    // g = v (1 - u) (u + 2v - 1/3): vanishes on v = 0 and u = 1.
    let lin = |c: [i64; 4]| Bernstein::new(&[1, 1], c.iter().map(|&k| q(k, 3)).collect()).unwrap();
    let v = lin([0, 3, 0, 3]);
    let one_minus_u = lin([3, 3, 0, 0]);
    let h = lin([-1, 5, 2, 8]);
    let g = &(&v * &one_minus_u) * &h;
    let d = deflate_side(&deflate_side(&g, Edge::V0), Edge::U1);
    // What is left is h (up to the degree it is written in).
    let x = [q(2, 7), q(3, 11)];
    assert_eq!(d.eval(&x), h.eval(&x));
    assert_eq!(d.reduce_degree_exact(), h.reduce_degree_exact());
    // A side on which g does not vanish is left alone.
    assert_eq!(deflate_side(&h, Edge::V0), h);
}

/// The graph patch (u, v, f(u, v)) with f_x = (x − 1/2)² + (y − 1/2)² − 1/100: seen along x,
/// its silhouette (f_x = 0) is a circle of radius 1/10 about the centre, inside one cell of
/// the 4 × 3 control grid. The float baselines of paper 002 miss it; limn finds it.
#[test]
fn a_small_loop_the_float_baselines_miss() {
    use limn::analysis::contour::baseline::{baseline_silhouette, BaselineMethod};
    use rug::Integer;
    // f = x³/3 − x²/2 + (49/100) x + x y² − x y − 1/24, written in Bernstein degree (3, 2).
    let terms: [((u32, u32), Rational); 6] = [
        ((3, 0), q(1, 3)),
        ((2, 0), q(-1, 2)),
        ((1, 0), q(49, 100)),
        ((1, 2), q(1, 1)),
        ((1, 1), q(-1, 1)),
        ((0, 0), q(-1, 24)),
    ];
    let (m, n) = (3u32, 2u32);
    let mono = |deg: u32, i: u32, k: u32| -> Rational {
        if k < i {
            Rational::new()
        } else {
            Rational::from((
                Integer::from(Integer::binomial_u(k, i)),
                Integer::from(Integer::binomial_u(deg, i)),
            ))
        }
    };
    let mut points = Vec::new();
    for k in 0..=m {
        for l in 0..=n {
            let z: Rational = terms
                .iter()
                .map(|((i, j), a)| (a * mono(m, *i, k)) * mono(n, *j, l))
                .sum();
            points.push([q(k as i64, 3), q(l as i64, 2), z]);
        }
    }
    let patch = limn::surface::RationalPatch::polynomial([3, 2], points).unwrap();
    let model = model(vec![patch]);
    let view = dir(1, 0, 0);
    let s = silhouette(
        &model,
        &view,
        &ContourOptions::new(CurveOptions::default(), WeldTolerance::Exact, None),
    )
    .expect("a valid view");
    assert!(s.unresolved.is_empty());
    assert_eq!(s.curves.len(), 1);
    assert!(s.curves[0].closed && s.curves[0].certified_topology);
    for p in &s.curves[0].points_uv {
        let r2 = (p.1 - 0.5).powi(2) + (p.2 - 0.5).powi(2);
        assert!((r2 - 0.01).abs() < 1e-9, "{p:?}");
    }
    // Srf-Node sees one sign at every node and misses the loop; the Mesh Method's control
    // mesh normals are not the surface normals, and it draws spurious open pieces instead.
    let srf = baseline_silhouette(&model, &view, BaselineMethod::SrfNode);
    assert!(srf.is_empty(), "Srf-Node found {} curves", srf.len());
    let mesh = baseline_silhouette(&model, &view, BaselineMethod::Mesh);
    assert!(
        !mesh.iter().any(|c| c.closed),
        "the Mesh Method is not expected to find the loop"
    );
}

#[test]
fn baselines_agree_with_limn_on_an_easy_case() {
    use limn::analysis::contour::baseline::{baseline_silhouette, BaselineMethod};
    // The graph of f = x²/2 − x/2 + x (y − 1/2)/4, seen along x: the silhouette is the line
    // f_x = x − 1/2 + (y − 1/2)/4 = 0, crossing the patch from v = 0 to v = 1.
    let f = |i: i64, j: i64| -> Rational {
        // Bernstein coefficients of f in degree (2, 1), computed by hand.
        match (i, j) {
            (0, _) => q(0, 1),
            (1, 0) => q(-1, 4) + q(-1, 16),
            (1, 1) => q(-1, 4) + q(1, 16),
            (2, 0) => q(-1, 8),
            _ => q(1, 8),
        }
    };
    let mut pts = Vec::new();
    for i in 0..=2 {
        for j in 0..=1 {
            pts.push([q(i, 2), q(j, 1), f(i, j)]);
        }
    }
    let patch = limn::surface::RationalPatch::polynomial([2, 1], pts).unwrap();
    let m = model(vec![patch]);
    let view = dir(1, 0, 0);
    let s = silhouette(
        &m,
        &view,
        &ContourOptions::new(CurveOptions::default(), WeldTolerance::Exact, None),
    )
    .expect("a valid view");
    assert_eq!(s.curves.len(), 1);
    assert!(s.curves[0].certified_topology && !s.curves[0].closed);
    for method in [BaselineMethod::SrfNode, BaselineMethod::Mesh] {
        let b = baseline_silhouette(&m, &view, method);
        assert_eq!(b.len(), 1, "{method:?}");
        for p in &b[0].points_uv {
            assert!(
                (p.1 - 0.5 + (p.2 - 0.5) / 4.0).abs() < 1e-9,
                "{method:?}: {p:?}"
            );
        }
    }
}

#[test]
fn traced_sphere_silhouette_is_within_the_tolerance() {
    // Radius 2, direction (1, 2, 2)/3: the true silhouette is the great circle in the plane
    // x + 2y + 2z = 0. Every point of every drawn segment (checked at vertices and midpoints)
    // must be within the reported bound, which must be at most the tolerance (soundness); and
    // every point of the true circle must be within the bound of the drawing (completeness).
    let m = model(shapes::sphere(&q(2, 1)));
    let n = [1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0];
    // An orthonormal basis of the circle's plane.
    let e1 = [2.0 / 3.0, 1.0 / 3.0, -2.0 / 3.0];
    let e2 = analytic::cross(n, e1);
    for tol in [1e-3, 1e-6, 1e-9] {
        let s = silhouette(
            &m,
            &dir(1, 2, 2),
            &ContourOptions::new(CurveOptions::default(), WeldTolerance::Exact, Some(tol)),
        )
        .expect("a valid view");
        assert_eq!(s.curves.len(), 1);
        let c = &s.curves[0];
        assert!(c.certified, "tol {tol}");
        let bound = c.error_bound.unwrap();
        assert!(bound <= tol, "{bound} > {tol}");
        let dist = |p: [f64; 3]| {
            let h = p[0] * n[0] + p[1] * n[1] + p[2] * n[2];
            let q = [p[0] - h * n[0], p[1] - h * n[1], p[2] - h * n[2]];
            let r = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt();
            (h * h + (r - 2.0) * (r - 2.0)).sqrt()
        };
        for w in c.points.windows(2) {
            let mid = [
                0.5 * (w[0][0] + w[1][0]),
                0.5 * (w[0][1] + w[1][1]),
                0.5 * (w[0][2] + w[1][2]),
            ];
            for p in [w[0], mid] {
                assert!(dist(p) <= bound + 1e-12, "tol {tol}: {} > {bound}", dist(p));
            }
        }
        let seg_dist = analytic::to_segment;
        let mut pts = c.points.clone();
        if c.closed {
            pts.push(pts[0]);
        }
        for k in 0..997 {
            let a = k as f64 * std::f64::consts::TAU / 997.0;
            let p = [0, 1, 2].map(|i| 2.0 * (a.cos() * e1[i] + a.sin() * e2[i]));
            let near = pts
                .windows(2)
                .map(|w| seg_dist(p, w[0], w[1]))
                .fold(f64::INFINITY, f64::min);
            assert!(
                near <= bound + 1e-12,
                "tol {tol}: true point {k} is {near} away"
            );
        }
    }
}

/// The torus (R = 3, r = 1, axis z) seen exactly side-on: the contour generator is the top and
/// bottom circles (normal vertical) and the two meridian circles in the plane x = 0, crossing
/// at (0, ±3, ±1). Each crossing is a singular point with four arcs, at exact parameters, and
/// every curve between them is certified.
#[test]
fn side_on_torus_has_four_exact_crossings() {
    let m = model(shapes::torus(&q(3, 1), &q(1, 1)));
    let s = solve(&m, &dir(1, 0, 0));
    assert!(s.unresolved.is_empty() && s.unjoined_edges.is_empty());
    assert!(s.curves.iter().all(|c| c.certified_topology));
    let mut points: Vec<[i64; 3]> = s
        .singular_points
        .iter()
        .map(|p| {
            assert_eq!(p.branches, 4, "{p:?}");
            assert!(p.exact, "{p:?}");
            p.point.map(|x| x.round() as i64)
        })
        .collect();
    points.sort();
    assert_eq!(points, [[0, -3, -1], [0, -3, 1], [0, 3, -1], [0, 3, 1]]);
    for p in &s.singular_points {
        let d: f64 = (0..3)
            .map(|k| (p.point[k] - p.point[k].round()).abs())
            .sum();
        assert!(d < 1e-12, "{p:?}");
    }
    // 4 circles cut at 4 crossings, each crossing on 2 circles: 8 arcs between crossings.
    assert_eq!(s.curves.len(), 8);
}

/// Seen side-on from directions whose crossings are irrational, the torus's top and bottom
/// circles are still found exactly (sides where g vanishes), and the crossings of the
/// meridians with them are joined across patches because the quotients are exactly
/// proportional along the shared sides: four crossings, at 3·(−b, a)/|(a, b)| and its
/// opposite, z = ±1, four arcs each, no spurious junction at patch corners.
#[test]
fn side_on_torus_generic_azimuth_has_four_crossings() {
    let m = model(shapes::torus(&q(3, 1), &q(1, 1)));
    for (a, b) in [(1i64, 2i64), (2, -3), (-5, 1)] {
        let s = solve(&m, &dir(a, b, 0));
        assert!(s.unresolved.is_empty() && s.unjoined_edges.is_empty());
        assert!(s.curves.iter().all(|c| c.certified_topology));
        assert_eq!(s.curves.len(), 8);
        assert_eq!(s.singular_points.len(), 4);
        let n = ((a * a + b * b) as f64).sqrt();
        let (x, y) = (-3.0 * b as f64 / n, 3.0 * a as f64 / n);
        for p in &s.singular_points {
            assert_eq!(p.branches, 4, "{p:?}");
            let d = [
                p.point[0].abs() - x.abs(),
                p.point[1].abs() - y.abs(),
                p.point[2].abs() - 1.0,
            ];
            assert!(d.iter().all(|e| e.abs() < 1e-8), "({a},{b}): {p:?}");
            assert!(
                (p.point[0] * y - p.point[1] * x).abs() < 1e-8,
                "({a},{b}): {p:?}"
            );
        }
    }
}

/// The teapot from the axis directions: its silhouette contains whole sides and grid lines
/// where the normal is perpendicular to the view (the rim's top circle, the handle's end
/// circles), met by the rest of the curve at exact points; all of it certified.
#[test]
fn teapot_axis_views_have_exact_junctions() {
    let m = limn::testing::teapot();
    for (view, junctions) in [(dir(1, 0, 0), 4), (dir(0, 0, 1), 2)] {
        let s = solve(&m, &view);
        assert!(s.unresolved.is_empty(), "{:?}", s.unresolved);
        assert!(s.unjoined_edges.is_empty());
        assert!(s.curves.iter().all(|c| c.certified_topology));
        assert_eq!(s.singular_points.len(), junctions);
        assert!(s.singular_points.iter().all(|p| p.exact && p.branches >= 3));
    }
}

/// The teapot from horizontal directions: the rim's top circle (u = 1/2 in the rim patches,
/// where the normal is vertical) is a line on which the silhouette function vanishes inside
/// the patch. It is found exactly, divided out and added back; the rim's meridian silhouette
/// crosses it in two junctions of four arcs, at the circle's height z = 2.4984375; the whole
/// view is certified, and so is its certificate.
#[test]
fn teapot_horizontal_views_cross_the_rim_circle() {
    use limn::analysis::contour::certificate::{check_silhouette, SilhouetteCertificate};
    let m = limn::testing::teapot();
    for view in [dir(1, 2, 0), dir(2, -1, 0), dir(1, 1, 0), dir(-3, 1, 0)] {
        let s = solve(&m, &view);
        assert!(s.unresolved.is_empty(), "{view:?}: {:?}", s.unresolved);
        assert!(s.curves.iter().all(|c| c.certified_topology), "{view:?}");
        let rim: Vec<usize> = (0..4).collect();
        for (i, p) in s.solved.iter().enumerate() {
            let names: Vec<String> = p.lines.iter().map(|z| z.to_string()).collect();
            if rim.contains(&i) {
                // From (1, 1, 0) the meridian silhouette is the line v = 1/2 too.
                assert!(names.contains(&"u=1/2".to_string()), "{view:?}: patch {i}");
            }
        }
        assert_eq!(s.singular_points.len(), 2, "{view:?}");
        for p in &s.singular_points {
            assert_eq!(p.branches, 4);
            assert_eq!(p.uv[0], 0.5);
            assert!((p.point[2] - 2.4984375).abs() < 1e-9, "{p:?}");
        }
        let cert = SilhouetteCertificate::new("teapot", &view, &s);
        assert!(check_silhouette(&m, &cert).unwrap().certified);
        // Without the line's factor, the solved polynomial is not the silhouette function.
        let mut bad = cert.clone();
        let k = bad
            .patches
            .iter()
            .position(|p| !p.divided.is_empty())
            .unwrap();
        bad.patches[k].divided.retain(|d| !d.side.contains('='));
        assert!(check_silhouette(&m, &bad).is_err());
    }
}

/// The a priori rounding bound of the f64 drawing points (`proofs/chord-accuracy.md`, "The
/// drawn points"): on the teapot's patches and the exact sphere's (rational), at a grid of
/// points with awkward coordinates, the f64 point is within the bound of the exact rational
/// point (the difference computed exactly), and the bound is tiny beside the model's size.
#[test]
fn drawn_points_are_within_the_rounding_bound() {
    use limn::surface::DrawPatch;
    let mut patches: Vec<limn::surface::RationalPatch> = limn::testing::teapot()
        .patches
        .iter()
        .map(|p| p.surface.clone())
        .collect();
    patches.extend(shapes::sphere(&q(7, 3)));
    let mut checked = 0;
    for (i, patch) in patches.iter().enumerate() {
        let draw = DrawPatch::new(patch);
        let bound = draw.rounding().expect("positive weights");
        assert!(bound < 1e-12, "patch {i}: {bound}");
        for a in 0..=6 {
            for b in 0..=6 {
                let (u, v) = (a as f64 / 6.0, (b as f64 / 6.0).powf(1.3));
                let got = draw.eval(u, v);
                let exact = patch.eval(
                    &Rational::from_f64(u).unwrap(),
                    &Rational::from_f64(v).unwrap(),
                );
                let d2: Rational = (0..3)
                    .map(|k| {
                        let d = Rational::from_f64(got[k]).unwrap() - &exact[k];
                        Rational::from(&d * &d)
                    })
                    .sum();
                let b2 = Rational::from_f64(bound * bound).unwrap();
                assert!(
                    d2 <= b2,
                    "patch {i} at ({u}, {v}): {} > {bound}",
                    d2.to_f64().sqrt()
                );
                checked += 1;
            }
        }
    }
    assert!(checked > 1500);
}

/// The library refuses the zero direction (the CLI did before; the front door now does too),
/// rather than certifying an answer for a view that is no view.
#[test]
fn the_zero_direction_is_refused() {
    let m = Model::from_patches(Format::Json, shapes::sphere(&Rational::from(1)));
    let r = silhouette(&m, &View::direction([0, 0, 0]), &ContourOptions::default());
    assert!(
        matches!(r, Err(limn::Error::View(_))),
        "{:?}",
        r.map(|s| s.curves.len())
    );
    // A direction along an axis is a view: the equator, one closed curve.
    let s = silhouette(&m, &View::direction([0, 0, 1]), &ContourOptions::default()).unwrap();
    assert_eq!(s.curves.len(), 1);
    assert!(s.curves[0].closed && s.topology_certified());
}

/// The eye on, inside and just outside a sphere of radius 2 about the origin, at its poles
/// (which lie on collapsed patch sides) and at ordinary points, against the closed form: the
/// contour generator of an eye `E` is `{P : P · E = r²}` on the sphere, a circle for
/// `|E| > r`, the single point `E` for `|E| = r`, empty inside (issue 26: at a pole the
/// single point was certified away).
#[test]
fn an_eye_on_inside_and_just_outside_a_sphere() {
    let m = model(shapes::sphere(&q(2, 1)));
    let eye = |x: Rational, y: Rational, z: Rational| View::Eye([x, y, z]);
    let tiny = |k: u32| {
        let mut t = Rational::from(1);
        for _ in 0..k {
            t /= 10;
        }
        t
    };
    // On the sphere at either pole: no curve, and the pole as an isolated point, certified.
    for z in [2, -2] {
        let s = solve(&m, &eye(q(0, 1), q(0, 1), q(z, 1)));
        assert!(s.unresolved.is_empty(), "{:?}", s.unresolved);
        assert!(s.curves.is_empty(), "pole {z}: {} curves", s.curves.len());
        assert_eq!(
            s.singular_points.len(),
            1,
            "pole {z}: {:?}",
            s.singular_points
        );
        let p = &s.singular_points[0];
        assert_eq!(p.branches, 0);
        assert!(
            p.point[0].abs() < 1e-12
                && p.point[1].abs() < 1e-12
                && (p.point[2] - z as f64).abs() < 1e-12,
            "{p:?}"
        );
    }
    // On the sphere at ordinary points (an exact rational point of it, a patch corner on the
    // equator): never certified, never empty-and-certified.
    for e in [
        eye(q(6, 5), q(8, 5), q(0, 1)),
        eye(q(2, 1), q(0, 1), q(0, 1)),
    ] {
        let s = solve(&m, &e);
        assert!(
            !s.unresolved.is_empty(),
            "{e:?}: certified with {} curves",
            s.curves.len()
        );
    }
    // Inside: nothing, certified.
    for e in [
        eye(q(0, 1), q(0, 1), q(1, 1)),
        eye(q(1, 1), q(0, 1), q(0, 1)),
    ] {
        let s = solve(&m, &e);
        assert!(s.unresolved.is_empty() && s.curves.is_empty() && s.singular_points.is_empty());
    }
    // Just outside (1e-9 and 1e-12), at a pole and at an ordinary point: one closed curve,
    // certified, near the closed-form circle (no tolerance asked: the drawing is not bounded,
    // so only roughly), and no isolated point.
    for k in [9, 12] {
        let out = Rational::from(2) + tiny(k);
        for e in [
            eye(q(0, 1), q(0, 1), out.clone()),
            eye(out.clone(), q(0, 1), q(0, 1)),
        ] {
            let s = solve(&m, &e);
            assert!(s.unresolved.is_empty(), "{e:?}: {:?}", s.unresolved);
            assert_eq!(s.curves.len(), 1, "{e:?}");
            assert!(s.curves[0].closed && s.singular_points.is_empty());
            let View::Eye(ev) = &e else { unreachable!() };
            let ef = ev.clone().map(|c| c.to_f64());
            for p in &s.curves[0].points {
                let dot: f64 = (0..3).map(|i| p[i] * ef[i]).sum();
                assert!((dot - 4.0).abs() < 1e-3, "{e:?}: {p:?}");
            }
        }
    }
    // Clearly outside, with a tolerance: every drawn point within it of the circle.
    let e = eye(q(0, 1), q(0, 1), q(21, 10));
    let tol = 1e-5;
    let s = silhouette(
        &m,
        &e,
        &ContourOptions::new(CurveOptions::default(), WeldTolerance::Exact, Some(tol)),
    )
    .unwrap();
    assert!(s.curves.len() == 1 && s.curves[0].error_bound.is_some_and(|b| b <= tol));
    for p in &s.curves[0].points {
        let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        assert!(
            (r - 2.0).abs() <= tol * 1.01 && (p[2] * 2.1 - 4.0).abs() <= 2.1 * tol * 1.01,
            "{p:?}"
        );
    }
}

/// A direction's length does not change the answer (issue 26): `d`, `d · 10^±300` and
/// `d · 10^±400` (beyond f64's range) give the same certified curves on a torus and a sphere.
#[test]
fn the_length_of_the_direction_does_not_matter() {
    let pow10 = |k: i32| {
        let mut p = Rational::from(1);
        for _ in 0..k.unsigned_abs() {
            if k > 0 {
                p *= 10;
            } else {
                p /= 10;
            }
        }
        p
    };
    for (name, patches) in [
        ("torus", shapes::torus(&q(2, 1), &q(1, 1))),
        ("sphere", shapes::sphere(&q(1, 1))),
    ] {
        let m = model(patches);
        for d in [[1, 2, 3], [1, 0, 0], [1, 1, 1]] {
            let base = solve(&m, &dir(d[0], d[1], d[2]));
            for k in [300, -300, 400, -400] {
                let v = View::Direction(d.map(|c| Rational::from(c) * pow10(k)));
                let s = solve(&m, &v);
                let what = format!("{name} {d:?} x 10^{k}");
                assert_eq!(s.curves.len(), base.curves.len(), "{what}");
                assert_eq!(s.unresolved.len(), base.unresolved.len(), "{what}");
                for (a, b) in s.curves.iter().zip(&base.curves) {
                    assert_eq!(
                        (a.closed, a.certified_topology),
                        (b.closed, b.certified_topology),
                        "{what}"
                    );
                }
            }
        }
    }
}

/// An eye at 10³⁰⁸ (and at −10³⁰⁰): the silhouette function's scale is brought into f64's
/// range (`proofs/silhouette-join.md`, "Scale"), so the sphere's one loop is certified quickly,
/// as from an eye at 10³ (it took more than 20 s before).
#[test]
fn an_eye_very_far_away_is_quick_and_certified() {
    let m = model(shapes::sphere(&q(2, 1)));
    let big = |e: &str| limn::number::parse_exact(e).unwrap();
    for e in ["1e308", "-1e300", "1000"] {
        let v = View::Eye([big(e), big(e), big(e)]);
        let start = std::time::Instant::now();
        let s = solve(&m, &v);
        assert!(s.topology_certified(), "{e}");
        assert_eq!((s.curves.len(), s.curves[0].closed), (1, true), "{e}");
        assert!(
            start.elapsed().as_secs_f64() < 10.0,
            "{e}: {:?}",
            start.elapsed()
        );
    }
}

/// A grid of 10,000 curved bilinear patches under a time limit of 20 ms (issue 26 §2): the
/// patches whose curves are not started before the deadline are unresolved by the time limit
/// without their exact set-up, and the joins along shared edges stop there (the edges left
/// unjoined), so the silhouette is not certified and every gap has its reason.
#[test]
fn a_large_grid_silhouette_respects_the_time_limit() {
    let m = Model::from_patches(Format::Json, shapes::bilinear_grid(100, 100));
    let start = std::time::Instant::now();
    let curve = CurveOptions {
        deadline: Some(start + std::time::Duration::from_millis(20)),
        ..CurveOptions::default()
    };
    let opts = ContourOptions::new(curve, WeldTolerance::Exact, None);
    let view = View::Direction([1, 2, -3].map(Rational::from));
    let s = silhouette(&m, &view, &opts).unwrap();
    let took = start.elapsed();
    assert!(!s.certified());
    assert!(
        s.unresolved.iter().any(|u| u.2 == limn::Reason::TimeLimit) || !s.unjoined_edges.is_empty()
    );
    assert!(took.as_secs_f64() < 60.0, "{took:?}");
    println!("10,000 patches under a 20 ms limit: {took:?}");
}
