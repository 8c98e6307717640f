//! Errors from reading model files: always the file, the place and what is wrong.

use std::fmt;

/// Where in a file something is wrong.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Place {
    /// The file as a whole (empty, unreadable, not text).
    File,
    /// A line (1-based).
    Line(usize),
    /// A line and column (1-based).
    LineColumn(usize, usize),
    /// An IGES entity: its directory-entry sequence number and type.
    Entity {
        /// Directory-entry sequence number.
        de: usize,
        /// Entity type number.
        kind: i64,
    },
    /// A STEP entity instance: its number (`#123`) and entity name.
    Instance {
        /// The instance number.
        id: u64,
        /// The entity name (a complex instance's names joined by `+`).
        kind: String,
    },
    /// A patch (0-based index) and the field within it.
    Patch {
        /// Patch index.
        index: usize,
        /// The field (`"points"`, `"weights[3]"`).
        field: String,
    },
    /// A JSON path or other named location.
    Named(String),
}

impl fmt::Display for Place {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Place::File => write!(f, "file"),
            Place::Line(l) => write!(f, "line {l}"),
            Place::LineColumn(l, c) => write!(f, "line {l}, column {c}"),
            Place::Entity { de, kind } => write!(f, "entity {kind} at directory entry {de}"),
            Place::Instance { id, kind } => write!(f, "#{id} ({kind})"),
            Place::Patch { index, field } if field.is_empty() => write!(f, "patch {index}"),
            Place::Patch { index, field } => write!(f, "patch {index}, {field}"),
            Place::Named(s) => write!(f, "{s}"),
        }
    }
}

/// A model file could not be read: one message naming the file, the place and the problem.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{file}: {place}: {message}")]
pub struct ReadError {
    /// The file name as given.
    pub file: String,
    /// Where.
    pub place: Place,
    /// What is wrong.
    pub message: String,
}

/// The longest message kept whole, in characters (a message quotes what it found, and a
/// corrupt file can hold a "number" of a million characters).
const MAX_MESSAGE: usize = 300;

impl ReadError {
    /// An error at a place in a file. The message is kept to one line of reasonable length.
    pub fn new(file: &str, place: Place, message: impl Into<String>) -> ReadError {
        let message: String = message.into();
        let mut message: String = message
            .chars()
            .map(|c| if c.is_control() { ' ' } else { c })
            .collect();
        let len = message.chars().count();
        if len > MAX_MESSAGE {
            let kept: String = message.chars().take(MAX_MESSAGE).collect();
            message = format!("{kept}... (message cut, {len} characters in all)");
        }
        ReadError {
            file: file.to_string(),
            place,
            message,
        }
    }
}

/// At most 40 characters of `text` (then "…"), for messages that quote what they found.
pub(crate) fn shortened(text: &str) -> String {
    match text.char_indices().nth(40) {
        Some((at, _)) => format!("{}…", &text[..at]),
        None => text.to_string(),
    }
}
