//! What the analyses whose curves live on a patch's parameter square share (flecnodal curves in
//! `(u, v, direction)`, bitangents in `(u, v, s, t)`): f64 evaluation of the surface and its
//! tangents at the solver's points, and the accuracy targets that make the drawn polyline lie
//! within a tolerance of the curve in space (`proofs/space-curves.md` §5).

use crate::analysis::chords::plane_curve::{restrict_enclosing, SurfaceBounds};
use crate::bernstein::Bernstein;
use crate::number::margin;
use crate::number::{Interval, Number, Precision, Rational};
use crate::solver::space_curve::{SpaceArc, SpaceCurve};
use crate::surface::RationalPatch;

/// The largest derivative of the Möbius map of [`crate::solver::space_curve::warp`] with factor
/// `l` from t to u (λ or 1/λ), and a bound on the magnitude of its second derivative,
/// `2λ|λ − 1| / min(1, λ)³`.
fn warp_bounds(l: f64) -> (f64, f64) {
    let first = l.max(1.0 / l);
    let second = 2.0 * l * (l - 1.0).abs() / l.min(1.0).powi(3);
    (
        margin::up(first, margin::FEW),
        margin::up(second, margin::FEW),
    )
}

/// Bounds of a patch's derivatives over its square (its variables `(u, v)` warped by the
/// factors `lambda`), for the bound in space of every drawn segment, which the solver's
/// acceptance of arcs compares with the tolerance.
#[derive(Clone, Debug)]
pub(crate) struct Accuracy {
    /// |S_u|, |S_v| over the patch.
    l: [f64; 2],
    /// |S_uu|, |S_uv|, |S_vv| over the patch.
    s2: [f64; 3],
    /// The warp factors of u and v.
    lambda: [f64; 2],
}

impl Accuracy {
    pub(crate) fn new(patch: &RationalPatch, lambda: [f64; 2]) -> Option<Accuracy> {
        let b = SurfaceBounds::new(patch);
        let [lu, suu, suv, svv] = b.bounds([0.0, 0.0], [1.0, 1.0], 0)?;
        let [lv, ..] = b.bounds([0.0, 0.0], [1.0, 1.0], 1)?;
        Some(Accuracy {
            l: [lu, lv],
            s2: [suu, suv, svv],
            lambda,
        })
    }

    /// The bound on the distance in space between an arc's image (its variables `offset`,
    /// `offset + 1` are this patch's `(u, v)`) and the segment between its ends' images:
    /// `Σ L_k (Λ_k dev_k + h_k² |φ_k''| / 8) + (S_uu Δu² + 2 S_uv |Δu Δv| + S_vv Δv²) / 8` with
    /// `Δ = Λ h` (`proofs/space-curves.md` §5).
    pub(crate) fn error(&self, c: &SpaceCurve, arc: &SpaceArc, offset: usize) -> Option<f64> {
        let dev = arc.deviation.as_ref()?;
        Some(self.error_of(
            &c.crossings[arc.from].enclosure,
            &c.crossings[arc.to].enclosure,
            dev,
            offset,
        ))
    }

    /// [`Accuracy::error`] from an arc's ends' enclosures and its deviation.
    pub(crate) fn error_of(
        &self,
        a: &[[f64; 2]],
        b: &[[f64; 2]],
        dev: &[f64],
        offset: usize,
    ) -> f64 {
        let h = |k: usize| a[k][1].max(b[k][1]) - a[k][0].min(b[k][0]);
        let mut e = 0.0;
        let mut delta = [0.0; 2];
        for k in 0..2 {
            let (d1, d2) = warp_bounds(self.lambda[k]);
            let hk = h(offset + k);
            e += self.l[k] * (d1 * dev[offset + k] + hk * hk * d2 / 8.0);
            delta[k] = d1 * hk;
        }
        e += (self.s2[0] * delta[0] * delta[0]
            + 2.0 * self.s2[1] * delta[0] * delta[1]
            + self.s2[2] * delta[1] * delta[1])
            / 8.0;
        // The rounding of this sum: a few dozen operations (`proofs/rounding-margins.md`).
        margin::up(e, margin::MANY)
    }
}

/// Interval tangents of a patch, for enclosures of the directions `a S_u + b S_v` over boxes.
pub(crate) struct TangentRanges {
    /// `T_u`, `T_v`: the same positive multiple (`W²`) of `S_u`, `S_v`.
    t: [[Bernstein<Interval>; 3]; 2],
}

impl TangentRanges {
    pub(crate) fn new(patch: &RationalPatch) -> TangentRanges {
        let (tu, tv) = patch.tangents();
        // One common degree for all six (degree elevation is exact), so that the restricted
        // coefficients pair up by index.
        let mut d = vec![0usize; 2];
        for p in tu.iter().chain(&tv) {
            for (a, &k) in d.iter_mut().zip(p.degrees()) {
                *a = (*a).max(k);
            }
        }
        let f = |p: &Bernstein<Rational>| p.elevate_to(&d).convert::<Interval>(Precision::F64);
        TangentRanges {
            t: [tu.each_ref().map(f), tv.each_ref().map(f)],
        }
    }

    /// An enclosure of `a T_u + b T_v` (a positive multiple of `a S_u + b S_v`) over the box
    /// `[lo, hi]` of the square, for all `a ∈ a`, `b ∈ b`: both tangents restricted to the box
    /// have coefficients of the same indices, so those of the combination are
    /// `a c_u + b c_v`, and their hull encloses its range.
    pub(crate) fn combination(
        &self,
        lo: [f64; 2],
        hi: [f64; 2],
        a: Interval,
        b: Interval,
    ) -> Option<[Interval; 3]> {
        let mut out = [Interval::point(0.0); 3];
        for (k, o) in out.iter_mut().enumerate() {
            let cu = restrict_enclosing(&self.t[0][k], lo, hi)?;
            let cv = restrict_enclosing(&self.t[1][k], lo, hi)?;
            if cu.degrees() != cv.degrees() {
                return None;
            }
            let c: Vec<Interval> = cu
                .coeffs()
                .iter()
                .zip(cv.coeffs())
                .map(|(x, y)| a.mul(x).add(&b.mul(y)))
                .collect();
            *o = c[1..].iter().fold(c[0], |p, q| p.hull(q));
        }
        Some(out)
    }
}

/// The sides of the parameter square: axis, at 1, name.
pub(crate) const SIDES: [(usize, bool, &str); 4] = [
    (0, false, "u=0"),
    (0, true, "u=1"),
    (1, false, "v=0"),
    (1, true, "v=1"),
];

/// Divides the linear factor of every side on which all the polynomials vanish identically out
/// of all of them (exactly, as often as it divides all), and names the sides divided.
pub(crate) fn deflate_common(polys: &mut [Bernstein<Rational>]) -> Vec<&'static str> {
    let mut divided = Vec::new();
    for (axis, at_one, name) in SIDES {
        let mut any = false;
        loop {
            let q: Option<Vec<Bernstein<Rational>>> = polys
                .iter()
                .map(|p| p.divide_face_factor(axis, at_one))
                .collect();
            match q {
                Some(q) if !polys.iter().all(Bernstein::is_zero) => {
                    polys.clone_from_slice(&q);
                    any = true;
                }
                _ => break,
            }
        }
        if any {
            divided.push(name);
        }
    }
    divided
}
