use super::*;
use crate::number::Rational;
use crate::surface::DrawPatch;
use crate::testing::shapes;

fn q(a: i64, b: i64) -> Rational {
    Rational::from((a, b))
}

/// The plane z = 1/2 cuts the unit sphere in the circle x² + y² = 3/4: once through each of
/// the four northern patches, from one meridian side to the other, and not at all through the
/// southern ones. Soundness: every crossing lies on both surfaces and on the circle;
/// completeness: exactly one branch per northern patch, ending on its two meridian sides.
#[test]
fn a_plane_cuts_the_sphere_in_its_circle() {
    let sphere = shapes::sphere(&q(1, 1));
    let plane = shapes::graph(&[(0, 0, q(1, 2))], [q(-1, 1), q(1, 1)], [q(-1, 1), q(1, 1)]);
    let opts = SpaceCurveOptions::default();
    let dp = DrawPatch::new(&plane);
    for (k, patch) in sphere.iter().enumerate() {
        let pair = pair_intersection(patch, &plane, &opts);
        let c = &pair.curve;
        assert!(c.is_certified(), "patch {k}: {:?}", c.unresolved);
        let north = k >= 4;
        assert_eq!(c.branches.len(), usize::from(north), "patch {k}");
        let ds = DrawPatch::new(patch);
        for x in &c.crossings {
            let p = pair.unwarp_point(&x.point());
            let a = ds.eval(p[0], p[1]);
            let b = dp.eval(p[2], p[3]);
            for i in 0..3 {
                assert!((a[i] - b[i]).abs() < 1e-6, "patch {k}: {a:?} vs {b:?}");
            }
            assert!((a[2] - 0.5).abs() < 1e-6);
            assert!((a[0] * a[0] + a[1] * a[1] - 0.75).abs() < 1e-6);
        }
        if north {
            let b = &c.branches[0];
            assert!(!b.closed && b.complete);
            let ends = [b.crossings[0], *b.crossings.last().unwrap()];
            // Both ends on the sphere patch's sides u = 0 and u = 1 (its meridians).
            let mut at: Vec<f64> = ends
                .iter()
                .map(|&e| {
                    let x = &c.crossings[e];
                    assert!(x.on_boundary && x.axis == 0, "patch {k}: {x:?}");
                    x.at.to_f64()
                })
                .collect();
            at.sort_by(f64::total_cmp);
            assert_eq!(at, vec![0.0, 1.0]);
        }
    }
}

/// Two unit spheres whose centres are (0, 0, 0) and c = (1/2, 1/3, 1/5) meet in a circle in
/// the plane x·c = |c|²/2. Every pair of patches is solved; every crossing lies on both
/// spheres and that plane; every end of a branch on the boundary of one pair's domain is the
/// end of a branch of the pair across that side (the circle is closed: no end is lost).
#[test]
fn two_spheres_meet_in_one_closed_circle() {
    let c = [q(1, 2), q(1, 3), q(1, 5)];
    let one = shapes::sphere(&q(1, 1));
    let id = shapes::rotation(0, 1, 0);
    let two: Vec<RationalPatch> = one.iter().map(|p| shapes::transform(p, &id, &c)).collect();
    let cf = c.each_ref().map(Rational::to_f64);
    let half = 0.5 * cf.iter().map(|x| x * x).sum::<f64>();
    let opts = SpaceCurveOptions::default();
    let mut ends: Vec<[f64; 3]> = Vec::new();
    let mut arcs = 0;
    for a in &one {
        let da = DrawPatch::new(a);
        for b in &two {
            let pair = pair_intersection(a, b, &opts);
            let curve = &pair.curve;
            assert!(curve.is_certified(), "{:?}", curve.unresolved);
            arcs += curve.arcs.len();
            let db = DrawPatch::new(b);
            for x in &curve.crossings {
                let p = pair.unwarp_point(&x.point());
                let (pa, pb) = (da.eval(p[0], p[1]), db.eval(p[2], p[3]));
                let r1: f64 = pa.iter().map(|x| x * x).sum();
                let r2: f64 = (0..3).map(|i| (pb[i] - cf[i]).powi(2)).sum();
                let plane: f64 = (0..3).map(|i| pa[i] * cf[i]).sum();
                assert!((r1 - 1.0).abs() < 1e-6 && (r2 - 1.0).abs() < 1e-6);
                assert!((plane - half).abs() < 1e-6);
                assert!((0..3).all(|i| (pa[i] - pb[i]).abs() < 1e-6));
            }
            for br in curve.branches.iter().filter(|b| !b.closed) {
                for e in [br.crossings[0], *br.crossings.last().unwrap()] {
                    let p = pair.unwarp_point(&curve.crossings[e].point());
                    ends.push(da.eval(p[0], p[1]));
                }
            }
        }
    }
    assert!(arcs > 0);
    // Each end is met by another end at the same point of space (the branch across the side),
    // an odd number of others at a point on two sides at once being impossible here.
    for (i, e) in ends.iter().enumerate() {
        let near = ends
            .iter()
            .enumerate()
            .filter(|(j, f)| *j != i && (0..3).all(|k| (e[k] - f[k]).abs() < 1e-6))
            .count();
        assert!(near >= 1, "end {e:?} unmatched");
    }
}
