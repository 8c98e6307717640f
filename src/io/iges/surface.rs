//! IGES entity 128, the rational B-spline surface, split into exact Bézier patches.

use super::{apply, Reader};
use crate::io::trimmed::{BezierPiece, SurfaceInfo};
use crate::io::ReadError;
use crate::number::Rational;
use crate::surface::{NurbsError, NurbsSurface, Point3};
use std::cmp::Ordering;

impl Reader<'_> {
    /// The surface of a 128 entity, its transformation applied, with the warnings its data
    /// call for (a stated range unlike the knot domain).
    pub(super) fn read_nurbs_surface(&mut self, de: usize) -> Result<NurbsSurface, ReadError> {
        let f = self.fields(de)?;
        let int = |i: usize, what: &str| self.count(de, &f, i, what, 100_000);
        let (k1, k2, m1, m2) = (int(0, "K1")?, int(1, "K2")?, int(2, "M1")?, int(3, "M2")?);
        let (nu, nv) = (k1 + 1, k2 + 1);
        if nu.checked_mul(nv).is_none_or(|n| n > 10_000_000) {
            return Err(self.entity_err(de, "too many control points"));
        }
        let mut i = 9;
        let ku = self.numbers(de, &f, &mut i, nu + m1 + 1, "u knot")?;
        let kv = self.numbers(de, &f, &mut i, nv + m2 + 1, "v knot")?;
        let w = self.numbers(de, &f, &mut i, nu * nv, "weight")?;
        let c = self.numbers(de, &f, &mut i, 3 * nu * nv, "control point coordinate")?;
        let range = self.numbers(de, &f, &mut i, 4, "parameter range value")?;
        // The file orders points with the u index fastest; limn's order is i * count_v + j.
        let mut points: Vec<Point3> = Vec::with_capacity(nu * nv);
        let mut weights = Vec::with_capacity(nu * nv);
        let map = self.transform(de)?;
        for ii in 0..nu {
            for jj in 0..nv {
                let k = jj * nu + ii;
                let p = apply(&map, &c[3 * k..3 * k + 3]);
                points.push([p[0].clone(), p[1].clone(), p[2].clone()]);
                weights.push(w[k].clone());
            }
        }
        // Weights and knots are named as the file counts them (1-based, u fastest).
        if let Some((k, x)) = w
            .iter()
            .enumerate()
            .find(|(_, x)| x.cmp0() != Ordering::Greater)
        {
            return Err(self.entity_err(
                de,
                format!(
                    "weight {}: {x} is not positive (weights must be positive)",
                    k + 1
                ),
            ));
        }
        let surface =
            NurbsSurface::new([m1, m2], ku, kv, [nu, nv], points, weights).map_err(|e| {
                let msg = match &e {
                    NurbsError::Decreasing { dir, index, value } => {
                        format!(
                            "{dir} knot {}: {value} is less than the knot before it",
                            index + 1
                        )
                    }
                    _ => e.to_string(),
                };
                self.entity_err(de, msg)
            })?;
        let dom = surface.domain();
        if range[0] != dom[0][0]
            || range[1] != dom[0][1]
            || range[2] != dom[1][0]
            || range[3] != dom[1][1]
        {
            let f = |q: &Rational| q.to_f64();
            self.warn(
                de,
                format!(
                    "the stated parameter range [{}, {}] x [{}, {}] differs from the knot domain [{}, {}] x [{}, {}]; the knot domain is used",
                    f(&range[0]), f(&range[1]), f(&range[2]), f(&range[3]),
                    f(&dom[0][0]), f(&dom[0][1]), f(&dom[1][0]), f(&dom[1][1])
                ),
            );
        }
        Ok(surface)
    }

    /// The Bézier patches of a 128 entity, counted against the model's budget of points, and
    /// what the trimming loops on it need to know of it.
    pub(super) fn read_surface(
        &mut self,
        de: usize,
        index: usize,
    ) -> Result<(SurfaceInfo, Vec<BezierPiece>), ReadError> {
        let surface = self.read_nurbs_surface(de)?;
        crate::io::count_bezier_points(&mut self.bezier_points, &surface)
            .map_err(|m| self.entity_err(de, m))?;
        let pieces = surface.to_bezier();
        // PROP1 and PROP2: the file states the surface closed in u, in v.
        let f = self.fields(de)?;
        let closed = [4, 5].map(|i| f.get(i).is_some_and(|x| x.trim() == "1"));
        let info = SurfaceInfo::of_nurbs(index, &surface, &pieces, closed);
        Ok((info, pieces))
    }
}
