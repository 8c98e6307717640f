//! Hidden lines on trimmed faces (`proofs/hidden-lines.md`, "Trimmed faces"): a square plate
//! with a round hole above a larger plate of two patches, seen obliquely from above, against
//! the closed form of what the hole shows; the IGES fixtures with faces, certified.

use crate::trim_models::{circle, q, unit, with_face};
use limn::analysis::visibility::hlr::{hidden_lines, HiddenLines, HlrOptions, LineKind};
use limn::model::{Format, Model, WeldTolerance};
use limn::surface::RationalPatch;
use limn::View;

/// A flat bilinear plate `[x0, x1] × [y0, y1]` at height `z`.
fn plate(x: [i64; 2], y: [i64; 2], z: i64) -> RationalPatch {
    let p = |a: i64, b: i64| [q(a, 1), q(b, 1), q(z, 1)];
    RationalPatch::polynomial(
        [1, 1],
        vec![p(x[0], y[0]), p(x[0], y[1]), p(x[1], y[0]), p(x[1], y[1])],
    )
    .unwrap()
}

/// The plate `[-1, 1]²` at z = 0 above the plate `[-2, 2]²` at z = -1 made of two patches
/// meeting at x = 0, every patch's parameter box the unit square.
fn plate_above_another() -> Model {
    let mut m = Model::from_patches(
        Format::Json,
        vec![
            plate([-1, 1], [-1, 1], 0),
            plate([-2, 0], [-2, 2], -1),
            plate([0, 2], [-2, 2], -1),
        ],
    );
    for p in &mut m.patches {
        p.source.parameters = Some(unit());
    }
    m
}

/// The plate `[-1, 1]²` at z = 0 with a hole of radius 1/2 about the origin (1/4 in its
/// parameters), above the plate `[-2, 2]²` at z = -1 made of two patches meeting at x = 0.
fn holed_plate_above_another() -> Model {
    let m = plate_above_another();
    let hole = circle([q(1, 2), q(1, 2)], q(1, 4), true);
    with_face(m, 0, None, vec![hole])
}

/// Looking down (into the scene along `dir`, z component negative).
const DIR: [i64; 3] = [1, 2, -8];

/// The closed form: a point `p` of the lower plate is behind the upper face when its ray
/// towards the viewer meets z = 0 inside the square and outside the hole (`None` within
/// `eps` of either boundary).
fn behind_upper(p: [f64; 3], eps: f64) -> Option<bool> {
    let s = -p[2] / -(DIR[2] as f64);
    let x = p[0] - s * DIR[0] as f64;
    let y = p[1] - s * DIR[1] as f64;
    let square = x.abs().max(y.abs());
    let r = x.hypot(y);
    if (square - 1.0).abs() < eps || (r - 0.5).abs() < eps {
        return None;
    }
    Some(square < 1.0 && r > 0.5)
}

fn drawing(model: &Model, tol: f64) -> HiddenLines {
    let opts = HlrOptions {
        tol: Some(tol),
        ..HlrOptions::default().with_weld(WeldTolerance::Exact)
    };
    hidden_lines(model, &View::direction(DIR), &opts).unwrap()
}

#[test]
fn a_hole_shows_the_plate_below_and_its_rim_is_drawn() {
    let model = holed_plate_above_another();
    let tol = 1e-6;
    let h = drawing(&model, tol);
    let uncertified: Vec<_> = h.pieces.iter().filter(|p| !p.certified).collect();
    assert!(uncertified.is_empty(), "unresolved: {uncertified:#?}");
    // The rim: trimming-curve pieces, visible, on the circle of radius 1/2 at z = 0, and
    // all round it.
    let rim: Vec<_> = h
        .pieces
        .iter()
        .filter(|p| p.kind == LineKind::Trim)
        .collect();
    assert!(!rim.is_empty());
    let mut angles = Vec::new();
    for p in &rim {
        assert_eq!(p.qi, Some(0), "the rim is in front of everything");
        let bound = p.error_bound.expect("drawn to the tolerance");
        assert!(bound <= tol);
        for x in &p.points {
            let r = x[0].hypot(x[1]);
            assert!(
                (r - 0.5).abs() <= bound + 1e-12 && x[2].abs() <= bound + 1e-12,
                "{x:?}"
            );
            angles.push(x[1].atan2(x[0]));
        }
    }
    angles.sort_by(f64::total_cmp);
    let gaps = angles.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max);
    assert!(
        gaps < 0.1,
        "the rim is drawn all round (largest gap {gaps})"
    );
    // Nothing of the upper plate is drawn inside the hole.
    for p in h
        .pieces
        .iter()
        .filter(|p| p.patch == 0 && p.kind != LineKind::Trim)
    {
        for x in &p.points {
            assert!(x[0].hypot(x[1]) >= 0.5 - 1e-9, "{x:?} inside the hole");
        }
    }
    // The lower plate's lines: hidden exactly where the upper face is in front (the closed
    // form at every drawn point off the boundaries' images), visible through the hole.
    let (mut through_hole, mut hidden) = (0, 0);
    for p in h.pieces.iter().filter(|p| p.patch != 0) {
        for x in &p.points {
            let Some(b) = behind_upper(*x, 1e-4) else {
                continue;
            };
            assert_eq!(p.qi, Some(usize::from(b)), "at {x:?}: {p:#?}");
            hidden += usize::from(b);
            let s = 1.0 / 8.0;
            let hole = (x[0] - s).hypot(x[1] - 2.0 * s) < 0.5;
            through_hole += usize::from(!b && hole);
        }
    }
    assert!(
        hidden > 0 && through_hole > 0,
        "{hidden} hidden, {through_hole} through the hole"
    );
    // The report states the trims' assumption.
    assert!(h.assumptions.iter().any(|a| a.contains("trimming curve")));
}

#[test]
fn whole_surfaces_when_asked_draw_the_plate_over_the_hole() {
    let model = holed_plate_above_another();
    let opts = HlrOptions {
        trims: false,
        ..HlrOptions::default().with_weld(WeldTolerance::Exact)
    };
    let h = hidden_lines(&model, &View::direction(DIR), &opts).unwrap();
    assert!(h.pieces.iter().all(|p| p.kind != LineKind::Trim));
    // Untrimmed, the upper plate covers the lower plate's shared edge wherever it is in
    // front, the hole included.
    for p in h.pieces.iter().filter(|p| p.patch != 0 && p.certified) {
        for x in &p.points {
            let s = 1.0 / 8.0;
            let (x0, y0) = (x[0] - s, x[1] - 2.0 * s);
            if x0.abs().max(y0.abs()) < 0.99 {
                assert_eq!(p.qi, Some(1), "at {x:?}");
            }
        }
    }
}

#[test]
fn the_fixtures_with_faces_draw_certified() {
    // (fixture, view, least certified share).
    let cases = [
        ("OCC8842_cylinder_Ideas.igs", [1, 2, 3], 1.0),
        ("OCC8842_cone_Ideas.igs", [1, 2, 3], 1.0),
        ("CTS17806-38038.igs", [1, 2, 3], 0.95),
    ];
    for (name, dir, least) in cases {
        let path = format!("{}/fixtures/iges/occt/{name}", env!("CARGO_MANIFEST_DIR"));
        let model = limn::read_model(std::path::Path::new(&path)).unwrap();
        let h = hidden_lines(&model, &View::direction(dir), &HlrOptions::default()).unwrap();
        let n = h.pieces.len();
        let ok = h.pieces.iter().filter(|p| p.certified).count();
        assert!(
            ok as f64 >= least * n as f64,
            "{name}: {ok} of {n} certified"
        );
        // Every trimming-curve piece of a face drawn lies on its face's boundary: its
        // parameters on the loop's patch are inside the square.
        for p in h.pieces.iter().filter(|p| p.kind == LineKind::Trim) {
            for &(_, u, v) in &p.points_uv {
                assert!((-1e-9..=1.0 + 1e-9).contains(&u) && (-1e-9..=1.0 + 1e-9).contains(&v));
            }
        }
    }
}

/// The drawing's pieces by (kind, visibility): their number and their summed length.
fn tally(h: &HiddenLines) -> std::collections::BTreeMap<(String, Option<usize>), (usize, f64)> {
    let mut t = std::collections::BTreeMap::new();
    for p in &h.pieces {
        let length: f64 = p
            .points
            .windows(2)
            .map(|w| {
                (0..3)
                    .map(|k| (w[1][k] - w[0][k]).powi(2))
                    .sum::<f64>()
                    .sqrt()
            })
            .sum();
        let e = t.entry((format!("{:?}", p.kind), p.qi)).or_insert((0, 0.0));
        e.0 += 1;
        e.1 += length;
    }
    t
}

/// The same part read from IGES and from OCCT's STEP translation of it draws the same: every
/// piece certified, as many pieces of each kind and visibility, of the same length (the files
/// hold the same surfaces; their trimming curves differ by the translation's rounding).
#[test]
fn step_and_iges_of_one_part_draw_the_same() {
    let root = env!("CARGO_MANIFEST_DIR");
    for name in ["OCC8842_cylinder_Ideas", "OCC8842_cone_Ideas"] {
        let draw = |path: String| {
            let model = limn::read_model(std::path::Path::new(&path)).unwrap();
            hidden_lines(&model, &View::direction([1, 2, 3]), &HlrOptions::default()).unwrap()
        };
        let iges = draw(format!("{root}/fixtures/iges/occt/{name}.igs"));
        let step = draw(format!("{root}/fixtures/step/occt-written/{name}.stp"));
        for (h, f) in [(&iges, "igs"), (&step, "stp")] {
            assert!(
                h.pieces.iter().all(|p| p.certified),
                "{name}.{f}: not all certified"
            );
        }
        let (a, b) = (tally(&iges), tally(&step));
        assert_eq!(
            a.iter().map(|(k, v)| (k, v.0)).collect::<Vec<_>>(),
            b.iter().map(|(k, v)| (k, v.0)).collect::<Vec<_>>(),
            "{name}: pieces by kind and visibility"
        );
        for ((k, (_, la)), (_, lb)) in a.iter().zip(b.values()) {
            assert!(
                (la - lb).abs() <= 1e-6 * la.max(1.0),
                "{name}: {k:?} length {la} (IGES) against {lb} (STEP)"
            );
        }
    }
}

/// A box of six planes (2 × 3 × 4) from STEP, seen from a general direction: three faces face
/// the eye, so nine of its twelve edges are visible (summed length 27) and the three meeting at
/// the far corner are hidden behind one face each (summed length 2 + 3 + 4 = 9). Planes have no
/// silhouette: the drawing is the edges.
#[test]
fn a_step_box_draws_nine_visible_edges_and_three_hidden() {
    let path = format!(
        "{}/fixtures/step/occt-written/box.stp",
        env!("CARGO_MANIFEST_DIR")
    );
    let model = limn::read_model(std::path::Path::new(&path)).unwrap();
    let h = hidden_lines(&model, &View::direction([1, 2, 3]), &HlrOptions::default()).unwrap();
    assert!(h.pieces.iter().all(|p| p.certified));
    let t = tally(&h);
    let by_qi = |qi: usize| {
        t.iter()
            .filter(|((_, q), _)| *q == Some(qi))
            .fold((0, 0.0), |(n, l), (_, v)| (n + v.0, l + v.1))
    };
    let ((n0, l0), (n1, l1)) = (by_qi(0), by_qi(1));
    assert_eq!((n0, n1), (9, 3), "{t:?}");
    assert!((l0 - 27.0).abs() < 1e-9 && (l1 - 9.0).abs() < 1e-9, "{t:?}");
    assert!(t.keys().all(|(_, q)| matches!(q, Some(0 | 1))), "{t:?}");
}

/// A drawing of a part the reader left a face out of says so among its assumptions (the box
/// with one face on a surface limn does not read: five faces drawn, the sixth named); so does
/// one of an assembly whose placements are not applied.
#[test]
fn a_drawing_with_faces_left_out_states_it() {
    let path = format!(
        "{}/fixtures/step/occt-written/box.stp",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(path).unwrap().replace(
        "#32 = PLANE('',#33);",
        "#32 = SURFACE_OF_LINEAR_EXTRUSION('',#27,#29);",
    );
    let model = limn::io::read_model_bytes("swept.stp", text.as_bytes(), None).unwrap();
    let h = hidden_lines(&model, &View::direction([1, 2, 3]), &HlrOptions::default()).unwrap();
    assert!(
        h.assumptions
            .iter()
            .any(|a| a.contains("1 of its surfaces or faces are left out")),
        "{:?}",
        h.assumptions
    );
    let whole = limn::read_model(std::path::Path::new(&format!(
        "{}/fixtures/step/occt-written/box.stp",
        env!("CARGO_MANIFEST_DIR")
    )))
    .unwrap();
    let h = hidden_lines(&whole, &View::direction([1, 2, 3]), &HlrOptions::default()).unwrap();
    assert!(!h
        .assumptions
        .iter()
        .any(|a| a.contains("left out") || a.contains("assembly")));
    // An assembly's placement (a complex instance, as writers give it), not applied: said.
    let text = std::fs::read_to_string(format!(
        "{}/fixtures/step/occt-written/box.stp",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap()
    .replace(
        "ENDSEC;\nEND-ISO-10303-21;",
        "#9000 = ( REPRESENTATION_RELATIONSHIP('','',#10,#10) REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION(#9001) SHAPE_REPRESENTATION_RELATIONSHIP() );\nENDSEC;\nEND-ISO-10303-21;",
    );
    let model = limn::io::read_model_bytes("assembly.stp", text.as_bytes(), None).unwrap();
    assert_eq!(model.placements_ignored, 1);
    let h = hidden_lines(&model, &View::direction([1, 2, 3]), &HlrOptions::default()).unwrap();
    assert!(
        h.assumptions
            .iter()
            .any(|a| a.contains("an assembly whose 1 placements")),
        "{:?}",
        h.assumptions
    );
}

/// The upper plate with two corners rounded off: the loop's fillets are conic arcs tangent to
/// the square's sides at both ends, ending on the sides at non-dyadic parameters, their
/// interval enclosures poking past the sides near their ends. In the image each fillet leaves
/// its side tangentially, so no solver separates the two there: only lemma I can, around the
/// shared vertex, on an injective box that reaches past the square
/// (`proofs/hidden-lines.md`). Every piece certified, and the sides drawn only along the loop.
#[test]
fn fillets_tangent_to_the_sides_are_certified() {
    use limn::surface::ParameterCurve;
    let m = plate_above_another();
    let pt = |u: (i64, i64), v: (i64, i64)| vec![q(u.0, u.1), q(v.0, v.1)];
    let line = |a: Vec<_>, b: Vec<_>| ParameterCurve::segment(&a, &b);
    let fillet = |a: Vec<_>, c: Vec<_>, b: Vec<_>| {
        ParameterCurve::new(&[a, c, b], &[q(1, 1), q(7, 10), q(1, 1)]).unwrap()
    };
    let outer = crate::trim_models::closed(vec![
        line(pt((0, 1), (0, 1)), pt((2, 3), (0, 1))),
        fillet(pt((2, 3), (0, 1)), pt((1, 1), (0, 1)), pt((1, 1), (1, 3))),
        line(pt((1, 1), (1, 3)), pt((1, 1), (1, 1))),
        line(pt((1, 1), (1, 1)), pt((1, 3), (1, 1))),
        fillet(pt((1, 3), (1, 1)), pt((0, 1), (1, 1)), pt((0, 1), (2, 3))),
        line(pt((0, 1), (2, 3)), pt((0, 1), (0, 1))),
    ]);
    let model = with_face(m, 0, Some(outer), Vec::new());
    let h = drawing(&model, 1e-6);
    let uncertified: Vec<_> = h.pieces.iter().filter(|p| !p.certified).collect();
    assert!(uncertified.is_empty(), "unresolved: {uncertified:#?}");
    // The fillets are drawn, in front of everything.
    let trims: Vec<_> = h
        .pieces
        .iter()
        .filter(|p| p.kind == LineKind::Trim)
        .collect();
    assert!(!trims.is_empty());
    assert!(trims.iter().all(|p| p.qi == Some(0)));
    // The upper plate's sides are drawn only where the loop runs along them: none of their
    // points in the two cut-off corners.
    for p in h
        .pieces
        .iter()
        .filter(|p| p.patch == 0 && p.kind == LineKind::Boundary)
    {
        for &(_, u, v) in &p.points_uv {
            let corner = (u > 2.0 / 3.0 + 1e-9 && v < 1.0 / 3.0 - 1e-9)
                || (u < 1.0 / 3.0 - 1e-9 && v > 2.0 / 3.0 + 1e-9);
            assert!(!corner, "side point ({u}, {v}) off the face");
        }
    }
}
