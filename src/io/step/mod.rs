//! STEP (ISO 10303-21 files of AP203, AP214 and AP242 geometry): the faces of B-reps and
//! surface models as trimmed faces with exact loops.
//!
//! Read: `ADVANCED_FACE` (and `FACE_SURFACE`) on `B_SPLINE_SURFACE_WITH_KNOTS` (rational or
//! not), on `PLANE` and on `CYLINDRICAL_SURFACE`; their bounds `FACE_OUTER_BOUND` /
//! `FACE_BOUND` of `EDGE_LOOP`s of `ORIENTED_EDGE`s of `EDGE_CURVE`s. On a B-spline surface
//! each edge is trimmed by its `PCURVE` (`SURFACE_CURVE`, `SEAM_CURVE`): a B-spline curve or a
//! line in the surface's parameter plane, on the edge's range: of the candidates (the
//! parameters of its vertices on its model-space curve, which Part 42 has the pcurve share; the
//! pcurve's own ends), the one whose ends land nearest the vertices on the surface, or, when
//! none lands near, the pcurve parameters nearest the vertices (an f64 search, snapped to the
//! pcurve's ends). The choice only interprets the file: the loop is the exact pcurve on it. On
//! a plane, the pcurve (ranged by the vertices' exact feet) or, without one, the model-space
//! curve mapped exactly into the plane's frame; on a cylinder, the model-space rulings and
//! circles mapped exactly onto its rational parameterisation (`proofs/trimmed-faces.md` 9).
//! The topology (shared edges, shells) is read from the B-rep. Every number is the exact
//! rational its decimal denotes; placements' axes are the file's directions (normalised to
//! within 2^-50 where they are not of unit length exactly). Faces on other surfaces (the
//! elementary cone, sphere and torus, swept and offset surfaces), or with edges limn cannot
//! place on the surface, are left out (counted in `Model::left_out`) or used untrimmed, with
//! the reason.
//!
//! Errors name the instance: `file.stp: #123 (EDGE_LOOP): ...`; syntax errors the line.

mod faces;
mod geometry;
mod part21;

use crate::io::{Place, ReadError};
use crate::model::Model;
use crate::number::Rational;
use part21::{Exchange, Instance, Param};

/// Reads a STEP file.
pub(super) fn read(name: &str, bytes: &[u8]) -> Result<Model, ReadError> {
    let ex =
        part21::parse(bytes).map_err(|e| ReadError::new(name, Place::Line(e.line), e.message))?;
    let mut r = Reader {
        name,
        ex,
        warnings: Vec::new(),
        bezier_points: 0,
        projected: Projected::default(),
    };
    r.read_model()
}

struct Reader<'a> {
    name: &'a str,
    ex: Exchange,
    warnings: Vec<crate::model::Warning>,
    /// Bézier control points the surfaces read so far split into.
    bezier_points: usize,
    /// Edges without a pcurve mapped onto their faces' planes.
    projected: Projected,
}

/// Edges without a pcurve whose model-space curves were mapped onto their faces' planes.
#[derive(Default)]
struct Projected {
    /// How many (an edge counts once per face).
    edges: usize,
    /// The largest bound on an edge's distance from its plane ([`geometry::Curve::off_plane`]).
    largest_off_plane: f64,
}

impl Reader<'_> {
    /// The place of instance `id`.
    fn place(&self, id: u64) -> Place {
        Place::Instance {
            id,
            kind: self
                .ex
                .instances
                .get(&id)
                .map_or_else(|| "?".to_string(), Instance::kind),
        }
    }

    /// An error at instance `id`.
    fn err(&self, id: u64, message: impl Into<String>) -> ReadError {
        ReadError::new(self.name, self.place(id), message)
    }

    /// Instance `id`, referred to by `from` as `what`.
    fn instance(&self, from: u64, id: u64, what: &str) -> Result<&Instance, ReadError> {
        self.ex
            .instances
            .get(&id)
            .ok_or_else(|| self.err(from, format!("its {what} #{id} is not in the file")))
    }

    /// The attributes of instance `id`, a simple instance of one of the entities `names`.
    fn simple(
        &self,
        from: u64,
        id: u64,
        what: &str,
        names: &[&str],
    ) -> Result<&[Param], ReadError> {
        let inst = self.instance(from, id, what)?;
        match (
            inst.complex,
            names.iter().find(|n| **n == inst.records[0].name),
        ) {
            (false, Some(_)) => Ok(&inst.records[0].params),
            _ => Err(self.err(
                from,
                format!(
                    "its {what} #{id} is a {}, not a {}",
                    inst.kind(),
                    names.join(" or ")
                ),
            )),
        }
    }

    /// Attribute `k` (0-based) of instance `id`.
    fn attr<'p>(
        &self,
        id: u64,
        a: &'p [Param],
        k: usize,
        what: &str,
    ) -> Result<&'p Param, ReadError> {
        a.get(k).ok_or_else(|| {
            self.err(
                id,
                format!(
                    "attribute {} ({what}) is missing: the instance has {}",
                    k + 1,
                    a.len()
                ),
            )
        })
    }

    /// A real (an integer is a real too; a typed measure is its value).
    fn real(&self, id: u64, p: &Param, what: &str) -> Result<Rational, ReadError> {
        match p {
            Param::Real(x) => Ok(x.clone()),
            Param::Integer(i) => Ok(Rational::from(*i)),
            Param::Typed(_, v) if v.len() == 1 => self.real(id, &v[0], what),
            other => Err(self.err(
                id,
                format!("the {what} is {}, not a number", describe(other)),
            )),
        }
    }

    /// A count: an integer from 0 to `max`.
    fn count(&self, id: u64, p: &Param, what: &str, max: usize) -> Result<usize, ReadError> {
        match p {
            Param::Integer(i) if *i >= 0 && (*i as u64) <= max as u64 => Ok(*i as usize),
            Param::Integer(i) => {
                Err(self.err(id, format!("the {what} {i} is not between 0 and {max}")))
            }
            other => Err(self.err(
                id,
                format!("the {what} is {}, not an integer", describe(other)),
            )),
        }
    }

    /// A reference `#n`.
    fn reference(&self, id: u64, p: &Param, what: &str) -> Result<u64, ReadError> {
        match p {
            Param::Ref(r) => Ok(*r),
            other => Err(self.err(
                id,
                format!("the {what} is {}, not a reference #n", describe(other)),
            )),
        }
    }

    /// A list.
    fn list<'p>(&self, id: u64, p: &'p Param, what: &str) -> Result<&'p [Param], ReadError> {
        match p {
            Param::List(l) => Ok(l),
            other => Err(self.err(id, format!("the {what} is {}, not a list", describe(other)))),
        }
    }

    /// A boolean `.T.` / `.F.`.
    fn logical(&self, id: u64, p: &Param, what: &str) -> Result<bool, ReadError> {
        match p {
            Param::Enum(e) if e == "T" => Ok(true),
            Param::Enum(e) if e == "F" => Ok(false),
            other => Err(self.err(
                id,
                format!("the {what} is {}, not .T. or .F.", describe(other)),
            )),
        }
    }
}

/// A parameter as a message names it.
fn describe(p: &Param) -> String {
    match p {
        Param::Integer(i) => format!("the integer {i}"),
        Param::Real(x) => format!("the number {}", x.to_f64()),
        Param::Str(s) => format!("the string '{}'", crate::io::shortened(s)),
        Param::Enum(e) => format!(".{}.", crate::io::shortened(e)),
        Param::Ref(r) => format!("the reference #{r}"),
        Param::Unset => "unset ($)".into(),
        Param::Derived => "derived (*)".into(),
        Param::List(l) => format!("a list of {}", l.len()),
        Param::Typed(n, _) => format!("a {}", crate::io::shortened(n)),
        Param::Binary(_) => "a binary".into(),
    }
}
