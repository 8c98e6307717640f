//! Visible regions (issue 5): two spheres from one skew direction (criterion medians, 1 and 2
//! threads), and the teapot from (2,3,-2) at cell depths 6 and 8, 1 and 2 threads, with and
//! without clusters, timed as whole runs (`LIMN_BENCH_TEAPOT=1` to include them; the median of
//! 3 runs is printed with the bounds on the visible share of the area).

use criterion::{criterion_group, criterion_main, Criterion};
use limn::analysis::visibility::visible::{visible_regions, VisibleOptions};
use limn::model::{Format, Model, WeldTolerance};
use limn::number::Rational;
use limn::testing::shapes;

mod common;
use common::{pool, spring_if_asked, view};

fn benches(c: &mut Criterion) {
    let mut spheres = shapes::sphere(&Rational::from(1));
    spheres.extend(
        shapes::sphere(&Rational::from(1)).into_iter().map(|p| {
            p.map_points(|x| std::array::from_fn(|k| Rational::from(&x[k] + [1, 0, -3][k])))
        }),
    );
    let spheres = Model::from_patches(Format::Json, spheres);
    // The cells (the trimming curves are timed on their own below).
    let opts = VisibleOptions {
        max_depth: 6,
        trimming: false,
        ..VisibleOptions::default()
    };
    let mut g = c.benchmark_group("visible");
    g.sample_size(10);
    for threads in [1, 2] {
        let pool = pool(threads);
        g.bench_function(
            format!("two-spheres-1,2,3-depth-6-{threads}-threads"),
            |b| {
                b.iter(|| {
                    pool.install(|| {
                        visible_regions(
                            &spheres,
                            &view([1, 2, 3]),
                            &opts.clone().with_weld(WeldTolerance::Exact),
                        )
                    })
                    .unwrap()
                })
            },
        );
    }
    g.finish();
    if std::env::var_os("LIMN_BENCH_TEAPOT").is_some() {
        let teapot = limn::testing::teapot();
        for depth in [6, 8] {
            for clusters in [true, false] {
                for threads in [1, 2] {
                    let opts = VisibleOptions {
                        max_depth: depth,
                        clusters,
                        trimming: false,
                        ..VisibleOptions::default()
                    };
                    let pool = pool(threads);
                    let mut share = [0.0; 2];
                    let mut times: Vec<f64> = (0..3)
                        .map(|_| {
                            let t = std::time::Instant::now();
                            let r = pool
                                .install(|| {
                                    visible_regions(
                                        &teapot,
                                        &view([2, 3, -2]),
                                        &opts.clone().with_weld(WeldTolerance::Exact),
                                    )
                                })
                                .unwrap();
                            share = r.area_fraction;
                            t.elapsed().as_secs_f64()
                        })
                        .collect();
                    times.sort_by(f64::total_cmp);
                    println!(
                        "visible/teapot-2,3,-2-depth-{depth}-clusters-{clusters}-{threads}-threads: median {:.2} s of 3 runs, area share [{:.4}, {:.4}]",
                        times[1], share[0], share[1]
                    );
                }
            }
        }
    }
}

/// The IGES coil spring (1,062 patches) at cell depth 5, with and without clusters, one whole
/// run each on 2 threads (`LIMN_BENCH_SPRING=1`; minutes).
fn spring() {
    let Some((spring, weld)) = spring_if_asked() else {
        return;
    };
    for clusters in [true, false] {
        let opts = VisibleOptions {
            max_depth: 5,
            clusters,
            trimming: false,
            ..VisibleOptions::default()
        };
        let t = std::time::Instant::now();
        let r = pool(2)
            .install(|| visible_regions(&spring, &view([2, 3, -2]), &opts.clone().with_weld(weld)))
            .unwrap();
        println!(
            "visible/spring-2,3,-2-depth-5-clusters-{clusters}-2-threads: {:.1} s, area share [{:.4}, {:.4}], {} cells",
            t.elapsed().as_secs_f64(),
            r.area_fraction[0],
            r.area_fraction[1],
            r.stats.cells
        );
    }
}

/// The trimming curves of the teapot from (2,3,-2) at tol 1e-6 (cell depth 4: the cells are
/// not what is timed), 1 and 2 threads, one whole run each, against the same run without them
/// (`LIMN_BENCH_TEAPOT=trim`).
fn trimming() {
    if std::env::var("LIMN_BENCH_TEAPOT").ok().as_deref() != Some("trim") {
        return;
    }
    let teapot = limn::testing::teapot();
    let tol = 1e-6 * teapot.diagonal();
    for threads in [1, 2] {
        for trimming in [false, true] {
            let opts = VisibleOptions {
                max_depth: 4,
                trimming,
                tol: Some(tol),
                ..VisibleOptions::default()
            };
            let t = std::time::Instant::now();
            let r = pool(threads)
                .install(|| {
                    visible_regions(
                        &teapot,
                        &view([2, 3, -2]),
                        &opts.clone().with_weld(WeldTolerance::Exact),
                    )
                })
                .unwrap();
            let s = &r.stats;
            println!(
                "visible/teapot-2,3,-2-trimming-{trimming}-tol-1e-6-{threads}-threads: {:.2} s, {} trimming curves ({} certified), {} loops ({} closed), {} pieces without an occlusion curve",
                t.elapsed().as_secs_f64(),
                s.trim_curves,
                s.certified_trim_curves,
                s.trim_loops,
                s.closed_trim_loops,
                r.missing_occlusions.len()
            );
        }
    }
}

fn all(c: &mut Criterion) {
    if std::env::var("LIMN_BENCH_TEAPOT").ok().as_deref() == Some("trim") {
        trimming();
        return;
    }
    benches(c);
    spring();
}

criterion_group!(visible_benches, all);
criterion_main!(visible_benches);
