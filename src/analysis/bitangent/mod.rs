//! Bitangent curves: pairs of surface points with one tangent plane. The exact system and the
//! lemmas that drop spurious boxes ([`system`]), the curves per pair of patches ([`curves`]),
//! and planes tangent along whole lines ([`tangent_lines`]).

pub mod curves;
pub mod result;
pub mod system;
pub mod tangent_lines;
