//! Which stretches of a shared edge the surface continues across in the image (the paper's
//! clusters of connected front- or back-facing patches, decided per edge and with proof).
//!
//! For a user of an edge, `det[T, I_n]` (the image tangent `T` along the edge, in the first
//! user's direction, and the image `I_n` of that user's inward derivative) says on which side
//! of the edge's image the user's sheet lies. Where the two users of an edge have opposite
//! strict signs, their sheets lie on opposite sides: near the edge the two patches together map
//! one-to-one onto a neighbourhood of its image, so the number of sheets a ray meets there does
//! not change when the ray crosses the edge's image. Such a stretch is not outline: it cannot
//! change the QI of anything behind it (`proofs/visible-regions.md`, lemma 2). The
//! determinant is, up to the sign of the side, the numerator determinant of the image map's
//! Jacobian restricted to the side (an exact polynomial, bounded in f64 intervals).

use crate::analysis::projection::side_restriction;
use crate::analysis::visibility::scene::Scene;
use crate::analysis::visibility::sheets::range_on;
use crate::bernstein::Bernstein;
use crate::number::{Interval, Precision, Rational};
use crate::surface::Edge;

use crate::bernstein::Poly;
type IPoly = Bernstein<Interval>;

/// The sign factor that turns the Jacobian determinant on a side into
/// `det[image tangent along the side, image of the inward derivative]`.
fn inward_sign(edge: Edge) -> i64 {
    match edge {
        Edge::V0 | Edge::U1 => 1,
        Edge::V1 | Edge::U0 => -1,
    }
}

/// For an edge with exactly two users `(patch, side, runs opposite to the first user)`, the
/// two users' orientation polynomials `det[T, I_n]` in the first user's side parameter.
/// `None` for a free or non-manifold edge (always outline).
pub fn edge_orientations(scene: &Scene, users: &[(usize, Edge, bool)]) -> Option<[IPoly; 2]> {
    let [(p, e, _), (q, f, rev)] = users else {
        return None;
    };
    // The determinant on the side, from the entries restricted to it (univariate products).
    let det = |patch: usize, side: Edge| -> Poly {
        let m = &scene.jacobians[patch];
        let r = |x: &Poly| side_restriction(x, side);
        &(&r(&m[0][0]) * &r(&m[1][1])) - &(&r(&m[0][1]) * &r(&m[1][0]))
    };
    let a = det(*p, *e).scale(&Rational::from(inward_sign(*e)));
    let mut b = det(*q, *f).scale(&Rational::from(inward_sign(*f)));
    if *rev {
        // In the first user's parameter t the second runs as 1 − t: its coefficients reverse,
        // and its tangent turns around.
        let mut c = b.coeffs().to_vec();
        c.reverse();
        b = Bernstein::new(b.degrees(), c).expect("same degree").neg();
    }
    Some([a, b].map(|x| x.convert(Precision::F64)))
}

/// Whether the surface provably continues across the edge's image on the stretch `[lo, hi]`
/// of the first user's parameter: the two orientations have opposite strict signs there.
pub fn continues_on(o: &[IPoly; 2], lo: f64, hi: f64) -> bool {
    let (a, b) = (range_on(&o[0], &[lo], &[hi]), range_on(&o[1], &[lo], &[hi]));
    (a.lo() > 0.0 && b.hi() < 0.0) || (a.hi() < 0.0 && b.lo() > 0.0)
}

/// Whether the edge is provably a fold on the stretch `[lo, hi]`: the two orientations have
/// the same strict sign there, so both patches lie on one side of the edge's image and it is
/// outline (what lies behind it shows on the other side).
pub fn folds_on(o: &[IPoly; 2], lo: f64, hi: f64) -> bool {
    let (a, b) = (range_on(&o[0], &[lo], &[hi]), range_on(&o[1], &[lo], &[hi]));
    (a.lo() > 0.0 && b.lo() > 0.0) || (a.hi() < 0.0 && b.hi() < 0.0)
}

/// The stretches of `[0, 1]` across which the surface provably continues: the dyadic
/// intervals (halved up to `depth` times) on which [`continues_on`] holds, adjacent ones
/// merged, in increasing order.
pub fn continuing_stretches(o: &[IPoly; 2], depth: u32) -> Vec<[f64; 2]> {
    stretches_where(o, depth, continues_on)
}

/// The stretches of `[0, 1]` across which the surface provably continues, and those on which
/// the edge is provably a fold: dyadic intervals halved where neither is proven, up to
/// `depth` times and `budget` intervals in all (so near a junction, where both orientations
/// vanish, the undecided stretch shrinks to `2^-depth`), adjacent ones merged.
pub fn edge_roles(o: &[IPoly; 2], depth: u32, budget: usize) -> [Vec<[f64; 2]>; 2] {
    let mut out: [Vec<[f64; 2]>; 2] = [Vec::new(), Vec::new()];
    let mut stack = vec![(0.0f64, 1.0f64, 0u32)];
    let mut visited = 0;
    let push = |v: &mut Vec<[f64; 2]>, lo: f64, hi: f64| match v.last_mut() {
        Some(last) if last[1] == lo => last[1] = hi,
        _ => v.push([lo, hi]),
    };
    // Depth first, left to right, so each list comes out in increasing order.
    while let Some((lo, hi, d)) = stack.pop() {
        visited += 1;
        if continues_on(o, lo, hi) {
            push(&mut out[0], lo, hi);
        } else if folds_on(o, lo, hi) {
            push(&mut out[1], lo, hi);
        } else if d < depth && visited + stack.len() < budget {
            let mid = 0.5 * (lo + hi);
            stack.push((mid, hi, d + 1));
            stack.push((lo, mid, d + 1));
        }
    }
    out
}

/// The dyadic stretches of `[0, 1]` (halved up to `depth` times) on which `holds` does,
/// adjacent ones merged, in increasing order.
pub fn stretches_where(
    o: &[IPoly; 2],
    depth: u32,
    holds: fn(&[IPoly; 2], f64, f64) -> bool,
) -> Vec<[f64; 2]> {
    fn go(
        o: &[IPoly; 2],
        lo: f64,
        hi: f64,
        depth: u32,
        holds: fn(&[IPoly; 2], f64, f64) -> bool,
        out: &mut Vec<[f64; 2]>,
    ) {
        if holds(o, lo, hi) {
            match out.last_mut() {
                Some(last) if last[1] == lo => last[1] = hi,
                _ => out.push([lo, hi]),
            }
            return;
        }
        if depth > 0 {
            let mid = 0.5 * (lo + hi);
            go(o, lo, mid, depth - 1, holds, out);
            go(o, mid, hi, depth - 1, holds, out);
        }
    }
    let mut out = Vec::new();
    go(o, 0.0, 1.0, depth, holds, &mut out);
    out
}
