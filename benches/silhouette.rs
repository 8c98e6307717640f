//! Silhouettes: the whole teapot for one generic view, one bicubic teapot patch, and the exact
//! sphere and torus; single-threaded (the parallel speed-up is measured by the CLI's --threads).

use criterion::{criterion_group, criterion_main, Criterion};
use limn::analysis::silhouette::{silhouette, silhouette_function, View};
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

criterion_group! {
    name = silhouettes;
    config = Criterion::default().sample_size(20).measurement_time(std::time::Duration::from_secs(3));
    targets = benches
}
criterion_main!(silhouettes);
