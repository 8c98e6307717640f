//! Layer 6: the documents limn writes for its analyses (JSON contracts, text summaries, SVG
//! and OBJ drawings).

pub mod bitangent;
pub mod document;
pub mod events;
pub mod flecnodal;
pub mod hlr;
pub mod render;
pub mod silhouette;
pub mod visible;
