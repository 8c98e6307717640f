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
    let at = |t: f64| [p[0] - t * d[0], p[1] - t * d[1], p[2] - t * d[2]];
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
            let f = |t: f64| {
                let x = at(t);
                let y = [x[0] - c[0], x[1] - c[1], x[2] - c[2]];
                let s = y[0] * y[0] + y[1] * y[1] + y[2] * y[2] + big * big - r * r;
                s * s - 4.0 * big * big * (y[0] * y[0] + y[1] * y[1])
            };
            let n = 4000;
            let t_max = 40.0;
            let mut out = Vec::new();
            let mut prev = f(1e-4);
            let mut prev_t = 1e-4;
            for k in 1..=n {
                let t = 1e-4 + t_max * k as f64 / n as f64;
                let v = f(t);
                if (v > 0.0) != (prev > 0.0) {
                    out.push(0.5 * (t + prev_t));
                }
                // Near-tangency: |f| tiny without a sign change.
                if v.abs() < 1e-7 {
                    return None;
                }
                prev = v;
                prev_t = t;
            }
            if f(1e-4).abs() < 1e-6 {
                return None;
            }
            Some(out)
        }
    }
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
