//! Exact rational models with known closed forms.
//!
//! The quarter circle `x = (1 − t²)/(1 + t²)`, `y = 2t/(1 + t²)`, t in `[0,1]`, is a rational
//! quadratic Bézier curve with control points (1,0), (1,1), (0,1) and weights 1, 1, 2: every
//! coefficient is rational, so spheres and tori built from it are exact.

use crate::number::Rational;
use crate::surface::{Point3, RationalPatch};

fn q(n: i64) -> Rational {
    Rational::from(n)
}

/// A plane curve as rational Bézier control points `(x, y)` and weights.
pub type Arc2 = (Vec<[Rational; 2]>, Vec<Rational>);

/// The quarter of the unit circle from (1,0) to (0,1), rotated by `quarter` × 90°.
pub fn quarter_circle(quarter: usize) -> Arc2 {
    let base = [[q(1), q(0)], [q(1), q(1)], [q(0), q(1)]];
    let pts = base
        .into_iter()
        .map(|[x, y]| {
            let mut p = [x, y];
            for _ in 0..quarter % 4 {
                p = [Rational::from(-&p[1]), p[0].clone()];
            }
            p
        })
        .collect();
    (pts, vec![q(1), q(1), q(2)])
}

/// The surface of revolution of a profile `(r, z)` (r ≥ 0) about the z axis, over one
/// quarter turn `quarter`: control points `(r_j cx_i, r_j cy_i, z_j)`, weights `ω_i w_j`, with
/// u along the turn and v along the profile.
pub fn revolve(profile: &Arc2, quarter: usize) -> RationalPatch {
    let (circle, cw) = quarter_circle(quarter);
    let (prof, pw) = profile;
    let mut pts = Vec::new();
    let mut ws = Vec::new();
    for (c, wc) in circle.iter().zip(&cw) {
        for (p, wp) in prof.iter().zip(pw) {
            pts.push([
                Rational::from(&p[0] * &c[0]),
                Rational::from(&p[0] * &c[1]),
                p[1].clone(),
            ]);
            ws.push(Rational::from(wc * wp));
        }
    }
    RationalPatch::new([2, prof.len() - 1], pts, ws).expect("valid by construction")
}

/// Maps a plane arc by `(x, y) -> (a + s x, b + s y)`.
fn affine2(arc: &Arc2, a: &Rational, b: &Rational, s: &Rational) -> Arc2 {
    let pts = arc
        .0
        .iter()
        .map(|p| [a + Rational::from(s * &p[0]), b + Rational::from(s * &p[1])])
        .collect();
    (pts, arc.1.clone())
}

/// The sphere of radius `r` about the origin: 8 biquadratic rational patches, outward normals,
/// each with one side collapsed to a pole.
pub fn sphere(r: &Rational) -> Vec<RationalPatch> {
    let zero = q(0);
    let mut patches = Vec::new();
    // Profile from the south pole (0,-r) to the north pole (0,r) through (r,0): quarters 3, 0.
    for half in [3, 0] {
        let prof = affine2(&quarter_circle(half), &zero, &zero, r);
        for quarter in 0..4 {
            patches.push(revolve(&prof, quarter));
        }
    }
    patches
}

/// The torus with tube radius `r` about the circle of radius `big_r` in the xy plane:
/// 16 biquadratic rational patches, no degenerate points when `big_r > r`.
pub fn torus(big_r: &Rational, r: &Rational) -> Vec<RationalPatch> {
    let zero = q(0);
    let mut patches = Vec::new();
    for tube in 0..4 {
        // The tube circle centred at (R, 0) in the (radius, z) plane, counter-clockwise.
        let prof = affine2(&quarter_circle(tube), big_r, &zero, r);
        for quarter in 0..4 {
            patches.push(revolve(&prof, quarter));
        }
    }
    patches
}

/// A quarter of the cylinder `x² + y² = r²`, `0 <= z <= h` (u around, v along the axis):
/// parabolic everywhere, and its silhouette from a direction across the axis is a ruling.
pub fn cylinder_quarter(r: &Rational, h: &Rational) -> RationalPatch {
    let prof: Arc2 = (
        vec![[r.clone(), q(0)], [r.clone(), h.clone()]],
        vec![q(1), q(1)],
    );
    revolve(&prof, 0)
}

/// A bilinear patch in the plane z = 0 spanning `[0, s]²` (planar: seen edge-on from any
/// direction in the plane, its normal is perpendicular to the view everywhere).
pub fn plane_square(s: &Rational) -> RationalPatch {
    let p = |x: &Rational, y: &Rational| -> Point3 { [x.clone(), y.clone(), q(0)] };
    let z = q(0);
    RationalPatch::polynomial([1, 1], vec![p(&z, &z), p(&z, s), p(s, &z), p(s, s)]).expect("valid")
}

/// An `nx` x `ny` grid of unit bilinear patches, patch `(i, j)` over `[i, i+1] x [j, j+1]`,
/// with heights `((7a + 3b) mod 5) / 10` at the grid points `(a, b)`: a C0 surface of many
/// patches whose neighbours are not tangent-continuous (the adversarial grids of issue 26,
/// as `tools/adversarial_models.py` writes them).
pub fn bilinear_grid(nx: i64, ny: i64) -> Vec<RationalPatch> {
    let z = |a: i64, b: i64| Rational::from(((a * 7 + b * 3) % 5, 10));
    let p = |a: i64, b: i64| [q(a), q(b), z(a, b)];
    let mut patches = Vec::new();
    for i in 0..nx {
        for j in 0..ny {
            patches.push(
                RationalPatch::polynomial(
                    [1, 1],
                    vec![p(i, j), p(i, j + 1), p(i + 1, j), p(i + 1, j + 1)],
                )
                .expect("valid"),
            );
        }
    }
    patches
}

/// An exact rotation matrix with rational entries: about axis 0, 1 or 2 by the angle whose
/// cosine and sine are `(a² − b²)/(a² + b²)` and `2ab/(a² + b²)` (a Pythagorean rotation).
pub fn rotation(axis: usize, a: i64, b: i64) -> [[Rational; 3]; 3] {
    let n = q(a * a + b * b);
    let c = q(a * a - b * b) / &n;
    let s = q(2 * a * b) / &n;
    let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
    let mut m: [[Rational; 3]; 3] =
        std::array::from_fn(|r| std::array::from_fn(|k| if r == k { q(1) } else { q(0) }));
    m[i][i] = c.clone();
    m[j][j] = c;
    m[i][j] = Rational::from(-&s);
    m[j][i] = s;
    m
}

/// The patch mapped by `x -> R x + t` (exact).
pub fn transform(patch: &RationalPatch, rot: &[[Rational; 3]; 3], shift: &Point3) -> RationalPatch {
    patch.map_points(|p| {
        std::array::from_fn(|r| {
            (0..3)
                .map(|k| Rational::from(&rot[r][k] * &p[k]))
                .sum::<Rational>()
                + &shift[r]
        })
    })
}

/// The graph `z = f(x, y)` of a polynomial `f = Σ c x^i y^j` (terms `(i, j, c)`) over the
/// rectangle `x ∈ [x0, x1]`, `y ∈ [y0, y1]`, as a polynomial patch with `u` along x and `v`
/// along y (its degree is f's, at least 1 in each). Graphs have closed-form differential
/// geometry (flecnodal points where `D²f(w, w) = D³f(w, w, w) = 0`), so they make exact
/// test cases.
///
/// # Examples
/// ```
/// use limn::number::Rational;
/// use limn::testing::shapes::graph;
/// let q = |n: i64| Rational::from(n);
/// // z = x y over [0, 1] × [0, 2].
/// let p = graph(&[(1, 1, q(1))], [q(0), q(1)], [q(0), q(2)]);
/// assert_eq!(p.eval(&q(1), &Rational::from((1, 2))), [q(1), q(1), q(1)]);
/// ```
pub fn graph(
    terms: &[(usize, usize, Rational)],
    x: [Rational; 2],
    y: [Rational; 2],
) -> RationalPatch {
    use crate::bernstein::Bernstein;
    let xs = Bernstein::new(&[1, 0], x.to_vec()).expect("degree (1, 0)");
    let ys = Bernstein::new(&[0, 1], y.to_vec()).expect("degree (0, 1)");
    let mut z = Bernstein::new(&[1, 1], vec![q(0); 4]).expect("degree (1, 1)");
    for (i, j, c) in terms {
        let mut t = Bernstein::constant(2, c.clone());
        for _ in 0..*i {
            t = &t * &xs;
        }
        for _ in 0..*j {
            t = &t * &ys;
        }
        z = &z + &t;
    }
    let d = z.degrees().to_vec();
    let (xs, ys) = (xs.elevate_to(&d), ys.elevate_to(&d));
    let points = (0..z.coeffs().len())
        .map(|k| {
            [
                xs.coeffs()[k].clone(),
                ys.coeffs()[k].clone(),
                z.coeffs()[k].clone(),
            ]
        })
        .collect();
    RationalPatch::polynomial([d[0], d[1]], points).expect("a graph is a valid patch")
}

/// A patch with one known family of bitangent planes: the graph of
/// `z = (x² − 1)² + y² + x y / 2` over `[−3/2, 3/2] × [−1, 1]` (with `swap`, x and y exchanged).
///
/// Equal gradients at `(x, y)` and `(x', y')` give `Δy = −Δx / 4`; then the chord condition is
/// the bitangent condition of the even double well `(x² − 1)² − x²/16`, whose only bitangent
/// touches at `x = ∓x₀`, `x₀² = 33/32`. So the bitangent pairs are `(−x₀, y)` and
/// `(x₀, y − x₀/2)` (x and y exchanged with `swap`), for every `y` that keeps both in the patch.
///
/// # Examples
/// ```
/// use limn::testing::shapes::double_well;
/// let p = double_well(false);
/// assert_eq!(p.degree(), [4, 2]);
/// ```
pub fn double_well(swap: bool) -> RationalPatch {
    let terms = [
        (4, 0, q(1)),
        (2, 0, q(-2)),
        (0, 0, q(1)),
        (0, 2, q(1)),
        (1, 1, Rational::from((1, 2))),
    ];
    let (a, b) = (
        [Rational::from((-3, 2)), Rational::from((3, 2))],
        [q(-1), q(1)],
    );
    if swap {
        let t: Vec<_> = terms.iter().map(|(i, j, c)| (*j, *i, c.clone())).collect();
        graph(&t, b, a)
    } else {
        graph(&terms, a, b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn on_sphere(p: &Point3, r: &Rational) -> bool {
        let s: Rational = p.iter().map(|c| Rational::from(c * c)).sum();
        s == Rational::from(r * r)
    }

    #[test]
    fn sphere_points_lie_on_the_sphere() {
        let r = Rational::from((3, 2));
        for patch in sphere(&r) {
            for (u, v) in [(0, 0), (1, 3), (2, 5), (7, 7)] {
                let p = patch.eval(&Rational::from((u, 7)), &Rational::from((v, 7)));
                assert!(on_sphere(&p, &r));
            }
        }
    }

    #[test]
    fn torus_points_satisfy_the_implicit_equation() {
        let (big, r) = (q(3), q(1));
        for patch in torus(&big, &r) {
            for (u, v) in [(0, 0), (1, 3), (2, 5), (7, 7)] {
                let p = patch.eval(&Rational::from((u, 7)), &Rational::from((v, 7)));
                // (x² + y² + z² + R² − r²)² = 4 R² (x² + y²)
                let rho2 = Rational::from(&p[0] * &p[0]) + Rational::from(&p[1] * &p[1]);
                let lhs = &rho2 + Rational::from(&p[2] * &p[2]) + 9 - 1;
                assert_eq!(Rational::from(&lhs * &lhs), rho2 * 36);
            }
        }
    }

    #[test]
    fn rotations_are_orthogonal() {
        let m = rotation(1, 2, 1);
        for i in 0..3 {
            for j in 0..3 {
                let d: Rational = (0..3).map(|k| Rational::from(&m[i][k] * &m[j][k])).sum();
                assert_eq!(d, if i == j { q(1) } else { q(0) });
            }
        }
    }
}
