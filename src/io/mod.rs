//! Model file readers. Every number is read exactly as the file writes it; every failure is a
//! [`ReadError`] naming the file, the place and what is wrong (never a panic).
//!
//! | format | recognised by |
//! |---|---|
//! | native JSON | `.json`, or text starting with `{` |
//! | Newell `.bpt` | `.bpt`, or a count line then `m n` |
//! | 1991 teaset archive | a count line then a line of 16 comma-separated indices |
//! | IGES (entity 128 surfaces) | `.igs` / `.iges`, or 80-column records with `S` in column 73 |
//! | STEP (faces on B-spline surfaces and planes) | `.stp` / `.step`, or text starting with `ISO-10303-21;` |
//! | Wavefront OBJ | `.obj` |

mod bpt;
mod error;
mod iges;
mod json;
mod obj;
mod step;
mod teaset;
mod text;
mod trimmed;

pub(crate) use error::shortened;
pub use error::{Place, ReadError};
pub use json::write_model;

use crate::model::{Format, Model};
use crate::surface::NurbsSurface;
use std::path::Path;

/// The most Bézier control points the NURBS surfaces of one model may split into. The split
/// of a surface of degree (p, q) with many knots has up to (p+1)(q+1) times the control points
/// of the file (a 200 kB file of degree 64 would make some 18 million points of four exact
/// rationals each), so a small file could otherwise exhaust memory.
pub(super) const MAX_BEZIER_POINTS: usize = 4_000_000;

/// Adds the Bézier control points `s.to_bezier()` will make to `total`, before the split is
/// made; the message if the model would then have more than [`MAX_BEZIER_POINTS`].
pub(super) fn count_bezier_points(total: &mut usize, s: &NurbsSurface) -> Result<(), String> {
    let [p, q] = s.degree();
    // Nonempty knot spans of the domain [t_deg, t_n].
    let spans = |d: usize| {
        let (k, deg, n) = (s.knots()[d], s.degree()[d], s.counts()[d]);
        (deg..n).filter(|&i| k[i] < k[i + 1]).count()
    };
    let (su, sv) = (spans(0), spans(1));
    let points = su.saturating_mul(sv).saturating_mul((p + 1) * (q + 1));
    *total = total.saturating_add(points);
    if *total > MAX_BEZIER_POINTS {
        return Err(format!(
            "the surface splits into {su} x {sv} Bézier patches of degree ({p},{q}) with {points} control points; \
             the model would have more than the {MAX_BEZIER_POINTS} allowed"
        ));
    }
    Ok(())
}

/// Reads a model file, choosing the reader by extension or, failing that, by content.
///
/// # Errors
/// [`ReadError`] if the file cannot be read or is malformed.
///
/// # Examples
/// ```no_run
/// let model = limn::io::read_model(std::path::Path::new("fixtures/bezier/teapot.bpt")).unwrap();
/// assert_eq!(model.patches.len(), 32);
/// ```
pub fn read_model(path: &Path) -> Result<Model, ReadError> {
    let name = path.display().to_string();
    let bytes = std::fs::read(path)
        .map_err(|e| ReadError::new(&name, Place::File, format!("cannot read: {e}")))?;
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase());
    let format = match ext.as_deref() {
        Some("json") => Some(Format::Json),
        Some("bpt") => Some(Format::Bpt),
        Some("igs") | Some("iges") => Some(Format::Iges),
        Some("stp") | Some("step") => Some(Format::Step),
        Some("obj") => Some(Format::Obj),
        _ => None,
    };
    read_model_bytes(&name, &bytes, format)
}

/// Reads a model from memory. `name` is used in error messages; `format` forces a reader
/// (`None`: detect from the content).
///
/// # Errors
/// [`ReadError`] if the content is malformed.
///
/// # Examples
/// ```
/// use limn::io::read_model_bytes;
/// let json = br#"{"patches":[{"kind":"bezier","degree":[1,1],
///     "points":[[0,0,0],[0,1,0],[1,0,0],["1","1/3",0]]}]}"#;
/// let m = read_model_bytes("example.json", json, None).unwrap();
/// assert_eq!(m.patches.len(), 1);
/// let bad = read_model_bytes("bad.json", br#"{"patches":[{"kind":"bezier","degree":[1,1],"points":[]}]}"#, None);
/// assert!(bad.unwrap_err().to_string().starts_with("bad.json: patch 0"));
/// ```
pub fn read_model_bytes(
    name: &str,
    bytes: &[u8],
    format: Option<Format>,
) -> Result<Model, ReadError> {
    if bytes.iter().all(|b| b.is_ascii_whitespace()) {
        return Err(ReadError::new(name, Place::File, "the file is empty"));
    }
    let format = match format {
        Some(f) => f,
        None => detect(bytes).ok_or_else(|| {
            ReadError::new(
                name,
                Place::File,
                "unknown model format (expected JSON, .bpt, teaset, IGES, STEP or OBJ; name the file with its extension)",
            )
        })?,
    };
    if format == Format::Iges {
        // IGES is ASCII; other bytes (Latin-1 in comments) are read as they are.
        return iges::read(name, bytes);
    }
    if format == Format::Step {
        // STEP is ASCII; strings may hold other bytes, read as they are.
        return step::read(name, bytes);
    }
    let text = std::str::from_utf8(bytes).map_err(|e| {
        // The line of the first bad byte: lines before it are valid UTF-8.
        let at = e.valid_up_to();
        let line = 1 + bytes[..at].iter().filter(|&&b| b == b'\n').count();
        ReadError::new(
            name,
            Place::Line(line),
            format!("not a text file (invalid UTF-8 at byte {at})"),
        )
    })?;
    match format {
        Format::Json => json::read(name, text),
        Format::Bpt => bpt::read(name, text),
        Format::Teaset => teaset::read(name, text),
        Format::Obj => obj::read(name, text),
        Format::Iges | Format::Step => unreachable!("handled above"),
    }
}

/// Guesses the format from the content.
fn detect(bytes: &[u8]) -> Option<Format> {
    let text = String::from_utf8_lossy(&bytes[..bytes.len().min(4096)]);
    let trimmed = text.trim_start();
    if trimmed.starts_with('{') {
        return Some(Format::Json);
    }
    if trimmed.starts_with("ISO-10303-21") {
        return Some(Format::Step);
    }
    let first_line = text.lines().next().unwrap_or("");
    if first_line.len() >= 73 && matches!(first_line.as_bytes()[72], b'S' | b'G') {
        return Some(Format::Iges);
    }
    let mut lines = text.lines().map(str::trim).filter(|l| !l.is_empty());
    let count = lines.next()?;
    if count.parse::<usize>().is_ok() {
        let second = lines.next()?;
        if second.contains(',') {
            return Some(Format::Teaset);
        }
        if second.split_whitespace().count() == 2 {
            return Some(Format::Bpt);
        }
    }
    if text
        .lines()
        .any(|l| l.trim_start().starts_with("v ") || l.trim_start().starts_with("f "))
    {
        return Some(Format::Obj);
    }
    None
}
