//! The curve's crossings of a box's faces: the square systems of `F` on each face, isolated by
//! Krawczyk's test, mapped back into the box, and refined.

use crate::bernstein::Bernstein;
use crate::number::{Interval, Number};
use crate::solver::space_curve::regular_minor::excludes;
use crate::solver::system::within;
use crate::solver::system::{
    krawczyk, krawczyk_in_box, krawczyk_verdict, newton, KrawczykVerdict, SystemOptions,
};

/// A zero of a face system: an enclosure and a region where it is the only zero (face
/// coordinates: local while the face is solved, then global on the hyperplane).
#[derive(Clone)]
pub(crate) struct FaceRoot {
    pub(crate) enclosure: Vec<[f64; 2]>,
    pub(crate) unique_in: Vec<[f64; 2]>,
}
/// The polynomial on its face `x_axis = 0` (`side` false) or `= 1`, in the remaining
/// variables: exactly its Bernstein coefficients with that index at 0 or at the degree.
pub(crate) fn face_slice(p: &Bernstein<Interval>, axis: usize, side: bool) -> Bernstein<Interval> {
    let d = p.degrees()[axis];
    let want = if side { d } else { 0 };
    let coeffs: Vec<Interval> = (0..p.coeffs().len())
        .filter(|&k| p.multi_index(k)[axis] == want)
        .map(|k| p.coeffs()[k])
        .collect();
    let degrees: Vec<usize> = (0..p.nvars())
        .filter(|&k| k != axis)
        .map(|k| p.degrees()[k])
        .collect();
    if degrees.is_empty() {
        return Bernstein::constant(1, coeffs[0]);
    }
    Bernstein::new(&degrees, coeffs).expect("the face keeps the other degrees")
}
/// Local unit-box coordinates `[lo, hi]` mapped into the box `[a, b]`, rounded outward (an
/// enclosure keeps what it holds).
pub(crate) fn to_global(local: &[[f64; 2]], a: &[f64], b: &[f64]) -> Vec<[f64; 2]> {
    map_into(local, a, b, false)
}
/// The same map for a uniqueness region, rounded inward (a region must not claim more than
/// was tested; with dyadic ends the map is exact anyway).
pub(crate) fn to_global_inward(local: &[[f64; 2]], a: &[f64], b: &[f64]) -> Vec<[f64; 2]> {
    map_into(local, a, b, true)
}
pub(crate) fn map_into(local: &[[f64; 2]], a: &[f64], b: &[f64], inward: bool) -> Vec<[f64; 2]> {
    local
        .iter()
        .enumerate()
        .map(|(k, t)| {
            let w = Interval::point(b[k]).sub(&Interval::point(a[k]));
            let at = |x: f64| Interval::point(a[k]).add(&w.mul(&Interval::point(x)));
            let (lo, hi) = (at(t[0]), at(t[1]));
            if inward {
                [lo.hi(), hi.lo()]
            } else {
                [lo.lo(), hi.hi()]
            }
        })
        .collect()
}
/// The zeros of a square system given on a face (local unit coordinates, the box's own
/// interval polynomials): each with an enclosure and a region where it is the only zero, both
/// local; `None` if some part of the face was not decided within the budget. Krawczyk's test
/// is run first on each sub-box as it is (no restriction needed), then, for a zero on a
/// sub-box side, on the sub-box grown by an eighth (restricted by extrapolation: the interval
/// polynomials enclose the exact ones there too); a zero found twice is recognised by its
/// enclosure lying in the other's uniqueness region (`proofs/krawczyk.md`).
pub(crate) fn face_roots(
    face: Vec<Bernstein<Interval>>,
    opts: &SystemOptions,
) -> Option<Vec<FaceRoot>> {
    let m = face.len();
    let mut out: Vec<FaceRoot> = Vec::new();
    let mut stack = vec![(vec![0.0; m], vec![1.0; m], 0u32, face)];
    let mut boxes = 0usize;
    while let Some((lo, hi, depth, polys)) = stack.pop() {
        boxes += 1;
        if polys.iter().any(excludes) {
            continue;
        }
        // Krawczyk's operator: one zero (found), none (`K` misses the box), or undecided.
        let verdict = krawczyk_verdict(&polys);
        if matches!(verdict, KrawczykVerdict::NoZero) {
            continue;
        }
        if !matches!(verdict, KrawczykVerdict::Unknown { worth: false }) {
            if let KrawczykVerdict::Unique(k) = verdict {
                let unique: Vec<[f64; 2]> = lo.iter().zip(&hi).map(|(a, b)| [*a, *b]).collect();
                let enc = refine_local(&polys, k, &lo, &hi, opts.refine_width);
                record(&mut out, enc, unique);
                continue;
            }
            // A zero near the sub-box's sides: the test on the grown box (not on the whole
            // face, which is subdivided first: the grown test costs a restriction). Tried only
            // where Newton's method from the centre (f64, a guess: the test decides) ends in the
            // margin of the grown box, not deep inside the box (where growing does not help)
            // nor far away.
            if depth >= 1 && near_the_sides(&polys) {
                let grown_lo: Vec<f64> =
                    lo.iter().zip(&hi).map(|(a, b)| a - (b - a) / 8.0).collect();
                let grown_hi: Vec<f64> =
                    lo.iter().zip(&hi).map(|(a, b)| b + (b - a) / 8.0).collect();
                let grown: Vec<Bernstein<Interval>> = polys
                    .iter()
                    .map(|p| p.restrict_box_f64(&vec![-0.125; m], &vec![1.125; m]))
                    .collect();
                if let Some(k) = krawczyk(&grown) {
                    let unique: Vec<[f64; 2]> = grown_lo
                        .iter()
                        .zip(&grown_hi)
                        .map(|(a, b)| [*a, *b])
                        .collect();
                    let enc = refine_local(&grown, k, &grown_lo, &grown_hi, opts.refine_width);
                    // A zero in the margin outside the face is not a crossing of this face.
                    if enc.iter().any(|e| e[1] < 0.0 || e[0] > 1.0) {
                        continue;
                    }
                    record(&mut out, enc, unique);
                    continue;
                }
            }
        }
        if depth >= opts.max_depth || boxes + stack.len() >= opts.max_boxes {
            return None;
        }
        let mut children = vec![(lo, hi, polys)];
        for axis in 0..m {
            let mut next = Vec::with_capacity(children.len() * 2);
            for (l, h, ps) in children {
                let mid = 0.5 * (l[axis] + h[axis]);
                let (mut lh, mut rl) = (h.clone(), l.clone());
                lh[axis] = mid;
                rl[axis] = mid;
                let (pl, pr): (Vec<_>, Vec<_>) = ps.iter().map(|p| p.subdivide_half(axis)).unzip();
                next.push((l, lh, pl));
                next.push((rl, h, pr));
            }
            children = next;
        }
        for (l, h, ps) in children.into_iter().rev() {
            stack.push((l, h, depth + 1, ps));
        }
    }
    Some(out)
}
/// Adds a zero of a face system to those found, unless it is one of them (found already by a
/// grown test of a neighbouring sub-box: one's enclosure lies in the other's uniqueness region).
pub(crate) fn record(out: &mut Vec<FaceRoot>, enclosure: Vec<[f64; 2]>, unique_in: Vec<[f64; 2]>) {
    let seen = out
        .iter()
        .any(|r| within(&enclosure, &r.unique_in) || within(&r.enclosure, &unique_in));
    if !seen {
        out.push(FaceRoot {
            enclosure,
            unique_in,
        });
    }
}
/// Whether Newton's method (f64, from the centre of the polynomials' unit box) ends within
/// 1/8 of the box's sides, inside or out: where a grown box may isolate a zero the box itself
/// could not.
pub(crate) fn near_the_sides(polys: &[Bernstein<Interval>]) -> bool {
    let f: Vec<Bernstein<f64>> = polys
        .iter()
        .map(|p| p.map(|x| 0.5 * (x.lo() + x.hi())))
        .collect();
    newton(&f, vec![0.5; polys.len()], 6).is_some_and(|x| {
        x.iter().all(|&t| (-0.125..=1.125).contains(&t))
            && x.iter().any(|&t| !(0.125..=0.875).contains(&t))
    })
}
/// Narrows a zero's Krawczyk image `k` (in the polynomials' own unit coordinates; the zero
/// is the only one in that unit box): Newton's method in f64 from its centre, then Krawczyk's
/// test on small boxes around the result inside the unit box, growing until one succeeds (a
/// success proves a zero there, which is the same zero: the only one in the unit box). The result is in the face's
/// local coordinates (the polynomials' box is `[lo, hi]` there); where nothing succeeds the
/// image itself is kept, still proven.
pub(crate) fn refine_local(
    polys: &[Bernstein<Interval>],
    k: Vec<Interval>,
    lo: &[f64],
    hi: &[f64],
    width: f64,
) -> Vec<[f64; 2]> {
    let m = polys.len();
    let image: Vec<[f64; 2]> = k.iter().map(|x| [x.lo(), x.hi()]).collect();
    let fallback = to_global(&image, lo, hi);
    if fallback.iter().all(|e| e[1] - e[0] <= width) {
        return fallback;
    }
    let f: Vec<Bernstein<f64>> = polys
        .iter()
        .map(|p| p.map(|x| 0.5 * (x.lo() + x.hi())))
        .collect();
    let Some(x) = newton(&f, image.iter().map(|e| 0.5 * (e[0] + e[1])).collect(), 30) else {
        return fallback;
    };
    // The first box about the target width (in the face's units, mapped to the polynomials'),
    // smaller ones only if needed.
    let scale = (0..m)
        .map(|k| hi[k] - lo[k])
        .fold(0.0, f64::max)
        .max(1e-300);
    let mut r = (0.25 * width / scale).max(1e-14);
    let mut tries = 0;
    // The partial derivatives once, for Krawczyk's test on each small box.
    let derivs: Vec<Vec<Bernstein<Interval>>> = polys
        .iter()
        .map(|p| (0..m).map(|j| p.deriv(j)).collect())
        .collect();
    while r < 0.25 && tries < 12 {
        tries += 1;
        // Inside the tested box (the polynomials' unit box), where the zero is unique.
        let b: Vec<[f64; 2]> = x.iter().map(|&v| [v - r, v + r]).collect();
        if !b.iter().all(|e| 0.0 <= e[0] && e[1] <= 1.0) {
            break;
        }
        let a: Vec<f64> = b.iter().map(|e| e[0]).collect();
        let c: Vec<f64> = b.iter().map(|e| e[1]).collect();
        if let Some(kk) = krawczyk_in_box(polys, &derivs, &a, &c) {
            let own: Vec<[f64; 2]> = kk.iter().map(|x| [x.lo(), x.hi()]).collect();
            return to_global(&own, lo, hi);
        }
        r *= 8.0;
    }
    fallback
}
