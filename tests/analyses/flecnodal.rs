//! The flecnodal system against closed forms (exact rational evaluation):
//! - the saddle `z = xy` as `S(u, v) = (u, v + u², u(v + u²))` (the counterexample):
//!   both rulings are asymptotic with infinite contact at every point, so the system vanishes
//!   there, while the paper's printed condition is 6 at the origin;
//! - the surface `z = xy + x⁴` in two parameterizations, the graph `G(x, y)` and
//!   `R(u, v) = G(u, v + u²)` (same normal `R_u × R_v = G_x × G_y`): the second asymptotic
//!   family `(1, −6x²)` has 4-point contact exactly on `x = 0`; the contact polynomial takes
//!   the same value in both parameterizations at the same point and line (it is invariant),
//!   the printed condition does not.

use limn::analysis::flecnodal::system::{flecnodal_system, printed_condition, Chart};
use limn::number::Rational;
use limn::surface::RationalPatch;

fn q(n: i64, d: i64) -> Rational {
    Rational::from((n, d))
}

fn binom(n: usize, k: usize) -> Rational {
    let mut r = Rational::from(1);
    for i in 0..k {
        r *= Rational::from(((n - i) as i64, (i + 1) as i64));
    }
    r
}

/// The Bernstein control values of degree (m, n) of `Σ c[k][l] u^k v^l`.
fn bernstein_of(c: &[Vec<Rational>], m: usize, n: usize) -> Vec<Rational> {
    let mut out = Vec::new();
    for i in 0..=m {
        for j in 0..=n {
            let mut s = Rational::new();
            for (k, row) in c.iter().enumerate().take(i + 1) {
                for (l, a) in row.iter().enumerate().take(j + 1) {
                    let w = (binom(i, k) / binom(m, k)) * binom(j, l) / binom(n, l);
                    s += w * a;
                }
            }
            out.push(s);
        }
    }
    out
}

/// A polynomial patch of degree (4, 1) from the power-basis coefficients of x, y, z.
fn patch(xyz: [Vec<Vec<Rational>>; 3]) -> RationalPatch {
    let [x, y, z] = xyz.map(|c| bernstein_of(&c, 4, 1));
    let pts = (0..x.len())
        .map(|k| [x[k].clone(), y[k].clone(), z[k].clone()])
        .collect();
    RationalPatch::polynomial([4, 1], pts).unwrap()
}

/// `c[k][l]` from a list of (k, l, coefficient).
fn power(terms: &[(usize, usize, i64)]) -> Vec<Vec<Rational>> {
    let mut c = vec![vec![Rational::new(); 2]; 5];
    for &(k, l, a) in terms {
        c[k][l] += Rational::from(a);
    }
    c
}

/// `(u, v + u², u v + u³ + quartic·u⁴)`.
fn reparameterized(quartic: i64) -> RationalPatch {
    patch([
        power(&[(1, 0, 1)]),
        power(&[(0, 1, 1), (2, 0, 1)]),
        power(&[(1, 1, 1), (3, 0, 1), (4, 0, quartic)]),
    ])
}

/// `(x, y, x y + x⁴)`.
fn graph() -> RationalPatch {
    patch([
        power(&[(1, 0, 1)]),
        power(&[(0, 1, 1)]),
        power(&[(1, 1, 1), (4, 0, 1)]),
    ])
}

/// The chart parameter s of σ (σ = 2s − 1).
fn s_of(sigma: &Rational) -> Rational {
    Rational::from(sigma + 1) / 2
}

#[test]
fn the_saddle_has_infinite_contact_along_both_rulings() {
    let saddle = reparameterized(0);
    let along_u = flecnodal_system(&saddle, Chart::AlongU);
    let along_v = flecnodal_system(&saddle, Chart::AlongV);
    let mut checked = 0;
    for a in 0..=8 {
        for b in 0..=8 {
            let (u, v) = (q(a, 16), q(b, 8));
            // The x-ruling: 3D direction (1, 0, ·) is S_u − 2u S_v, d = (1, −2u).
            let p = [u.clone(), v.clone(), s_of(&Rational::from(-2 * &u))];
            assert_eq!(along_u.asymptotic.eval(&p), 0, "({u}, {v})");
            assert_eq!(along_u.contact.eval(&p), 0, "({u}, {v})");
            // The y-ruling: d = (0, 1).
            let p = [u.clone(), v.clone(), q(1, 2)];
            assert_eq!(along_v.asymptotic.eval(&p), 0, "({u}, {v})");
            assert_eq!(along_v.contact.eval(&p), 0, "({u}, {v})");
            checked += 1;
        }
    }
    assert_eq!(checked, 81);
    // The paper's printed condition is not zero on the x axis, which lies in the surface.
    let printed = printed_condition(&saddle, Chart::AlongU);
    assert_eq!(printed.eval(&[q(0, 1), q(0, 1), q(1, 2)]), 6);
    // A direction that is not asymptotic is not a solution.
    assert_ne!(along_u.asymptotic.eval(&[q(1, 4), q(1, 2), q(3, 4)]), 0);
}

#[test]
fn the_contact_condition_is_invariant_and_vanishes_exactly_on_the_flecnodal_curve() {
    let g = flecnodal_system(&graph(), Chart::AlongU);
    let r = flecnodal_system(&reparameterized(1), Chart::AlongU);
    let pg = printed_condition(&graph(), Chart::AlongU);
    let pr = printed_condition(&reparameterized(1), Chart::AlongU);
    let mut printed_differs = 0;
    for a in 0..=6 {
        for b in 0..=4 {
            // The point x = u, y = v + u² (inside both squares).
            let (u, y) = (q(a, 16), q(b, 8));
            let v = &y - Rational::from(&u * &u);
            if v < 0 {
                continue;
            }
            // The second asymptotic family: 3D direction (1, −6x², ·), in the graph's
            // parameters d = (1, −6x²), in R's d = (1, −6u² − 2u).
            let sg = s_of(&(Rational::from(&u * &u) * -6));
            let sr = s_of(&((Rational::from(&u * &u) * -6) - Rational::from(&u * 2)));
            let at_g = [u.clone(), y.clone(), sg];
            let at_r = [u.clone(), v.clone(), sr];
            assert_eq!(g.asymptotic.eval(&at_g), 0);
            assert_eq!(r.asymptotic.eval(&at_r), 0);
            let (cg, cr) = (g.contact.eval(&at_g), r.contact.eval(&at_r));
            // Invariant: the same value (same line, same speed, same normal).
            assert_eq!(cg, cr, "at x = {u}, y = {y}");
            // 4-point contact exactly on x = 0; the sign of x elsewhere (f_xxx = 24 x).
            assert_eq!(cg == 0, u == 0, "at x = {u}");
            assert!(u == 0 || cg > 0);
            if pg.eval(&at_g) != pr.eval(&at_r) {
                printed_differs += 1;
            }
        }
    }
    assert!(
        printed_differs > 0,
        "the printed form should depend on the parameterization"
    );
}

#[test]
fn a_sphere_has_no_real_asymptotic_direction() {
    // Elliptic everywhere: Ψ has the strict sign of the second fundamental form, never 0.
    let sphere = &limn::testing::shapes::sphere(&Rational::from(1))[0];
    for chart in [Chart::AlongU, Chart::AlongV] {
        let f = flecnodal_system(sphere, chart);
        for a in 1..8 {
            for b in 1..8 {
                for c in 0..=4 {
                    let p = [q(a, 8), q(b, 8), q(c, 4)];
                    assert_ne!(f.asymptotic.eval(&p), 0, "{p:?}");
                }
            }
        }
    }
}

/// The same surface `z = xy + x⁴` as a truly rational patch, `x = φ(u) = u/(2 − u)`, `y = v`:
/// the homogeneous form of the system vanishes exactly on `x = 0` along the second asymptotic
/// family and has the sign of `x` elsewhere (the invariant value times positive factors).
#[test]
fn the_homogeneous_form_agrees_on_a_rational_reparameterization() {
    // Homogeneous (P, W) with W = (2 − u)⁴: P = (u (2 − u)³, v (2 − u)⁴, u v (2 − u)³ + u⁴).
    let two_minus_u_pow = |k: u32| -> Vec<i64> {
        // Power-basis coefficients of (2 − u)^k.
        let mut c = vec![1i64];
        for _ in 0..k {
            let mut next = vec![0i64; c.len() + 1];
            for (i, a) in c.iter().enumerate() {
                next[i] += 2 * a;
                next[i + 1] -= a;
            }
            c = next;
        }
        c
    };
    let (w3, w4) = (two_minus_u_pow(3), two_minus_u_pow(4));
    let mut px = Vec::new();
    let mut pz = Vec::new();
    let mut py = Vec::new();
    let mut w = Vec::new();
    for (k, a) in w3.iter().enumerate() {
        px.push((k + 1, 0, *a));
        pz.push((k + 1, 1, *a));
    }
    pz.push((4, 0, 1));
    for (k, a) in w4.iter().enumerate() {
        py.push((k, 1, *a));
        w.push((k, 0, *a));
    }
    let [bx, by, bz, bw] =
        [power(&px), power(&py), power(&pz), power(&w)].map(|c| bernstein_of(&c, 4, 1));
    let pts = (0..bw.len())
        .map(|k| {
            [
                Rational::from(&bx[k] / &bw[k]),
                Rational::from(&by[k] / &bw[k]),
                Rational::from(&bz[k] / &bw[k]),
            ]
        })
        .collect();
    let patch = RationalPatch::new([4, 1], pts, bw).unwrap();
    assert!(!patch.is_polynomial());
    let f = flecnodal_system(&patch, Chart::AlongU);
    for a in 0..=8 {
        for b in 0..=4 {
            let (u, v) = (q(a, 8), q(b, 4));
            let two_minus_u = 2 - Rational::from(&u);
            let x = Rational::from(&u / &two_minus_u);
            // d = (1, −6x² φ'(u)), φ' = 2 / (2 − u)².
            let sigma =
                (Rational::from(&x * &x) * -12) / Rational::from(&two_minus_u * &two_minus_u);
            let p = [u.clone(), v.clone(), s_of(&sigma)];
            assert_eq!(f.asymptotic.eval(&p), 0, "u = {u}, v = {v}");
            let c = f.contact.eval(&p);
            assert_eq!(c == 0, u == 0, "u = {u}: {c}");
            assert!(u == 0 || c > 0, "u = {u}: {c}");
        }
    }
}
