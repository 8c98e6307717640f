//! Layer 5: the analyses, one folder per capability, each built on the solver, with the
//! pieces they share beside them: the exact image of a view ([`projection`]) and the chord
//! bounds that make drawn curves certified ([`chords`]).

pub mod bitangent;
pub mod chords;
pub mod contour;
pub mod events;
pub mod flecnodal;
pub mod frame;
pub mod intersection;
pub mod projection;
pub mod view;
pub mod visibility;
