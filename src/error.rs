//! The one error type of the library's entry points.

use crate::analysis::projection::ProjectionError;
use crate::io::ReadError;

/// Why a call of limn's library gave no answer. Undecided parts of an answer are not errors:
/// they are reported in the result as unresolved, with where and why.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A model file could not be read (the message names the file and the place).
    #[error(transparent)]
    Read(#[from] ReadError),
    /// The view is not one the analysis can take (the zero direction, an eye that does not see
    /// the whole model on one side of it).
    #[error(transparent)]
    View(#[from] ProjectionError),
}
