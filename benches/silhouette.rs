//! Silhouettes: the whole teapot for one generic view, one bicubic teapot patch, and the exact
//! sphere and torus, single-threaded; the certified drawing at tolerances 1e-3, 1e-6, 1e-9 on
//! 1 and 2 threads; writing and independently checking a certificate.

use criterion::{criterion_group, criterion_main, Criterion};
use limn::analysis::contour::baseline::{baseline_silhouette, BaselineMethod};
use limn::analysis::contour::certificate::{check_silhouette, SilhouetteCertificate};
use limn::analysis::contour::silhouette::{silhouette, silhouette_function};
use limn::analysis::view::View;
use limn::model::{Format, Model, WeldTolerance};
use limn::number::Rational;
use limn::solver::{solve_curve, CurveOptions};
use limn::testing::shapes;
use limn::ContourOptions;

fn dir(x: i64, y: i64, z: i64) -> View {
    View::Direction([Rational::from(x), Rational::from(y), Rational::from(z)])
}

fn benches(c: &mut Criterion) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let teapot = limn::testing::teapot();
    let opts = CurveOptions::default();
    let mut g = c.benchmark_group("silhouette");
    g.bench_function("teapot-1,2,3", |b| {
        b.iter(|| {
            pool.install(|| {
                silhouette(
                    &teapot,
                    &dir(1, 2, 3),
                    &ContourOptions::new(opts.clone(), WeldTolerance::Exact, None),
                )
                .expect("a valid view")
            })
        })
    });
    let patch = &teapot.patches[0].surface;
    g.bench_function("teapot-patch0-function", |b| {
        b.iter(|| silhouette_function(patch, &dir(1, 2, 3)))
    });
    let g0 = silhouette_function(patch, &dir(1, 2, 3));
    g.bench_function("teapot-patch0-solve", |b| {
        b.iter(|| solve_curve(&g0, &opts))
    });
    let sphere = Model::from_patches(Format::Json, shapes::sphere(&Rational::from(1)));
    g.bench_function("sphere-1,2,3", |b| {
        b.iter(|| {
            pool.install(|| {
                silhouette(
                    &sphere,
                    &dir(1, 2, 3),
                    &ContourOptions::new(opts.clone(), WeldTolerance::Exact, None),
                )
                .expect("a valid view")
            })
        })
    });
    let torus = Model::from_patches(
        Format::Json,
        shapes::torus(&Rational::from(3), &Rational::from(1)),
    );
    g.bench_function("torus-1,2,3", |b| {
        b.iter(|| {
            pool.install(|| {
                silhouette(
                    &torus,
                    &dir(1, 2, 3),
                    &ContourOptions::new(opts.clone(), WeldTolerance::Exact, None),
                )
                .expect("a valid view")
            })
        })
    });
    g.finish();
}

/// The certified drawing at a tolerance (relative to the teapot's diagonal), on 1 and 2
/// threads; one patch at 1e-6; and the independent check of a certificate.
fn traced(c: &mut Criterion) {
    let teapot = limn::testing::teapot();
    let diag = teapot.diagonal();
    let opts = CurveOptions::default();
    let mut g = c.benchmark_group("silhouette-tol");
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        for tol in [1e-3, 1e-6, 1e-9] {
            g.bench_function(format!("teapot-1,2,3-tol{tol:e}-threads{threads}"), |b| {
                b.iter(|| {
                    pool.install(|| {
                        silhouette(
                            &teapot,
                            &dir(1, 2, 3),
                            &ContourOptions::new(
                                opts.clone(),
                                WeldTolerance::Exact,
                                Some(tol * diag),
                            ),
                        )
                        .expect("a valid view")
                    })
                })
            });
        }
    }
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let patch0 = Model::from_patches(Format::Bpt, vec![teapot.patches[0].surface.clone()]);
    g.bench_function("teapot-patch0-tol1e-6", |b| {
        b.iter(|| {
            one.install(|| {
                silhouette(
                    &patch0,
                    &dir(1, 2, 3),
                    &ContourOptions::new(opts.clone(), WeldTolerance::Exact, Some(1e-6 * diag)),
                )
                .expect("a valid view")
            })
        })
    });
    let s = one.install(|| {
        silhouette(
            &teapot,
            &dir(1, 2, 3),
            &ContourOptions::new(opts.clone(), WeldTolerance::Exact, None),
        )
        .expect("a valid view")
    });
    g.bench_function("teapot-1,2,3-certificate", |b| {
        b.iter(|| one.install(|| SilhouetteCertificate::new("teapot", &dir(1, 2, 3), &s)))
    });
    let cert = SilhouetteCertificate::new("teapot", &dir(1, 2, 3), &s);
    g.bench_function("teapot-1,2,3-check", |b| {
        b.iter(|| one.install(|| check_silhouette(&teapot, &cert).unwrap()))
    });
    g.finish();
}

/// The largest distance from a sampled point of polyline set `a` to polyline set `b`.
fn one_sided(a: &[Vec<[f64; 3]>], b: &[Vec<[f64; 3]>]) -> f64 {
    let seg = |p: [f64; 3], x: [f64; 3], y: [f64; 3]| {
        let d = [y[0] - x[0], y[1] - x[1], y[2] - x[2]];
        let w = [p[0] - x[0], p[1] - x[1], p[2] - x[2]];
        let dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        let t = if dd > 0.0 {
            ((w[0] * d[0] + w[1] * d[1] + w[2] * d[2]) / dd).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let r = [w[0] - t * d[0], w[1] - t * d[1], w[2] - t * d[2]];
        (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt()
    };
    let mut worst: f64 = 0.0;
    for line in a {
        for w in line.windows(2) {
            for k in 0..=8 {
                let t = k as f64 / 8.0;
                let p = [0, 1, 2].map(|i| w[0][i] + t * (w[1][i] - w[0][i]));
                let near = b
                    .iter()
                    .flat_map(|l| l.windows(2))
                    .map(|v| seg(p, v[0], v[1]))
                    .fold(f64::INFINITY, f64::min);
                worst = worst.max(near);
            }
        }
    }
    worst
}

/// The Mesh Method of paper 002 against limn at the accuracy the Mesh Method reaches: the
/// distance of its drawing from the certified curve (traced at 1e-6 × the diagonal), and the
/// converse, are measured once and printed; then both are timed, limn certified at the first.
fn mesh_ratio(c: &mut Criterion) {
    let teapot = limn::testing::teapot();
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let opts = CurveOptions::default();
    let view = dir(1, 2, 3);
    let diag = teapot.diagonal();
    let reference = one.install(|| {
        silhouette(
            &teapot,
            &view,
            &ContourOptions::new(opts.clone(), WeldTolerance::Exact, Some(1e-6 * diag)),
        )
        .expect("a valid view")
    });
    let reference: Vec<Vec<[f64; 3]>> = reference.curves.iter().map(|c| c.points.clone()).collect();
    let mesh = baseline_silhouette(&teapot, &view, BaselineMethod::Mesh);
    let mesh: Vec<Vec<[f64; 3]>> = mesh.iter().map(|c| c.points.clone()).collect();
    // What it draws is this far from the true curve (its accuracy); the true curve is this
    // far from what it draws (large if it misses or misconnects a piece).
    let error = one_sided(&mesh, &reference);
    let missed = one_sided(&reference, &mesh);
    eprintln!(
        "Mesh Method on the teapot from (1,2,3): its drawing is within {error:.3e} ({:.3e} x diagonal) of the certified curve; the certified curve is up to {missed:.3e} from its drawing; limn is certified at the first distance below",
        error / diag
    );
    let mut g = c.benchmark_group("mesh-ratio");
    g.bench_function("teapot-1,2,3-mesh-method", |b| {
        b.iter(|| baseline_silhouette(&teapot, &view, BaselineMethod::Mesh))
    });
    g.bench_function("teapot-1,2,3-certified-at-mesh-accuracy", |b| {
        b.iter(|| {
            one.install(|| {
                silhouette(
                    &teapot,
                    &view,
                    &ContourOptions::new(opts.clone(), WeldTolerance::Exact, Some(error)),
                )
                .expect("a valid view")
            })
        })
    });
    g.finish();
}

criterion_group! {
    name = silhouettes;
    config = Criterion::default().sample_size(20).measurement_time(std::time::Duration::from_secs(3));
    targets = benches
}
criterion_group! {
    name = tolerances;
    config = Criterion::default().sample_size(10).measurement_time(std::time::Duration::from_secs(5));
    targets = traced
}
criterion_group! {
    name = ratios;
    config = Criterion::default().sample_size(20).measurement_time(std::time::Duration::from_secs(3));
    targets = mesh_ratio
}
criterion_main!(silhouettes, tolerances, ratios);
