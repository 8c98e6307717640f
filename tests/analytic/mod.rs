//! Independent analytic references shared by the tests: ray counts through spheres (a
//! quadratic) and tori (the quartic, sampled and bisected in f64), with ambiguous cases
//! (near-tangent rays, roots near the point) refused rather than guessed; the distance from a
//! point to a segment.
#![allow(dead_code)]

use limn::number::Rational;
use limn::surface::RationalPatch;

/// The cross product `a × b`.
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Patches moved by an integer vector (exactly).
pub fn shifted(patches: Vec<RationalPatch>, by: [i64; 3]) -> Vec<RationalPatch> {
    patches
        .into_iter()
        .map(|p| p.map_points(|x| std::array::from_fn(|k| Rational::from(&x[k] + by[k]))))
        .collect()
}

/// An analytic shape: a sphere (centre, radius) or a torus about the z axis (centre, R, r).
#[derive(Clone, Copy, Debug)]
pub enum Shape {
    Sphere([f64; 3], f64),
    Torus([f64; 3], f64, f64),
}

/// The ray parameters t in (0, T] where p − t d meets the shape, or None if some root is
/// too close to 0 or to a double root to be counted reliably in f64.
pub fn roots(shape: Shape, p: [f64; 3], d: [f64; 3]) -> Option<Vec<f64>> {
    match shape {
        Shape::Sphere(c, r) => {
            let o = [p[0] - c[0], p[1] - c[1], p[2] - c[2]];
            // |o − t d|² = r²: t² − 2 (o·d) t + |o|² − r² = 0 (|d| = 1).
            let b = o[0] * d[0] + o[1] * d[1] + o[2] * d[2];
            let cc = o[0] * o[0] + o[1] * o[1] + o[2] * o[2] - r * r;
            let disc = b * b - cc;
            if disc < -1e-9 {
                return Some(vec![]);
            }
            if disc.abs() <= 1e-9 {
                // Tangent ray: fine only if the tangency is at p itself (a silhouette point).
                return (b.abs() < 1e-6).then(Vec::new);
            }
            let s = disc.sqrt();
            let ts = [b - s, b + s];
            if ts.iter().any(|t| t.abs() > 1e-12 && t.abs() < 1e-5) {
                return None;
            }
            Some(ts.into_iter().filter(|t| *t > 1e-5).collect())
        }
        Shape::Torus(c, big, r) => {
            // f(t) = S² − 4R²ρ with S = |o − t d|² + R² − r², ρ = (o − t d)ₓ² + (o − t d)ᵧ²:
            // a quartic in t (coefficients lowest first), its real roots isolated between the
            // roots of its derivatives.
            let o = [p[0] - c[0], p[1] - c[1], p[2] - c[2]];
            let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
            let s = [
                dot(&o, &o) + big * big - r * r,
                -2.0 * dot(&o, &d),
                dot(&d, &d),
            ];
            let rho = [
                dot(&o[..2], &o[..2]),
                -2.0 * dot(&o[..2], &d[..2]),
                dot(&d[..2], &d[..2]),
            ];
            let mut f = [0.0; 5];
            for i in 0..3 {
                for j in 0..3 {
                    f[i + j] += s[i] * s[j];
                }
                f[i] -= 4.0 * big * big * rho[i];
            }
            // The point's own sheet: roots at t = 0 (two where the ray is tangent there, a
            // silhouette point) are divided out; a root left near 0 is not counted reliably.
            let mut f = f.to_vec();
            for _ in 0..2 {
                let scale: f64 = f.iter().map(|x| x.abs()).sum();
                if f[0].abs() <= 1e-9 * scale {
                    f.remove(0);
                }
            }
            let ts = real_roots(&f, -1.0, 40.0)?;
            if ts.iter().any(|t| t.abs() < 1e-5) {
                return None;
            }
            Some(ts.into_iter().filter(|t| *t > 0.0).collect())
        }
    }
}

/// The value of a polynomial (coefficients lowest first) and a bound on its rounding scale.
fn horner(c: &[f64], t: f64) -> (f64, f64) {
    let v = c.iter().rev().fold(0.0, |acc, x| acc * t + x);
    let scale = c
        .iter()
        .rev()
        .fold(0.0, |acc, x: &f64| acc * t.abs() + x.abs());
    (v, scale)
}

/// The real roots of a polynomial in [a, b], each found by bisection on an interval between
/// consecutive roots of its derivative (where it is monotone); `None` if it nearly vanishes at
/// a root of its derivative (a double root, or two roots closer than f64 can separate).
pub fn real_roots(c: &[f64], a: f64, b: f64) -> Option<Vec<f64>> {
    let n = c.len();
    if n <= 1 {
        return Some(Vec::new());
    }
    let dc: Vec<f64> = c
        .iter()
        .enumerate()
        .skip(1)
        .map(|(k, x)| k as f64 * x)
        .collect();
    let mut cuts = vec![a];
    cuts.extend(real_roots(&dc, a, b)?);
    cuts.push(b);
    let mut out = Vec::new();
    for w in cuts.windows(2) {
        let (mut lo, mut hi) = (w[0], w[1]);
        let (flo, slo) = horner(c, lo);
        let (fhi, shi) = horner(c, hi);
        for (v, sc, x) in [(flo, slo, lo), (fhi, shi, hi)] {
            if x != a && x != b && v.abs() <= 1e-9 * sc {
                return None;
            }
        }
        if (flo > 0.0) == (fhi > 0.0) || flo == 0.0 && fhi == 0.0 {
            continue;
        }
        let up = fhi > 0.0;
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if (horner(c, mid).0 > 0.0) == up {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        let t = 0.5 * (lo + hi);
        if out.last().is_none_or(|x: &f64| (t - x).abs() > 1e-12) {
            out.push(t);
        }
    }
    Some(out)
}

pub fn reference_qi(shapes: &[Shape], p: [f64; 3], d: [f64; 3]) -> Option<usize> {
    let mut n = 0;
    for s in shapes {
        n += roots(*s, p, d)?.len();
    }
    Some(n)
}

/// A viewer: a parallel direction (from the viewer into the scene) or an eye point.
#[derive(Clone, Copy, Debug)]
pub enum Viewer {
    Dir([f64; 3]),
    Eye([f64; 3]),
}

/// The reference QI of a point: ray hits between the point and the viewer.
pub fn reference_at(shapes: &[Shape], p: [f64; 3], viewer: Viewer) -> Option<usize> {
    let unit = |d: [f64; 3]| {
        let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        (d.map(|x| x / n), n)
    };
    match viewer {
        Viewer::Dir(d) => reference_qi(shapes, p, unit(d).0),
        Viewer::Eye(e) => {
            let (d, dist) = unit([p[0] - e[0], p[1] - e[1], p[2] - e[2]]);
            let mut n = 0;
            for s in shapes {
                let ts = roots(*s, p, d)?;
                if ts.iter().any(|t| (t - dist).abs() < 1e-6) {
                    return None;
                }
                n += ts.iter().filter(|t| **t < dist).count();
            }
            Some(n)
        }
    }
}

/// Distance from `p` to the segment `[a, b]`.
pub fn to_segment(p: [f64; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let w = [p[0] - a[0], p[1] - a[1], p[2] - a[2]];
    let dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    let t = if dd > 0.0 {
        ((w[0] * d[0] + w[1] * d[1] + w[2] * d[2]) / dd).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let e = [w[0] - t * d[0], w[1] - t * d[1], w[2] - t * d[2]];
    (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]).sqrt()
}
