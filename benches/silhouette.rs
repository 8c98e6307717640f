//! Silhouettes: the whole teapot for one generic view, one bicubic teapot patch, and the exact
//! sphere and torus, single-threaded; the certified drawing at tolerances 1e-3, 1e-6, 1e-9 on
//! 1 and 2 threads; writing and independently checking a certificate.

use criterion::{criterion_group, criterion_main, Criterion};
use limn::analysis::silhouette::{silhouette, silhouette_function, View};
use limn::analysis::silhouette_certificate::{check_silhouette, SilhouetteCertificate};
use limn::model::{Format, Model, WeldTolerance};
use limn::number::Rational;
use limn::solver::{solve_curve, CurveOptions};
use limn::testing::shapes;

fn dir(x: i64, y: i64, z: i64) -> View {
    View::Direction([Rational::from(x), Rational::from(y), Rational::from(z)])
}

fn benches(c: &mut Criterion) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let teapot = limn::io::read_model_bytes(
        "teapot",
        limn::cli::EMBEDDED_TEAPOT.as_bytes(),
        Some(Format::Bpt),
    )
    .unwrap();
    let opts = CurveOptions::default();
    let mut g = c.benchmark_group("silhouette");
    g.bench_function("teapot-1,2,3", |b| {
        b.iter(|| {
            pool.install(|| silhouette(&teapot, &dir(1, 2, 3), &opts, WeldTolerance::Exact, None))
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
            pool.install(|| silhouette(&sphere, &dir(1, 2, 3), &opts, WeldTolerance::Exact, None))
        })
    });
    let torus = Model::from_patches(
        Format::Json,
        shapes::torus(&Rational::from(3), &Rational::from(1)),
    );
    g.bench_function("torus-1,2,3", |b| {
        b.iter(|| {
            pool.install(|| silhouette(&torus, &dir(1, 2, 3), &opts, WeldTolerance::Exact, None))
        })
    });
    g.finish();
}

/// The certified drawing at a tolerance (relative to the teapot's diagonal), on 1 and 2
/// threads; one patch at 1e-6; and the independent check of a certificate.
fn traced(c: &mut Criterion) {
    let teapot = limn::io::read_model_bytes(
        "teapot",
        limn::cli::EMBEDDED_TEAPOT.as_bytes(),
        Some(Format::Bpt),
    )
    .unwrap();
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
                            &opts,
                            WeldTolerance::Exact,
                            Some(tol * diag),
                        )
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
                    &opts,
                    WeldTolerance::Exact,
                    Some(1e-6 * diag),
                )
            })
        })
    });
    let s = one.install(|| silhouette(&teapot, &dir(1, 2, 3), &opts, WeldTolerance::Exact, None));
    g.bench_function("teapot-1,2,3-certificate", |b| {
        b.iter(|| one.install(|| SilhouetteCertificate::new("teapot", &dir(1, 2, 3), &s)))
    });
    let cert = SilhouetteCertificate::new("teapot", &dir(1, 2, 3), &s);
    g.bench_function("teapot-1,2,3-check", |b| {
        b.iter(|| one.install(|| check_silhouette(&teapot, &cert).unwrap()))
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
criterion_main!(silhouettes, tolerances);
