//! Bitangent curves against closed forms: a double well (a patch with itself, one family of
//! bitangent planes, both orders of each pair) and two spheres (the cones tangent to both).

use limn::analysis::bitangent::curves::{
    bitangent_curves, pair_bitangents, BitangentOptions, PairBitangents,
};
use limn::model::{Format, Model};
use limn::number::Rational;
use limn::testing::shapes;
use limn::Reason;

fn q(a: i64, b: i64) -> Rational {
    Rational::from((a, b))
}

/// The double well of `shapes::double_well`: one family of bitangent pairs, `(−x₀, y)` and
/// `(x₀, y − x₀/2)` with `x₀² = 33/32`.
fn double_well(swap: bool) -> limn::surface::RationalPatch {
    shapes::double_well(swap)
}

fn check_double_well(b: &PairBitangents, swap: bool, tol: f64) {
    let x0 = (33.0f64 / 32.0).sqrt();
    // (across, along): the coordinate of the well, and the other.
    let (w, o) = if swap { (1, 0) } else { (0, 1) };
    assert!(b.is_certified(), "{} unresolved", b.unresolved.len());
    assert_eq!(b.branches.len(), 1, "one family, each pair once");
    let br = &b.branches[0];
    assert!(br.complete && !br.closed);
    let mut along = Vec::new();
    for pt in &br.points {
        // Soundness: every pair is one of the closed form's, in either order.
        let (m, p) = if pt.p[w] < 0.0 {
            (pt.p, pt.q)
        } else {
            (pt.q, pt.p)
        };
        assert!((m[w] + x0).abs() < tol && (p[w] - x0).abs() < tol, "{pt:?}");
        assert!((p[o] - (m[o] - x0 / 2.0)).abs() < tol, "{pt:?}");
        assert!((p[2] - m[2]).abs() < tol, "{pt:?}");
        along.push(m[o]);
    }
    // Completeness: the family runs from the point whose partner is on the side o = −1 to the
    // side o = 1, with no gap longer than the solver's boxes allow.
    along.sort_by(f64::total_cmp);
    assert!((along[0] - (-1.0 + x0 / 2.0)).abs() < tol, "{}", along[0]);
    assert!((along[along.len() - 1] - 1.0).abs() < tol);
    assert!(along.windows(2).all(|w| w[1] - w[0] < 0.25));
}

#[test]
fn double_well_has_one_family_reported_once() {
    for swap in [false, true] {
        let p = double_well(swap);
        let b = pair_bitangents(&p, 0, &p, 0, &BitangentOptions::default());
        eprintln!(
            "swap {swap}: {} boxes, {} points",
            b.boxes,
            b.branches.iter().map(|b| b.points.len()).sum::<usize>()
        );
        check_double_well(&b, swap, 1e-6);
    }
}

#[test]
fn double_well_within_tolerance() {
    let p = double_well(true);
    let b = pair_bitangents(&p, 0, &p, 0, &BitangentOptions::with_tolerance(Some(1e-3)));
    eprintln!("tol: {} boxes, bound {:?}", b.boxes, b.error_bound);
    assert!(b.within_tolerance, "{:?}", b.error_bound);
    check_double_well(&b, true, 1e-6);
}

#[test]
fn a_convex_patch_has_no_bitangent() {
    let p = shapes::graph(
        &[(2, 0, q(1, 1)), (0, 2, q(1, 1)), (1, 1, q(1, 3))],
        [q(-1, 1), q(1, 1)],
        [q(-1, 1), q(2, 1)],
    );
    let b = pair_bitangents(&p, 0, &p, 0, &BitangentOptions::default());
    assert!(b.is_certified() && b.branches.is_empty());
}

/// A convex bowl made of two patches that share a side (and a saddle made of two): no
/// bitangent, and no box left near the shared side (Lemma 5), in either order of the sides.
#[test]
fn a_shared_side_is_not_mistaken_for_bitangents() {
    for (terms, note) in [
        (
            vec![(2, 0, q(1, 1)), (0, 2, q(1, 1)), (1, 1, q(1, 3))],
            "bowl",
        ),
        (
            vec![(2, 0, q(1, 1)), (0, 2, q(-1, 1)), (1, 0, q(1, 5))],
            "saddle",
        ),
    ] {
        let left = shapes::graph(&terms, [q(-1, 1), q(0, 1)], [q(-1, 1), q(1, 1)]);
        let right = shapes::graph(&terms, [q(0, 1), q(1, 1)], [q(-1, 1), q(1, 1)]);
        assert_eq!(
            limn::analysis::bitangent::system::shared_sides(&left, &right).len(),
            1
        );
        for patches in [vec![left.clone(), right.clone()], vec![right, left]] {
            let model = Model::from_patches(Format::Json, patches);
            let out = bitangent_curves(&model, &BitangentOptions::default()).unwrap();
            // Both halves are excluded with themselves by Lemma 1; the pair is solved.
            assert_eq!(
                (out.pruned, out.excluded_self, out.pairs.len()),
                (0, 2, 1),
                "{note}"
            );
            assert!(out.pairs[0].boxes > 1);
            for p in &out.pairs {
                assert!(
                    p.is_certified() && p.branches.is_empty(),
                    "{note} {:?}: {} unresolved",
                    p.patches,
                    p.unresolved.len()
                );
            }
        }
    }
}

/// The sphere of radius 1/2 about (3, 1, 2), turned so that its patches' sides are in general
/// position with respect to the unit sphere's.
fn second_sphere() -> Vec<limn::surface::RationalPatch> {
    let zero = [q(0, 1), q(0, 1), q(0, 1)];
    shapes::sphere(&q(1, 2))
        .iter()
        .map(|p| {
            let p = shapes::transform(p, &shapes::rotation(1, 2, 1), &zero);
            shapes::transform(&p, &shapes::rotation(2, 3, 1), &[q(3, 1), q(1, 1), q(2, 1)])
        })
        .collect()
}

/// Two spheres, radii 1 and 1/2, centres 0 and (3, 1, 2)/... : the common tangent planes touch
/// along two circles on each sphere (the outer cone: `n·e = (r₁ − r₂)/d`, `q = c₂ + r₂ n`; the
/// inner: `n·e = (r₁ + r₂)/d`, `q = c₂ − r₂ n`).
#[test]
fn two_spheres_bitangents_are_the_tangent_cones() {
    let (r1, r2) = (1.0, 0.5);
    let c2 = [3.0, 1.0, 2.0];
    let a = shapes::sphere(&q(1, 1));
    let b = second_sphere();
    let model = Model::from_patches(Format::Json, a.into_iter().chain(b).collect());
    let tol = 5e-2;
    let t = std::time::Instant::now();
    let out = bitangent_curves(&model, &BitangentOptions::with_tolerance(Some(tol))).unwrap();
    eprintln!(
        "{:?}: {} pairs solved, {} pruned, {} excluded whole",
        t.elapsed(),
        out.pairs.len(),
        out.pruned,
        out.excluded_self
    );
    let d = (c2.iter().map(|x| x * x).sum::<f64>()).sqrt();
    let e = c2.map(|x| x / d);
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    // Soundness: every pair is a common tangent plane's, and on one sphere there is none.
    let mut segments: [Vec<([f64; 3], [f64; 3])>; 2] = [Vec::new(), Vec::new()];
    let mut lines: [Vec<[f64; 3]>; 2] = [Vec::new(), Vec::new()];
    let mut line_errors = [0.0f64; 2];
    for pair in &out.pairs {
        let across = pair.patches[0] < 8 && pair.patches[1] >= 8;
        if !across {
            assert!(pair.branches.is_empty(), "{:?}", pair.patches);
            // What is left on one sphere is where its patches meet: the shared sides and poles.
            for u in &pair.unresolved {
                assert!(
                    u.reason == Reason::CoincidentPieces,
                    "{:?}: {}",
                    pair.patches,
                    u.reason
                );
            }
            continue;
        }
        assert!(pair.is_certified(), "{:?}", pair.patches);
        assert!(
            pair.within_tolerance,
            "{:?}: {:?}",
            pair.patches, pair.error_bound
        );
        for br in &pair.branches {
            for pt in &br.points {
                let n = pt.p.map(|x| x / r1);
                let ne = dot(n, e);
                let along = |s: f64| (0..3).all(|k| (c2[k] + s * r2 * n[k] - pt.q[k]).abs() < 1e-6);
                let kind = if (ne - (r1 - r2) / d).abs() < 1e-6 && along(1.0) {
                    0
                } else if (ne - (r1 + r2) / d).abs() < 1e-6 && along(-1.0) {
                    1
                } else {
                    panic!("not a common tangent plane: {pt:?}");
                };
                let _ = kind;
            }
            for w in br.points.windows(2) {
                let k = if (dot(w[0].p, e) - (r1 - r2) / d).abs() < 1e-6 {
                    0
                } else {
                    1
                };
                segments[k].push((w[0].p, w[1].p));
            }
            // The lines on the viewing sphere are enclosed: a bound exists, and the drawn
            // lines are within it of the cone's (each line meets the axis at a fixed angle).
            let err = br.line_error.expect("the lines are enclosed");
            let k = usize::from((dot(br.points[0].p, e) - (r1 - r2) / d).abs() >= 1e-6);
            let c = [(r1 - r2) / d, (r1 + r2) / d][k];
            for pt in &br.points {
                let off = (dot(pt.line, e).abs().min(1.0).acos() - c.asin()).abs();
                assert!(off <= err, "{off} > {err}");
                lines[k].push(pt.line);
            }
            line_errors[k] = line_errors[k].max(err);
        }
    }
    // Completeness: both circles of contact on the first sphere are covered by the drawn
    // segments, within the tolerance (sampled every 5 degrees).
    let dist = |x: [f64; 3], (a, b): ([f64; 3], [f64; 3])| {
        let ab: [f64; 3] = std::array::from_fn(|k| b[k] - a[k]);
        let ax: [f64; 3] = std::array::from_fn(|k| x[k] - a[k]);
        let t = (dot(ax, ab) / dot(ab, ab).max(1e-300)).clamp(0.0, 1.0);
        let p: [f64; 3] = std::array::from_fn(|k| a[k] + t * ab[k] - x[k]);
        dot(p, p).sqrt()
    };
    let f1 = {
        let h = if e[0].abs() < 0.9 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        let c = dot(h, e);
        let v: [f64; 3] = std::array::from_fn(|k| h[k] - c * e[k]);
        let l = dot(v, v).sqrt();
        v.map(|x| x / l)
    };
    let f2 = [
        e[1] * f1[2] - e[2] * f1[1],
        e[2] * f1[0] - e[0] * f1[2],
        e[0] * f1[1] - e[1] * f1[0],
    ];
    for (k, c) in [(r1 - r2) / d, (r1 + r2) / d].into_iter().enumerate() {
        let s = (1.0 - c * c).sqrt();
        for i in 0..72 {
            let a = i as f64 * std::f64::consts::PI / 36.0;
            let n: [f64; 3] =
                std::array::from_fn(|j| c * e[j] + s * (a.cos() * f1[j] + a.sin() * f2[j]));
            let p = n.map(|x| x * r1);
            let near = segments[k]
                .iter()
                .map(|&sg| dist(p, sg))
                .fold(f64::INFINITY, f64::min);
            assert!(near <= tol, "circle {k} at {a}: {near}");
            // On the viewing sphere: the true line of this pair (in the plane of e and n,
            // perpendicular to n) is within the proven error of a drawn line.
            let t: [f64; 3] = std::array::from_fn(|j| e[j] - c * n[j]);
            let near_line = lines[k]
                .iter()
                .map(|l| (dot(*l, t).abs() / dot(t, t).sqrt()).min(1.0).acos())
                .fold(f64::INFINITY, f64::min);
            assert!(
                near_line <= line_errors[k],
                "circle {k} at {a}: line {near_line} > {}",
                line_errors[k]
            );
        }
    }
    eprintln!("line error bounds on the sphere: {line_errors:?}");
}

#[test]
fn the_teapots_rim_top_is_a_plane_of_bitangent_pairs() {
    // The horizontal plane on the rim's top circle (u = 1/2 of patches 0-3) is tangent all
    // along it: every two of its points are a bitangent pair, a 2-dimensional set that no
    // Jacobian minor resolves. It is found exactly (through the singular points of the
    // system there) and the boxes next to it say so.
    let teapot = limn::testing::teapot();
    let p = |k: usize| &teapot.patches[k].surface;
    let started = std::time::Instant::now();
    let b = pair_bitangents(p(0), 0, p(1), 1, &BitangentOptions::default());
    eprintln!("pair 0-1: {:?}, {} boxes", started.elapsed(), b.boxes);
    assert!(!b.singular_points.is_empty());
    let set = b
        .plane_sets
        .iter()
        .find(|s| s.first == "u = 1/2" && s.second == "u = 1/2")
        .unwrap_or_else(|| panic!("{:#?}", b.plane_sets));
    assert!((set.normal[2].abs() - 1.0).abs() < 1e-12, "{set:?}");
    assert!(
        (set.offset * set.normal[2] - 2.4984375).abs() < 1e-9,
        "{set:?}"
    );
    let labelled = b
        .unresolved
        .iter()
        .filter(|u| matches!(u.reason, Reason::PlaneSet { .. }))
        .count();
    eprintln!(
        "{labelled} of {} unresolved boxes are next to it",
        b.unresolved.len()
    );
    assert!(labelled > 0);
    // Those boxes do lie next to both lines.
    for u in b
        .unresolved
        .iter()
        .filter(|u| matches!(u.reason, Reason::PlaneSet { .. }))
    {
        for k in [0, 2] {
            let w = u.cell[k][1] - u.cell[k][0];
            assert!(u.cell[k][0] - w <= 0.5 && 0.5 <= u.cell[k][1] + w, "{u:?}");
        }
    }
}

#[test]
fn a_plane_found_through_one_pair_explains_the_others() {
    // The rim alone (patches 0-3): the plane z = 2.4984375 on the top circle u = 1/2 is found
    // through the singular points of the neighbouring pairs; the opposite pairs 0-2 and 1-3,
    // where the search finds none, get it from the model's lines.
    let teapot = limn::testing::teapot();
    let rim = Model::from_patches(
        Format::Bpt,
        teapot.patches[..4]
            .iter()
            .map(|p| p.surface.clone())
            .collect(),
    );
    let started = std::time::Instant::now();
    let out = bitangent_curves(&rim, &BitangentOptions::default()).unwrap();
    eprintln!("rim: {:?}", started.elapsed());
    for pair in &out.pairs {
        let set = pair
            .plane_sets
            .iter()
            .find(|s| s.first == "u = 1/2" && s.second == "u = 1/2");
        assert!(set.is_some(), "{:?}: {:#?}", pair.patches, pair.plane_sets);
        let generic = pair
            .unresolved
            .iter()
            .filter(|u| u.reason == Reason::NoRegularMinor)
            .count();
        eprintln!(
            "{:?}: {} unresolved, {generic} generic",
            pair.patches,
            pair.unresolved.len()
        );
        assert_eq!(generic, 0, "{:?}", pair.patches);
    }
}

/// The bitangents of a grid of 144 bilinear patches (some 10⁴ pairs) under a time limit of
/// 50 ms (issue 26 §2): past the deadline a pair is left unresolved by the time limit before
/// its exact set-up (600 patches with `--time-limit 1` ran 12 s before, 2.6 s after).
#[test]
fn many_pairs_respect_the_time_limit() {
    let m = Model::from_patches(Format::Json, shapes::bilinear_grid(12, 12));
    let start = std::time::Instant::now();
    let opts = BitangentOptions::default()
        .with_deadline(Some(start + std::time::Duration::from_millis(50)));
    let b = bitangent_curves(&m, &opts).unwrap();
    let took = start.elapsed();
    assert!(!b.is_certified());
    assert!(b
        .pairs
        .iter()
        .flat_map(|p| &p.unresolved)
        .any(|u| u.reason == Reason::TimeLimit));
    assert!(took.as_secs_f64() < 60.0, "{took:?}");
    println!("144 patches under a 50 ms limit: {took:?}");
}
