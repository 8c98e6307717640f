//! Silhouettes (contour generators) of rational Bézier models, with certified topology.
//!
//! For a patch with unnormalized normal Ñ (a positive multiple of S_u × S_v), the silhouette
//! function is `g = Ñ · V` for a parallel view direction V (front-facing where g < 0), or
//! `g = Ñ · (E W − P)` for a perspective eye E, with `P = [wx, wy, wz]` and W the weight
//! (front-facing where g > 0). Both are exact polynomials; the silhouette is `g = 0`, solved
//! per patch and joined across shared edges where the join is proven, by the model-level
//! curve machinery ([`model_curves`], `proofs/silhouette-join.md`).

use crate::analysis::contour::family::{ContourOptions, Faces};
use crate::analysis::frame::Frame;
use crate::analysis::projection::ProjectionError;
use crate::analysis::view::View;
use crate::bernstein::Bernstein;
use crate::error::Error;
use crate::model::{Model, WeldTolerance};
use crate::number::Rational;
use crate::solver::CurveOptions;
use crate::surface::{Edge, RationalPatch};
use rayon::prelude::*;

use crate::analysis::contour::family::{model_curves, CurveRules};

use crate::analysis::contour::curves::Silhouette;

/// The silhouette function of a patch for a view (exact).
///
/// # Examples
/// ```
/// use limn::analysis::contour::silhouette::silhouette_function;
/// use limn::analysis::view::View;
/// use limn::number::Rational;
/// use limn::testing::shapes;
/// let patch = &shapes::sphere(&Rational::from(1))[0];
/// let z = Rational::new();
/// let g = silhouette_function(patch, &View::Direction([z.clone(), z, Rational::from(1)]));
/// assert_eq!(g.nvars(), 2);
/// ```
pub fn silhouette_function(patch: &RationalPatch, view: &View) -> Bernstein<Rational> {
    in_f64_range(function(patch, view))
}

/// `g` times a power of two that brings its largest coefficient into `[1, 2)`, if it lies
/// outside `[2⁻²⁵⁶, 2²⁵⁶]` (an eye at 10³⁰⁸, a model of size 10²⁰⁰): f64 enclosures of the
/// coefficients would overflow or lose every digit, and every box would fall through to
/// exact arithmetic. A positive constant changes no sign and no zero
/// (`proofs/silhouette-join.md`, "Scale"); others are returned as they are.
fn in_f64_range(mut g: Bernstein<Rational>) -> Bernstein<Rational> {
    let Some(m) = g.coeffs().iter().map(|c| c.clone().abs()).max() else {
        return g;
    };
    if m.cmp0() == std::cmp::Ordering::Equal {
        return g;
    }
    let bits = |i: &rug::Integer| i64::from(i.significant_bits());
    // ⌊log₂ m⌋ within one of this.
    let k = bits(m.numer()) - bits(m.denom());
    if (-256..=256).contains(&k) {
        return g;
    }
    for c in g.coeffs_mut() {
        if k > 0 {
            *c >>= k as u32;
        } else {
            *c <<= (-k) as u32;
        }
    }
    g
}

/// [`silhouette_function`] before its scale is brought into range.
fn function(patch: &RationalPatch, view: &View) -> Bernstein<Rational> {
    let n = patch.normal();
    match view {
        View::Direction(d) => {
            let d = crate::analysis::view::working_direction(d);
            let terms: Vec<Bernstein<Rational>> = (0..3).map(|k| n[k].scale(&d[k])).collect();
            (&(&terms[0] + &terms[1]) + &terms[2]).reduce_degree_exact()
        }
        View::Eye(e) => {
            let [px, py, pz, w] = patch.homogeneous();
            let p = [px, py, pz];
            let mut sum: Option<Bernstein<Rational>> = None;
            for k in 0..3 {
                let to_eye = &w.scale(&e[k]) - &p[k];
                let term = &n[k] * &to_eye;
                sum = Some(match sum {
                    None => term,
                    Some(s) => &s + &term,
                });
            }
            sum.expect("three terms").reduce_degree_exact()
        }
    }
}

/// The silhouette (contour generator) of a model for a view: curves with certified topology,
/// and with `opts.tol` every drawn segment within it of the true curve.
///
/// Patches are solved in parallel (rayon); the result does not depend on the thread count.
///
/// # Errors
/// [`Error::View`] for the zero direction.
///
/// # Examples
/// ```
/// use limn::{silhouette, ContourOptions, View};
/// let sphere = limn::Model::from_patches(
///     limn::model::Format::Json,
///     limn::testing::shapes::sphere(&limn::number::Rational::from(1)),
/// );
/// let s = silhouette(&sphere, &View::direction([0, 0, 1]), &ContourOptions::default())?;
/// // The equator: one closed curve, its topology proven.
/// assert_eq!(s.curves.len(), 1);
/// assert!(s.curves[0].closed && s.topology_certified());
/// # Ok::<(), limn::Error>(())
/// ```
pub fn silhouette(model: &Model, view: &View, opts: &ContourOptions) -> Result<Silhouette, Error> {
    if view.is_degenerate() {
        return Err(ProjectionError::ZeroDirection.into());
    }
    // In the model's own frame (`proofs/model-frame.md`).
    let frame = Frame::of(model);
    let local = frame.model(model);
    let s = silhouette_curves(
        &local,
        &frame.view(view),
        &opts.curve,
        opts.weld_for(&local),
        opts.tol,
        Faces::Trimmed,
    );
    Ok(s.in_model_frame(&frame, opts.tol))
}

/// [`silhouette`] for a view known to be valid, with its parts given separately (the
/// analyses built on it).
pub(crate) fn silhouette_curves(
    model: &Model,
    view: &View,
    opts: &CurveOptions,
    weld: WeldTolerance,
    tol: Option<f64>,
    faces: Faces,
) -> Silhouette {
    let gs: Vec<Bernstein<Rational>> = model
        .patches
        .par_iter()
        .map(|p| silhouette_function(&p.surface, view))
        .collect();
    let rules = CurveRules {
        parallel_normal_joins: true,
        whole_patch: "edge-on",
        whole_side: "silhouette side",
        whole_line: "silhouette line",
        spurious_collapse: Some(normal_side_order),
    };
    model_curves(model, gs, &rules, opts, weld, tol, faces)
}

/// The order to which the normal `Ñ` (every component) vanishes on a side: the spurious
/// factor of the silhouette function on a collapsed side (`proofs/silhouette-join.md`,
/// "Collapsed sides").
fn normal_side_order(patch: &RationalPatch, edge: Edge) -> usize {
    patch
        .normal()
        .iter()
        .filter(|c| !c.is_zero())
        .map(|c| crate::analysis::contour::sides::deflate_side_counted(c, edge).1)
        .min()
        .unwrap_or(usize::MAX)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::contour::joins::{parallel_normals, proportional};
    use crate::analysis::contour::sides::side_polynomial;
    use crate::solver::precision::Policy;
    use crate::solver::{Escalations, Ladder};
    use crate::surface::Edge;

    fn quad(p: [[i64; 3]; 4]) -> RationalPatch {
        let q = |v: [i64; 3]| v.map(Rational::from);
        RationalPatch::polynomial([1, 1], p.into_iter().map(q).collect()).unwrap()
    }

    /// Two patches of one plane, the second not a parallelogram: their normals along the
    /// shared edge are parallel with a varying ratio (1 + v), so the silhouette functions are
    /// not proportional but the join is still proven; lifting the far side makes a crease.
    #[test]
    fn parallel_normals_join_tangent_continuous_edges_only() {
        let a = quad([[0, 0, 0], [0, 1, 0], [1, 0, 0], [1, 1, 0]]);
        let b = quad([[1, 0, 0], [1, 1, 0], [2, 0, 0], [3, 1, 0]]);
        assert!(parallel_normals(
            &a,
            Edge::U1,
            &b,
            Edge::U0,
            false,
            &mut Policy::new(&Ladder::default(), &mut Escalations::default())
        ));
        let v = View::Direction([Rational::from(1), Rational::from(2), Rational::from(3)]);
        let (ga, gb) = (silhouette_function(&a, &v), silhouette_function(&b, &v));
        assert!(!proportional(
            &side_polynomial(&ga, Edge::U1),
            &side_polynomial(&gb, Edge::U0),
            false
        ));
        let creased = quad([[1, 0, 0], [1, 1, 0], [2, 0, 1], [3, 1, 1]]);
        assert!(!parallel_normals(
            &a,
            Edge::U1,
            &creased,
            Edge::U0,
            false,
            &mut Policy::new(&Ladder::default(), &mut Escalations::default())
        ));
        // Opposite parameter directions are handled by the reversal flag.
        let flipped = quad([[1, 1, 0], [1, 0, 0], [3, 1, 0], [2, 0, 0]]);
        assert!(parallel_normals(
            &a,
            Edge::U1,
            &flipped,
            Edge::U0,
            true,
            &mut Policy::new(&Ladder::default(), &mut Escalations::default())
        ));
    }
}
