//! Certified enclosures of lines through the origin (points of the viewing sphere up to sign):
//! a cone of lines around an axis, from an interval box of direction vectors, and the bound it
//! gives on the distance between a drawn piece of a sphere curve and the true piece
//! (`proofs/events.md`, "Enclosures").
//!
//! Angles are between lines: `angle(x, y) = acos(|x·y| / (|x| |y|))`, in `[0, π/2]`.

use crate::number::margin;
use crate::number::{Interval, Number};

/// The largest angle, between two lines, that [`piece_error`] accepts for its cone: below
/// `π/4`, two drawn directions of one piece are within `π/2` of each other, so the drawing's
/// choice of signs (each direction within 90° of the one before) keeps them in one cap.
const MAX_RADIUS: f64 = std::f64::consts::FRAC_PI_4;

/// Every line whose direction lies in the box is within `radius` of the line of `axis`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineCone {
    /// A direction of the axis (not unit).
    pub axis: [f64; 3],
    /// The angle, in radians, an upper bound.
    pub radius: f64,
}

/// An upper bound of `asin(s)` for `0 ≤ s`, `π/2` from `s ≥ 1` (a relative margin covers the
/// rounding of the library's `asin`).
fn asin_up(s: f64) -> f64 {
    if s.is_nan() || s >= 1.0 {
        return std::f64::consts::FRAC_PI_2;
    }
    margin::up(s.max(0.0).asin(), margin::FEW).min(std::f64::consts::FRAC_PI_2)
}

fn sum_sq(v: &[Interval; 3]) -> Interval {
    v.iter()
        .map(|x| x.mul(x))
        .fold(Interval::point(0.0), |a, b| a.add(&b))
}

impl LineCone {
    /// The cone around the box's midpoint `m` that holds the lines of all its nonzero vectors:
    /// each `x` in the box has `|x − m| ≤ ρ` (ρ from the half-widths, rounded up), and when
    /// `ρ < |m|` the angle between `x` and `m` is at most `asin(ρ / |m|)`. `None` when the box
    /// may hold the zero vector in that sense (`ρ ≥ |m|`).
    pub fn enclosing(d: &[Interval; 3]) -> Option<LineCone> {
        let m: [f64; 3] = std::array::from_fn(|k| 0.5 * d[k].lo() + 0.5 * d[k].hi());
        if m.iter().any(|x| !x.is_finite()) {
            return None;
        }
        // Per coordinate the larger distance from m to an end, rounded up.
        let r: [Interval; 3] = std::array::from_fn(|k| {
            let a = Interval::point(d[k].hi()).sub(&Interval::point(m[k]));
            let b = Interval::point(m[k]).sub(&Interval::point(d[k].lo()));
            Interval::point(a.hi().max(b.hi()))
        });
        let rho2 = sum_sq(&r).hi();
        let m2 = sum_sq(&m.map(Interval::point)).lo();
        if m2.is_nan() || m2 <= 0.0 || !rho2.is_finite() || rho2 >= m2 {
            return None;
        }
        // sin² of the angle ≤ ρ² / |m|², rounded up.
        let s2 = Interval::point(rho2)
            .mul(&Interval::point(m2).recip()?)
            .hi();
        Some(LineCone {
            axis: m,
            radius: asin_up(margin::up(s2.sqrt(), margin::TIGHT)),
        })
    }

    /// An upper bound of the angle between the line of `x` and the axis (`π/2` if `x` is zero
    /// or not finite).
    pub fn angle_to(&self, x: [f64; 3]) -> f64 {
        let (a, b) = (x.map(Interval::point), self.axis.map(Interval::point));
        let c: [Interval; 3] = std::array::from_fn(|k| {
            let (i, j) = ((k + 1) % 3, (k + 2) % 3);
            a[i].mul(&b[j]).sub(&a[j].mul(&b[i]))
        });
        // sin² = |x × m|² / (|x|² |m|²), rounded up.
        let den = sum_sq(&a).mul(&sum_sq(&b));
        match den.recip() {
            Some(r) if den.lo() > 0.0 => {
                let s2 = sum_sq(&c).mul(&r).hi();
                if s2.is_finite() {
                    asin_up(margin::up(s2.sqrt(), margin::TIGHT))
                } else {
                    std::f64::consts::FRAC_PI_2
                }
            }
            _ => std::f64::consts::FRAC_PI_2,
        }
    }
}

/// A proven bound on the distance, as an angle between lines, from every point of a drawn
/// piece of a sphere curve to the true piece and back (the Hausdorff distance, both antipodes
/// drawn): the true piece's directions lie in the box `d`, and the drawn piece is the polyline
/// through `drawn` (with the drawing's signs, each within 90° of the one before), its great
/// arcs included. With `R` the largest of the cone's radius and the drawn vertices' angles to
/// its axis, both pieces lie in the cap of radius `R` (caps under `π/2` are convex), so every
/// point of one is within `2R` of every point of the other. `None` when `R ≥ π/4` or the box
/// has no cone.
pub fn piece_error(d: &[Interval; 3], drawn: &[[f64; 3]]) -> Option<f64> {
    let cone = LineCone::enclosing(d)?;
    let r = drawn
        .iter()
        .map(|&x| cone.angle_to(x))
        .fold(cone.radius, f64::max);
    (r < MAX_RADIUS).then_some(2.0 * r)
}

/// The largest of the pieces' bounds; `None` if any piece has none.
pub fn largest(errors: impl IntoIterator<Item = Option<f64>>) -> Option<f64> {
    errors
        .into_iter()
        .try_fold(0.0f64, |m, e| e.map(|e| m.max(e)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_box_around_the_z_axis() {
        let d = [
            Interval::new(-0.1, 0.1),
            Interval::new(-0.1, 0.1),
            Interval::new(1.0, 1.2),
        ];
        let c = LineCone::enclosing(&d).unwrap();
        // Every corner's angle to the axis is within the radius, and the radius is not loose
        // by much (the farthest corner is at asin(√0.02 / |(0.1, 0.1, 1)|) or so).
        for x in [-0.1f64, 0.1] {
            for y in [-0.1f64, 0.1] {
                for z in [1.0f64, 1.2] {
                    let a = (x * x + y * y).sqrt().atan2(z);
                    assert!(a <= c.radius, "{a} > {}", c.radius);
                    assert!(c.angle_to([x, y, z]) >= a - 1e-15);
                }
            }
        }
        assert!(c.radius < 0.2, "{}", c.radius);
        // Lines: the opposite vector is the same line.
        assert_eq!(c.angle_to([0.0, 0.0, -1.0]), c.angle_to([0.0, 0.0, 1.0]));
        assert!(c.angle_to([0.0, 0.0, 1.0]) < 1e-7);
    }

    #[test]
    fn a_box_with_the_zero_vector_has_no_cone() {
        let d = [
            Interval::new(-0.1, 0.1),
            Interval::new(-0.1, 0.1),
            Interval::new(-0.1, 0.2),
        ];
        assert!(LineCone::enclosing(&d).is_none());
        assert!(piece_error(&d, &[]).is_none());
    }

    #[test]
    fn a_drawn_vertex_far_from_the_cone_widens_the_bound() {
        let d = [
            Interval::new(-1e-3, 1e-3),
            Interval::new(-1e-3, 1e-3),
            Interval::new(1.0, 1.0),
        ];
        let tight = piece_error(&d, &[[0.0, 0.0, 1.0]]).unwrap();
        assert!(tight < 3e-3, "{tight}");
        let off = piece_error(&d, &[[0.0, 0.0, 1.0], [0.1, 0.0, 1.0]]).unwrap();
        assert!((off - 2.0 * 0.1f64.atan()).abs() < 1e-6, "{off}");
        // Past π/4 there is no bound.
        assert!(piece_error(&d, &[[1.0, 0.0, 0.9]]).is_none());
        assert_eq!(largest([Some(1.0), Some(2.0)]), Some(2.0));
        assert_eq!(largest([Some(1.0), None]), None);
    }
}
