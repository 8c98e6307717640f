//! Silhouette certificates: per patch, the curve certificate of the polynomial solved, and
//! the claim that this polynomial is the patch's silhouette function for the view (up to a
//! positive factor and the linear factors of collapsed sides); checked independently of the
//! fast path (`proofs/certificate-check.md`).

use crate::analysis::contour::curves::Silhouette;

use crate::analysis::view::View;
use crate::model::Model;
use crate::number::to_big_rational;
use crate::number::Rational;
use crate::solver::certificate::CurveCertificate;
use crate::solver::checker::{check_curve, parse_rational, CheckFailure};
use crate::surface::Edge;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// The `format` field of a silhouette certificate.
pub const FORMAT: &str = "limn-silhouette-certificate";
/// The schema version written.
pub const VERSION: u32 = 1;

/// The view a certificate is for.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct ViewClaim {
    /// "direction" or "eye".
    pub kind: String,
    /// Its exact coordinates.
    pub vector: [String; 3],
}

/// A linear factor divided out of the silhouette function: a side of the square or a line
/// inside it.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct DividedSide {
    /// "u0" (factor u), "u1" (1 − u), "v0" (v) or "v1" (1 − v); or a line inside the square,
    /// "u=c" (factor u − c) or "v=c", with c an exact rational in (0, 1).
    pub side: String,
    /// How many times.
    pub power: usize,
}

/// One patch's part.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct PatchCertificate {
    /// The patch index in the model.
    pub patch: usize,
    /// Collapsed-side factors divided out of the silhouette function before solving.
    pub divided: Vec<DividedSide>,
    /// What was proven about the polynomial solved.
    pub curve: CurveCertificate,
}

/// What a silhouette run proved, per patch.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct SilhouetteCertificate {
    /// Always [`FORMAT`].
    pub format: String,
    /// The schema version.
    pub version: u32,
    /// The model's name as given to the run (informative).
    pub model: String,
    /// The number of patches of the model.
    pub patch_count: usize,
    /// The view.
    pub view: ViewClaim,
    /// The origin of the frame the polynomials are stated in, exact (`"p/q"`): they are the
    /// silhouette functions of the model translated by minus this point, for the view
    /// translated with it (an eye moves, a direction does not; `proofs/model-frame.md`).
    /// Absent means the origin, as in certificates written before frames.
    #[serde(default = "zero_origin", skip_serializing_if = "is_zero_origin")]
    pub origin: [String; 3],
    /// Every patch's square was decided.
    pub certified: bool,
    /// One entry per patch, in order.
    pub patches: Vec<PatchCertificate>,
}

fn side_name(e: Edge) -> &'static str {
    match e {
        Edge::U0 => "u0",
        Edge::U1 => "u1",
        Edge::V0 => "v0",
        Edge::V1 => "v1",
    }
}

impl SilhouetteCertificate {
    /// The certificate of a silhouette run.
    ///
    /// # Examples
    /// ```
    /// use limn::analysis::contour::silhouette::silhouette;
    /// use limn::analysis::view::View;
    /// use limn::analysis::contour::certificate::{check_silhouette, SilhouetteCertificate};
    /// use limn::model::{Format, Model, WeldTolerance};
    /// use limn::number::Rational;
    /// use limn::solver::CurveOptions;
    /// use limn::testing::shapes;
    /// let model = Model::from_patches(Format::Json, shapes::sphere(&Rational::from(1)));
    /// let view = View::Direction([1, 2, 3].map(Rational::from));
    /// let s = silhouette(&model, &view, &limn::ContourOptions::new(CurveOptions::default(), WeldTolerance::Exact, None)).unwrap();
    /// let cert = SilhouetteCertificate::new("sphere", &view, &s);
    /// let verdict = check_silhouette(&model, &cert).unwrap();
    /// assert!(verdict.certified);
    /// ```
    pub fn new(model: &str, view: &View, s: &Silhouette) -> SilhouetteCertificate {
        let (kind, v) = match view {
            View::Direction(d) => ("direction", d),
            View::Eye(e) => ("eye", e),
        };
        let patches: Vec<PatchCertificate> = s
            .solved
            .par_iter()
            .enumerate()
            .map(|(i, p)| PatchCertificate {
                patch: i,
                divided: p
                    .divided
                    .iter()
                    .map(|&(e, k)| DividedSide {
                        side: side_name(e).into(),
                        power: k,
                    })
                    .chain(p.lines.iter().map(|z| DividedSide {
                        side: z.to_string(),
                        power: z.power,
                    }))
                    .collect(),
                curve: CurveCertificate::new(&p.g, &p.topology),
            })
            .collect();
        SilhouetteCertificate {
            format: FORMAT.into(),
            version: VERSION,
            model: model.into(),
            patch_count: s.solved.len(),
            view: ViewClaim {
                kind: kind.into(),
                vector: v.clone().map(|x| x.to_string()),
            },
            origin: s.frame.origin().clone().map(|x| x.to_string()),
            certified: patches.iter().all(|p| p.curve.certified),
            patches,
        }
    }
}

fn zero_origin() -> [String; 3] {
    ["0".into(), "0".into(), "0".into()]
}

fn is_zero_origin(o: &[String; 3]) -> bool {
    o.iter().all(|x| x == "0")
}

/// The verdict on a valid certificate.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct SilhouetteCheck {
    /// Patches checked.
    pub patches: usize,
    /// Cells verified (all patches).
    pub cells: usize,
    /// Crossings verified as roots.
    pub crossings: usize,
    /// Arcs recomputed and matched.
    pub arcs: usize,
    /// Branches verified.
    pub branches: usize,
    /// Unresolved cells (nothing is claimed inside them).
    pub unresolved: usize,
    /// The whole model was decided.
    pub certified: bool,
}

type Q = BigRational;
type Z = BigInt;

/// de Casteljau evaluation of a univariate Bernstein polynomial with integer coefficients at
/// an integer t (the checker's own; the identity below holds everywhere, so integer points
/// outside [0, 1] serve and keep everything integer).
fn bern1(c: &[Z], t: &Z) -> Z {
    let s = Z::one() - t;
    let mut w = c.to_vec();
    for len in (2..=w.len()).rev() {
        for i in 0..len - 1 {
            w[i] = &s * &w[i] + t * &w[i + 1];
        }
    }
    w.swap_remove(0)
}

/// A bivariate Bernstein polynomial with integer coefficients, row-major, degrees (m, n).
#[derive(Clone)]
struct Poly2 {
    m: usize,
    n: usize,
    c: Vec<Z>,
}

impl Poly2 {
    fn eval(&self, u: &Z, v: &Z) -> Z {
        let rows: Vec<Z> = self.c.chunks(self.n + 1).map(|r| bern1(r, v)).collect();
        bern1(&rows, u)
    }
    fn du(&self) -> Poly2 {
        if self.m == 0 {
            return Poly2 {
                m: 0,
                n: self.n,
                c: vec![Z::zero(); self.n + 1],
            };
        }
        let k = Z::from(self.m);
        let w = self.n + 1;
        let c = (0..self.m)
            .flat_map(|i| (0..w).map(move |j| (i, j)))
            .map(|(i, j)| &k * (&self.c[(i + 1) * w + j] - &self.c[i * w + j]))
            .collect();
        Poly2 {
            m: self.m - 1,
            n: self.n,
            c,
        }
    }
    fn dv(&self) -> Poly2 {
        if self.n == 0 {
            return Poly2 {
                m: self.m,
                n: 0,
                c: vec![Z::zero(); self.m + 1],
            };
        }
        let k = Z::from(self.n);
        let c = self
            .c
            .chunks(self.n + 1)
            .flat_map(|r| {
                r.windows(2)
                    .map(|p| &k * (&p[1] - &p[0]))
                    .collect::<Vec<_>>()
            })
            .collect();
        Poly2 {
            m: self.m,
            n: self.n - 1,
            c,
        }
    }
}

fn cross(a: &[Z; 3], b: &[Z; 3]) -> [Z; 3] {
    [
        &a[1] * &b[2] - &a[2] * &b[1],
        &a[2] * &b[0] - &a[0] * &b[2],
        &a[0] * &b[1] - &a[1] * &b[0],
    ]
}

/// Positive integer multiples of rationals sharing one factor (the lcm of the denominators).
fn to_integers(q: &[Q]) -> Vec<Z> {
    use num_integer::Integer;
    let l = q.iter().fold(Z::one(), |l, x| l.lcm(x.denom()));
    q.iter()
        .map(|x| (x * Q::from_integer(l.clone())).to_integer())
        .collect()
}

/// Checks that the certificate's polynomial is the patch's silhouette function: with
/// `T_u = W P_u − W_u P`, `T_v` likewise (so `T_u × T_v = W⁴ S_u × S_v`), the polynomial
/// `Q = (T_u × T_v) · V` (or `· (E W − P)` for an eye) equals `λ · W · F · g` for a constant
/// `λ > 0`, F the divided side factors. Both sides have bidegree at most D, so agreement on a
/// (D_u + 1) × (D_v + 1) grid proves the identity. Homogeneous coordinates, view and g are
/// first scaled to integers by positive factors (absorbed in λ).
fn check_function(
    model: &Model,
    index: usize,
    origin: &[Q],
    view: &[Q; 3],
    eye: bool,
    pc: &PatchCertificate,
) -> Result<(), CheckFailure> {
    let item = format!("patch {index}");
    let bad = |reason: &str| {
        Err(CheckFailure {
            item: item.clone(),
            reason: reason.into(),
        })
    };
    let patch = &model.patches[index].surface;
    let [m, n] = patch.degree();
    let big = |q: &Rational| to_big_rational(q);
    let w: Vec<Q> = patch.weights().iter().map(big).collect();
    if w.iter().any(|x| !x.is_positive()) {
        return bad("a weight is not positive");
    }
    // [wx, wy, wz, w] as one list, scaled together (S = P / W is unchanged).
    let mut hom: Vec<Q> = Vec::with_capacity(4 * w.len());
    for k in 0..3 {
        // The point in the certificate's frame: translated by minus its origin.
        hom.extend(
            patch
                .points()
                .iter()
                .zip(&w)
                .map(|(p, wi)| (big(&p[k]) - &origin[k]) * wi),
        );
    }
    hom.extend(w.iter().cloned());
    let hom = to_integers(&hom);
    let len = w.len();
    let part = |k: usize| Poly2 {
        m,
        n,
        c: hom[k * len..(k + 1) * len].to_vec(),
    };
    let p = [part(0), part(1), part(2)];
    let wp = part(3);
    let (pu, pv) = (p.clone().map(|c| c.du()), p.clone().map(|c| c.dv()));
    let (wu, wv) = (wp.du(), wp.dv());
    // The view times the lcm d of its denominators; for an eye, E W − P is then d E W − d P.
    let d_view = {
        use num_integer::Integer;
        view.iter().fold(Z::one(), |l, x| l.lcm(x.denom()))
    };
    let view = to_integers(view);
    let [gm, gn] = pc.curve.degrees;
    if pc.curve.g.len() != (gm + 1) * (gn + 1) {
        return bad("g's coefficient count does not match its degrees");
    }
    let gq: Vec<Q> = pc
        .curve
        .g
        .iter()
        .enumerate()
        .map(|(i, s)| parse_rational(s, &format!("{item}: g coefficient {i}")))
        .collect::<Result<_, _>>()?;
    let g = Poly2 {
        m: gm,
        n: gn,
        c: to_integers(&gq),
    };
    let mut powers = [0usize; 4];
    // Lines inside the square: (axis, c as p/q scaled to the integer factor q t − p, power).
    let mut lines: Vec<(usize, Z, Z, usize)> = Vec::new();
    let mut line_powers = [0usize; 2];
    for d in &pc.divided {
        let k = match d.side.as_str() {
            "u0" => 0,
            "u1" => 1,
            "v0" => 2,
            "v1" => 3,
            other => {
                let (axis, c) = match other.split_once('=') {
                    Some(("u", c)) => (0, c),
                    Some(("v", c)) => (1, c),
                    _ => return bad(&format!("unknown side {:?}", d.side)),
                };
                let c = parse_rational(c, &format!("{item}: divided line {other:?}"))?;
                if !c.is_positive() || c >= Q::one() {
                    return bad(&format!("divided line {other:?} is not inside the square"));
                }
                line_powers[axis] = line_powers[axis].saturating_add(d.power);
                lines.push((axis, c.numer().clone(), c.denom().clone(), d.power));
                continue;
            }
        };
        powers[k] = powers[k].saturating_add(d.power);
    }
    let eye_deg = usize::from(eye);
    let du = (4 * m + eye_deg * m).max(
        (m + powers[0] + gm)
            .saturating_add(powers[1])
            .saturating_add(line_powers[0]),
    );
    let dv = (4 * n + eye_deg * n).max(
        (n + powers[2] + gn)
            .saturating_add(powers[3])
            .saturating_add(line_powers[1]),
    );
    if du > 4096 || dv > 4096 {
        return bad("degrees too large");
    }
    let pow = |x: &Z, k: usize| -> Z { (0..k).fold(Z::one(), |a, _| a * x) };
    let mut reference: Option<(Z, Z)> = None;
    let mut pairs = Vec::with_capacity((du + 1) * (dv + 1));
    for i in 0..=du {
        for j in 0..=dv {
            let (u, v) = (Z::from(i), Z::from(j));
            let w0 = wp.eval(&u, &v);
            let p0 = [0, 1, 2].map(|k| p[k].eval(&u, &v));
            let (wu0, wv0) = (wu.eval(&u, &v), wv.eval(&u, &v));
            let tu = [0, 1, 2].map(|k| &w0 * pu[k].eval(&u, &v) - &wu0 * &p0[k]);
            let tv = [0, 1, 2].map(|k| &w0 * pv[k].eval(&u, &v) - &wv0 * &p0[k]);
            let nrm = cross(&tu, &tv);
            let q: Z = (0..3)
                .map(|k| {
                    let f = if eye {
                        &view[k] * &w0 - &d_view * &p0[k]
                    } else {
                        view[k].clone()
                    };
                    &nrm[k] * f
                })
                .sum();
            let one = Z::one();
            let mut factor = pow(&u, powers[0])
                * pow(&(&one - &u), powers[1])
                * pow(&v, powers[2])
                * pow(&(&one - &v), powers[3]);
            // (t − p/q) scaled by q > 0 (absorbed in λ).
            for (axis, p, q, k) in &lines {
                let t = if *axis == 0 { &u } else { &v };
                factor *= pow(&(q * t - p), *k);
            }
            let r = w0 * factor * g.eval(&u, &v);
            if reference.is_none() && !r.is_zero() {
                reference = Some((q.clone(), r.clone()));
            }
            pairs.push((q, r));
        }
    }
    match reference {
        None => {
            if pairs.iter().any(|(q, _)| !q.is_zero()) {
                return bad("g is zero but the silhouette function is not");
            }
        }
        Some((q0, r0)) => {
            // λ = q0 / r0 must be positive, and q = λ r everywhere on the grid.
            if q0.is_zero() || q0.is_positive() != r0.is_positive() {
                return bad("g is not a positive multiple of the silhouette function");
            }
            if pairs.iter().any(|(q, r)| q * &r0 != &q0 * r) {
                return bad("g is not the silhouette function of this patch for this view");
            }
        }
    }
    Ok(())
}

/// Re-verifies a silhouette certificate against the model, in exact arithmetic and without
/// the fast path: the polynomial of each patch is checked to be its silhouette function for
/// the view, then every claim of its curve certificate is recomputed
/// ([`check_curve`]). Returns the first failing item.
pub fn check_silhouette(
    model: &Model,
    cert: &SilhouetteCertificate,
) -> Result<SilhouetteCheck, CheckFailure> {
    let top = |reason: String| CheckFailure {
        item: "certificate".into(),
        reason,
    };
    if cert.format != FORMAT || cert.version != VERSION {
        return Err(top(format!(
            "not a {FORMAT} of version {VERSION} (format {:?}, version {})",
            cert.format, cert.version
        )));
    }
    if cert.patch_count != model.patches.len() || cert.patches.len() != model.patches.len() {
        return Err(top(format!(
            "it is for {} patches, the model has {}",
            cert.patches.len(),
            model.patches.len()
        )));
    }
    let eye = match cert.view.kind.as_str() {
        "direction" => false,
        "eye" => true,
        other => return Err(top(format!("unknown view kind {other:?}"))),
    };
    let view = [0, 1, 2]
        .map(|k| parse_rational(&cert.view.vector[k], "view"))
        .into_iter()
        .collect::<Result<Vec<Q>, _>>()?;
    let mut view: [Q; 3] = [view[0].clone(), view[1].clone(), view[2].clone()];
    if !eye && view.iter().all(Zero::is_zero) {
        return Err(top("the view direction is zero".into()));
    }
    let origin = [0, 1, 2]
        .map(|k| parse_rational(&cert.origin[k], "origin"))
        .into_iter()
        .collect::<Result<Vec<Q>, _>>()?;
    if eye {
        for k in 0..3 {
            view[k] = &view[k] - &origin[k];
        }
    }
    let results: Vec<Result<_, CheckFailure>> = cert
        .patches
        .par_iter()
        .enumerate()
        .map(|(i, pc)| {
            if pc.patch != i {
                return Err(top(format!("entry {i} is for patch {}", pc.patch)));
            }
            check_function(model, i, &origin, &view, eye, pc)?;
            check_curve(&pc.curve).map_err(|e| CheckFailure {
                item: format!("patch {i}: {}", e.item),
                reason: e.reason,
            })
        })
        .collect();
    let mut out = SilhouetteCheck::default();
    for r in results {
        let s = r?;
        out.patches += 1;
        out.cells += s.cells;
        out.crossings += s.crossings;
        out.arcs += s.arcs;
        out.branches += s.branches;
        out.unresolved += s.unresolved;
    }
    out.certified = out.unresolved == 0;
    if cert.certified && !out.certified {
        return Err(top(
            "it claims the model is decided, but lists unresolved cells".into(),
        ));
    }
    Ok(out)
}
