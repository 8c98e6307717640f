//! Writing results: output files (never overwritten without `--force`), JSON, the text
//! summaries, and the silhouette's drawings.

use crate::analysis::view::View;
use crate::cli::args::{CurveFormat, HlrFormat, OutputFormat};
use crate::cli::CliError;
use crate::model::{Model, ModelInfo, WeldTolerance};
use crate::report::document::{Document, Format};
use std::io::Write;
use std::path::PathBuf;

/// An output error (exit code 1).
pub(crate) fn w(r: std::io::Result<()>) -> Result<(), CliError> {
    r.map_err(|e| CliError {
        message: format!("cannot write the output: {e}"),
        code: 1,
    })
}
/// Checks the output files before any work (exit 2): each must be writable where it is named
/// (its folder exists and is a folder), none may be an existing file unless `force`, and no two
/// may name the same file, however they are spelled.
pub(crate) fn refuse_overwrite<'a>(
    paths: impl Iterator<Item = &'a PathBuf>,
    force: bool,
) -> Result<(), CliError> {
    let mut seen: Vec<(PathBuf, &PathBuf)> = Vec::new();
    for path in paths {
        let folder = match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        if !folder.is_dir() {
            return Err(CliError::input(format!(
                "{}: cannot write there: {} is not a folder",
                path.display(),
                folder.display()
            )));
        }
        if path.is_dir() {
            return Err(CliError::input(format!(
                "{}: is a folder, not a file",
                path.display()
            )));
        }
        if path.exists() && !force {
            return Err(CliError::input(format!(
                "{}: exists; not overwritten (use --force)",
                path.display()
            )));
        }
        // The same file under two spellings: compare the canonical folder and the name.
        let canonical = folder
            .canonicalize()
            .unwrap_or(folder)
            .join(path.file_name().unwrap_or_default());
        if let Some((_, other)) = seen.iter().find(|(c, _)| *c == canonical) {
            return Err(CliError::input(format!(
                "{} and {} name the same file",
                other.display(),
                path.display()
            )));
        }
        seen.push((canonical, path));
    }
    Ok(())
}
pub(crate) fn write_output(
    output: Option<PathBuf>,
    text: &str,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    match output {
        Some(path) => std::fs::write(&path, text).map_err(|e| CliError {
            message: format!("{}: cannot write: {e}", path.display()),
            code: 1,
        }),
        None => w(out.write_all(text.as_bytes())),
    }
}
/// Writes a report in the format asked, to the output file or `out` (exit code 1 if it
/// cannot be serialised or written; 2 if the command does not write that format).
pub(crate) fn emit(
    doc: &dyn Document,
    format: Format,
    model: &Model,
    view: &View,
    output: Option<PathBuf>,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    let text = doc
        .render(format, model, view)
        .ok_or_else(|| {
            CliError::input(format!(
                "--format: {} is not written by this command",
                format!("{format:?}").to_lowercase()
            ))
        })?
        .map_err(|e| CliError {
            message: format!("cannot write JSON: {e}"),
            code: 1,
        })?;
    write_output(output, &text, out)
}
impl From<CurveFormat> for Format {
    fn from(f: CurveFormat) -> Format {
        match f {
            CurveFormat::Text => Format::Text,
            CurveFormat::Json => Format::Json,
            CurveFormat::Svg => Format::Svg,
            CurveFormat::Obj => Format::Obj,
        }
    }
}
impl From<HlrFormat> for Format {
    fn from(f: HlrFormat) -> Format {
        match f {
            HlrFormat::Text => Format::Text,
            HlrFormat::Json => Format::Json,
            HlrFormat::Svg => Format::Svg,
        }
    }
}
pub(crate) fn print_info(
    info: &ModelInfo,
    format: OutputFormat,
    out: &mut dyn Write,
) -> std::io::Result<()> {
    if format == OutputFormat::Json {
        let s = serde_json::to_string_pretty(info).map_err(std::io::Error::other)?;
        return writeln!(out, "{s}");
    }
    writeln!(out, "model: {} ({:?})", info.file, info.format)?;
    writeln!(
        out,
        "surfaces: {}, Bézier patches: {} ({} rational)",
        info.surfaces, info.patches, info.rational_patches
    )?;
    if !info.degrees.is_empty() {
        let d: Vec<String> = info
            .degrees
            .iter()
            .map(|(k, v)| format!("{v} of degree {k}"))
            .collect();
        writeln!(out, "degrees: {}", d.join(", "))?;
    }
    if let Some(b) = &info.bounding_box {
        writeln!(
            out,
            "bounding box: [{}, {}, {}] .. [{}, {}, {}]",
            b.min[0], b.min[1], b.min[2], b.max[0], b.max[1], b.max[2]
        )?;
    }
    if let Some(t) = &info.topology {
        let weld = match t.weld {
            WeldTolerance::Exact => "exact".to_string(),
            WeldTolerance::Absolute(x) => {
                format!("within {x:.3e} (largest gap welded {:.3e})", t.max_weld_gap)
            }
        };
        writeln!(out, "edges: {} ({} shared, {} boundary, {} non-manifold); {} collapsed patch sides; weld {}", t.edges, t.shared_edges, t.boundary_edges, t.nonmanifold_edges, t.collapsed_edges, weld)?;
        writeln!(
            out,
            "vertices: {}, components: {}",
            t.vertices, t.components
        )?;
        match t.genus {
            Some(g) => writeln!(
                out,
                "closed: yes, Euler characteristic {}, genus {}",
                t.euler_characteristic, g
            )?,
            None => writeln!(
                out,
                "closed: no (Euler characteristic of the patch complex {})",
                t.euler_characteristic
            )?,
        }
    }
    if let Some(c) = info.side_contacts.as_ref().filter(|c| !c.pairs.is_empty()) {
        writeln!(
            out,
            "side contacts: {} pairs of patches whose sides run along each other within {:.1e} without a common corner (largest gap {:.1e}): taken as adjacent",
            c.pairs.len(),
            c.tolerance,
            c.largest_gap
        )?;
    }
    if let Some(f) = &info.faces {
        writeln!(
            out,
            "faces: {} trimmed ({} with the domain as outer loop), {} surfaces untrimmed; loops: {} ({} inner), {} curves, {} bridges ({} along collapsed sides, largest straight gap {:.3e})",
            f.faces, f.domain_outer_loops, f.untrimmed_surfaces, f.loops, f.inner_loops, f.curves, f.bridges, f.side_bridges, f.largest_gap
        )?;
        writeln!(
            out,
            "loop orientation (proven): {} counter-clockwise, {} clockwise, {} undecided; {} against the usual convention (outer counter-clockwise, inner clockwise)",
            f.counter_clockwise, f.clockwise, f.undecided, f.unusual_orientation
        )?;
        if f.inverted_curves > 0 {
            writeln!(
                out,
                "inverted edges: {} trimming curves made from model-space edges, proven within {:.3e} of their edges",
                f.inverted_curves, f.inversion_distance
            )?;
        }
    }
    if let Some(b) = &info.brep {
        writeln!(
            out,
            "B-rep: {} shells, {} faces, {} loops ({} inner), {} edges ({} shared, {} boundary, {} non-manifold), {} vertices",
            b.shells, b.faces, b.loops, b.inner_loops, b.edges, b.shared_edges, b.boundary_edges, b.nonmanifold_edges, b.vertices
        )?;
        match b.genus {
            Some(g) => writeln!(
                out,
                "B-rep closed: yes, Euler-Poincaré characteristic {}, genus {}",
                b.euler_characteristic, g
            )?,
            None => writeln!(
                out,
                "B-rep closed: no (Euler-Poincaré characteristic {})",
                b.euler_characteristic
            )?,
        }
    }
    for (i, m) in info.meshes.iter().enumerate() {
        writeln!(out, "mesh {i}: {} vertices, {} edges, {} faces ({}), {} boundary edges, {} non-manifold, {} components", m.vertices, m.edges, m.faces, if m.triangles { "triangles" } else { "polygons" }, m.boundary_edges, m.nonmanifold_edges, m.components)?;
        match m.genus {
            Some(g) => writeln!(
                out,
                "  closed: yes, Euler characteristic {}, genus {}",
                m.euler_characteristic, g
            )?,
            None => writeln!(
                out,
                "  closed: no (Euler characteristic {})",
                m.euler_characteristic
            )?,
        }
    }
    for wn in &info.warnings {
        writeln!(out, "warning: {wn}")?;
    }
    Ok(())
}
