//! Layer 3: models (patches and meshes read from one file) and their topology.

mod brep;
mod face;
mod info;
mod side_contact;
mod topology;

pub use brep::{Brep, BrepEdge, BrepSummary};
pub use face::{
    in_domain, orientation, Closing, Face, InDomain, LoopError, Orientation, TrimLoop, TrimPiece,
};
pub use info::{default_weld, BoundingBox, FacesSummary, ModelInfo};
pub use side_contact::{
    contact_assumption, contact_tolerance, model_contacts, side_contacts, ContactSummary,
    SideContact,
};

pub use topology::{MeshTopology, PatchAdjacency, PatchTopology, SideUse, WeldTolerance};

use crate::number::Rational;
use crate::surface::{Mesh, Point3, RationalPatch};

/// Where a patch came from in its file.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct PatchSource {
    /// The index of the surface in the file (patch number, or position among the surfaces).
    pub surface: usize,
    /// For IGES, the directory-entry sequence number of the surface entity.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub entity: Option<usize>,
    /// For a NURBS surface split into Bézier pieces, the knot span (u, v) of this piece.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub span: Option<(usize, usize)>,
    /// For a NURBS piece, its box `[[u0, u1], [v0, v1]]` in the surface's parameter plane (the
    /// plane of the trimming loops); the patch's `[0,1]²` maps onto it affinely.
    #[serde(skip)]
    pub parameters: Option<[[Rational; 2]; 2]>,
}

impl PatchSource {
    /// The source of piece `span` of a NURBS surface whose spans are `spans`
    /// ([`crate::surface::NurbsSurface::spans`]).
    pub fn of_span(
        surface: usize,
        entity: Option<usize>,
        span: (usize, usize),
        spans: &[Vec<[Rational; 2]>; 2],
    ) -> PatchSource {
        PatchSource {
            surface,
            entity,
            span: Some(span),
            parameters: Some([spans[0][span.0].clone(), spans[1][span.1].clone()]),
        }
    }
}

/// One Bézier patch of a model.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelPatch {
    /// The patch.
    pub surface: RationalPatch,
    /// Where it came from.
    pub source: PatchSource,
}

/// A message about the input that does not stop reading (something not yet honoured, such
/// as a trim, or an entity type that is skipped).
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct Warning {
    /// Where: "entity 13 (DE 25)", "patch 4", "line 12".
    pub place: String,
    /// What.
    pub message: String,
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.place, self.message)
    }
}

/// The file formats limn reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Format {
    /// limn's native JSON (see README).
    Json,
    /// Newell's `.bpt`: patch count, then per patch `m n` and the points.
    Bpt,
    /// The 1991 teaset archive: patches as 16 vertex indices, then the vertices.
    Teaset,
    /// IGES 5.3, entity 128 surfaces.
    Iges,
    /// STEP (ISO 10303-21): faces on B-spline surfaces, planes and cylinders.
    Step,
    /// Wavefront OBJ meshes.
    Obj,
}

/// A model: Bézier patches (from any surface format) and meshes (from OBJ).
#[derive(Clone, Debug, PartialEq)]
pub struct Model {
    /// The format it was read from.
    pub format: Format,
    /// The Bézier patches, NURBS surfaces already split.
    pub patches: Vec<ModelPatch>,
    /// The meshes.
    pub meshes: Vec<Mesh>,
    /// Things in the file that were read but not (yet) honoured.
    pub warnings: Vec<Warning>,
    /// The number of surfaces in the file (before splitting NURBS into Bézier pieces).
    pub surfaces: usize,
    /// A welding tolerance the file suggests (IGES: the global minimum resolution).
    pub suggested_weld: Option<Rational>,
    /// The trimmed faces the file states (IGES 144, 510). A surface no face names is used
    /// whole; a surface with faces is the union of their regions.
    pub faces: Vec<Face>,
    /// The B-rep topology the file states, if any (IGES 186/514/510/508/504/502).
    pub brep: Option<Brep>,
    /// Surfaces and faces of the file that are not in the model (of a type, or with edges,
    /// limn does not read yet; each named in `warnings`): analyses that depend on the whole
    /// part (hidden lines, visible regions) state it among their assumptions.
    pub left_out: usize,
    /// Placements of parts the file states (a STEP assembly's transformations) that limn does
    /// not apply: each part is in its own coordinates. Stated like `left_out`.
    pub placements_ignored: usize,
}

impl Model {
    /// A model of Bézier patches, one surface each.
    pub fn from_patches(format: Format, patches: Vec<RationalPatch>) -> Model {
        let surfaces = patches.len();
        Model {
            format,
            patches: patches
                .into_iter()
                .enumerate()
                .map(|(i, surface)| ModelPatch {
                    surface,
                    source: PatchSource {
                        surface: i,
                        entity: None,
                        span: None,
                        parameters: None,
                    },
                })
                .collect(),
            meshes: Vec::new(),
            warnings: Vec::new(),
            surfaces,
            suggested_weld: None,
            faces: Vec::new(),
            brep: None,
            left_out: 0,
            placements_ignored: 0,
        }
    }

    /// The assumptions of an analysis of the whole part when the reader left some of it out or
    /// did not place its parts.
    pub fn reader_assumptions(&self) -> Vec<String> {
        let mut out = Vec::new();
        if self.left_out > 0 {
            out.push(format!(
                "the part is what limn read of the file: {} of its surfaces or faces are left out (named in the reader's warnings, `limn info`), and what they would hide or show is not drawn",
                self.left_out
            ));
        }
        if self.placements_ignored > 0 {
            out.push(format!(
                "the file is an assembly whose {} placements of parts limn does not apply: each part is in its own coordinates, as read",
                self.placements_ignored
            ));
        }
        out
    }

    /// The axis-aligned bounding box of all control points and mesh vertices (it contains
    /// the model), or `None` for an empty model.
    pub fn bounding_box(&self) -> Option<[Point3; 2]> {
        let mut b: Option<[Point3; 2]> = None;
        let mut grow = |p: &Point3| match &mut b {
            None => b = Some([p.clone(), p.clone()]),
            Some([lo, hi]) => {
                for k in 0..3 {
                    if p[k] < lo[k] {
                        lo[k] = p[k].clone();
                    }
                    if p[k] > hi[k] {
                        hi[k] = p[k].clone();
                    }
                }
            }
        };
        for p in &self.patches {
            for q in p.surface.points() {
                grow(q);
            }
        }
        for m in &self.meshes {
            for q in &m.vertices {
                grow(q);
            }
        }
        b
    }

    /// The proven bound between the trimming curves limn inverted from model-space edges
    /// and those edges (max norm; 0 when no curve was inverted).
    pub fn inversion_distance(&self) -> f64 {
        self.faces
            .iter()
            .flat_map(Face::loops)
            .map(|l| l.inversion_distance)
            .fold(0.0, f64::max)
    }

    /// The length of the bounding box diagonal, in `f64` (for relative tolerances).
    pub fn diagonal(&self) -> f64 {
        self.bounding_box().map_or(0.0, |[lo, hi]| {
            (0..3)
                .map(|k| {
                    let d = Rational::from(&hi[k] - &lo[k]).to_f64();
                    d * d
                })
                .sum::<f64>()
                .sqrt()
        })
    }
}
