//! Visual events on the viewing sphere against closed forms.

use limn::analysis::bitangent::curves::BitangentOptions;
use limn::analysis::events::{events, EventKind, EventOptions};
use limn::model::{Format, Model, WeldTolerance};
use limn::number::Rational;
use limn::solver::CurveOptions;
use limn::testing::shapes;

fn q(a: i64, b: i64) -> Rational {
    Rational::from((a, b))
}

/// A torus's parabolic curves are its top and bottom circles, where the tangent plane is
/// horizontal and the asymptotic direction is along the circle: the lip and beak-to-beak
/// directions are the horizontal ones, the equator of the viewing sphere, all longitudes.
#[test]
fn torus_parabolic_events_are_the_equator() {
    let model = Model::from_patches(Format::Json, shapes::torus(&q(3, 1), &q(1, 1)));
    let opts = EventOptions {
        parabolic: Some((CurveOptions::default(), WeldTolerance::Exact, Some(1e-3))),
        flecnodal: None,
        bitangent: None,
    };
    let ev = events(&model, &opts).unwrap();
    assert!(ev.sources_certified());
    // Every curve's distance to the true one on the sphere is bounded.
    assert!(ev.certified(), "{:?}", ev.largest_error());
    let error = ev.largest_error().expect("bounded");
    println!("torus parabolic events: error bound {error:.3e} rad");
    assert!(error < 0.1, "{error}");
    let curves: Vec<_> = ev
        .curves
        .iter()
        .filter(|c| c.kind == EventKind::Parabolic)
        .collect();
    assert_eq!(curves.len(), 2, "top and bottom circles");
    let mut longitudes = Vec::new();
    for c in &curves {
        assert!(c.closed);
        for d in &c.directions {
            assert!(d[2].abs() < 1e-6, "{d:?}");
            assert!(((d[0] * d[0] + d[1] * d[1]).sqrt() - 1.0).abs() < 1e-9);
            longitudes.push(d[1].atan2(d[0]));
        }
    }
    // Completeness within the bound: every horizontal direction (the true curve) is within the
    // error of a drawn direction.
    for i in 0..64 {
        let a = -std::f64::consts::PI + i as f64 * std::f64::consts::PI / 32.0;
        let near = longitudes
            .iter()
            .map(|l| {
                let d = (l - a).rem_euclid(std::f64::consts::PI);
                d.min(std::f64::consts::PI - d)
            })
            .fold(f64::INFINITY, f64::min);
        assert!(near <= error, "longitude {a}: {near} > {error}");
    }
}

/// The double well's bitangent pairs all differ by the same vector `(2x₀, −x₀/2, 0)`: the event
/// curve on the sphere is one point (and its antipode).
#[test]
fn double_well_bitangent_events_are_one_direction() {
    let model = Model::from_patches(Format::Json, vec![shapes::double_well(false)]);
    let opts = EventOptions {
        parabolic: None,
        flecnodal: None,
        bitangent: Some(BitangentOptions::default()),
    };
    let ev = events(&model, &opts).unwrap();
    assert!(ev.sources_certified());
    assert!(ev.certified());
    let error = ev.curves[0].error.expect("bounded");
    println!("double well bitangent events: error bound {error:.3e} rad");
    let x0 = (33.0f64 / 32.0).sqrt();
    let l = (4.0 * x0 * x0 + x0 * x0 / 4.0).sqrt();
    let want = [2.0 * x0 / l, -x0 / 2.0 / l, 0.0];
    assert_eq!(ev.curves.len(), 1);
    for d in &ev.curves[0].directions {
        let dot = d[0] * want[0] + d[1] * want[1] + d[2] * want[2];
        assert!((dot.abs() - 1.0).abs() < 1e-9, "{d:?}");
    }
}
