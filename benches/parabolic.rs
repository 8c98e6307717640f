//! Parabolic curves of the whole teapot, certified at tolerance 1e-6 × diagonal (aim ≤ 50 ms on
//! one thread), on 1 and 2 threads; the topology alone; and forming the exact parabolic
//! functions (the part shared by every run).

use criterion::{criterion_group, criterion_main, Criterion};
use limn::analysis::contour::parabolic::{parabolic, parabolic_function};
use limn::model::WeldTolerance;
use limn::solver::CurveOptions;
use limn::ContourOptions;

fn benches(c: &mut Criterion) {
    let teapot = limn::testing::teapot();
    let opts = CurveOptions::default();
    let tol = 1e-6 * teapot.diagonal();
    let mut g = c.benchmark_group("parabolic");
    g.sample_size(10);
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        g.bench_function(format!("teapot-tol-1e-6-{threads}-threads"), |b| {
            b.iter(|| {
                pool.install(|| {
                    parabolic(
                        &teapot,
                        &ContourOptions::new(opts.clone(), WeldTolerance::Exact, Some(tol)),
                    )
                    .expect("no error")
                })
            })
        });
        if threads == 1 {
            g.bench_function("teapot-topology-1-thread", |b| {
                b.iter(|| {
                    pool.install(|| {
                        parabolic(
                            &teapot,
                            &ContourOptions::new(opts.clone(), WeldTolerance::Exact, None),
                        )
                        .expect("no error")
                    })
                })
            });
            g.bench_function("teapot-functions-1-thread", |b| {
                b.iter(|| {
                    teapot
                        .patches
                        .iter()
                        .map(|p| parabolic_function(&p.surface))
                        .collect::<Vec<_>>()
                })
            });
        }
    }
    g.finish();
}

criterion_group!(parabolic_benches, benches);
criterion_main!(parabolic_benches);
