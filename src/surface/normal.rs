//! Derivatives and the unnormalized normal of a rational patch, as exact polynomials.

use super::RationalPatch;
use crate::bernstein::Bernstein;

use crate::bernstein::Poly;

/// `a × b` for vectors of polynomials.
pub(crate) fn cross(a: &[Poly; 3], b: &[Poly; 3]) -> [Poly; 3] {
    [
        &(&a[1] * &b[2]) - &(&a[2] * &b[1]),
        &(&a[2] * &b[0]) - &(&a[0] * &b[2]),
        &(&a[0] * &b[1]) - &(&a[1] * &b[0]),
    ]
}

impl RationalPatch {
    /// The Cartesian polynomials `[x, y, z]` of a polynomial patch (weights all equal), or
    /// `None` for a truly rational one.
    fn cartesian(&self) -> Option<[Poly; 3]> {
        if !self.is_polynomial() {
            return None;
        }
        let d = self.degree();
        Some([0, 1, 2].map(|k| {
            Bernstein::new(&d, self.points().iter().map(|p| p[k].clone()).collect())
                .expect("counts checked")
        }))
    }

    /// The numerators of the first partial derivatives: `(W P_u − W_u P, W P_v − W_v P)` with
    /// `P = [wx, wy, wz]`, so that `S_u = T_u / W²` and `S_v = T_v / W²` (for a polynomial
    /// patch, simply `S_u`, `S_v`). Exact.
    pub fn tangents(&self) -> ([Poly; 3], [Poly; 3]) {
        if let Some(x) = self.cartesian() {
            return (x.clone().map(|c| c.deriv(0)), x.map(|c| c.deriv(1)));
        }
        let [px, py, pz, w] = self.homogeneous();
        let p = [px, py, pz];
        let (wu, wv) = (w.deriv(0), w.deriv(1));
        let tu = p.clone().map(|c| &(&w * &c.deriv(0)) - &(&wu * &c));
        let tv = p.map(|c| &(&w * &c.deriv(1)) - &(&wv * &c));
        (tu, tv)
    }

    /// The unnormalized normal `Ñ`, a positive multiple of `S_u × S_v` on the whole closed
    /// domain, as three exact polynomials at their lowest exact degrees.
    ///
    /// For a polynomial patch of degree (m, n), `Ñ = S_u × S_v`, of degree at most
    /// (2m − 1, 2n − 1). For a rational patch with `P = [wx, wy, wz]` and weight `W`,
    /// `Ñ = W (P_u × P_v) + W_u (P_v × P) + W_v (P × P_u) = W³ (S_u × S_v)`, of degree at most
    /// (3m − 2, 3n − 2): the formal degree 3m − 1 cancels (`proofs/normal-degree.md`).
    /// The normal vanishes where the patch is singular (a collapsed edge, a pole).
    pub fn normal(&self) -> [Poly; 3] {
        if let Some(x) = self.cartesian() {
            let xu = x.clone().map(|c| c.deriv(0));
            let xv = x.map(|c| c.deriv(1));
            return cross(&xu, &xv).map(|c| c.reduce_degree_exact());
        }
        let [px, py, pz, w] = self.homogeneous();
        let p = [px, py, pz];
        let pu = p.clone().map(|c| c.deriv(0));
        let pv = p.clone().map(|c| c.deriv(1));
        let (wu, wv) = (w.deriv(0), w.deriv(1));
        let a = cross(&pu, &pv);
        let b = cross(&pv, &p);
        let c = cross(&p, &pu);
        [0, 1, 2].map(|k| {
            let sum = &(&(&w * &a[k]) + &(&wu * &b[k])) + &(&wv * &c[k]);
            sum.reduce_degree_exact()
        })
    }
}
