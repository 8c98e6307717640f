//! An axis-parallel rectangle of the plane in `f64`: a box in a patch's parameters `(u, v)`
//! or in the image plane.
//!
//! One type for every such box in limn: the solver's cells read in `f64`, enclosures of
//! critical and singular points, the pieces of a traced arc, a sample's parameters, the boxes
//! of the occlusion walk, the hulls of a report. A `Rect` is closed (it holds its sides), and
//! its corners are plain `f64` values: a rectangle that encloses something exact was rounded
//! outwards where it was made (see the maker's doc), and every method here that builds a new
//! rectangle from old ones only takes minima, maxima and sides, which round nothing, except
//! [`Rect::grown`] and [`Rect::center`], whose docs say so.
//!
//! In JSON a rectangle is written by its corners, `[[u_lo, v_lo], [u_hi, v_hi]]`: every box of
//! every report has that one form (the visible regions' cells, which are written as two
//! fields `lo` and `hi`, say the same corners).

/// A closed axis-parallel rectangle `[lo[0], hi[0]] × [lo[1], hi[1]]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect {
    /// The lower corner.
    pub lo: [f64; 2],
    /// The upper corner.
    pub hi: [f64; 2],
}

impl Rect {
    /// The rectangle with corners `lo` and `hi`.
    pub const fn new(lo: [f64; 2], hi: [f64; 2]) -> Rect {
        Rect { lo, hi }
    }

    /// The rectangle of two ranges, `[u_lo, u_hi]` and `[v_lo, v_hi]`.
    pub const fn from_axes(u: [f64; 2], v: [f64; 2]) -> Rect {
        Rect {
            lo: [u[0], v[0]],
            hi: [u[1], v[1]],
        }
    }

    /// The rectangle that is one point.
    pub const fn point(p: [f64; 2]) -> Rect {
        Rect { lo: p, hi: p }
    }

    /// The unit square `[0, 1]²`, a patch's whole parameter domain.
    pub const UNIT: Rect = Rect {
        lo: [0.0, 0.0],
        hi: [1.0, 1.0],
    };

    /// The range `[lo, hi]` along `axis` (0 for u, 1 for v).
    pub fn axis(&self, axis: usize) -> [f64; 2] {
        [self.lo[axis], self.hi[axis]]
    }

    /// Sets the range along `axis` to `r = [lo, hi]`.
    pub fn set_axis(&mut self, axis: usize, r: [f64; 2]) {
        self.lo[axis] = r[0];
        self.hi[axis] = r[1];
    }

    /// The corners `[lo, hi]`.
    pub fn corners(&self) -> [[f64; 2]; 2] {
        [self.lo, self.hi]
    }

    /// The two ranges `[[u_lo, u_hi], [v_lo, v_hi]]`.
    pub fn axes(&self) -> [[f64; 2]; 2] {
        [self.axis(0), self.axis(1)]
    }

    /// The width along `axis`, `hi − lo` rounded to nearest.
    pub fn width(&self, axis: usize) -> f64 {
        self.hi[axis] - self.lo[axis]
    }

    /// Half the width along `axis`, rounded to nearest.
    pub fn half_width(&self, axis: usize) -> f64 {
        0.5 * (self.hi[axis] - self.lo[axis])
    }

    /// The centre, `(lo + hi) / 2` per axis rounded to nearest (so it may lie a rounding off
    /// the true centre, never outside the rectangle).
    pub fn center(&self) -> [f64; 2] {
        [0, 1].map(|k| 0.5 * (self.lo[k] + self.hi[k]))
    }

    /// Whether `other` lies in this rectangle (closed: touching sides count).
    pub fn contains(&self, other: &Rect) -> bool {
        (0..2).all(|k| self.lo[k] <= other.lo[k] && other.hi[k] <= self.hi[k])
    }

    /// Whether the point lies in this rectangle (closed).
    pub fn contains_point(&self, p: [f64; 2]) -> bool {
        (0..2).all(|k| self.lo[k] <= p[k] && p[k] <= self.hi[k])
    }

    /// Whether the two closed rectangles have a point in common.
    pub fn meets(&self, other: &Rect) -> bool {
        (0..2).all(|k| self.lo[k] <= other.hi[k] && other.lo[k] <= self.hi[k])
    }

    /// The smallest rectangle holding both (exact: minima and maxima round nothing).
    pub fn hull(&self, other: &Rect) -> Rect {
        Rect {
            lo: [0, 1].map(|k| self.lo[k].min(other.lo[k])),
            hi: [0, 1].map(|k| self.hi[k].max(other.hi[k])),
        }
    }

    /// The rectangle grown on every side by `by`, rounded to nearest: a search region, not an
    /// enclosure (use directed rounding where the result must enclose).
    pub fn grown(&self, by: f64) -> Rect {
        Rect {
            lo: self.lo.map(|x| x - by),
            hi: self.hi.map(|x| x + by),
        }
    }

    /// Whether every corner coordinate is finite.
    pub fn is_finite(&self) -> bool {
        self.lo.iter().chain(&self.hi).all(|x| x.is_finite())
    }
}

impl serde::Serialize for Rect {
    /// By its corners, `[[u_lo, v_lo], [u_hi, v_hi]]`.
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        serde::Serialize::serialize(&self.corners(), s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn corners_axes_and_relations() {
        let a = Rect::new([0.0, 1.0], [2.0, 3.0]);
        assert_eq!(a, Rect::from_axes([0.0, 2.0], [1.0, 3.0]));
        assert_eq!(serde_json::to_string(&a).unwrap(), "[[0.0,1.0],[2.0,3.0]]");
        assert_eq!(a.axes(), [[0.0, 2.0], [1.0, 3.0]]);
        let mut d = a;
        d.set_axis(0, [5.0, 6.0]);
        assert_eq!(d, Rect::new([5.0, 1.0], [6.0, 3.0]));
        let b = Rect::new([1.0, 2.0], [2.0, 2.5]);
        assert!(a.contains(&b) && !b.contains(&a) && a.meets(&b));
        let c = Rect::point([2.0, 3.0]);
        assert!(a.meets(&c) && a.contains(&c) && a.contains_point([2.0, 3.0]));
        assert!(!Rect::point([2.0, 3.5]).meets(&a));
        assert_eq!(
            b.hull(&Rect::point([-1.0, 9.0])),
            Rect::new([-1.0, 2.0], [2.0, 9.0])
        );
        assert_eq!(a.center(), [1.0, 2.0]);
        assert_eq!((a.width(0), a.half_width(1)), (2.0, 1.0));
        assert_eq!(a.grown(1.0), Rect::new([-1.0, 0.0], [3.0, 4.0]));
        assert!(!Rect::new([0.0, f64::NAN], [1.0, 1.0]).is_finite());
    }
}
