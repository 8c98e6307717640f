//! Layer 5: analyses, one module per capability, each built on the solver.

pub mod accuracy;
pub mod baseline;
pub mod bitangent;
pub mod bitangent_curves;
pub mod bitangent_report;
pub mod events;
pub mod facing;
pub mod flecnodal;
pub mod flecnodal_curves;
pub mod flecnodal_report;
pub mod fold_edges;
pub mod hlr;
pub mod line_cone;
pub mod model_curves;
pub mod parabolic;
pub mod patch_curve;
pub mod projection;
pub mod ray;
pub mod render;
pub mod silhouette;
pub mod silhouette_certificate;
pub mod tangent_lines;
pub mod vec3;
pub mod visible;
