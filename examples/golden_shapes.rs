//! Writes the exact test shapes of `limn::testing::shapes` as native JSON models into a
//! folder (written by `limn::io::write_model`), for the golden comparison (`tools/golden.py`) and for trying the CLI by hand.
//!
//! `cargo run --example golden_shapes -- DIR`

use limn::number::Rational;
use limn::surface::RationalPatch;
use limn::testing::shapes;
use std::path::PathBuf;

fn main() {
    let Some(dir) = std::env::args().nth(1).map(PathBuf::from) else {
        eprintln!("usage: golden_shapes DIR");
        std::process::exit(2);
    };
    if let Err(e) = std::fs::create_dir_all(&dir) {
        eprintln!("golden_shapes: {}: {e}", dir.display());
        std::process::exit(2);
    }
    let q = |n: i64| Rational::from(n);
    let zero = [q(0), q(0), q(0)];
    let rot = shapes::rotation(0, 2, 1);
    let rot2 = shapes::rotation(2, 3, 1);
    let turn = |ps: Vec<RationalPatch>| -> Vec<RationalPatch> {
        ps.iter()
            .map(|p| shapes::transform(&shapes::transform(p, &rot, &zero), &rot2, &zero))
            .collect()
    };
    let mut two_spheres = shapes::sphere(&q(1));
    two_spheres.extend(
        shapes::sphere(&q(1))
            .iter()
            .map(|p| shapes::transform(p, &shapes::rotation(2, 1, 0), &[q(1), q(1), q(3)])),
    );
    let models: Vec<(&str, Vec<RationalPatch>)> = vec![
        ("sphere", shapes::sphere(&q(2))),
        ("torus", shapes::torus(&q(3), &q(1))),
        ("torus_rotated", turn(shapes::torus(&q(3), &q(1)))),
        ("two_spheres", two_spheres),
        (
            "cylinder_quarter",
            vec![shapes::cylinder_quarter(&q(1), &q(2))],
        ),
        ("double_well", vec![shapes::double_well(false)]),
    ];
    for (name, patches) in models {
        let path = dir.join(format!("{name}.json"));
        if let Err(e) = std::fs::write(&path, limn::io::write_model(&patches)) {
            eprintln!("golden_shapes: {}: {e}", path.display());
            std::process::exit(2);
        }
    }
}
