//! Boxes of a patch's square on which its image map is injective, from a grid of interval
//! Jacobian ranges.
//!
//! The image map `F` is injective on a convex box `R` if the interval matrix of its
//! Jacobian's ranges over `R` is regular: by the mean value theorem `F(w₁) − F(w₂) = M (w₁ − w₂)`
//! with the rows of `M` gradients at points of the segment (inside `R`), and each row a
//! positive multiple of the corresponding row of the numerator Jacobian (as
//! [`crate::analysis::visibility::sheets::injective_box`], `proofs/ray-count.md`). The ranges over a box made
//! of grid boxes are the hulls of the grid boxes' ranges, so each test is a hull of stored
//! intervals; the grid is computed once per patch by midpoint subdivision.

use crate::analysis::visibility::visible::outline::quarters;
use crate::bernstein::Bernstein;
use crate::geometry::Rect;
use crate::number::{Interval, Number};

type IPoly = Bernstein<Interval>;

/// The ranges of the four numerator Jacobian entries on every box of a `2^level` grid.
pub(super) struct JacobianGrid {
    level: u32,
    /// `[i * 2^level + j]`.
    ranges: Vec<[Interval; 4]>,
}

fn fill(out: &mut [[Interval; 4]], side: usize, left: u32, i: usize, j: usize, m: &[IPoly; 4]) {
    if left == 0 {
        out[i * side + j] = [m[0].hull(), m[1].hull(), m[2].hull(), m[3].hull()];
        return;
    }
    let q: Vec<[IPoly; 4]> = m.iter().map(quarters).collect();
    let kids: Vec<[IPoly; 4]> = (0..4)
        .map(|k| std::array::from_fn(|e| q[e][k].clone()))
        .collect();
    for (k, child) in kids.iter().enumerate() {
        fill(out, side, left - 1, 2 * i + k % 2, 2 * j + k / 2, child);
    }
}

impl JacobianGrid {
    /// The grid of a patch's numerator Jacobian entries `[m00, m01, m10, m11]`.
    pub(super) fn new(m: &[IPoly; 4], level: u32) -> JacobianGrid {
        let side = 1usize << level;
        let mut ranges = vec![[Interval::point(0.0); 4]; side * side];
        fill(&mut ranges, side, level, 0, 0, m);
        JacobianGrid { level, ranges }
    }

    /// Whether the interval Jacobian over the grid boxes `[i0, i1] × [j0, j1]` is regular.
    fn regular(&self, i0: usize, i1: usize, j0: usize, j1: usize) -> bool {
        let side = 1usize << self.level;
        let mut h: Option<[Interval; 4]> = None;
        for i in i0..=i1 {
            for j in j0..=j1 {
                let r = &self.ranges[i * side + j];
                h = Some(match h {
                    None => *r,
                    Some(a) => [0, 1, 2, 3].map(|k| a[k].hull(&r[k])),
                });
            }
        }
        let Some(r) = h else { return false };
        let det = r[0].mul(&r[3]).sub(&r[1].mul(&r[2]));
        det.lo() > 0.0 || det.hi() < 0.0
    }

    /// A box of grid boxes around the cell `(i, j)` at `level`, reaching at least one cell
    /// width beyond each of its sides (clipped to the square), on which the image map is
    /// injective; failing that, the grid boxes covering the cell; or `None`.
    pub(super) fn around(&self, level: u32, i: u32, j: u32) -> Option<Rect> {
        let side = 1i64 << self.level;
        // The cell's span of grid boxes.
        let (a0, a1, b0, b1, grow) = if level >= self.level {
            let s = level - self.level;
            let (a, b) = ((i >> s) as i64, (j >> s) as i64);
            (a, a, b, b, 1i64)
        } else {
            let s = self.level - level;
            let n = 1i64 << s;
            let (a, b) = (i as i64 * n, j as i64 * n);
            (a, a + n - 1, b, b + n - 1, n)
        };
        let unit = 0.5f64.powi(self.level as i32);
        for g in [grow, 0] {
            let c = |x: i64| x.clamp(0, side - 1) as usize;
            let (i0, i1, j0, j1) = (c(a0 - g), c(a1 + g), c(b0 - g), c(b1 + g));
            if self.regular(i0, i1, j0, j1) {
                return Some(Rect::new(
                    [i0 as f64 * unit, j0 as f64 * unit],
                    [(i1 + 1) as f64 * unit, (j1 + 1) as f64 * unit],
                ));
            }
        }
        None
    }
}
