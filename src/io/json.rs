//! limn's native JSON model format (see README, "Model formats"):
//! `{"patches": [{"kind": "bezier", "degree": [m, n], "points": [[x, y, z], ...],
//! "weights": [...]}, {"kind": "nurbs", "degree": [p, q], "knots_u": [...], "knots_v": [...],
//! "points": [...], "weights": [...]}]}`. Numbers are JSON numbers or strings ("0.125",
//! "1/3"), read exactly; weights default to 1. [`write_model`] writes Bézier patches in this
//! format with every number an exact fraction string, so that reading gives them back.

use super::{Place, ReadError};
use crate::model::{Format, Model, ModelPatch, PatchSource};
use crate::number::{parse_exact, Rational};
use crate::surface::{
    NurbsError, NurbsSurface, PatchError, Point3, RationalPatch, MAX_PATCH_DEGREE,
};
use serde_json::Value;

struct Ctx<'a> {
    name: &'a str,
    patch: usize,
}

impl Ctx<'_> {
    fn err(&self, field: &str, msg: impl Into<String>) -> ReadError {
        ReadError::new(
            self.name,
            Place::Patch {
                index: self.patch,
                field: field.to_string(),
            },
            msg,
        )
    }

    /// A patch that cannot be built, placed at the field that is wrong.
    fn patch_err(&self, e: &PatchError) -> ReadError {
        let field = match e {
            PatchError::PointCount { .. } => "points".to_string(),
            PatchError::WeightCount { .. } => "weights".to_string(),
            PatchError::NonPositiveWeight { index, .. } => format!("weights[{index}]"),
            PatchError::DegreeTooHigh { .. } => "degree".to_string(),
        };
        self.err(&field, e.to_string())
    }

    /// A NURBS surface that cannot be built, placed at the field that is wrong.
    fn nurbs_err(&self, e: &NurbsError) -> ReadError {
        let field = match e {
            NurbsError::KnotCount { dir, .. }
            | NurbsError::TooFewPoints { dir, .. }
            | NurbsError::EmptyDomain { dir } => format!("knots_{dir}"),
            NurbsError::Decreasing { dir, index, .. } => format!("knots_{dir}[{index}]"),
            NurbsError::PointCount { .. } => "points".to_string(),
            NurbsError::NonPositiveWeight { index, .. } => format!("weights[{index}]"),
            NurbsError::DegreeTooHigh(_) => "degree".to_string(),
            NurbsError::Range { .. } => "range".to_string(),
        };
        self.err(&field, e.to_string())
    }

    fn number(&self, field: &str, v: &Value) -> Result<Rational, ReadError> {
        let text = match v {
            Value::Number(n) => n.to_string(),
            Value::String(s) => s.clone(),
            other => {
                return Err(self.err(field, format!("expected a number, found {}", kind(other))))
            }
        };
        parse_exact(&text).map_err(|e| self.err(field, e.to_string()))
    }

    fn array<'v>(&self, field: &str, v: Option<&'v Value>) -> Result<&'v Vec<Value>, ReadError> {
        match v {
            Some(Value::Array(a)) => Ok(a),
            Some(other) => {
                Err(self.err(field, format!("expected an array, found {}", kind(other))))
            }
            None => Err(self.err(field, "missing")),
        }
    }

    fn degree(&self, v: Option<&Value>) -> Result<[usize; 2], ReadError> {
        let a = self.array("degree", v)?;
        if a.len() != 2 {
            return Err(self.err(
                "degree",
                format!("expected [m, n], found {} entries", a.len()),
            ));
        }
        let mut d = [0; 2];
        for (k, x) in a.iter().enumerate() {
            d[k] = x
                .as_u64()
                .filter(|&n| n as usize <= MAX_PATCH_DEGREE)
                .ok_or_else(|| {
                    self.err(
                        "degree",
                        format!("expected a whole number 0..={MAX_PATCH_DEGREE}, found {x}"),
                    )
                })? as usize;
        }
        Ok(d)
    }

    fn numbers(&self, field: &str, v: Option<&Value>) -> Result<Vec<Rational>, ReadError> {
        let a = self.array(field, v)?;
        a.iter()
            .enumerate()
            .map(|(i, x)| self.number(&format!("{field}[{i}]"), x))
            .collect()
    }

    fn points(&self, v: Option<&Value>) -> Result<Vec<Point3>, ReadError> {
        let a = self.array("points", v)?;
        a.iter()
            .enumerate()
            .map(|(i, p)| {
                let field = format!("points[{i}]");
                let c = self.array(&field, Some(p))?;
                if c.len() != 3 {
                    return Err(self.err(
                        &field,
                        format!("expected [x, y, z], found {} numbers", c.len()),
                    ));
                }
                Ok([
                    self.number(&field, &c[0])?,
                    self.number(&field, &c[1])?,
                    self.number(&field, &c[2])?,
                ])
            })
            .collect()
    }
}

fn kind(v: &Value) -> &'static str {
    match v {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "an array",
        Value::Object(_) => "an object",
    }
}

pub(super) fn read(name: &str, text: &str) -> Result<Model, ReadError> {
    let root: Value = serde_json::from_str(text).map_err(|e| {
        // serde_json ends its message with the position, which the place already gives.
        let full = e.to_string();
        let suffix = format!(" at line {} column {}", e.line(), e.column());
        let what = full.strip_suffix(&suffix).unwrap_or(&full);
        // serde_json gives column 0 for an error found just after a line break (at the end
        // of the file, or a token cut by the break): that is the break ending the previous
        // line, the column after its last character.
        let (line, column) = match (e.line(), e.column()) {
            (l, 0) if l > 1 => {
                let before = text.split('\n').nth(l - 2).unwrap_or("");
                let before = before.strip_suffix('\r').unwrap_or(before);
                (l - 1, before.chars().count() + 1)
            }
            (l, c) => (l.max(1), c.max(1)),
        };
        ReadError::new(
            name,
            Place::LineColumn(line, column),
            format!("invalid JSON: {what}"),
        )
    })?;
    let top = |msg: &str| ReadError::new(name, Place::Named("top level".into()), msg.to_string());
    let obj = root
        .as_object()
        .ok_or_else(|| top("expected an object with a \"patches\" array"))?;
    let list = obj
        .get("patches")
        .and_then(Value::as_array)
        .ok_or_else(|| top("expected an object with a \"patches\" array"))?;
    let mut model = Model::from_patches(Format::Json, Vec::new());
    model.surfaces = list.len();
    // Bézier control points the NURBS surfaces so far split into.
    let mut bezier_points = 0;
    for (index, p) in list.iter().enumerate() {
        let cx = Ctx { name, patch: index };
        let o = p
            .as_object()
            .ok_or_else(|| cx.err("", format!("expected an object, found {}", kind(p))))?;
        let kind_name = o.get("kind").and_then(Value::as_str).unwrap_or("bezier");
        let degree = cx.degree(o.get("degree"))?;
        let points = cx.points(o.get("points"))?;
        let weights = match o.get("weights") {
            None | Some(Value::Null) => vec![Rational::from(1); points.len()],
            w => cx.numbers("weights", w)?,
        };
        if weights.len() != points.len() {
            return Err(cx.err(
                "weights",
                format!(
                    "{} control points but {} weights",
                    points.len(),
                    weights.len()
                ),
            ));
        }
        match kind_name {
            "bezier" => {
                let s =
                    RationalPatch::new(degree, points, weights).map_err(|e| cx.patch_err(&e))?;
                model.patches.push(ModelPatch {
                    surface: s,
                    source: PatchSource {
                        surface: index,
                        entity: None,
                        span: None,
                        parameters: None,
                    },
                });
            }
            "nurbs" => {
                let ku = cx.numbers("knots_u", o.get("knots_u"))?;
                let kv = cx.numbers("knots_v", o.get("knots_v"))?;
                let nu = ku
                    .len()
                    .checked_sub(degree[0] + 1)
                    .ok_or_else(|| cx.err("knots_u", "fewer knots than degree + 1"))?;
                let nv = kv
                    .len()
                    .checked_sub(degree[1] + 1)
                    .ok_or_else(|| cx.err("knots_v", "fewer knots than degree + 1"))?;
                if nu.checked_mul(nv) != Some(points.len()) {
                    return Err(cx.err(
                        "points",
                        format!(
                            "the knot vectors give {nu} x {nv} = {} control points, found {}",
                            nu as u128 * nv as u128,
                            points.len()
                        ),
                    ));
                }
                let s = NurbsSurface::new(degree, ku, kv, [nu, nv], points, weights)
                    .map_err(|e| cx.nurbs_err(&e))?;
                super::count_bezier_points(&mut bezier_points, &s).map_err(|m| cx.err("", m))?;
                let spans = s.spans();
                for (span, piece) in s.to_bezier() {
                    model.patches.push(ModelPatch {
                        surface: piece,
                        source: PatchSource::of_span(index, None, span, &spans),
                    });
                }
            }
            other => {
                return Err(cx.err(
                    "kind",
                    format!("unknown kind {other:?} (expected \"bezier\" or \"nurbs\")"),
                ))
            }
        }
    }
    Ok(model)
}

/// The native JSON model of these Bézier patches, every coordinate and weight written as an
/// exact fraction string (`"-3/4"`), so that [`read_model_bytes`](super::read_model_bytes)
/// gives back the same patches (tested).
///
/// # Examples
/// ```
/// use limn::io::{read_model_bytes, write_model};
/// use limn::model::Format;
/// let text = br#"{"patches":[{"kind":"bezier","degree":[1,1],
///     "points":[[0,0,0],[0,1,"1/3"],[1,0,0.1],[1,1,0]],"weights":[1,2,"3/7",1]}]}"#;
/// let read = |t: &[u8]| read_model_bytes("m.json", t, Some(Format::Json)).unwrap();
/// let patches: Vec<_> = read(text).patches.into_iter().map(|p| p.surface).collect();
/// let written = write_model(&patches);
/// assert!(written.contains(r#""1/3""#) && written.contains(r#""3/7""#));
/// let back: Vec<_> = read(written.as_bytes()).patches.into_iter().map(|p| p.surface).collect();
/// assert_eq!(back, patches);
/// ```
pub fn write_model(patches: &[RationalPatch]) -> String {
    let strings = |xs: &mut dyn Iterator<Item = &Rational>| -> Vec<String> {
        xs.map(|c| c.to_string()).collect()
    };
    let patches: Vec<Value> = patches
        .iter()
        .map(|p| {
            serde_json::json!({
                "kind": "bezier",
                "degree": p.degree(),
                "points": p
                    .points()
                    .iter()
                    .map(|q| strings(&mut q.iter()))
                    .collect::<Vec<_>>(),
                "weights": strings(&mut p.weights().iter()),
            })
        })
        .collect();
    serde_json::json!({ "patches": patches }).to_string()
}
