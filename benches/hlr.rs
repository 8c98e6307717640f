//! Hidden-line drawings (issue 5): the torus and two spheres from one skew direction (criterion
//! medians, 1 and 2 threads), and the teapot from (2,3,-2) and (1,2,3) with and without clusters,
//! and from (1,2,3) drawn to tolerances 1e-6 and 1e-9 (relative to its diagonal), timed as whole
//! runs (each takes seconds: `LIMN_BENCH_TEAPOT=1` to include them, `LIMN_BENCH_TEAPOT=tol` for
//! the tolerance runs only; a few runs, the median printed); the IGES coil spring from (2,3,-2)
//! with and without clusters, one run each on 2 threads (`LIMN_BENCH_SPRING=1`; minutes).

use criterion::{criterion_group, criterion_main, Criterion};
use limn::analysis::visibility::hlr::{hidden_lines, HlrOptions};
use limn::model::{Format, Model, WeldTolerance};
use limn::number::Rational;
use limn::testing::shapes;

mod common;
use common::{pool, spring_if_asked, view};

fn benches(c: &mut Criterion) {
    let opts = HlrOptions::default();
    let torus = Model::from_patches(
        Format::Json,
        shapes::torus(&Rational::from(2), &Rational::from(1)),
    );
    let mut spheres = shapes::sphere(&Rational::from(1));
    spheres.extend(
        shapes::sphere(&Rational::from(1)).into_iter().map(|p| {
            p.map_points(|x| std::array::from_fn(|k| Rational::from(&x[k] + [1, 0, -3][k])))
        }),
    );
    let spheres = Model::from_patches(Format::Json, spheres);
    let mut g = c.benchmark_group("hlr");
    g.sample_size(10);
    for threads in [1, 2] {
        let pool = pool(threads);
        for (name, m) in [("torus", &torus), ("two-spheres", &spheres)] {
            g.bench_function(format!("{name}-1,2,3-{threads}-threads"), |b| {
                b.iter(|| {
                    pool.install(|| {
                        hidden_lines(
                            m,
                            &view([1, 2, 3]),
                            &opts.clone().with_weld(WeldTolerance::Exact),
                        )
                    })
                    .unwrap()
                })
            });
        }
    }
    g.finish();
    if let Some(which) = std::env::var_os("LIMN_BENCH_TEAPOT") {
        let teapot = limn::testing::teapot();
        let off = HlrOptions {
            clusters: false,
            ..HlrOptions::default()
        };
        let to = |t: f64| HlrOptions {
            tol: Some(t * teapot.diagonal()),
            ..HlrOptions::default()
        };
        let (tol6, tol9) = (to(1e-6), to(1e-9));
        let mut runs = vec![
            ([1, 2, 3], &tol6, "tol-1e-6"),
            ([1, 2, 3], &tol9, "tol-1e-9"),
        ];
        if which != "tol" {
            runs.extend([
                ([2, 3, -2], &opts, "clusters"),
                ([1, 2, 3], &opts, "clusters"),
                ([2, 3, -2], &off, "no-clusters"),
                ([1, 2, 3], &off, "no-clusters"),
            ]);
        }
        for (d, opts, label) in runs {
            for threads in [1, 2] {
                let pool = pool(threads);
                let mut times: Vec<f64> = (0..3)
                    .map(|_| {
                        let t = std::time::Instant::now();
                        let h = pool
                            .install(|| {
                                hidden_lines(
                                    &teapot,
                                    &view(d),
                                    &(opts).clone().with_weld(WeldTolerance::Exact),
                                )
                            })
                            .unwrap();
                        std::hint::black_box(h);
                        t.elapsed().as_secs_f64()
                    })
                    .collect();
                times.sort_by(f64::total_cmp);
                println!(
                    "hlr/teapot-{d:?}-{label}-{threads}-threads: median {:.2} s of 3 runs",
                    times[1]
                );
            }
        }
    }
}

/// The IGES coil spring (1,062 patches) from (2,3,-2), with and without clusters, one run each
/// on 2 threads (`LIMN_BENCH_SPRING=1`; minutes).
fn spring(_: &mut Criterion) {
    let Some((spring, weld)) = spring_if_asked() else {
        return;
    };
    let pool = pool(2);
    for clusters in [true, false] {
        let opts = HlrOptions {
            clusters,
            ..HlrOptions::default()
        };
        let t = std::time::Instant::now();
        let h = pool
            .install(|| hidden_lines(&spring, &view([2, 3, -2]), &opts.clone().with_weld(weld)))
            .unwrap();
        println!(
            "hlr/spring-2,3,-2-clusters-{clusters}-2-threads: {:.1} s, {} pieces, {} unresolved, {} cluster pairs",
            t.elapsed().as_secs_f64(),
            h.pieces.len(),
            h.pieces.iter().filter(|p| !p.certified).count(),
            h.stats.cluster_pairs
        );
    }
}

criterion_group!(hlr_benches, benches, spring);
criterion_main!(hlr_benches);
