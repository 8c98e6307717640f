//! STEP geometry (ISO 10303-42) as exact data: points, directions and placements; the curves
//! of edges and trims (B-spline curves with knots or quasi-uniform, rational or not, lines,
//! circles and ellipses as exact rational quarter arcs, trimmed curves of these, polylines);
//! the surfaces of faces (B-spline surfaces with knots or quasi-uniform, planes, circular
//! cylinders as exact rational patches). Other entity types are reported as not read, never
//! approximated.

use super::part21::{Instance, Param};
use super::Reader;
use crate::io::ReadError;
use crate::number::Rational;
use crate::surface::{NurbsCurve, NurbsError, NurbsSurface, Point3};

/// A curve of an edge or a trim, in any dimension.
#[derive(Clone, Debug)]
pub(super) enum Curve {
    /// A rational B-spline curve: degree, full knot vector, affine control points, weights.
    Nurbs {
        degree: usize,
        knots: Vec<Rational>,
        points: Vec<Vec<Rational>>,
        weights: Vec<Rational>,
    },
    /// The line `p + t d` (`d` the direction times the vector's magnitude).
    Line { p: Vec<Rational>, d: Vec<Rational> },
}

impl Curve {
    /// The knot domain `[t_p, t_n]` of a B-spline curve.
    pub(super) fn domain(&self) -> Option<[Rational; 2]> {
        match self {
            Curve::Nurbs {
                degree,
                knots,
                points,
                ..
            } => Some([knots[*degree].clone(), knots[points.len()].clone()]),
            Curve::Line { .. } => None,
        }
    }

    /// The point at `t`, exact, in the curve's dimension (2 or 3; `None` outside a B-spline
    /// curve's domain).
    pub(super) fn point(&self, t: &Rational) -> Option<Vec<Rational>> {
        match self {
            Curve::Line { p, d } => Some(
                p.iter()
                    .zip(d)
                    .map(|(x, y)| x + Rational::from(t * y))
                    .collect(),
            ),
            Curve::Nurbs {
                degree,
                knots,
                points,
                weights,
            } => {
                let d = self.domain()?;
                if *t < d[0] || *t > d[1] {
                    return None;
                }
                if points.first()?.len() == 3 {
                    let n =
                        NurbsCurve::<4>::new(*degree, knots.clone(), points, weights, None).ok()?;
                    Some(n.eval(t))
                } else {
                    let n =
                        NurbsCurve::<3>::new(*degree, knots.clone(), points, weights, None).ok()?;
                    Some(n.eval(t))
                }
            }
        }
    }

    /// The same point set run the other way: `t ↦ -t` (a B-spline's knots negated and
    /// reversed with its control points and weights), exact.
    pub(super) fn reversed(self) -> Curve {
        match self {
            Curve::Line { p, d } => Curve::Line {
                p,
                d: d.into_iter().map(|c| -c).collect(),
            },
            Curve::Nurbs {
                degree,
                knots,
                mut points,
                mut weights,
            } => {
                points.reverse();
                weights.reverse();
                Curve::Nurbs {
                    degree,
                    knots: knots.into_iter().rev().map(|k| -k).collect(),
                    points,
                    weights,
                }
            }
        }
    }

    /// The image under the affine map `P ↦ ((P − o)·x, (P − o)·y)` of a model-space curve:
    /// its coordinates in a plane's frame. Exact, and exactly the image (an affine map commutes
    /// with the rational B-spline's weighted sum, weights kept).
    pub(super) fn in_plane(&self, f: &PlaneFrame) -> Curve {
        let at = |p: &[Rational]| {
            let d: Vec<Rational> = p
                .iter()
                .zip(&f.o)
                .map(|(a, b)| Rational::from(a - b))
                .collect();
            vec![dot(&d, &f.x), dot(&d, &f.y)]
        };
        match self {
            Curve::Line { p, d } => Curve::Line {
                p: at(p),
                d: vec![dot(d, &f.x), dot(d, &f.y)],
            },
            Curve::Nurbs {
                degree,
                knots,
                points,
                weights,
            } => Curve::Nurbs {
                degree: *degree,
                knots: knots.clone(),
                points: points.iter().map(|p| at(p)).collect(),
                weights: weights.clone(),
            },
        }
    }

    /// A bound (max norm) on the distance between the model-space curve on `range` and its
    /// image through [`Curve::in_plane`] mapped back onto the plane `o + u x + v y`: the
    /// difference `(I − x xᵀ − y yᵀ)(C(t) − o)` is affine in `C(t)`, so on a line it is
    /// largest at an end of the range and on a B-spline (positive weights) it lies in the
    /// convex hull of the differences at the control points (`proofs/trimmed-faces.md` 9).
    pub(super) fn off_plane(&self, f: &PlaneFrame, range: &(Rational, Rational)) -> Rational {
        let off = |p: &[Rational]| {
            let d: Vec<Rational> = p
                .iter()
                .zip(&f.o)
                .map(|(a, b)| Rational::from(a - b))
                .collect();
            let (a, b) = (dot(&d, &f.x), dot(&d, &f.y));
            (0..3)
                .map(|k| {
                    (&d[k] - Rational::from(&a * &f.x[k]) - Rational::from(&b * &f.y[k])).abs()
                })
                .max()
                .unwrap_or_default()
        };
        match self {
            Curve::Line { p, d } => [&range.0, &range.1]
                .map(|t| {
                    let q: Vec<Rational> = p
                        .iter()
                        .zip(d)
                        .map(|(a, b)| a + Rational::from(t * b))
                        .collect();
                    off(&q)
                })
                .into_iter()
                .max()
                .unwrap_or_default(),
            Curve::Nurbs { points, .. } => points.iter().map(|p| off(p)).max().unwrap_or_default(),
        }
    }
}

/// A surface a face lies on.
#[derive(Clone, Debug)]
pub(super) enum StepSurface {
    /// A B-spline surface and whether the file states it closed in u and in v.
    Nurbs(Box<NurbsSurface>, [bool; 2]),
    /// A plane.
    Plane(Box<PlaneFrame>),
    /// A circular cylinder (its patch made per face, over the heights its loops reach).
    Cylinder(Box<Cylinder>),
}

/// The cylinder `c + r cos θ x + r sin θ y + v z`, parameterised by `(t, v)`: `t ∈ [0, 4]` the
/// parameter of its base circle as a [`Conic`] (the seam `t = 0` on the placement's `x` axis),
/// `v` the height along `z = x × y`.
#[derive(Clone, Debug)]
pub(super) struct Cylinder {
    pub(super) circle: Conic,
    pub(super) z: Point3,
}

impl Cylinder {
    /// The point at `(t, v)`, exact (`t` taken modulo 4).
    pub(super) fn point(&self, t: &Rational, v: &Rational) -> Option<Point3> {
        let mut t = t.clone();
        while t < 0 {
            t += 4;
        }
        while t > 4 {
            t -= 4;
        }
        let p = self.circle.curve().point(&t)?;
        Some([0, 1, 2].map(|k| &p[k] + Rational::from(v * &self.z[k])))
    }

    /// The parameters `(t, v)` of a point: its height along the axis, and the circle's
    /// parameter of its direction from the axis ([`Conic::parameter`]; `x`, `y` are
    /// perpendicular to `z`, so the height does not enter it).
    pub(super) fn parameters(&self, p: &[Rational]) -> [Rational; 2] {
        let d: Vec<Rational> = p
            .iter()
            .zip(&self.circle.c)
            .map(|(a, b)| Rational::from(a - b))
            .collect();
        [self.circle.parameter(p), dot(&d, &self.z)]
    }

    /// The radius.
    pub(super) fn radius(&self) -> &Rational {
        &self.circle.radii[0]
    }

    /// The cylinder over `t ∈ [m, m + 4]` and heights `[v0, v1]` as an exact rational B-spline
    /// surface of degree (2, 1): the circle's B-spline ([`Conic::curve_from`]) swept along `z`,
    /// closed in `t`.
    pub(super) fn surface(&self, m: usize, v0: &Rational, v1: &Rational) -> Option<NurbsSurface> {
        let Curve::Nurbs {
            knots,
            points,
            weights,
            ..
        } = self.circle.curve_from(m)
        else {
            return None;
        };
        let mut net = Vec::with_capacity(2 * points.len());
        let mut w = Vec::with_capacity(2 * points.len());
        for (p, wi) in points.iter().zip(&weights) {
            for v in [v0, v1] {
                net.push([0, 1, 2].map(|k| &p[k] + Rational::from(v * &self.z[k])));
                w.push(wi.clone());
            }
        }
        let kv = vec![v0.clone(), v0.clone(), v1.clone(), v1.clone()];
        NurbsSurface::new([2, 1], knots, kv, [points.len(), 2], net, w).ok()
    }
}

/// A circle or an ellipse `c + a cos θ x + b sin θ y` (`x`, `y` its placement's unit axes),
/// for edges mapped into a plane.
#[derive(Clone, Debug)]
pub(super) struct Conic {
    pub(super) c: Point3,
    pub(super) x: Point3,
    pub(super) y: Point3,
    /// The semi-axes `a` along `x` and `b` along `y` (equal on a circle).
    pub(super) radii: [Rational; 2],
    /// Run the other way (a trimmed curve against its sense): the parameter negated.
    pub(super) reversed: bool,
}

impl Conic {
    /// The conic as an exact rational B-spline: four quarter arcs of degree 2 on the knots
    /// `0,0,0,1,1,2,2,3,3,4,4,4`, quarter `k` the affine image of the unit circle's
    /// `((1 − s²)/(1 + s²), 2s/(1 + s²))` rotated by `k` right angles (`s = t − k`: Bézier
    /// points `e_k`, `e_k + e_{k+1}`, `e_{k+1}` with weights `1, 1, 2`, scaled by `2^k` so that
    /// the quarters join), run backwards when `reversed`.
    pub(super) fn curve(&self) -> Curve {
        self.curve_from(0)
    }

    /// [`Conic::curve`] on `[m, m + 4]` (`m` a whole quarter): the same point at `t` as at
    /// `t − 4` (the quarters repeat; `m` not reversed).
    pub(super) fn curve_from(&self, m: usize) -> Curve {
        let [a, b] = &self.radii;
        let ax: Vec<Rational> = self.x.iter().map(|v| Rational::from(v * a)).collect();
        let by: Vec<Rational> = self.y.iter().map(|v| Rational::from(v * b)).collect();
        let neg = |v: &[Rational]| v.iter().map(|c| -c.clone()).collect::<Vec<_>>();
        let quarter = [ax.clone(), by.clone(), neg(&ax), neg(&by)];
        let e: Vec<Vec<Rational>> = (0..5).map(|k| quarter[(m + k) % 4].clone()).collect();
        let at = |d: &[Rational]| -> Vec<Rational> {
            self.c.iter().zip(d).map(|(c, d)| c + d.clone()).collect()
        };
        let mut points = Vec::with_capacity(9);
        let mut weights = Vec::with_capacity(9);
        for k in 0..4 {
            let sum: Vec<Rational> = e[k]
                .iter()
                .zip(&e[k + 1])
                .map(|(p, q)| Rational::from(p + q))
                .collect();
            points.push(at(&e[k]));
            points.push(at(&sum));
            let w = Rational::from(1u32 << k);
            weights.push(w.clone());
            weights.push(w);
        }
        points.push(at(&e[4]));
        weights.push(Rational::from(16));
        let knots = [0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4]
            .map(|k| Rational::from(k + m as u32))
            .to_vec();
        let c = Curve::Nurbs {
            degree: 2,
            knots,
            points,
            weights,
        };
        if self.reversed {
            c.reversed()
        } else {
            c
        }
    }

    /// The parameter of [`Conic::curve`] at `p`: exact for a point on the conic; for a point
    /// off it, a nearby parameter (its error grows with the point's distance from the conic,
    /// and the vertex check of the face judges it): the quarter `k` whose right angle holds `p`'s direction, and `s = Y'/(1 + X')` there (at
    /// most 1, and taken as 0 or 1 within 2^-40 of them), `(X', Y')` the point's coordinates on
    /// the unit circle's scale rotated back by `k`; in `[0, 4)`.
    pub(super) fn parameter(&self, p: &[Rational]) -> Rational {
        let d: Vec<Rational> = p
            .iter()
            .zip(&self.c)
            .map(|(a, b)| Rational::from(a - b))
            .collect();
        let x = dot(&d, &self.x) / &self.radii[0];
        let y = dot(&d, &self.y) / &self.radii[1];
        let rotated = [
            (x.clone(), y.clone()),
            (y.clone(), -x.clone()),
            (-x.clone(), -y.clone()),
            (-y, x),
        ];
        let (k, (xr, yr)) = rotated
            .into_iter()
            .enumerate()
            .find(|(_, (a, b))| *a > 0 && *b >= 0)
            .unwrap_or((0, (Rational::from(0), Rational::from(0))));
        // Off the conic `s` may pass 1 (a point just outside it near the quarter's end): the
        // quarter's end is then the nearer parameter.
        // Within 2^-40 of a quarter's end (a vertex written a rounding away from the seam or
        // an axis), the end: the vertex check of its face judges the difference.
        let s = (yr / (xr + Rational::from(1))).min(Rational::from(1));
        let eps = Rational::from((1, 1u64 << 40));
        let s = if s < eps {
            Rational::from(0)
        } else if Rational::from(1 - &s) < eps {
            Rational::from(1)
        } else {
            s
        };
        let mut t = Rational::from(k as u32) + s;
        if t == 4 {
            t = Rational::from(0);
        }
        if self.reversed {
            -t
        } else {
            t
        }
    }

    /// The parameter domain of [`Conic::curve`].
    pub(super) fn domain(&self) -> [Rational; 2] {
        if self.reversed {
            [Rational::from(-4), Rational::from(0)]
        } else {
            [Rational::from(0), Rational::from(4)]
        }
    }
}

/// The plane `o + u x + v y`: `x` and `y` the placement's unit axes.
#[derive(Clone, Debug)]
pub(super) struct PlaneFrame {
    pub(super) o: Point3,
    pub(super) x: Point3,
    pub(super) y: Point3,
}

/// `a · b`, exact.
pub(super) fn dot(a: &[Rational], b: &[Rational]) -> Rational {
    a.iter().zip(b).map(|(x, y)| Rational::from(x * y)).sum()
}

/// A B-spline entity's head attributes and its knot attributes (`None`: implied).
type BsplineParts<'i> = (&'i [Param], Option<&'i [Param]>);

/// The knots Part 42 implies for a quasi-uniform B-spline of `n` control points and degree `p`:
/// `0` and `n − p` each `p + 1` times, the integers between once (too few points give a
/// vector the B-spline's own checks refuse).
fn quasi_uniform(n: usize, p: usize) -> Vec<Rational> {
    let spans = n.saturating_sub(p).max(1) as u64;
    let mut k = vec![Rational::from(0); p + 1];
    k.extend((1..spans).map(Rational::from));
    k.extend(std::iter::repeat_n(Rational::from(spans), p + 1));
    k
}

/// `a × b` of points given as slices, exact.
pub(super) fn cross3(a: &[Rational], b: &[Rational]) -> [Rational; 3] {
    cross(
        &[a[0].clone(), a[1].clone(), a[2].clone()],
        &[b[0].clone(), b[1].clone(), b[2].clone()],
    )
}

/// `a × b`, exact.
fn cross(a: &[Rational; 3], b: &[Rational; 3]) -> [Rational; 3] {
    let c = |i: usize, j: usize| Rational::from(&a[i] * &b[j]) - Rational::from(&a[j] * &b[i]);
    [c(1, 2), c(2, 0), c(0, 1)]
}

/// A vector of length within 2^-50 of 1 in the direction of `v` (nonzero): `v` itself when
/// its squared length is exactly 1, else `v` divided by a dyadic close to its length.
fn unit(v: [Rational; 3]) -> ([Rational; 3], bool) {
    let n2 = dot(&v, &v);
    if n2 == 1 {
        return (v, true);
    }
    let len = Rational::from_f64(n2.to_f64().sqrt()).unwrap_or_else(|| Rational::from(1));
    (v.map(|c| c / &len), false)
}

impl Reader<'_> {
    /// The coordinates of a `CARTESIAN_POINT` (`dim` of them).
    pub(super) fn point(&self, from: u64, id: u64, dim: usize) -> Result<Vec<Rational>, ReadError> {
        let a = self.simple(from, id, "point", &["CARTESIAN_POINT"])?;
        let c = self.list(id, self.attr(id, a, 1, "coordinates")?, "coordinates")?;
        if c.len() != dim {
            return Err(self.err(
                id,
                format!(
                    "the point has {} coordinates where {dim} are needed",
                    c.len()
                ),
            ));
        }
        c.iter().map(|x| self.real(id, x, "coordinate")).collect()
    }

    /// The ratios of a `DIRECTION` (`dim` of them, not all zero).
    pub(super) fn direction(
        &self,
        from: u64,
        id: u64,
        dim: usize,
    ) -> Result<Vec<Rational>, ReadError> {
        let a = self.simple(from, id, "direction", &["DIRECTION"])?;
        let c = self.list(
            id,
            self.attr(id, a, 1, "direction ratios")?,
            "direction ratios",
        )?;
        if c.len() != dim {
            return Err(self.err(
                id,
                format!(
                    "the direction has {} ratios where {dim} are needed",
                    c.len()
                ),
            ));
        }
        let d: Vec<Rational> = c
            .iter()
            .map(|x| self.real(id, x, "direction ratio"))
            .collect::<Result<_, _>>()?;
        if d.iter().all(|x| *x == 0) {
            return Err(self.err(id, "the direction is the zero vector"));
        }
        Ok(d)
    }

    fn direction3(
        &self,
        from: u64,
        p: &Param,
        what: &str,
        default: [i64; 3],
    ) -> Result<[Rational; 3], ReadError> {
        match p {
            Param::Unset => Ok(default.map(Rational::from)),
            _ => {
                let d = self.direction(from, self.reference(from, p, what)?, 3)?;
                Ok([d[0].clone(), d[1].clone(), d[2].clone()])
            }
        }
    }

    /// An `AXIS2_PLACEMENT_3D`: its origin and the axes x, y of its xy-plane (x the reference
    /// direction made orthogonal to the axis, y = axis × x), each of length 1 up to 2^-50
    /// (exactly when the file's directions have exact unit length; the second value says so).
    pub(super) fn placement(
        &self,
        from: u64,
        id: u64,
    ) -> Result<(Point3, Point3, Point3, bool), ReadError> {
        let a = self.simple(from, id, "placement", &["AXIS2_PLACEMENT_3D"])?;
        let o = self.point(
            id,
            self.reference(id, self.attr(id, a, 1, "location")?, "location")?,
            3,
        )?;
        let z = self.direction3(id, self.attr(id, a, 2, "axis")?, "axis", [0, 0, 1])?;
        let r = self.attr(id, a, 3, "ref_direction")?;
        let r = match r {
            Param::Unset => {
                if z[1] == 0 && z[2] == 0 {
                    [0, 1, 0].map(Rational::from)
                } else {
                    [1, 0, 0].map(Rational::from)
                }
            }
            _ => self.direction3(id, r, "ref_direction", [1, 0, 0])?,
        };
        let (z, z_exact) = unit(z);
        let k = dot(&r, &z);
        let x = [0, 1, 2].map(|i| &r[i] - Rational::from(&k * &z[i]));
        if x.iter().all(|c| *c == 0) {
            return Err(self.err(id, "the reference direction is parallel to the axis"));
        }
        let (x, x_exact) = unit(x);
        let y = cross(&z, &x);
        Ok((
            [o[0].clone(), o[1].clone(), o[2].clone()],
            x,
            y,
            z_exact && x_exact,
        ))
    }

    /// An edge's model-space curve, to be mapped onto a plane: what [`Reader::curve`] reads, a
    /// `CIRCLE` or `ELLIPSE` as its exact rational B-spline ([`Conic::curve`]) with the conic,
    /// a `TRIMMED_CURVE` as its basis curve (the edge's vertices trim it; run the other way
    /// where its sense disagrees with the basis) and a `POLYLINE` as the degree-1 B-spline
    /// through its points.
    pub(super) fn model_curve(
        &self,
        from: u64,
        id: u64,
    ) -> Result<Result<(Curve, Option<Conic>), String>, ReadError> {
        let inst = self.instance(from, id, "curve")?;
        match (inst.complex, inst.records[0].name.as_str()) {
            (false, "CIRCLE" | "ELLIPSE") => {
                let a = &inst.records[0].params;
                let pl = self.reference(id, self.attr(id, a, 1, "position")?, "position")?;
                let (c, x, y, _) = self.placement(id, pl)?;
                let circle = inst.records[0].name == "CIRCLE";
                let mut radii = Vec::with_capacity(2);
                let first = if circle { "radius" } else { "semi_axis_1" };
                for (k, what) in [(2, first), (3, "semi_axis_2")] {
                    if k == 3 && circle {
                        break;
                    }
                    let r = self.real(id, self.attr(id, a, k, what)?, what)?;
                    if r <= 0 {
                        return Err(self.err(id, format!("the {what} {r} is not positive")));
                    }
                    radii.push(r);
                }
                let b = radii.last().cloned().unwrap_or_default();
                let conic = Conic {
                    c,
                    x,
                    y,
                    radii: [radii[0].clone(), b],
                    reversed: false,
                };
                Ok(Ok((conic.curve(), Some(conic))))
            }
            (false, "TRIMMED_CURVE") => {
                let a = &inst.records[0].params;
                let basis =
                    self.reference(id, self.attr(id, a, 1, "basis_curve")?, "basis_curve")?;
                let sense = self.logical(
                    id,
                    self.attr(id, a, 4, "sense_agreement")?,
                    "sense_agreement",
                )?;
                if basis == id {
                    return Err(self.err(id, "the trimmed curve is its own basis curve"));
                }
                // A basis that is itself trimmed is refused (no chains: a cycle cannot hang).
                let basis = match self.instance(id, basis, "basis curve")?.records[0].name.as_str() {
                    "TRIMMED_CURVE" => {
                        return Ok(Err(format!(
                            "its curve #{id} is a trimmed curve of a trimmed curve, which limn does not read yet"
                        )))
                    }
                    _ => self.model_curve(id, basis)?,
                };
                Ok(basis.map(|(c, conic)| {
                    if sense {
                        (c, conic)
                    } else {
                        (
                            c.reversed(),
                            conic.map(|k| Conic {
                                reversed: !k.reversed,
                                ..k
                            }),
                        )
                    }
                }))
            }
            (false, "POLYLINE") => {
                let a = &inst.records[0].params;
                let pts = self.list(id, self.attr(id, a, 1, "points")?, "points")?;
                if pts.len() < 2 {
                    return Err(self.err(id, format!("a polyline of {} point(s)", pts.len())));
                }
                let points: Vec<Vec<Rational>> = pts
                    .iter()
                    .map(|p| self.point(id, self.reference(id, p, "point")?, 3))
                    .collect::<Result<_, _>>()?;
                let n = points.len();
                let mut knots = vec![Rational::from(0)];
                knots.extend((0..n).map(|k| Rational::from(k as u64)));
                knots.push(Rational::from((n - 1) as u64));
                Ok(Ok((
                    Curve::Nurbs {
                        degree: 1,
                        knots,
                        weights: vec![Rational::from(1); n],
                        points,
                    },
                    None,
                )))
            }
            _ => Ok(self.curve(from, id, 3)?.map(|c| (c, None))),
        }
    }

    /// A B-spline curve's or surface's (`kind` `CURVE` or `SURFACE`) attributes: those of
    /// `B_SPLINE_kind` (`counts[0]` of them) and those of its knots (`counts[1]`; `None` for a
    /// `QUASI_UNIFORM_kind`, whose knots are implied), from a simple instance (after its name)
    /// or from the parts of a complex one (with `RATIONAL_B_SPLINE_kind` beside them); `None`
    /// when the instance is neither.
    fn bspline_parts<'i>(
        &self,
        id: u64,
        inst: &'i Instance,
        kind: &str,
        [head, knot_count]: [usize; 2],
    ) -> Result<Option<BsplineParts<'i>>, ReadError> {
        let knotted = inst.record(&format!("B_SPLINE_{kind}_WITH_KNOTS"));
        let quasi = inst.record(&format!("QUASI_UNIFORM_{kind}"));
        let ((Some(b), _) | (None, Some(b))) = (knotted, quasi) else {
            return Ok(None);
        };
        if inst.complex {
            let Some(h) = inst.record(&format!("B_SPLINE_{kind}")) else {
                return Err(self.err(
                    id,
                    format!(
                        "a complex B-spline {} without its B_SPLINE_{kind} part",
                        kind.to_lowercase()
                    ),
                ));
            };
            return Ok(Some((&h.params[..], knotted.map(|k| &k.params[..]))));
        }
        let needed = 1 + head + if knotted.is_some() { knot_count } else { 0 };
        let p = &b.params[..];
        if p.len() < needed {
            return Err(self.err(
                id,
                format!("{} attributes where {needed} are needed", p.len()),
            ));
        }
        Ok(Some((
            &p[1..1 + head],
            knotted.map(|_| &p[1 + head..1 + head + knot_count]),
        )))
    }

    /// A curve of dimension `dim`, or why it is not read.
    pub(super) fn curve(
        &self,
        from: u64,
        id: u64,
        dim: usize,
    ) -> Result<Result<Curve, String>, ReadError> {
        let inst = self.instance(from, id, "curve")?;
        // (degree, points, form, closed, self_intersect); (mults, knots, spec).
        if let Some((head, knots)) = self.bspline_parts(id, inst, "CURVE", [5, 3])? {
            let degree = self.count(id, self.attr(id, head, 0, "degree")?, "degree", 1_000)?;
            let cps = self.list(
                id,
                self.attr(id, head, 1, "control_points_list")?,
                "control points",
            )?;
            let points: Vec<Vec<Rational>> = cps
                .iter()
                .map(|p| self.point(id, self.reference(id, p, "control point")?, dim))
                .collect::<Result<_, _>>()?;
            let knots = match knots {
                Some(knots) => self.knots(id, knots, (0, 1), points.len() + degree + 1)?,
                None => quasi_uniform(points.len(), degree),
            };
            let weights = match inst.record("RATIONAL_B_SPLINE_CURVE") {
                None => vec![Rational::from(1); points.len()],
                Some(r) => {
                    let w =
                        self.list(id, self.attr(id, &r.params, 0, "weights_data")?, "weights")?;
                    w.iter()
                        .map(|x| self.real(id, x, "weight"))
                        .collect::<Result<_, _>>()?
                }
            };
            if weights.len() != points.len() {
                return Err(self.err(
                    id,
                    format!(
                        "{} weights for {} control points",
                        weights.len(),
                        points.len()
                    ),
                ));
            }
            if let Some((k, w)) = weights.iter().enumerate().find(|(_, w)| **w <= 0) {
                return Err(self.err(
                    id,
                    format!(
                        "weight {}: {w} is not positive (weights must be positive)",
                        k + 1
                    ),
                ));
            }
            if degree == 0 || points.len() <= degree {
                return Err(self.err(
                    id,
                    format!("degree {degree} with {} control points", points.len()),
                ));
            }
            return Ok(Ok(Curve::Nurbs {
                degree,
                knots,
                points,
                weights,
            }));
        }
        match (inst.complex, inst.records[0].name.as_str()) {
            (false, "LINE") => {
                let a = &inst.records[0].params;
                let p = self.point(
                    id,
                    self.reference(id, self.attr(id, a, 1, "pnt")?, "pnt")?,
                    dim,
                )?;
                let v = self.reference(id, self.attr(id, a, 2, "dir")?, "dir")?;
                let va = self.simple(id, v, "vector", &["VECTOR"])?;
                let d = self.direction(
                    v,
                    self.reference(v, self.attr(v, va, 1, "orientation")?, "orientation")?,
                    dim,
                )?;
                let m = self.real(v, self.attr(v, va, 2, "magnitude")?, "magnitude")?;
                if m <= 0 {
                    return Err(self.err(v, format!("the vector's magnitude {m} is not positive")));
                }
                // The file's direction is meant to be of unit length: normalised as in
                // [`unit`] when it is not exactly.
                let d = if dim == 3 {
                    unit([d[0].clone(), d[1].clone(), d[2].clone()]).0.to_vec()
                } else {
                    let (u, _) = unit([d[0].clone(), d[1].clone(), Rational::from(0)]);
                    u[..2].to_vec()
                };
                Ok(Ok(Curve::Line {
                    p,
                    d: d.into_iter().map(|c| c * &m).collect(),
                }))
            }
            _ => Ok(Err(format!(
                "its curve #{id} is a {}, which limn does not read yet",
                inst.kind()
            ))),
        }
    }

    /// A knot vector from the multiplicities at `a[m]` and the knots at `a[k]`, expanded, of
    /// length `n`.
    fn knots(
        &self,
        id: u64,
        a: &[Param],
        (m, k): (usize, usize),
        n: usize,
    ) -> Result<Vec<Rational>, ReadError> {
        let mults = self.list(
            id,
            self.attr(id, a, m, "knot_multiplicities")?,
            "knot multiplicities",
        )?;
        let values = self.list(id, self.attr(id, a, k, "knots")?, "knots")?;
        if mults.len() != values.len() {
            return Err(self.err(
                id,
                format!(
                    "{} knot multiplicities for {} knots",
                    mults.len(),
                    values.len()
                ),
            ));
        }
        let mut out = Vec::with_capacity(n);
        for (m, k) in mults.iter().zip(values) {
            let m = self.count(id, m, "knot multiplicity", n)?;
            let k = self.real(id, k, "knot")?;
            if out.len() + m > n {
                break;
            }
            out.extend(std::iter::repeat_n(k, m));
        }
        if out.len() != n {
            let total: usize = mults
                .iter()
                .filter_map(|m| match m {
                    Param::Integer(i) => usize::try_from(*i).ok(),
                    _ => None,
                })
                .sum();
            return Err(self.err(id, format!("the knot multiplicities add up to {total}, but {n} knots are needed (control points + degree + 1)")));
        }
        if let Some(k) = (1..out.len()).find(|&k| out[k] < out[k - 1]) {
            return Err(self.err(
                id,
                format!("knot {}: {} is less than the knot before it", k + 1, out[k]),
            ));
        }
        Ok(out)
    }

    /// The surface of a face, or why it is not read.
    pub(super) fn surface(
        &self,
        from: u64,
        id: u64,
    ) -> Result<Result<StepSurface, String>, ReadError> {
        let inst = self.instance(from, id, "surface")?;
        // (u_degree, v_degree, points, form, u_closed, v_closed, self_intersect);
        // (u_mults, v_mults, u_knots, v_knots, spec).
        if let Some((head, knots)) = self.bspline_parts(id, inst, "SURFACE", [7, 5])? {
            let deg = [
                self.count(id, self.attr(id, head, 0, "u_degree")?, "u_degree", 1_000)?,
                self.count(id, self.attr(id, head, 1, "v_degree")?, "v_degree", 1_000)?,
            ];
            let rows = self.list(
                id,
                self.attr(id, head, 2, "control_points_list")?,
                "control points",
            )?;
            let nu = rows.len();
            let mut nv = 0;
            let mut points: Vec<Point3> = Vec::new();
            for (i, row) in rows.iter().enumerate() {
                let row = self.list(id, row, "a row of control points")?;
                if i == 0 {
                    nv = row.len();
                } else if row.len() != nv {
                    return Err(self.err(
                        id,
                        format!(
                            "row {} of the control points has {} points, row 1 has {nv}",
                            i + 1,
                            row.len()
                        ),
                    ));
                }
                if nu.saturating_mul(nv) > 10_000_000 {
                    return Err(self.err(id, "too many control points"));
                }
                for p in row {
                    let c = self.point(id, self.reference(id, p, "control point")?, 3)?;
                    points.push([c[0].clone(), c[1].clone(), c[2].clone()]);
                }
            }
            // (u_degree, v_degree, points, form, u_closed, v_closed, self_intersect)
            let closed = [4, 5].map(|k| matches!(head.get(k), Some(Param::Enum(e)) if e == "T"));
            let (ku, kv) = match knots {
                Some(knots) => (
                    self.knots(id, knots, (0, 2), nu + deg[0] + 1)?,
                    self.knots(id, knots, (1, 3), nv + deg[1] + 1)?,
                ),
                None => (quasi_uniform(nu, deg[0]), quasi_uniform(nv, deg[1])),
            };
            let weights: Vec<Rational> = match inst.record("RATIONAL_B_SPLINE_SURFACE") {
                None => vec![Rational::from(1); nu * nv],
                Some(r) => {
                    let w =
                        self.list(id, self.attr(id, &r.params, 0, "weights_data")?, "weights")?;
                    let mut out = Vec::with_capacity(nu * nv);
                    for row in w {
                        for x in self.list(id, row, "a row of weights")? {
                            out.push(self.real(id, x, "weight")?);
                        }
                    }
                    out
                }
            };
            if weights.len() != nu * nv {
                return Err(self.err(
                    id,
                    format!("{} weights for {} control points", weights.len(), nu * nv),
                ));
            }
            if let Some((k, w)) = weights.iter().enumerate().find(|(_, w)| **w <= 0) {
                return Err(self.err(
                    id,
                    format!(
                        "weight {}: {w} is not positive (weights must be positive)",
                        k + 1
                    ),
                ));
            }
            let s = NurbsSurface::new(deg, ku, kv, [nu, nv], points, weights).map_err(|e| {
                self.err(
                    id,
                    match e {
                        NurbsError::Decreasing { dir, index, value } => {
                            format!(
                                "{dir} knot {}: {value} is less than the knot before it",
                                index + 1
                            )
                        }
                        e => e.to_string(),
                    },
                )
            })?;
            return Ok(Ok(StepSurface::Nurbs(Box::new(s), closed)));
        }
        match (inst.complex, inst.records[0].name.as_str()) {
            (false, "PLANE") => {
                let a = &inst.records[0].params;
                let pl = self.reference(id, self.attr(id, a, 1, "position")?, "position")?;
                let (o, x, y, _) = self.placement(id, pl)?;
                Ok(Ok(StepSurface::Plane(Box::new(PlaneFrame { o, x, y }))))
            }
            (false, "CYLINDRICAL_SURFACE") => {
                let a = &inst.records[0].params;
                let pl = self.reference(id, self.attr(id, a, 1, "position")?, "position")?;
                let (c, x, y, _) = self.placement(id, pl)?;
                let r = self.real(id, self.attr(id, a, 2, "radius")?, "radius")?;
                if r <= 0 {
                    return Err(self.err(id, format!("the radius {r} is not positive")));
                }
                let z = cross(&x, &y);
                Ok(Ok(StepSurface::Cylinder(Box::new(Cylinder {
                    circle: Conic {
                        c,
                        x,
                        y,
                        radii: [r.clone(), r],
                        reversed: false,
                    },
                    z,
                }))))
            }
            _ if inst
                .records
                .iter()
                .any(|r| r.name.contains("SURFACE") || r.name == "PLANE") =>
            {
                Ok(Err(format!(
                    "its surface #{id} is a {}, which limn does not read yet",
                    inst.kind()
                )))
            }
            // Not a surface at all (every surface entity of Part 42 but PLANE is named for
            // one): the file is broken.
            _ => Err(self.err(
                from,
                format!("its surface #{id} is a {}, not a surface", inst.kind()),
            )),
        }
    }
}
