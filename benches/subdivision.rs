//! de Casteljau subdivision of bivariate Bernstein polynomials of degree (6,6), (9,9),
//! (12,12): one full split of the box into four (at 1/2 in u, then in v), in f64, f64
//! intervals, MPFR at 128 bits (float and interval) and exact rationals.
//! Ratios to f64: `python3 benches/ratios.py subdivision`.

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion};
use limn::bernstein::Bernstein;
use limn::number::{Interval, MpFloat, MpInterval, Number, Precision, Rational};

/// A reproducible polynomial with non-dyadic rational coefficients.
fn exact(d: usize) -> Bernstein<Rational> {
    let n = (d + 1) * (d + 1);
    let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
    let coeffs = (0..n)
        .map(|_| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let p = (state >> 40) as i64 % 2001 - 1000;
            let q = 1 + (state >> 20) as i64 % 97;
            Rational::from((p, q))
        })
        .collect();
    Bernstein::new(&[d, d], coeffs).unwrap()
}

fn split4<N: Number>(p: &Bernstein<N>) -> [Bernstein<N>; 4] {
    let (l, r) = p.subdivide_half(0);
    let (ll, lr) = l.subdivide_half(1);
    let (rl, rr) = r.subdivide_half(1);
    [ll, lr, rl, rr]
}

fn bench_type<N: Number>(c: &mut Criterion, label: &str, prec: Precision) {
    let mut group = c.benchmark_group(format!("subdivide/{label}"));
    for d in [6, 9, 12] {
        let p: Bernstein<N> = exact(d).convert(prec);
        group.bench_with_input(
            BenchmarkId::from_parameter(format!("{d}x{d}")),
            &p,
            |b, p| b.iter(|| split4(black_box(p))),
        );
    }
    group.finish();
}

fn benches(c: &mut Criterion) {
    bench_type::<f64>(c, "f64", Precision::F64);
    bench_type::<Interval>(c, "interval", Precision::F64);
    bench_type::<MpFloat>(c, "mpfr128", Precision(128));
    bench_type::<MpInterval>(c, "mpfr-interval128", Precision(128));
    bench_type::<Rational>(c, "rational", Precision::F64);
}

criterion_group! {
    name = subdivision;
    config = Criterion::default().sample_size(30).measurement_time(std::time::Duration::from_secs(2)).warm_up_time(std::time::Duration::from_millis(500));
    targets = benches
}
criterion_main!(subdivision);
