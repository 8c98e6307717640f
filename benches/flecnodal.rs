//! Flecnodal curves of one bicubic teapot patch (the rim, patch 0): its topology, certified at
//! tolerance 1e-4 × diagonal, and the exact systems (the part every run shares); with
//! `LIMN_BENCH_TEAPOT=1` also at 1e-6 × diagonal (the aim: ≤ 100 ms; seconds today), the
//! handle's patch 16, a per-patch survey of the whole teapot (time, curves, unresolved boxes,
//! printed once) and the whole teapot's topology on 1 and 2 threads (one timed run each).

use criterion::{criterion_group, criterion_main, Criterion};
use limn::analysis::flecnodal::curves::{flecnodal_curves, patch_flecnodal, FlecnodalOptions};
use limn::analysis::flecnodal::system::{flecnodal_system, Chart};

fn benches(c: &mut Criterion) {
    let teapot = limn::testing::teapot();
    let heavy = std::env::var("LIMN_BENCH_TEAPOT").is_ok();
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let mut g = c.benchmark_group("flecnodal");
    g.sample_size(10);
    // Patch 0 (the rim) and patch 16 (the handle) have flecnodal curves.
    let runs: Vec<(usize, &str, Option<f64>)> = if heavy {
        vec![
            (0, "topology", None),
            (0, "tol-1e-4", Some(1e-4)),
            (0, "tol-1e-6", Some(1e-6)),
            (16, "topology", None),
        ]
    } else {
        vec![(0, "topology", None), (0, "tol-1e-4", Some(1e-4))]
    };
    for (patch, label, t) in runs {
        let p = &teapot.patches[patch].surface;
        let t = t.map(|t| t * teapot.diagonal());
        {
            let opts = FlecnodalOptions::with_tolerance(t);
            let r = one.install(|| patch_flecnodal(p, patch, &opts));
            eprintln!(
                "patch {patch} {label}: {} curves, {} points, {} unresolved, {} boxes, error bound {:?}",
                r.branches.len(),
                r.branches.iter().map(|b| b.points.len()).sum::<usize>(),
                r.unresolved.len(),
                r.boxes,
                r.error_bound
            );
            g.bench_function(format!("patch-{patch}-{label}-1-thread"), |b| {
                b.iter(|| one.install(|| patch_flecnodal(p, patch, &opts)))
            });
        }
    }
    g.bench_function("patch-0-systems", |b| {
        b.iter(|| {
            [Chart::AlongU, Chart::AlongV].map(|c| flecnodal_system(&teapot.patches[0].surface, c))
        })
    });
    if heavy {
        let opts = FlecnodalOptions::with_tolerance(None);
        for (i, p) in teapot.patches.iter().enumerate() {
            let t = std::time::Instant::now();
            let r = one.install(|| patch_flecnodal(&p.surface, i, &opts));
            eprintln!(
                "survey patch {i}: {:.1} ms, {} curves ({} complete), {} unresolved, {} boxes",
                t.elapsed().as_secs_f64() * 1e3,
                r.branches.len(),
                r.branches.iter().filter(|b| b.complete).count(),
                r.unresolved.len(),
                r.boxes
            );
        }
        // Whole runs of tens of seconds: one timed run each, not criterion samples.
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let t = std::time::Instant::now();
            let r = pool.install(|| flecnodal_curves(&teapot, &opts)).unwrap();
            eprintln!(
                "teapot topology, {threads} threads: {:.2} s (one run), {} curves, {} unresolved boxes",
                t.elapsed().as_secs_f64(),
                r.patches.iter().map(|p| p.branches.len()).sum::<usize>(),
                r.patches.iter().map(|p| p.unresolved.len()).sum::<usize>()
            );
        }
    }
    g.finish();
}

criterion_group!(flecnodal_benches, benches);
criterion_main!(flecnodal_benches);
