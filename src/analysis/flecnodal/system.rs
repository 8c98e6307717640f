//! The flecnodal system of a patch (paper 003, with the invariant third-order condition of
//! `proofs/flecnodal.md`): exact polynomials whose common zeros with a real asymptotic
//! direction `d` are the points where the tangent line along `d` has 4-point contact.
//!
//! With `X` the surface in the coordinates of its kind (the Cartesian `S` of a polynomial patch,
//! the homogeneous `H = (P, W)` of a rational one), `ν` its normal functional (`S_u × S_v`, or the
//! negated generalized cross product of `H, H_u, H_v`, oriented as `S_u × S_v`), and `D^k X(d, …)` the directional derivatives:
//!
//! - asymptotic: `Ψ = ν · D²X(d, d) = a² L + 2ab M + b² N`;
//! - 4-point contact: `Φ = Δ ν · D³X(d, d, d) − 3 ν · D²X(d, c̃)`, where `c̃ = (μ₁ · D²X(d, d),
//!   μ₂ · D²X(d, d))` are the coordinates of `D²X(d, d)` along `X_u, X_v` times `Δ` (Cramer:
//!   `μ₁ = S_v × ν`, `μ₂ = ν × S_u`, `Δ = ν · ν`; homogeneously `ν = −×(H, H_u, H_v)`,
//!   `μ₁ = −×(H, H_v, ν)`, `μ₂ = ×(H, H_u, ν)`, `Δ = ν · ν`, with `×(a, b, c) · x = det[a, b, c, x]`).
//!
//! Where `Ψ = 0` and `Δ > 0`, `Φ / Δ` is the invariant form `D³S(d,d,d)·n + 3 D²S(d,e)·n` of the
//! issue up to a positive factor (`proofs/flecnodal.md`), not the paper's printed
//! `D³S(d,d,d)·n`, which depends on the parameterization.
//!
//! The direction is taken in one of two charts, `d = (1, σ)` or `d = (σ, 1)` with
//! `σ = 2s − 1 ∈ [−1, 1]`: every direction up to sign appears (the `(a, b) ~ (−a, −b)` duplicate
//! is gone by construction; `(1, ±1)` appear in both charts), and `(u, v, s)` is a box.

use crate::bernstein::lift;
use crate::number::Rational;
use crate::surface::normal::cross;
use crate::surface::RationalPatch;

use crate::bernstein::Poly;

/// How the direction `d = (a, b)` is written with `σ = 2s − 1`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Chart {
    /// `d = (1, σ)`: directions within 45° of the u axis.
    AlongU,
    /// `d = (σ, 1)`: directions within 45° of the v axis.
    AlongV,
}

/// The flecnodal system of a patch in one chart, in the variables `(u, v, s)`.
#[derive(Clone, Debug, PartialEq)]
pub struct FlecnodalSystem {
    /// The chart.
    pub chart: Chart,
    /// `Ψ`: zero where `d` is an asymptotic direction.
    pub asymptotic: Poly,
    /// `Φ`: zero (with `Ψ`) where the tangent line along `d` has 4-point contact.
    pub contact: Poly,
}

fn dot(a: &[Poly], b: &[Poly]) -> Poly {
    let mut s = &a[0] * &b[0];
    for k in 1..a.len() {
        s = &s + &(&a[k] * &b[k]);
    }
    s
}

fn det3(a: &[Poly; 3], b: &[Poly; 3], c: &[Poly; 3]) -> Poly {
    dot(a, &cross(b, c))
}

/// The generalized cross product of three 4-vectors: `×(a, b, c) · x = det[a, b, c, x]`.
fn cross4(a: &[Poly; 4], b: &[Poly; 4], c: &[Poly; 4]) -> [Poly; 4] {
    // Cofactors along the last row of [a; b; c; e_i]: (−1)^(3 + i) times the minor without
    // column i.
    let minor = |skip: usize| -> Poly {
        let pick = |v: &[Poly; 4]| -> [Poly; 3] {
            let r: Vec<Poly> = (0..4)
                .filter(|&k| k != skip)
                .map(|k| v[k].clone())
                .collect();
            r.try_into().unwrap_or_else(|_| unreachable!())
        };
        det3(&pick(a), &pick(b), &pick(c))
    };
    [minor(0).neg(), minor(1), minor(2).neg(), minor(3)]
}

/// The scalar ingredients of the system, polynomials in `(u, v)`.
struct Forms {
    /// `ν · X_uu`, `ν · X_uv`, `ν · X_vv`.
    second: [Poly; 3],
    /// `ν · X_uuu`, `ν · X_uuv`, `ν · X_uvv`, `ν · X_vvv`.
    third: [Poly; 4],
    /// `μ₁ · X_uu`, `μ₁ · X_uv`, `μ₁ · X_vv`.
    first_coordinate: [Poly; 3],
    /// `μ₂ · X_uu`, `μ₂ · X_uv`, `μ₂ · X_vv`.
    second_coordinate: [Poly; 3],
    /// `Δ = ν · ν`.
    delta: Poly,
}

/// The forms from the coordinates `x` of the surface (3 Cartesian or 4 homogeneous), the
/// normal functional and the two coordinate functionals.
fn forms(x: &[Poly], nu: &[Poly], mu1: &[Poly], mu2: &[Poly]) -> Forms {
    let d = |v: &[Poly], axis: usize| -> Vec<Poly> { v.iter().map(|p| p.deriv(axis)).collect() };
    let (xu, xv) = (d(x, 0), d(x, 1));
    let (xuu, xuv, xvv) = (d(&xu, 0), d(&xu, 1), d(&xv, 1));
    let (xuuu, xuuv, xuvv, xvvv) = (d(&xuu, 0), d(&xuu, 1), d(&xuv, 1), d(&xvv, 1));
    let seconds = [&xuu, &xuv, &xvv];
    Forms {
        second: seconds.map(|s| dot(nu, s).reduce_degree_exact()),
        third: [&xuuu, &xuuv, &xuvv, &xvvv].map(|s| dot(nu, s).reduce_degree_exact()),
        first_coordinate: seconds.map(|s| dot(mu1, s).reduce_degree_exact()),
        second_coordinate: seconds.map(|s| dot(mu2, s).reduce_degree_exact()),
        delta: dot(nu, nu).reduce_degree_exact(),
    }
}

/// The forms of a patch: Cartesian for a polynomial patch, homogeneous for a rational one.
fn patch_forms(patch: &RationalPatch) -> Forms {
    let h = patch.homogeneous();
    if patch.is_polynomial() {
        // W is a positive constant: S = P / W, and the constant is dropped (Ψ and Φ only gain
        // positive factors).
        let s: [Poly; 3] = [h[0].clone(), h[1].clone(), h[2].clone()];
        let (su, sv) = (s.clone().map(|p| p.deriv(0)), s.clone().map(|p| p.deriv(1)));
        let n = cross(&su, &sv).map(|p| p.reduce_degree_exact());
        let mu1 = cross(&sv, &n);
        let mu2 = cross(&n, &su);
        forms(&s, &n, &mu1, &mu2)
    } else {
        let hu = h.clone().map(|p| p.deriv(0));
        let hv = h.clone().map(|p| p.deriv(1));
        // ν = −×(H, H_u, H_v) = (Ñ, −D): its Cartesian part has the orientation of S_u × S_v
        // (as in `parabolic.rs`). Then det[H, H_u, H_v, ν] = −Δ, and Cramer's numerators with
        // the signs below are the coordinates times +Δ.
        let nu = cross4(&h, &hu, &hv).map(|p| p.reduce_degree_exact().neg());
        let mu1 = cross4(&h, &hv, &nu).map(|p| p.neg());
        let mu2 = cross4(&h, &hu, &nu);
        forms(&h, &nu, &mu1, &mu2)
    }
}

/// The flecnodal system of a patch in a chart.
///
/// # Examples
/// ```
/// use limn::analysis::flecnodal::system::{flecnodal_system, Chart};
/// use limn::number::Rational;
/// use limn::surface::RationalPatch;
/// // The saddle z = xy as S(u, v) = (u, v + u², u (v + u²)): the x axis lies in it, so at the
/// // origin the direction d = (1, 0) (s = 1/2 in the chart along u) is asymptotic and the
/// // tangent line has infinite contact.
/// let q = |n: i64| Rational::from(n);
/// let pts = vec![
///     [q(0), q(0), q(0)], [q(0), q(1), q(0)],
///     [Rational::from((1, 3)), q(0), q(0)], [Rational::from((1, 3)), q(1), Rational::from((1, 3))],
///     [Rational::from((2, 3)), Rational::from((1, 3)), q(0)],
///     [Rational::from((2, 3)), Rational::from((4, 3)), Rational::from((2, 3))],
///     [q(1), q(1), q(1)], [q(1), q(2), q(2)],
/// ];
/// let saddle = RationalPatch::polynomial([3, 1], pts).unwrap();
/// let f = flecnodal_system(&saddle, Chart::AlongU);
/// let origin = [q(0), q(0), Rational::from((1, 2))];
/// assert_eq!(f.asymptotic.eval(&origin), 0);
/// assert_eq!(f.contact.eval(&origin), 0);
/// ```
pub fn flecnodal_system(patch: &RationalPatch, chart: Chart) -> FlecnodalSystem {
    let f = patch_forms(patch);
    let (a, b) = direction(chart);
    let uv = |p: &Poly| lift(p, 3, 0);
    let quad = |c: &[Poly; 3]| -> Poly {
        let two = Rational::from(2);
        &(&(&(&a * &a) * &uv(&c[0])) + &(&(&a * &b) * &uv(&c[1])).scale(&two))
            + &(&(&b * &b) * &uv(&c[2]))
    };
    let psi = quad(&f.second);
    let c1 = quad(&f.first_coordinate);
    let c2 = quad(&f.second_coordinate);
    let [l, m, n] = f.second.each_ref().map(uv);
    // ν · D²X(d, e_u) = a L + b M, ν · D²X(d, e_v) = a M + b N.
    let along_u = &(&a * &l) + &(&b * &m);
    let along_v = &(&a * &m) + &(&b * &n);
    let correction = &(&c1 * &along_u) + &(&c2 * &along_v);
    let phi = &(&uv(&f.delta) * &cubic(&a, &b, &f.third)) - &correction.scale(&Rational::from(3));
    FlecnodalSystem {
        chart,
        asymptotic: psi.reduce_degree_exact(),
        contact: phi.reduce_degree_exact(),
    }
}

/// The paper's printed third-order condition `ν · D³X(d, d, d)` in the same chart (not
/// invariant under reparameterization: kept to show the difference, `proofs/flecnodal.md`).
pub fn printed_condition(patch: &RationalPatch, chart: Chart) -> Poly {
    let f = patch_forms(patch);
    let (a, b) = direction(chart);
    cubic(&a, &b, &f.third).reduce_degree_exact()
}

/// The chart's `(a(s), b(s))` as polynomials in `(u, v, s)`.
fn direction(chart: Chart) -> (Poly, Poly) {
    let sigma = Poly::new(&[1], vec![Rational::from(-1), Rational::from(1)]).expect("degree 1");
    let one = Poly::constant(1, Rational::from(1));
    let (a, b) = match chart {
        Chart::AlongU => (one, sigma),
        Chart::AlongV => (sigma, one),
    };
    (lift(&a, 3, 2), lift(&b, 3, 2))
}

/// `ν · D³X(d, d, d) = a³ t₀ + 3a²b t₁ + 3ab² t₂ + b³ t₃` in `(u, v, s)`.
fn cubic(a: &Poly, b: &Poly, t: &[Poly; 4]) -> Poly {
    let uv = |p: &Poly| lift(p, 3, 0);
    let three = Rational::from(3);
    let (aa, bb) = (a * a, b * b);
    let terms = [
        &(&aa * a) * &uv(&t[0]),
        (&(&aa * b) * &uv(&t[1])).scale(&three),
        (&(a * &bb) * &uv(&t[2])).scale(&three),
        &(&bb * b) * &uv(&t[3]),
    ];
    &(&(&terms[0] + &terms[1]) + &terms[2]) + &terms[3]
}
