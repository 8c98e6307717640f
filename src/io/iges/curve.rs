//! IGES curves as exact rational Bézier pieces in model space: the rational B-spline curve
//! (126) on its parameter range, the line segment (110, form 0), and the composite curve (102)
//! of those; each with its transformation matrices (124) applied. Other curve types are
//! reported as not read (the face that needs them is used untrimmed), never approximated.

use super::{apply, Reader};
use crate::io::ReadError;
use crate::number::Rational;
use crate::surface::{ModelCurve, NurbsCurve, NurbsError, ParameterCurve};

/// Why a curve was not read.
pub(super) enum CurveFailure {
    /// The file is malformed: the read stops with this error.
    Malformed(ReadError),
    /// A curve limn does not read yet: the entity, its type and what is missing.
    Unsupported(String),
}

impl From<ReadError> for CurveFailure {
    fn from(e: ReadError) -> Self {
        CurveFailure::Malformed(e)
    }
}

/// How deep composite curves may nest (a cycle of pointers would otherwise never end).
const MAX_NESTING: usize = 16;

/// The most Bézier pieces one curve may split into.
const MAX_CURVE_PIECES: usize = 100_000;

impl Reader<'_> {
    /// The curve at `de` as exact Bézier pieces in model space, in its direction.
    pub(super) fn read_curve(&mut self, de: usize) -> Result<Vec<ModelCurve>, CurveFailure> {
        self.read_curve_nested(de, 0)
    }

    /// The curve at `de` as pieces in a surface's parameter plane: its (x, y) coordinates
    /// after its transformation, as IGES defines parameter-space curves (z is not used).
    pub(super) fn read_parameter_curve(
        &mut self,
        de: usize,
    ) -> Result<Vec<ParameterCurve>, CurveFailure> {
        Ok(self
            .read_curve(de)?
            .iter()
            .map(|c| c.map_points(|p| vec![p[0].clone(), p[1].clone()]))
            .collect())
    }

    fn read_curve_nested(
        &mut self,
        de: usize,
        depth: usize,
    ) -> Result<Vec<ModelCurve>, CurveFailure> {
        let kind = self.kind(de);
        let form = self.dir[&de].form;
        let pieces = match kind {
            126 => self.read_bspline_curve(de)?,
            110 if form == 0 => {
                let f = self.fields(de)?;
                let mut i = 0;
                let c = self.numbers(de, &f, &mut i, 6, "coordinate")?;
                if c[..3] == c[3..] {
                    return Err(self
                        .entity_err(de, "the line segment's two end points are equal")
                        .into());
                }
                vec![ModelCurve::segment(&c[..3], &c[3..])]
            }
            102 => {
                let f = self.fields(de)?;
                if depth >= MAX_NESTING {
                    return Err(self
                        .entity_err(
                            de,
                            format!("composite curves nest deeper than {MAX_NESTING} (a cycle?)"),
                        )
                        .into());
                }
                let n = self.count(de, &f, 0, "N (number of curves)", 100_000)?;
                if n == 0 {
                    return Err(self.entity_err(de, "a composite curve of no curves").into());
                }
                let mut all = Vec::new();
                for k in 0..n {
                    let what = format!("curve {}", k + 1);
                    let p = self
                        .pointer_at(de, &f, 1 + k, &what, false)?
                        .expect("a required pointer");
                    all.extend(self.read_curve_nested(p, depth + 1)?);
                }
                all
            }
            _ => {
                let name = match kind {
                    100 => "circular arc",
                    104 => "conic arc",
                    106 => "copious data (polyline)",
                    110 => "unbounded line (form 1 or 2)",
                    112 => "parametric spline curve",
                    130 => "offset curve",
                    _ => "entity",
                };
                return Err(CurveFailure::Unsupported(format!(
                    "the curve at directory entry {de} is a {name} (type {kind}), which limn does not read yet"
                )));
            }
        };
        let map = self.transform(de)?;
        Ok(match map {
            None => pieces,
            Some(_) => pieces
                .iter()
                .map(|c| c.map_points(|p| apply(&map, p)))
                .collect(),
        })
    }

    /// Entity 126: K (upper index), M (degree), four flags, knots `T(-M)..T(N)`, weights,
    /// points, the range `V0, V1` (and the normal of a planar curve, unused).
    fn read_bspline_curve(&mut self, de: usize) -> Result<Vec<ModelCurve>, CurveFailure> {
        let f = self.fields(de)?;
        let k = self.count(de, &f, 0, "K", 1_000_000)?;
        let m = self.count(de, &f, 1, "M (degree)", 1_000)?;
        let n = k + 1;
        let mut i = 6;
        let knots = self.numbers(de, &f, &mut i, n + m + 1, "knot")?;
        let weights = self.numbers(de, &f, &mut i, n, "weight")?;
        let coords = self.numbers(de, &f, &mut i, 3 * n, "control point coordinate")?;
        let range = self.numbers(de, &f, &mut i, 2, "parameter range value")?;
        let points: Vec<Vec<Rational>> = coords.chunks_exact(3).map(<[_]>::to_vec).collect();
        // Some writers put V0 = V1 (an empty range) on edges of their B-reps; such a curve is
        // read on its whole knot domain, and said so. Whether that is the edge is checked
        // where it is used: its loop must close.
        let range = if range[0] == range[1] && knots.len() > n {
            let warning = crate::model::Warning {
                place: format!("directory entry {de}"),
                message: format!(
                    "the B-spline curve's range V0 = V1 = {} is empty: its whole knot domain is used",
                    range[0].to_f64()
                ),
            };
            // An edge's curve is read once per face that uses it: said once.
            if !self.warnings.contains(&warning) {
                self.warnings.push(warning);
            }
            None
        } else {
            Some([range[0].clone(), range[1].clone()])
        };
        let curve = NurbsCurve::<4>::new(m, knots, &points, &weights, range).map_err(|e| {
            let msg = match &e {
                NurbsError::Decreasing { index, value, .. } => {
                    format!(
                        "knot {}: {value} is less than the knot before it",
                        index + 1
                    )
                }
                NurbsError::NonPositiveWeight { index, value } => {
                    format!(
                        "weight {}: {value} is not positive (weights must be positive)",
                        index + 1
                    )
                }
                NurbsError::Range { .. } => format!("V0, V1: {e}"),
                _ => e.to_string(),
            };
            self.entity_err(de, msg)
        })?;
        let pieces = curve.span_count();
        if pieces > MAX_CURVE_PIECES {
            return Err(self
                .entity_err(
                    de,
                    format!("the curve splits into {pieces} Bézier pieces, more than the {MAX_CURVE_PIECES} allowed"),
                )
                .into());
        }
        self.bezier_points = self.bezier_points.saturating_add(pieces * (m + 1));
        if self.bezier_points > crate::io::MAX_BEZIER_POINTS {
            return Err(self
                .entity_err(
                    de,
                    format!(
                        "the model's surfaces and curves would have more than the {} Bézier control points allowed",
                        crate::io::MAX_BEZIER_POINTS
                    ),
                )
                .into());
        }
        Ok(curve.to_bezier().into_iter().map(|(_, c)| c).collect())
    }
}
