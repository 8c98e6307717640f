//! Certified cubic pieces of silhouettes against closed forms (`proofs/cubic-pieces.md`): on
//! a sphere and on a torus under a rational rotation, at every tolerance of a sweep from 1e-3
//! to 1e-10 in half-decade steps, every sample of every space cubic and of every (u, v)
//! cubic's image is within the cubic's bound of the true curve (soundness), every sampled
//! point of the true curve is within the bound of a cubic (completeness), and every bound is
//! at most the tolerance.

use limn::analysis::contour::curves::{CubicPiece, Silhouette};
use limn::analysis::contour::silhouette::silhouette;
use limn::analysis::view::View;
use limn::model::{Format, Model, WeldTolerance};
use limn::number::Rational;
use limn::solver::CurveOptions;
use limn::surface::{DrawPatch, RationalPatch};
use limn::testing::shapes;
use limn::ContourOptions;

use crate::analytic;

fn q(a: i64, b: i64) -> Rational {
    Rational::from((a, b))
}

/// The tolerances 1e-3, 10^-3.5, …, 1e-10.
fn sweep() -> Vec<f64> {
    (6..=20).map(|k| 10f64.powf(-(k as f64) / 2.0)).collect()
}

fn solve(patches: &[RationalPatch], view: &View, tol: f64) -> Silhouette {
    let m = Model::from_patches(Format::Json, patches.to_vec());
    silhouette(
        &m,
        view,
        &ContourOptions::new(CurveOptions::default(), WeldTolerance::Exact, Some(tol)),
    )
    .expect("a valid view")
}

fn bezier<const D: usize>(c: &[[f64; D]; 4], t: f64) -> [f64; D] {
    let s = 1.0 - t;
    let w = [s * s * s, 3.0 * s * s * t, 3.0 * s * t * t, t * t * t];
    std::array::from_fn(|k| (0..4).map(|i| w[i] * c[i][k]).sum())
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// The least value of `f` near the best of `n + 1` samples `at(0..=n)` spaced `step` apart:
/// golden-section search between the samples' neighbours, kept in `within` (`f` smooth and
/// unimodal there).
fn least_near(
    f: &dyn Fn(f64) -> f64,
    at: &dyn Fn(usize) -> f64,
    n: usize,
    step: f64,
    within: [f64; 2],
) -> f64 {
    let k = (0..=n)
        .min_by(|&a, &b| f(at(a)).total_cmp(&f(at(b))))
        .expect("samples");
    let (mut lo, mut hi) = ((at(k) - step).max(within[0]), (at(k) + step).min(within[1]));
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..80 {
        let (a, b) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if f(a) < f(b) {
            hi = b;
        } else {
            lo = a;
        }
    }
    f(0.5 * (lo + hi)).min(f(at(k)))
}

/// The least distance from `p` to a space cubic, by sampling and golden-section refinement
/// (the distance is smooth and unimodal near its minimum on a short piece).
fn to_cubic(p: [f64; 3], c: &[[f64; 3]; 4]) -> f64 {
    let f = |t: f64| norm(sub(bezier(c, t), p));
    let n = 32;
    least_near(&f, &|i| i as f64 / n as f64, n, 1.0 / n as f64, [0.0, 1.0])
}

/// Checks one silhouette's cubics against a closed form: `dist` is the distance from a point
/// to the true curve, `truth` samples points of it.
fn check(
    s: &Silhouette,
    patches: &[RationalPatch],
    tol: f64,
    dist: &dyn Fn([f64; 3]) -> f64,
    truth: &[[f64; 3]],
) {
    let draw: Vec<DrawPatch> = patches.iter().map(DrawPatch::new).collect();
    let mut all: Vec<&CubicPiece> = Vec::new();
    for c in &s.curves {
        let bound = c
            .cubic_bound
            .unwrap_or_else(|| panic!("tol {tol}: a curve without cubics"));
        assert!(bound <= tol, "tol {tol}: cubic bound {bound}");
        // The polyline sampled from the cubics is certified too.
        assert!(
            c.certified,
            "tol {tol}: polyline not certified, bound {:?}",
            c.error_bound
        );
        all.extend(&c.cubics);
    }
    // The f64 evaluations of the test itself: a few ulps of the model's size.
    let slack = 1e-13;
    for (i, piece) in all.iter().enumerate() {
        let c = &piece.cubic;
        assert!(c.uv_bound <= tol && c.bound <= tol, "tol {tol}: {c:?}");
        for k in 0..=8 {
            let t = k as f64 / 8.0;
            let d = dist(bezier(&c.space, t));
            assert!(
                d <= c.bound + slack,
                "tol {tol}: cubic {i} at {t}: {d} > {}",
                c.bound
            );
            let [u, v] = bezier(&c.uv, t);
            let d = dist(draw[piece.patch].eval(u, v));
            assert!(
                d <= c.uv_bound + slack,
                "tol {tol}: uv cubic {i} at {t}: {d} > {}",
                c.uv_bound
            );
        }
    }
    // Completeness: each true point is near some cubic (the nearest by its control points'
    // centre first, then the least distance over the candidates).
    let worst = all.iter().map(|p| p.cubic.bound).fold(0.0, f64::max);
    for (k, p) in truth.iter().enumerate() {
        let mut near: Vec<(f64, usize)> = all
            .iter()
            .enumerate()
            .map(|(i, c)| {
                let m = bezier(&c.cubic.space, 0.5);
                (norm(sub(m, *p)), i)
            })
            .collect();
        near.sort_by(|a, b| a.0.total_cmp(&b.0));
        let d = near
            .iter()
            .take(4)
            .map(|&(_, i)| to_cubic(*p, &all[i].cubic.space))
            .fold(f64::INFINITY, f64::min);
        assert!(
            d <= worst + slack,
            "tol {tol}: true point {k} is {d} from the cubics"
        );
    }
}

#[test]
fn sphere_cubics_are_within_their_bounds_over_a_tolerance_sweep() {
    // Radius 2, direction (1, 2, 2)/3: the great circle in the plane x + 2y + 2z = 0.
    let patches = shapes::sphere(&q(2, 1));
    let n = [1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0];
    let e1 = [2.0 / 3.0, 1.0 / 3.0, -2.0 / 3.0];
    let e2 = analytic::cross(n, e1);
    let dist = |p: [f64; 3]| {
        let h = p[0] * n[0] + p[1] * n[1] + p[2] * n[2];
        let r = norm([p[0] - h * n[0], p[1] - h * n[1], p[2] - h * n[2]]);
        (h * h + (r - 2.0) * (r - 2.0)).sqrt()
    };
    let truth: Vec<[f64; 3]> = (0..211)
        .map(|k| {
            let a = k as f64 * std::f64::consts::TAU / 211.0;
            [0, 1, 2].map(|i| 2.0 * (a.cos() * e1[i] + a.sin() * e2[i]))
        })
        .collect();
    let view = View::Direction([q(1, 1), q(2, 1), q(2, 1)]);
    for tol in sweep() {
        let s = solve(&patches, &view, tol);
        assert_eq!(s.curves.len(), 1);
        check(&s, &patches, tol, &dist, &truth);
    }
}

#[test]
fn rotated_torus_cubics_are_within_their_bounds_over_a_tolerance_sweep() {
    // The torus R = 3, r = 1 about z, turned about x by the rotation with cos 3/5, sin 4/5,
    // seen along (7, 2, 4). In the torus' frame the direction is d' = Rᵀ d, and the contour
    // generator is φ(θ) with cos φ (d'₁ cos θ + d'₂ sin θ) + sin φ d'₃ = 0: two loops.
    let rot = shapes::rotation(0, 2, 1);
    let zero = [q(0, 1), q(0, 1), q(0, 1)];
    let patches: Vec<RationalPatch> = shapes::torus(&q(3, 1), &q(1, 1))
        .iter()
        .map(|p| shapes::transform(p, &rot, &zero))
        .collect();
    let r: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|k| rot[i][k].to_f64()));
    let d = [7.0, 2.0, 4.0];
    let dl: [f64; 3] = std::array::from_fn(|k| (0..3).map(|i| r[i][k] * d[i]).sum());
    let point = |theta: f64, branch: usize| -> [f64; 3] {
        let phi = (-(dl[0] * theta.cos() + dl[1] * theta.sin())).atan2(dl[2])
            + std::f64::consts::PI * branch as f64;
        let w = 3.0 + phi.cos();
        let local = [w * theta.cos(), w * theta.sin(), phi.sin()];
        std::array::from_fn(|i| (0..3).map(|k| r[i][k] * local[k]).sum())
    };
    // The nearest point of a loop has about the angle θ of p itself (p is within 1e-3 of
    // the torus): search a window around it.
    let dist = |p: [f64; 3]| {
        let local: [f64; 3] = std::array::from_fn(|k| (0..3).map(|i| r[i][k] * p[i]).sum());
        let theta = local[1].atan2(local[0]);
        let mut best = f64::INFINITY;
        for branch in 0..2 {
            let f = |t: f64| norm(sub(point(t, branch), p));
            let (n, w) = (32, 0.02);
            let at = |i: usize| theta - w + 2.0 * w * i as f64 / n as f64;
            let step = 2.0 * w / n as f64;
            best = best.min(least_near(&f, &at, n, step, [f64::MIN, f64::MAX]));
        }
        best
    };
    let truth: Vec<[f64; 3]> = (0..2)
        .flat_map(|b| (0..97).map(move |k| (b, k as f64 * std::f64::consts::TAU / 97.0)))
        .map(|(b, t)| point(t, b))
        .collect();
    let view = View::Direction([q(7, 1), q(2, 1), q(4, 1)]);
    for tol in sweep() {
        let s = solve(&patches, &view, tol);
        assert_eq!(s.curves.len(), 2, "tol {tol}");
        check(&s, &patches, tol, &dist, &truth);
    }
}
