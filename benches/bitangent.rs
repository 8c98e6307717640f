//! Bitangent curves: the double well (a patch with itself, one family of pairs) and one pair of
//! patches across two spheres, topology and tolerance 1e-3; with `LIMN_BENCH_TEAPOT=1` the
//! teapot: a survey of every pair of patches on one thread (time, boxes, curves, unresolved,
//! printed once) and the whole teapot at tolerance 1e-4 × diagonal on 1 and 2 threads (one
//! timed run each).

use criterion::{criterion_group, criterion_main, Criterion};
use limn::analysis::bitangent::curves::{bitangent_curves, pair_bitangents, BitangentOptions};
use limn::number::Rational;
use limn::testing::shapes;

fn benches(c: &mut Criterion) {
    let heavy = std::env::var("LIMN_BENCH_TEAPOT").is_ok();
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let mut g = c.benchmark_group("bitangent");
    g.sample_size(10);
    let q = |a: i64, b: i64| Rational::from((a, b));
    let well = shapes::double_well(false);
    let a = shapes::sphere(&q(1, 1));
    let zero = [q(0, 1), q(0, 1), q(0, 1)];
    let b: Vec<_> = shapes::sphere(&q(1, 2))
        .iter()
        .map(|p| {
            let p = shapes::transform(p, &shapes::rotation(1, 2, 1), &zero);
            shapes::transform(&p, &shapes::rotation(2, 3, 1), &[q(3, 1), q(1, 1), q(2, 1)])
        })
        .collect();
    let runs = [
        ("double-well", &well, &well, 0, 0),
        ("spheres-0-10", &a[0], &b[2], 0, 10),
    ];
    for (name, p, r, i, j) in runs {
        for (label, tol) in [("topology", None), ("tol-1e-3", Some(1e-3))] {
            let opts = BitangentOptions::with_tolerance(tol);
            let out = one.install(|| pair_bitangents(p, i, r, j, &opts));
            eprintln!(
                "{name} {label}: {} curves, {} points, {} unresolved, {} boxes, error bound {:?}",
                out.branches.len(),
                out.branches.iter().map(|b| b.points.len()).sum::<usize>(),
                out.unresolved.len(),
                out.boxes,
                out.error_bound
            );
            g.bench_function(format!("{name}-{label}-1-thread"), |bch| {
                bch.iter(|| one.install(|| pair_bitangents(p, i, r, j, &opts)))
            });
        }
    }
    g.finish();
    if heavy {
        let teapot = limn::testing::teapot();
        let opts = BitangentOptions::with_tolerance(None);
        let n = teapot.patches.len();
        let mut total = 0.0;
        for i in 0..n {
            for j in i..n {
                let t = std::time::Instant::now();
                let r = one.install(|| {
                    pair_bitangents(
                        &teapot.patches[i].surface,
                        i,
                        &teapot.patches[j].surface,
                        j,
                        &opts,
                    )
                });
                let ms = t.elapsed().as_secs_f64() * 1e3;
                total += ms;
                eprintln!(
                    "survey pair {i}-{j}: {ms:.1} ms, {} curves ({} complete), {} unresolved, {} boxes",
                    r.branches.len(),
                    r.branches.iter().filter(|b| b.complete).count(),
                    r.unresolved.len(),
                    r.boxes
                );
            }
        }
        eprintln!(
            "survey total (topology, 1 thread, no pruning): {:.1} s",
            total / 1e3
        );
        // Whole runs of minutes: one timed run each, not criterion samples.
        let tol = 1e-4 * teapot.diagonal();
        let opts = BitangentOptions::with_tolerance(Some(tol));
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let t = std::time::Instant::now();
            let r = pool.install(|| bitangent_curves(&teapot, &opts)).unwrap();
            eprintln!(
                "teapot tol 1e-4 x diagonal, {threads} threads: {:.1} s (one run), {} pairs, {} pruned, {} self-pairs excluded, {} curves, {} boxes, {} unresolved boxes",
                t.elapsed().as_secs_f64(),
                r.pairs_total,
                r.pruned,
                r.excluded_self,
                r.pairs.iter().map(|p| p.branches.len()).sum::<usize>(),
                r.pairs.iter().map(|p| p.boxes).sum::<usize>(),
                r.pairs.iter().map(|p| p.unresolved.len()).sum::<usize>()
            );
        }
    }
}

criterion_group!(bitangent_benches, benches);
criterion_main!(bitangent_benches);
