//! Models with trimmed faces for the tests: exact loops (polygons, circles as rational
//! quadratic arcs) on patches whose parameter box is the unit square.

use limn::model::{Closing, Face, Model, TrimLoop};
use limn::number::Rational;
use limn::surface::ParameterCurve;

pub(crate) fn q(n: i64, d: i64) -> Rational {
    Rational::from((n, d))
}

pub(crate) fn unit() -> [[Rational; 2]; 2] {
    [[q(0, 1), q(1, 1)], [q(0, 1), q(1, 1)]]
}

pub(crate) fn closed(curves: Vec<ParameterCurve>) -> TrimLoop {
    let domain = unit();
    let closing = Closing {
        tolerance: q(0, 1),
        domain: &domain,
        collapsed: [false; 4],
    };
    TrimLoop::close(
        curves.into_iter().map(|c| (c, None)).collect(),
        &closing,
        None,
    )
    .unwrap()
}

pub(crate) fn polygon(p: &[[Rational; 2]]) -> TrimLoop {
    closed(
        (0..p.len())
            .map(|i| ParameterCurve::segment(&p[i], &p[(i + 1) % p.len()]))
            .collect(),
    )
}

/// A circle of radius `r` about `c` as four exact rational quadratic arcs, counter-clockwise
/// (`reverse`: clockwise, as a hole).
pub(crate) fn circle(c: [Rational; 2], r: Rational, reverse: bool) -> TrimLoop {
    let at = |x: i64, y: i64| {
        vec![
            &c[0] + Rational::from(&r * x),
            &c[1] + Rational::from(&r * y),
        ]
    };
    let arc = |a: (i64, i64), m: (i64, i64), b: (i64, i64)| {
        ParameterCurve::new(
            &[at(a.0, a.1), at(m.0, m.1), at(b.0, b.1)],
            &[q(1, 1), q(1, 1), q(2, 1)],
        )
        .unwrap()
    };
    let mut arcs = vec![
        arc((1, 0), (1, 1), (0, 1)),
        arc((0, 1), (-1, 1), (-1, 0)),
        arc((-1, 0), (-1, -1), (0, -1)),
        arc((0, -1), (1, -1), (1, 0)),
    ];
    if reverse {
        arcs.reverse();
        arcs = arcs.into_iter().map(|a| a.reversed()).collect();
    }
    closed(arcs)
}

/// `model` with one face on surface `p` (its domain the unit square).
pub(crate) fn with_face(
    mut model: Model,
    p: usize,
    outer: Option<TrimLoop>,
    inner: Vec<TrimLoop>,
) -> Model {
    model.faces.push(Face {
        surface: p,
        entity: None,
        domain: unit(),
        outer,
        inner,
    });
    model
}
