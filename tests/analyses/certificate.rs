//! Curve certificates: every certificate the solver writes is accepted by the independent
//! checker (exact num-rational arithmetic), and mutated certificates (a box moved, a sign
//! flipped, a crossing moved, a piece dropped, an arc rewired) are rejected.

use limn::analysis::contour::silhouette::silhouette_function;
use limn::ContourOptions;

use limn::analysis::view::View;
use limn::bernstein::Bernstein;
use limn::model::Format;
use limn::number::Rational;
use limn::solver::certificate::{CrossingClaim, CurveCertificate};
use limn::solver::checker::check_curve;
use limn::solver::{solve_curve, CurveOptions};
use limn::testing::{shapes, strategies};
use proptest::prelude::*;
use proptest::test_runner::FileFailurePersistence;

fn q(a: i64, b: i64) -> Rational {
    Rational::from((a, b))
}

fn dir(x: i64, y: i64, z: i64) -> View {
    View::Direction([q(x, 1), q(y, 1), q(z, 1)])
}

fn teapot_functions(view: &View) -> Vec<Bernstein<Rational>> {
    let m = limn::testing::teapot();
    m.patches
        .iter()
        .map(|p| silhouette_function(&p.surface, view))
        .collect()
}

fn certify(g: &Bernstein<Rational>) -> CurveCertificate {
    let t = solve_curve(g, &CurveOptions::default());
    CurveCertificate::new(g, &t)
}

#[test]
fn teapot_certificates_are_valid() {
    let mut arcs = 0;
    for view in [dir(1, 2, 3), dir(0, 0, 1), dir(1, 0, 0), dir(-3, 1, 2)] {
        for (i, g) in teapot_functions(&view).iter().enumerate() {
            let cert = certify(g);
            let summary = check_curve(&cert).unwrap_or_else(|e| panic!("patch {i}: {e}"));
            assert_eq!(summary.cells, cert.cells.len());
            arcs += summary.arcs;
        }
    }
    assert!(
        arcs > 40,
        "the views cross the teapot's patches ({arcs} arcs)"
    );
}

#[test]
fn closed_form_certificates_are_valid() {
    // Sphere and torus patches from generic and axis directions (zero edges, touches, corners).
    let mut patches = shapes::sphere(&q(3, 2));
    patches.extend(shapes::torus(&q(3, 1), &q(1, 1)));
    for view in [dir(1, 2, 3), dir(0, 0, 1), dir(1, 0, 0), dir(0, 1, 1)] {
        for (i, p) in patches.iter().enumerate() {
            let g = silhouette_function(p, &view);
            let cert = certify(&g);
            check_curve(&cert).unwrap_or_else(|e| panic!("patch {i}: {e}"));
        }
    }
}

/// A patch with arcs, to mutate.
fn sample() -> CurveCertificate {
    let g = &teapot_functions(&dir(1, 2, 3))[0];
    let cert = certify(g);
    assert!(!cert.arcs.is_empty() && cert.certified);
    check_curve(&cert).unwrap();
    cert
}

#[test]
fn a_flipped_sign_is_rejected() {
    let mut cert = sample();
    let i = cert
        .cells
        .iter()
        .position(|c| c.kind == "excluded")
        .unwrap();
    cert.cells[i].sign = cert.cells[i].sign.map(|s| -s);
    let e = check_curve(&cert).unwrap_err();
    assert_eq!(e.item, format!("cell {i}"), "{e}");
    let mut cert = sample();
    let i = cert.cells.iter().position(|c| c.kind == "graph").unwrap();
    cert.cells[i].sign = cert.cells[i].sign.map(|s| -s);
    assert_eq!(check_curve(&cert).unwrap_err().item, format!("cell {i}"));
}

#[test]
fn a_moved_or_dropped_box_is_rejected() {
    // Moved: the tiling breaks (overlap and a hole).
    let mut cert = sample();
    let i = cert.cells.iter().position(|c| c.hi[0] != "1").unwrap();
    let width = |c: &limn::solver::certificate::CellClaim| {
        let lo: Rational = c.lo[0].parse().unwrap();
        let hi: Rational = c.hi[0].parse().unwrap();
        (lo, hi)
    };
    let (lo, hi) = width(&cert.cells[i]);
    let w = Rational::from(&hi - &lo);
    cert.cells[i].lo[0] = Rational::from(&lo + &w).to_string();
    cert.cells[i].hi[0] = Rational::from(&hi + &w).to_string();
    assert!(check_curve(&cert).is_err());
    // Dropped: area missing.
    let mut cert = sample();
    cert.cells.pop();
    assert_eq!(check_curve(&cert).unwrap_err().item, "cells");
    // Split claim: an excluded box replaced by a box twice its size elsewhere is caught too.
    let mut cert = sample();
    let k = cert
        .cells
        .iter()
        .position(|c| c.kind == "excluded")
        .unwrap();
    cert.cells[k].kind = "graph".into();
    cert.cells[k].along = Some("u".into());
    let _ = check_curve(&cert); // may be valid (g can be monotone there); must not panic
}

#[test]
fn a_dropped_or_rewired_piece_is_rejected() {
    // An arc dropped.
    let mut cert = sample();
    cert.arcs.pop();
    assert!(check_curve(&cert).is_err());
    // An arc's end moved to another crossing.
    let mut cert = sample();
    let n = cert.crossings.len();
    if n > 2 {
        let a = &mut cert.arcs[0];
        a.to = (0..n).find(|&c| c != a.from && c != a.to).unwrap();
        assert!(check_curve(&cert).is_err());
    }
    // A branch dropped.
    let mut cert = sample();
    cert.branches.pop();
    assert!(check_curve(&cert).is_err());
    // A crossing dropped from the list (and its references renumbered away).
    let mut cert = sample();
    let last = cert.crossings.len() - 1;
    cert.crossings.pop();
    cert.arcs.retain(|a| a.from != last && a.to != last);
    cert.branches.clear();
    assert!(check_curve(&cert).is_err());
}

#[test]
fn a_moved_crossing_is_rejected() {
    let mut cert = sample();
    let i = cert
        .crossings
        .iter()
        .position(|c| matches!(c, CrossingClaim::OnLine { lo, hi, .. } if lo != hi))
        .unwrap();
    if let CrossingClaim::OnLine { lo, hi, .. } = &mut cert.crossings[i] {
        // Shift the interval past itself: it no longer brackets the root.
        let (a, b): (Rational, Rational) = (lo.parse().unwrap(), hi.parse().unwrap());
        let w = Rational::from(&b - &a);
        *lo = Rational::from(&b + &w).to_string();
        *hi = Rational::from(&b + &(w * 2u32)).to_string();
    }
    assert_eq!(
        check_curve(&cert).unwrap_err().item,
        format!("crossing {i}")
    );
    // A claimed certified run with an unresolved cell.
    let mut cert = sample();
    cert.cells[0].kind = "unresolved".into();
    assert!(check_curve(&cert).is_err());
    // Garbage numbers are an error, never a panic.
    let mut cert = sample();
    cert.g[0] = "1/0".into();
    assert!(check_curve(&cert).is_err());
    let mut cert = sample();
    cert.cells[0].lo[0] = "x".into();
    assert!(check_curve(&cert).is_err());
}

proptest! {
    #![proptest_config(ProptestConfig {
        failure_persistence: Some(Box::new(FileFailurePersistence::Direct(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/proptest-regressions/certificate.txt"
        )))),
        ..ProptestConfig::with_cases(limn::testing_cases(24))
    })]

    /// Random and degenerate patches (planar, cylindrical, collapsed, perturbed): the
    /// certificate of whatever the solver proved is accepted.
    #[test]
    fn random_certificates_are_valid(
        p in prop_oneof![strategies::patch(3), strategies::degenerate_patch(3)],
        d in (-3i64..=3, -3i64..=3, 1i64..=3),
    ) {
        let g = silhouette_function(&p, &dir(d.0, d.1, d.2));
        let opts = CurveOptions { max_boxes: 4_000, ..CurveOptions::default() };
        let t = solve_curve(&g, &opts);
        let cert = CurveCertificate::new(&g, &t);
        if let Err(e) = check_curve(&cert) {
            prop_assert!(false, "{e}");
        }
    }
}

/// Whole-model certificates of exact models, parallel and perspective views: the silhouette
/// function relation (with collapsed-side factors divided out) and every curve claim hold; a
/// changed coefficient of g, or a wrong divided side, is caught.
#[test]
fn model_certificates_check_against_the_model() {
    use limn::analysis::contour::certificate::{check_silhouette, SilhouetteCertificate};
    use limn::analysis::contour::silhouette::silhouette;
    use limn::model::{Model, WeldTolerance};
    let sphere = Model::from_patches(Format::Json, shapes::sphere(&q(3, 2)));
    let torus = Model::from_patches(Format::Json, shapes::torus(&q(3, 1), &q(1, 1)));
    let eye = View::Eye([q(7, 1), q(-5, 2), q(9, 1)]);
    for (m, view) in [
        (&sphere, dir(1, 2, 3)),
        (&sphere, eye.clone()),
        (&torus, eye),
    ] {
        let s = silhouette(
            m,
            &view,
            &ContourOptions::new(CurveOptions::default(), WeldTolerance::Exact, None),
        )
        .expect("a valid view");
        let cert = SilhouetteCertificate::new("exact", &view, &s);
        let v = check_silhouette(m, &cert).unwrap_or_else(|e| panic!("{e}"));
        assert!(v.certified && v.arcs > 0);
        // The sphere's poles are collapsed sides: their factors were divided out.
        let divided = cert.patches.iter().find(|p| !p.divided.is_empty()).cloned();
        if let Some(p) = divided {
            let mut bad = cert.clone();
            bad.patches[p.patch].divided.clear();
            let e = check_silhouette(m, &bad).unwrap_err();
            assert_eq!(e.item, format!("patch {}", p.patch), "{e}");
        }
        let mut bad = cert.clone();
        let k = bad.patches[0].curve.g.len() / 2;
        bad.patches[0].curve.g[k] = format!("{}1/3", bad.patches[0].curve.g[k].replace('/', "0/"));
        assert!(check_silhouette(m, &bad).is_err());
    }
}
