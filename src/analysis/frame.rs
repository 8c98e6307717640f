//! The model's own frame: every analysis works on the model translated exactly so that its
//! control box is centred near the origin, and its results are carried back.
//!
//! Why: the exact input does not care where the model sits, but every f64 enclosure built
//! from it does. Interval bounds of a rational patch's derivatives, the chord tracer's
//! bounds and the f64 evaluators all carry errors proportional to the coordinates' size, so
//! a sphere shifted by (100, 100, 100) would lose its certified accuracy at `--tol 1e-6`, and
//! one shifted by 10⁶ most of its hidden-line verdicts. In the model's own frame those errors
//! scale with the model's size, as the tolerance does.
//!
//! The origin `c` is the centre of the control box rounded to a multiple of
//! `g = 2^(⌊log₂ extent⌋ − 8)` (`extent` the box's largest side; rounding half up): a short
//! dyadic, so that the translated coordinates stay short, and translating the model by any
//! multiple of `g` moves `c` by exactly that much (so the translated model in its own frame
//! is the same exact model, and every proof and every parameter-space answer is the same).
//! A model already centred within `g / 2` has `c = 0`: nothing changes.
//!
//! What is carried back (`proofs/model-frame.md`): points in space are `p + c` in f64 (the
//! rounding added to every error bound); parameters, topology, directions, areas and
//! verdicts are unchanged by a translation; a plane `n · x = d` becomes `n · x = d + n · c`;
//! an eye `E` is `E − c` in the frame. The tolerance is the same in the frame (so that the run
//! on a translated model is the same run); a drawing whose bound, grown by the rounding, then
//! exceeds it is no longer certified within it (a model some 2⁵⁰ times its tolerance from
//! the origin).

use crate::analysis::view::View;
use crate::model::Model;
use crate::number::margin;
use crate::number::{Number, Rational};
use crate::surface::Point3;
use std::borrow::Cow;

/// 2⁻⁵²: twice the unit roundoff, covering one rounding of a sum and the rounding of the
/// origin (`proofs/model-frame.md`).
const TWO_ULPS: f64 = f64::EPSILON;

/// A model's own frame: the exact origin its analyses work relative to.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// The origin, exactly (a short dyadic per coordinate).
    origin: Point3,
    /// The origin in f64, rounded to nearest.
    origin_f64: [f64; 3],
    /// Per coordinate, an upper bound of `|c − fl(c)|` (0 where the origin is exact in f64).
    origin_error: [f64; 3],
}

impl Frame {
    /// The frame of no translation.
    pub fn identity() -> Frame {
        Frame {
            origin: [Rational::new(), Rational::new(), Rational::new()],
            origin_f64: [0.0; 3],
            origin_error: [0.0; 3],
        }
    }

    /// The model's own frame (the identity for an empty model, a single point, or a model
    /// already centred).
    pub fn of(model: &Model) -> Frame {
        let Some([lo, hi]) = model.bounding_box() else {
            return Frame::identity();
        };
        let extent = (0..3)
            .map(|k| Rational::from(&hi[k] - &lo[k]))
            .max()
            .unwrap_or_default();
        if extent.cmp0() != std::cmp::Ordering::Greater {
            return Frame::identity();
        }
        let g = pow2(floor_log2(&extent) - 8);
        let half = Rational::from((1, 2));
        let origin: Point3 = std::array::from_fn(|k| {
            let centre = Rational::from(&lo[k] + &hi[k]) * &half;
            // floor(centre / g + 1/2) · g: rounding half up commutes with shifts by g.
            let steps = (centre / &g + &half).floor();
            steps * &g
        });
        if origin.iter().all(|c| c.cmp0() == std::cmp::Ordering::Equal) {
            return Frame::identity();
        }
        let origin_f64 = origin.clone().map(|c| c.to_f64());
        let origin_error: [f64; 3] = std::array::from_fn(|k| {
            let e = &origin[k] - Rational::from_f64(origin_f64[k]).unwrap_or_default();
            e.abs().upper_f64()
        });
        Frame {
            origin,
            origin_f64,
            origin_error,
        }
    }

    /// Whether the frame is the identity (the model is analysed as given).
    pub fn is_identity(&self) -> bool {
        self.origin
            .iter()
            .all(|c| c.cmp0() == std::cmp::Ordering::Equal)
    }

    /// The origin, exactly.
    pub fn origin(&self) -> &Point3 {
        &self.origin
    }

    /// The model in this frame: every control point and mesh vertex minus the origin,
    /// exactly (borrowed as it is for the identity).
    pub fn model<'a>(&self, model: &'a Model) -> Cow<'a, Model> {
        if self.is_identity() {
            return Cow::Borrowed(model);
        }
        let shift = |p: &Point3| -> Point3 {
            std::array::from_fn(|k| Rational::from(&p[k] - &self.origin[k]))
        };
        let mut local = model.clone();
        for p in &mut local.patches {
            p.surface = p.surface.map_points(shift);
        }
        for m in &mut local.meshes {
            for v in &mut m.vertices {
                *v = shift(v);
            }
        }
        Cow::Owned(local)
    }

    /// The view in this frame: a direction as it is, an eye minus the origin (exactly).
    pub fn view(&self, view: &View) -> View {
        match view {
            View::Eye(e) if !self.is_identity() => View::Eye(std::array::from_fn(|k| {
                Rational::from(&e[k] - &self.origin[k])
            })),
            _ => view.clone(),
        }
    }

    /// A point of the frame carried back to the model's coordinates, in f64.
    pub fn point(&self, p: [f64; 3]) -> [f64; 3] {
        std::array::from_fn(|k| p[k] + self.origin_f64[k])
    }

    /// An upper bound of the distance between `point(p)` and the exact `p + c`, from the
    /// carried-back point `q = point(p)` (`proofs/model-frame.md`).
    pub fn point_error(&self, q: &[f64; 3]) -> f64 {
        if self.is_identity() {
            return 0.0;
        }
        // Per coordinate: |c − fl(c)| + one rounding of the sum, ≤ 2⁻⁵² |q| (with room for
        // the sum's own rounding); the Euclidean distance is at most the sum over k.
        let e: f64 = (0..3)
            .map(|k| self.origin_error[k] + TWO_ULPS * q[k].abs())
            .sum();
        margin::up(e, margin::TIGHT)
    }

    /// Carries points back in place, returning the largest distance that added.
    pub fn points(&self, ps: &mut [[f64; 3]]) -> f64 {
        if self.is_identity() {
            return 0.0;
        }
        let mut worst = 0.0f64;
        for p in ps {
            *p = self.point(*p);
            worst = worst.max(self.point_error(p));
        }
        worst
    }

    /// Carries a drawn polyline back in place and grows its error bound by the rounding that
    /// adds; whether the bound is then still within `tol` (true without a bound or a
    /// tolerance).
    pub fn drawing(
        &self,
        points: &mut [[f64; 3]],
        bound: &mut Option<f64>,
        tol: Option<f64>,
    ) -> bool {
        let added = self.points(points);
        *bound = self.bound(*bound, added);
        match (*bound, tol) {
            (Some(b), Some(t)) => b <= t,
            _ => true,
        }
    }

    /// An error bound of drawn points after carrying them back: `bound + added`, rounded up
    /// (`None` stays `None`).
    pub fn bound(&self, bound: Option<f64>, added: f64) -> Option<f64> {
        bound.map(|b| {
            if added == 0.0 {
                b
            } else {
                margin::up(b + added, margin::TIGHT)
            }
        })
    }

    /// The offset of the plane `n · x = d` of the frame in model coordinates, `d + n · c`, in
    /// f64 (rounded to nearest: a drawing value, as `d` is).
    pub fn plane_offset(&self, n: [f64; 3], d: f64) -> f64 {
        d + (0..3).map(|k| n[k] * self.origin_f64[k]).sum::<f64>()
    }
}

/// 2^k, exactly.
fn pow2(k: i64) -> Rational {
    let mut p = Rational::from(1);
    if k >= 0 {
        p <<= k as u32;
    } else {
        p >>= (-k) as u32;
    }
    p
}

/// ⌊log₂ x⌋ of a positive rational, exactly.
fn floor_log2(x: &Rational) -> i64 {
    let bits = |i: &rug::Integer| i64::from(i.significant_bits());
    let mut k = bits(x.numer()) - bits(x.denom());
    while pow2(k) > *x {
        k -= 1;
    }
    while pow2(k + 1) <= *x {
        k += 1;
    }
    k
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Format;
    use crate::testing::shapes;

    fn shifted(t: [i64; 3]) -> Model {
        let q = Rational::from;
        let patches = shapes::sphere(&q(2))
            .iter()
            .map(|p| p.map_points(|x| std::array::from_fn(|k| Rational::from(&x[k] + t[k]))))
            .collect();
        Model::from_patches(Format::Json, patches)
    }

    #[test]
    fn a_centred_model_is_its_own_frame_and_a_shifted_one_comes_back_exactly() {
        let at_origin = shifted([0, 0, 0]);
        assert!(Frame::of(&at_origin).is_identity());
        for t in [[100, 100, 100], [1_000_000, -3, 7], [-5, 0, 0]] {
            let model = shifted(t);
            let frame = Frame::of(&model);
            assert_eq!(frame.origin().clone(), t.map(Rational::from));
            // The model in its frame is exactly the model at the origin.
            assert_eq!(frame.model(&model).patches, at_origin.patches);
            // Its own frame is then the identity (the frame is idempotent).
            assert!(Frame::of(&frame.model(&model)).is_identity());
        }
    }

    #[test]
    fn the_origin_is_short_and_the_rounding_is_bounded() {
        // A sphere of radius 2 centred at (1/3, 0, 0): the origin is a multiple of 2^-6
        // (extent 4 = 2^2, g = 2^-6), within g/2 of the centre.
        let q = Rational::from;
        let patches = shapes::sphere(&q(2))
            .iter()
            .map(|p| p.map_points(|x| [&x[0] + Rational::from((1, 3)), x[1].clone(), x[2].clone()]))
            .collect();
        let model = Model::from_patches(Format::Json, patches);
        let frame = Frame::of(&model);
        let c = frame.origin()[0].clone();
        assert_eq!(c, Rational::from((21, 64)));
        let p = frame.point([1.0, 2.0, 3.0]);
        assert_eq!(p, [1.0 + 21.0 / 64.0, 2.0, 3.0]);
        assert!(frame.point_error(&p) > 0.0 && frame.point_error(&p) < 1e-14);
        assert_eq!(Frame::identity().point_error(&p), 0.0);
    }

    #[test]
    fn an_eye_moves_with_the_frame_and_a_direction_does_not() {
        let frame = Frame::of(&shifted([100, 0, 0]));
        let e = View::Eye([Rational::from(103), Rational::from(1), Rational::from(2)]);
        assert_eq!(
            frame.view(&e),
            View::Eye([Rational::from(3), Rational::from(1), Rational::from(2)])
        );
        let d = View::Direction([Rational::from(1), Rational::from(2), Rational::from(3)]);
        assert_eq!(frame.view(&d), d);
        assert_eq!(frame.plane_offset([1.0, 0.0, 0.0], 2.0), 102.0);
    }
}
