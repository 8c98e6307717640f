//! Writing results: output files (never overwritten without `--force`), JSON, the text
//! summaries, and the silhouette's drawings.

use crate::analysis::contour::curves::Silhouette;
use crate::analysis::view::View;
use crate::cli::args::{CurveFormat, OutputFormat};
use crate::cli::CliError;
use crate::model::{ModelInfo, WeldTolerance};
use crate::report::render::{silhouette_obj, silhouette_svg};
use crate::report::silhouette::SilhouetteReport;
use std::io::Write;
use std::path::PathBuf;

/// An output error (exit code 1).
pub(crate) fn w(r: std::io::Result<()>) -> Result<(), CliError> {
    r.map_err(|e| CliError {
        message: format!("cannot write the output: {e}"),
        code: 1,
    })
}
/// Refuses to overwrite an existing file unless asked.
pub(crate) fn refuse_overwrite<'a>(
    paths: impl Iterator<Item = &'a PathBuf>,
    force: bool,
) -> Result<(), CliError> {
    for path in paths {
        if path.exists() && !force {
            return Err(CliError::input(format!(
                "{}: exists; not overwritten (use --force)",
                path.display()
            )));
        }
    }
    Ok(())
}
/// A report as pretty JSON with a final newline (exit code 1 if it cannot be written).
pub(crate) fn pretty_json(report: &impl serde::Serialize) -> Result<String, CliError> {
    serde_json::to_string_pretty(report)
        .map(|t| t + "\n")
        .map_err(|e| CliError {
            message: e.to_string(),
            code: 1,
        })
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
pub(crate) fn render_silhouette(
    format: CurveFormat,
    report: &SilhouetteReport,
    m: &crate::model::Model,
    view: &View,
    s: &Silhouette,
) -> Result<String, CliError> {
    Ok(match format {
        CurveFormat::Json => pretty_json(report)?,
        CurveFormat::Svg => {
            let title = format!(
                "{}: {} {} curves ({}), {} unresolved regions",
                report.model,
                report.curves.len(),
                report.kind,
                if report.certified {
                    "certified"
                } else if report.topology_certified {
                    "topology certified"
                } else {
                    "topology NOT fully certified"
                },
                report.unresolved.len()
            );
            silhouette_svg(m, view, s, &title)
        }
        CurveFormat::Text => silhouette_text(report),
        CurveFormat::Obj => silhouette_obj(s, &report.model),
    })
}
pub(crate) fn silhouette_text(r: &SilhouetteReport) -> String {
    let mut t = String::new();
    let closed = r.curves.iter().filter(|c| c.closed).count();
    t += &format!("model: {}\n", r.model);
    if r.method != "certified" {
        t += &format!(
            "method: {} (uncertified float baseline of paper 002: nothing is proven)\n",
            r.method
        );
    }
    if r.view.is_null() {
        t += &format!("kind: {}\n", r.kind);
    } else {
        t += &format!("view: {}\n", r.view);
    }
    t += &format!(
        "curves: {} ({} closed); topology {}\n",
        r.curves.len(),
        closed,
        if r.topology_certified {
            "certified"
        } else {
            "NOT fully certified (see unresolved / unjoined)"
        }
    );
    if r.method == "certified" {
        let worst = r
            .curves
            .iter()
            .filter_map(|c| c.error_bound)
            .fold(0.0f64, f64::max);
        match r.tolerance {
            Some(tol) if r.certified => t += &format!("accuracy: certified, every segment within {worst:.3e} of the true curve (tolerance {tol:.3e})\n"),
            Some(tol) => t += &format!("accuracy: tolerance {tol:.3e}; not certified for every curve (see the curves)\n"),
            None => t += "accuracy: not bounded (no tolerance asked)\n",
        }
    }
    for (i, c) in r.curves.iter().enumerate() {
        t += &format!(
            "  curve {i}: {} points, patches {:?}, {}{}\n",
            c.points.len(),
            c.patches,
            if c.closed { "closed" } else { "open" },
            if c.certified_topology {
                ""
            } else {
                ", topology not certified"
            }
        );
    }
    for p in &r.singular_points {
        t += &format!(
            "singular point: patch {} at ({:.6}, {:.6}), {} arcs meet ({}), point [{:.6}, {:.6}, {:.6}]\n",
            p.patch,
            p.uv[0],
            p.uv[1],
            p.branches,
            if p.exact { "exact" } else { "isolated" },
            p.point[0],
            p.point[1],
            p.point[2]
        );
    }
    for u in &r.unresolved {
        t += &format!(
            "unresolved: patch {}, {} boxes in [{:.6}, {:.6}] x [{:.6}, {:.6}]: {}\n",
            u.patch, u.boxes, u.hull[0][0], u.hull[1][0], u.hull[0][1], u.hull[1][1], u.reason
        );
    }
    for e in &r.unjoined_edges {
        t += &format!("unjoined edge: patch {} {:?} / patch {} {:?} (no proven join: the two patches' functions are not proportional there (nor, for silhouettes, the normals parallel), and their zeros on it are not proven apart; or the curve meets a side on which it lies at a point known only within an interval)\n", e.0, e.1, e.2, e.3);
    }
    if !r.ending_edges.is_empty() {
        t += &format!(
            "edges where curves end: {} (the function jumps across them; crossings common to both patches are joined, every other is proven not to be a zero of the other patch's function)\n",
            r.ending_edges.len()
        );
    }
    let mut kinds: std::collections::BTreeMap<&str, usize> = std::collections::BTreeMap::new();
    for d in &r.degenerate {
        *kinds.entry(d.kind).or_default() += 1;
    }
    for (k, n) in kinds {
        t += &format!("degenerate: {n} x {k}\n");
    }
    t += &format!(
        "stats: {} boxes, {} sign questions escalated beyond f64, {:.1} ms on {} threads\n",
        r.stats.boxes,
        r.stats.escalations.escalated(),
        r.stats.time_ms,
        r.stats.threads
    );
    t
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
                format!("within {x} (largest gap welded {:.3e})", t.max_weld_gap)
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
