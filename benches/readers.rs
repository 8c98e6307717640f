//! Reading every fixture model (Bézier, IGES, OBJ), exactly: the total time, and per format.

use criterion::{criterion_group, criterion_main, Criterion};
use std::path::{Path, PathBuf};

fn fixtures() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures");
    let mut out = Vec::new();
    let mut stack = vec![root];
    while let Some(dir) = stack.pop() {
        for e in std::fs::read_dir(&dir).unwrap().flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if limn::io::read_model(&p).is_ok() {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

fn benches(c: &mut Criterion) {
    let files = fixtures();
    assert!(files.len() >= 19, "found {} readable fixtures", files.len());
    let mut group = c.benchmark_group("read");
    group.bench_function("all-fixtures", |b| {
        b.iter(|| {
            for f in &files {
                limn::io::read_model(f).unwrap();
            }
        })
    });
    for (name, ext) in [("iges", "igs"), ("obj", "obj"), ("bpt", "bpt")] {
        let some: Vec<_> = files
            .iter()
            .filter(|f| f.extension().is_some_and(|e| e == ext))
            .cloned()
            .collect();
        group.bench_function(name, |b| {
            b.iter(|| {
                for f in &some {
                    limn::io::read_model(f).unwrap();
                }
            })
        });
    }
    group.finish();
}

criterion_group! {
    name = readers;
    config = Criterion::default().sample_size(10).measurement_time(std::time::Duration::from_secs(3));
    targets = benches
}
criterion_main!(readers);
