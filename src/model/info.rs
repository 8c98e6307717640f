//! A summary of a model: what `limn info` prints.

use super::{MeshTopology, Model, PatchTopology, Warning, WeldTolerance};
use crate::number::Number;
use std::collections::BTreeMap;

/// The axis-aligned bounding box, outward rounded to `f64`.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct BoundingBox {
    /// Lower corner (rounded down).
    pub min: [f64; 3],
    /// Upper corner (rounded up).
    pub max: [f64; 3],
}

/// The summary of a model (the JSON of `limn info --format json`; its field names are a
/// public contract, see README).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ModelInfo {
    /// The file as given.
    pub file: String,
    /// The format it was read as.
    pub format: super::Format,
    /// Surfaces in the file (a NURBS surface counts once).
    pub surfaces: usize,
    /// Bézier patches after splitting.
    pub patches: usize,
    /// Patch count by degree, keyed "m x n".
    pub degrees: BTreeMap<String, usize>,
    /// Patches with unequal weights.
    pub rational_patches: usize,
    /// The bounding box of the control points and mesh vertices.
    pub bounding_box: Option<BoundingBox>,
    /// Patch topology (absent for a mesh-only model).
    pub topology: Option<PatchTopology>,
    /// Topology of each mesh.
    pub meshes: Vec<MeshTopology>,
    /// What was read but not honoured.
    pub warnings: Vec<Warning>,
}

impl ModelInfo {
    /// Summarises a model, matching patch boundaries with `weld`.
    pub fn of(file: &str, model: &Model, weld: WeldTolerance) -> ModelInfo {
        let mut degrees = BTreeMap::new();
        for p in &model.patches {
            let [m, n] = p.surface.degree();
            *degrees.entry(format!("{m}x{n}")).or_insert(0) += 1;
        }
        let bounding_box = model.bounding_box().map(|[lo, hi]| BoundingBox {
            min: [0, 1, 2].map(|k| lo[k].lower_f64()),
            max: [0, 1, 2].map(|k| hi[k].upper_f64()),
        });
        ModelInfo {
            file: file.to_string(),
            format: model.format,
            surfaces: model.surfaces,
            patches: model.patches.len(),
            degrees,
            rational_patches: model
                .patches
                .iter()
                .filter(|p| !p.surface.is_polynomial())
                .count(),
            bounding_box,
            topology: (!model.patches.is_empty()).then(|| PatchTopology::of_model(model, weld)),
            meshes: model.meshes.iter().map(MeshTopology::of_mesh).collect(),
            warnings: model.warnings.clone(),
        }
    }
}

/// The welding tolerance to use when none is asked for: exact for exact formats; for IGES the
/// file's minimum resolution, or 10⁻⁶ of the bounding-box diagonal if it states none.
pub fn default_weld(model: &Model) -> WeldTolerance {
    match model.format {
        super::Format::Iges => {
            let r = model
                .suggested_weld
                .as_ref()
                .map(|r| r.to_f64())
                .filter(|r| r.is_finite() && *r > 0.0)
                .unwrap_or(1e-6 * model.diagonal());
            WeldTolerance::Absolute(r)
        }
        _ => WeldTolerance::Exact,
    }
}
