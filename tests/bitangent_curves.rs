//! Bitangent curves against closed forms.

use limn::analysis::bitangent_curves::{pair_bitangents, BitangentOptions};
use limn::number::Rational;
use limn::testing::shapes;

fn q(a: i64, b: i64) -> Rational {
    Rational::from((a, b))
}

/// z = (x² − 1)² + y² + x y / 2 over [−3/2, 3/2] × [−1, 1]: its only bitangent planes touch at
/// x = ∓x₀, x₀² = 33/32, with q = p + (2x₀, −x₀/2) (the reduced double well, see the test).
fn double_well() -> limn::surface::RationalPatch {
    shapes::graph(
        &[(4, 0, q(1, 1)), (2, 0, q(-2, 1)), (0, 0, q(1, 1)), (0, 2, q(1, 1)), (1, 1, q(1, 2))],
        [q(-3, 2), q(3, 2)],
        [q(-1, 1), q(1, 1)],
    )
}

#[test]
fn double_well_has_one_bitangent_family() {
    let p = double_well();
    let t = std::time::Instant::now();
    let b = pair_bitangents(&p, 0, &p, 0, &BitangentOptions::default());
    eprintln!("{:?} boxes {} branches {} unresolved {}", t.elapsed(), b.boxes, b.branches.len(), b.unresolved.len());
    for u in b.unresolved.iter().take(10) {
        eprintln!("{:?} {}", u.cell, u.reason);
    }
    for br in &b.branches {
        eprintln!("branch closed {} complete {} n {}", br.closed, br.complete, br.points.len());
        for pt in &br.points {
            eprintln!("  p {:?} q {:?}", pt.p, pt.q);
        }
    }
    assert!(b.is_certified());
}
