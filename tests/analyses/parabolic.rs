//! Parabolic curves (K = 0) against closed forms: the torus's top and bottom circles (both
//! directions: every output point on them, every point of them near the output), none on a
//! sphere, planes and cylinders parabolic everywhere, the sign of the parabolic function
//! against the torus's closed-form curvature sign, and the teapot without panic.

use limn::analysis::contour::parabolic::{parabolic, parabolic_function};
use limn::model::{Format, Model, WeldTolerance};
use limn::number::Rational;
use limn::solver::CurveOptions;
use limn::testing::shapes;
use limn::ContourOptions;

fn q(a: i64, b: i64) -> Rational {
    Rational::from((a, b))
}

fn model(patches: Vec<limn::surface::RationalPatch>) -> Model {
    Model::from_patches(Format::Json, patches)
}

fn solve(m: &Model, tol: Option<f64>) -> limn::analysis::contour::curves::Silhouette {
    parabolic(
        m,
        &ContourOptions::new(CurveOptions::default(), WeldTolerance::Exact, tol),
    )
    .expect("no error")
}

/// On the torus (R = 3, r = 1) K = cos φ / (r (R + r cos φ)): positive on the outer half
/// (distance from the axis above 3), negative on the inner half. The parabolic function has
/// that sign at every sampled interior point of every patch (exact evaluation).
#[test]
fn sign_matches_the_torus_curvature() {
    let patches = shapes::torus(&q(3, 1), &q(1, 1));
    for (i, p) in patches.iter().enumerate() {
        let k = parabolic_function(p);
        for a in 1..8 {
            for b in 1..8 {
                let (u, v) = (q(a, 8), q(b, 8));
                let s = p.eval(&u, &v);
                let rho2 = Rational::from(&s[0] * &s[0]) + Rational::from(&s[1] * &s[1]);
                let outer = rho2 > 9;
                let kv = k.eval(&[u, v]);
                assert!(kv != 0, "patch {i} at ({a}/8, {b}/8)");
                assert_eq!(kv > 0, outer, "patch {i} at ({a}/8, {b}/8)");
            }
        }
    }
}

/// The torus's parabolic curves are its top and bottom circles (z = ±1, distance 3 from the
/// axis): two closed loops, certified, and (with a tolerance) every output point on them and
/// every point of them within the tolerance of the output.
#[test]
fn torus_has_its_top_and_bottom_circles() {
    let m = model(shapes::torus(&q(3, 1), &q(1, 1)));
    let tol = 1e-6;
    let s = solve(&m, Some(tol));
    assert!(s.unresolved.is_empty() && s.unjoined_edges.is_empty());
    assert_eq!(
        s.curves.len(),
        2,
        "{:?}",
        s.curves.iter().map(|c| &c.patches).collect::<Vec<_>>()
    );
    let abs_tol = s.tolerance.unwrap();
    for c in &s.curves {
        assert!(c.closed && c.certified_topology && c.certified);
        // Soundness: every vertex on a circle.
        for p in &c.points {
            let rho = (p[0] * p[0] + p[1] * p[1]).sqrt();
            assert!(
                (rho - 3.0).abs() <= abs_tol && (p[2].abs() - 1.0).abs() <= abs_tol,
                "{p:?}"
            );
        }
    }
    // Completeness: every point of both circles is near some output segment's vertex chain.
    for z in [-1.0f64, 1.0] {
        for i in 0..360 {
            let t = (i as f64).to_radians();
            let x = [3.0 * t.cos(), 3.0 * t.sin(), z];
            let near = s.curves.iter().any(|c| {
                c.points
                    .windows(2)
                    .any(|w| segment_distance(x, w[0], w[1]) <= 2.0 * abs_tol)
            });
            assert!(near, "circle z = {z} at {i} degrees not covered");
        }
    }
}

fn segment_distance(x: [f64; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    let ab = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let ax = [x[0] - a[0], x[1] - a[1], x[2] - a[2]];
    let l2 = ab.iter().map(|c| c * c).sum::<f64>();
    let t = if l2 > 0.0 {
        (ab.iter().zip(&ax).map(|(p, q)| p * q).sum::<f64>() / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (0..3)
        .map(|k| (ax[k] - t * ab[k]).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// A sphere has no parabolic points (its poles are collapsed sides, reported); a plane and a
/// cylinder are parabolic everywhere, reported as such, not as curves.
#[test]
fn sphere_none_plane_and_cylinder_everywhere() {
    let s = solve(&model(shapes::sphere(&q(2, 1))), None);
    assert!(s.curves.is_empty() && s.unresolved.is_empty());
    assert!(s.degenerate.iter().all(|d| d.kind == "collapsed side"));
    for p in [
        shapes::plane_square(&q(1, 1)),
        shapes::cylinder_quarter(&q(1, 1), &q(2, 1)),
    ] {
        let s = solve(&model(vec![p]), None);
        assert_eq!(s.degenerate.len(), 1);
        assert_eq!(s.degenerate[0].kind, "parabolic everywhere");
        assert!(s.curves.is_empty());
    }
}

/// The teapot: every patch solved without panic; what is not decided is reported.
#[test]
fn teapot_parabolic_curves() {
    let m = limn::testing::teapot();
    let s = solve(&m, Some(1e-6));
    eprintln!(
        "teapot parabolic: {} curves, {} unresolved boxes, {} unjoined edges, {} degenerate",
        s.curves.len(),
        s.unresolved.len(),
        s.unjoined_edges.len(),
        s.degenerate.len()
    );
    assert!(!s.curves.is_empty());
    // The curvature jumps across several patch edges (the teapot is only tangent-continuous):
    // curves end there, proven, or continue where both patches vanish at the same point; the
    // rim's top and the body's top edge are parabolic on one side only. All of it certified.
    assert!(s.unresolved.is_empty() && s.unjoined_edges.is_empty());
    assert!(!s.ending_edges.is_empty());
    assert!(s.curves.iter().all(|c| c.certified_topology && c.certified));
}

/// Where the parabolic curve reaches an edge across which the curvature jumps, it ends there;
/// the body's top edge (u = 0 of patches 4..8, parabolic on the body's side only) is part of
/// the curve, and the rim's crossings with it are joined to it.
#[test]
fn one_sided_parabolic_edges_are_curve() {
    let m = limn::testing::teapot();
    let s = solve(&m, None);
    for patch in 4..8 {
        assert!(
            s.degenerate
                .iter()
                .any(|d| d.patch == patch && d.kind == "parabolic side"),
            "patch {patch}"
        );
    }
    // The top edge of the body is a closed circle through patches 4..8.
    let circle = s.curves.iter().find(|c| {
        c.closed
            && (4..8).all(|p| c.patches.contains(&p))
            && c.patches.iter().all(|p| (4..8).contains(p))
    });
    let circle = circle.expect("the body's top circle");
    let z0 = circle.points[0][2];
    assert!(circle.points.iter().all(|p| (p[2] - z0).abs() < 1e-12));
}

/// The parabolic function is exactly a positive constant times `W⁸ (LN − M²)` with `L = S_uu · (S_u × S_v)` etc.,
/// computed here independently from the quotient rule on `S = P / W` in exact rationals, at
/// sample points of rational patches (sphere, torus, a rotated and shifted torus) and of a
/// polynomial teapot patch.
#[test]
fn identity_with_the_second_fundamental_form() {
    use limn::bernstein::Bernstein;
    type R = Rational;
    let rot = shapes::rotation(0, 3, 4);
    let shift = [q(1, 2), q(-2, 1), q(3, 1)];
    let mut patches = vec![
        shapes::sphere(&q(2, 1))[3].clone(),
        shapes::torus(&q(3, 1), &q(1, 1))[5].clone(),
        shapes::transform(&shapes::torus(&q(5, 2), &q(1, 1))[2], &rot, &shift),
    ];
    let teapot = limn::testing::teapot();
    patches.push(teapot.patches[5].surface.clone());
    for p in &patches {
        let k = parabolic_function(p);
        let [px, py, pz, w] = p.homogeneous();
        let comps = [px, py, pz, w];
        let d = |b: &Bernstein<R>, du: usize, dv: usize| {
            let mut b = b.clone();
            for _ in 0..du {
                b = b.deriv(0);
            }
            for _ in 0..dv {
                b = b.deriv(1);
            }
            b
        };
        let mut scale: Option<R> = None;
        for (a, b) in [(1, 3), (2, 5), (5, 7), (1, 2)] {
            let pt = [q(a, 8), q(b, 8)];
            let ev = |du, dv| -> [R; 4] { [0, 1, 2, 3].map(|i| d(&comps[i], du, dv).eval(&pt)) };
            let (h, hu, hv, huu, huv, hvv) =
                (ev(0, 0), ev(1, 0), ev(0, 1), ev(2, 0), ev(1, 1), ev(0, 2));
            let w0 = h[3].clone();
            let s: [R; 3] = [0, 1, 2].map(|i| R::from(&h[i] / &w0));
            let su: [R; 3] = [0, 1, 2].map(|i| (R::from(&hu[i] - &s[i] * hu[3].clone())) / &w0);
            let sv: [R; 3] = [0, 1, 2].map(|i| (R::from(&hv[i] - &s[i] * hv[3].clone())) / &w0);
            let suu: [R; 3] = [0, 1, 2].map(|i| {
                (huu[i].clone() - R::from(2) * &su[i] * &hu[3] - &s[i] * huu[3].clone()) / &w0
            });
            let suv: [R; 3] = [0, 1, 2].map(|i| {
                (huv[i].clone()
                    - &su[i] * hv[3].clone()
                    - &sv[i] * hu[3].clone()
                    - &s[i] * huv[3].clone())
                    / &w0
            });
            let svv: [R; 3] = [0, 1, 2].map(|i| {
                (hvv[i].clone() - R::from(2) * &sv[i] * &hv[3] - &s[i] * hvv[3].clone()) / &w0
            });
            let n = [
                R::from(&su[1] * &sv[2]) - R::from(&su[2] * &sv[1]),
                R::from(&su[2] * &sv[0]) - R::from(&su[0] * &sv[2]),
                R::from(&su[0] * &sv[1]) - R::from(&su[1] * &sv[0]),
            ];
            let dot = |x: &[R; 3]| -> R { (0..3).map(|i| R::from(&x[i] * &n[i])).sum() };
            let (l, m, nn) = (dot(&suu), dot(&suv), dot(&svv));
            let w8 = (0..8).fold(R::from(1), |acc, _| acc * &w0);
            let expected = w8 * (R::from(&l * &nn) - R::from(&m * &m));
            // Equal up to one positive constant per patch (the scaling to integer coordinates).
            let got = k.eval(&pt);
            assert!(expected != 0, "at ({a}/8, {b}/8)");
            let ratio = got / expected;
            assert!(ratio > 0, "at ({a}/8, {b}/8)");
            match &scale {
                None => scale = Some(ratio),
                Some(r) => assert_eq!(*r, ratio, "at ({a}/8, {b}/8)"),
            }
        }
    }
}

/// The answer does not depend on the thread count (teapot, with a tolerance: joins, ending
/// edges, lines and traced vertices all the same).
#[test]
fn thread_count_does_not_change_the_answer() {
    let m = limn::testing::teapot();
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| solve(&m, Some(1e-4)))
    };
    let (a, b) = (run(1), run(2));
    assert_eq!(a.curves, b.curves);
    assert_eq!(a.singular_points, b.singular_points);
    assert_eq!(a.ending_edges, b.ending_edges);
    assert_eq!(a.degenerate, b.degenerate);
}
