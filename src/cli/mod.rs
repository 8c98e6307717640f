//! The `limn` command line: a thin layer over the library. Every command that computes
//! something can print JSON (`--format json`) whose field names are documented in README.

use crate::analysis::bitangent::curves::{bitangent_curves, BitangentOptions};
use crate::analysis::contour::baseline::{baseline_silhouette, BaselineMethod};
use crate::analysis::contour::certificate::{check_silhouette, SilhouetteCertificate};
use crate::analysis::contour::curves::Silhouette;
use crate::analysis::contour::parabolic::parabolic;
use crate::analysis::contour::silhouette::silhouette;
use crate::analysis::events::{events, EventOptions};
use crate::analysis::flecnodal::curves::{flecnodal_curves, FlecnodalOptions};
use crate::analysis::view::{parse_vector, View};
use crate::analysis::visibility::hlr::{hidden_lines, HlrOptions};
use crate::analysis::visibility::visible::{visible_regions, VisibleOptions};
use crate::io::{read_model, read_model_bytes};
use crate::model::{default_weld, Format, ModelInfo, WeldTolerance};
use crate::report::bitangent::BitangentReport;
use crate::report::events::{events_svg, EventsReport};
use crate::report::flecnodal::FlecnodalReport;
use crate::report::hlr::HlrReport;
use crate::report::render::CurveDocument;
use crate::report::render::{hlr_svg, silhouette_obj, silhouette_svg, visible_svg};
use crate::report::silhouette::SilhouetteReport;
use crate::report::visible::VisibleReport;
use crate::solver::CurveOptions;
use crate::ContourOptions;
use clap::{Parser, Subcommand, ValueEnum};
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

/// The tolerance of `limn demo`, relative to the bounding-box diagonal.
pub const DEMO_TOLERANCE: f64 = 1e-3;

/// The view direction of `limn demo`.
pub const DEMO_DIRECTION: &str = "1,2,3";

/// The view direction of the demo's hidden-line drawing (from above, in front of the spout).
pub const DEMO_HLR_DIRECTION: &str = "2,3,-2";

/// The Newell teapot (32 bicubic patches), embedded so that `limn demo` needs no files.
pub const EMBEDDED_TEAPOT: &str = crate::TEAPOT;

#[derive(Parser, Debug)]
#[command(
    name = "limn",
    version,
    about = "Certified visibility analysis of free-form surfaces"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Patch count and degrees, bounding box, shared / boundary / collapsed edges, closedness,
    /// Euler characteristic and genus of a model.
    Info {
        /// The model file (.json, .bpt, teaset, .igs/.iges, .obj).
        model: PathBuf,
        /// Output format.
        #[arg(long, value_enum, default_value_t = OutputFormat::Text)]
        format: OutputFormat,
        /// How patch boundaries are matched: "exact", or an absolute distance. Default: exact,
        /// except for IGES (the file's minimum resolution).
        #[arg(long, allow_hyphen_values = true)]
        weld: Option<String>,
    },
    /// The silhouette (contour generator) of a model for a view: curves with certified
    /// topology (see README: accuracy of the drawn chords is not certified yet).
    Silhouette {
        /// The model file.
        model: PathBuf,
        #[command(flatten)]
        view: ViewArgs,
        /// Output format.
        #[arg(long, value_enum, default_value_t = CurveFormat::Text)]
        format: CurveFormat,
        #[command(flatten)]
        run: RunArgs,
        /// "certified" (limn), or an uncertified float baseline of paper 002 for comparison:
        /// "mesh" (control-mesh normals) or "srf-node" (signs at the control points' parameters).
        #[arg(long, value_enum, default_value_t = Method::Certified)]
        method: Method,
        /// Also write the certificate of what was proven (JSON; see README) to this file, for
        /// `limn check` (refused if it exists, unless --force; certified method only).
        #[arg(long)]
        certificate: Option<PathBuf>,
    },
    /// Curves on a model that do not depend on a view, with certified topology (and accuracy
    /// with --tol): `parabolic` (Gaussian curvature zero), `flecnodal` (an asymptotic tangent
    /// line with 4-point contact), `bitangent` (pairs of points with one tangent plane).
    Curves {
        /// The model file.
        model: PathBuf,
        /// The curve family.
        #[arg(long, value_enum)]
        kind: CurveKind,
        /// Output format.
        #[arg(long, value_enum, default_value_t = CurveFormat::Text)]
        format: CurveFormat,
        /// The direction along which the SVG drawing is projected, x,y,z.
        #[arg(long, allow_hyphen_values = true, default_value = DEMO_DIRECTION)]
        dir: String,
        #[command(flatten)]
        run: RunArgs,
    },
    /// Visual events on the viewing sphere: the view directions of the events of the parabolic
    /// (lip, beak-to-beak), flecnodal (swallowtail) and bitangent curves, each with its
    /// antipode, as JSON or as an SVG map of the sphere (cylindrical equal-area).
    Events {
        /// The model file.
        model: PathBuf,
        /// The families, comma separated: parabolic, flecnodal, bitangent.
        #[arg(long, default_value = "parabolic,flecnodal,bitangent")]
        kinds: String,
        /// Output format.
        #[arg(long, value_enum, default_value_t = CurveFormat::Text)]
        format: CurveFormat,
        #[command(flatten)]
        run: RunArgs,
    },
    /// The hidden-line drawing of a model for a view: its silhouettes and patch boundaries,
    /// each piece with its proven number of surface layers in front (QI: 0 = visible); with
    /// --tol, each piece drawn provably within the tolerance of the true line.
    Hlr {
        /// The model file.
        model: PathBuf,
        #[command(flatten)]
        view: ViewArgs,
        /// Output format.
        #[arg(long, value_enum, default_value_t = HlrFormat::Text)]
        format: HlrFormat,
        #[command(flatten)]
        run: RunArgs,
    },
    /// The visible regions of each patch for a view: the parameter cells proven visible,
    /// hidden (with their QI) or unresolved, the loops around the proven-visible and the
    /// possibly-visible cells, bounds on each patch's visible share of its area, and the
    /// trimming curves that bound its visible region (silhouette, boundary and occlusion
    /// curves, each within a proven distance with --tol), chained into loops.
    Visible {
        /// The model file.
        model: PathBuf,
        #[command(flatten)]
        view: ViewArgs,
        /// Output format (svg: the visible cells drawn in the view plane, unresolved in red,
        /// the trimming curves on top).
        #[arg(long, value_enum, default_value_t = HlrFormat::Text)]
        format: HlrFormat,
        /// The deepest cell level: cells of side 2^-depth in the parameter square, 1..=14.
        #[arg(long, default_value_t = 8)]
        cell_depth: u32,
        /// Include every leaf cell with its QI in the JSON (the certificate of the result).
        #[arg(long)]
        cells: bool,
        #[command(flatten)]
        run: RunArgs,
    },
    /// Re-verifies a silhouette certificate against its model, independently of the solver, in
    /// exact arithmetic. Exit 0: valid; 1: invalid (the first failing item is named).
    Check {
        /// The model file the certificate was written for.
        model: PathBuf,
        /// The certificate (from `limn silhouette --certificate`).
        certificate: PathBuf,
        /// Output format.
        #[arg(long, value_enum, default_value_t = OutputFormat::Text)]
        format: OutputFormat,
        /// Worker threads (default: all cores).
        #[arg(long)]
        threads: Option<usize>,
    },
    /// Runs the main job on the embedded Newell teapot (no files needed).
    Demo {
        /// Output format: a text summary and the silhouette report (JSON, OBJ), or the
        /// hidden-line drawing (SVG, from 2,3,-2: silhouettes and patch boundaries, hidden
        /// lines dashed; it takes some seconds).
        #[arg(long, value_enum, default_value_t = CurveFormat::Text)]
        format: CurveFormat,
    },
}

/// The view of the commands that depend on one.
#[derive(clap::Args, Debug)]
struct ViewArgs {
    /// Parallel view direction x,y,z (from the viewer into the scene).
    #[arg(
        long,
        allow_hyphen_values = true,
        conflicts_with = "eye",
        required_unless_present = "eye"
    )]
    dir: Option<String>,
    /// Perspective eye point x,y,z.
    #[arg(long, allow_hyphen_values = true)]
    eye: Option<String>,
}

/// The options shared by the commands that solve curves on a model.
#[derive(clap::Args, Debug)]
struct RunArgs {
    /// Write to this file instead of standard output (refused if it exists, unless --force).
    #[arg(short = 'o', long = "output")]
    output: Option<PathBuf>,
    /// Overwrite the output file if it exists.
    #[arg(long)]
    force: bool,
    /// Worker threads (default: all cores).
    #[arg(long)]
    threads: Option<usize>,
    /// How patch boundaries are matched: "exact" or a distance (default as for `info`).
    #[arg(long, allow_hyphen_values = true)]
    weld: Option<String>,
    /// The deepest subdivision (the box side is 2^-depth), 1..=40.
    #[arg(long, default_value_t = 24)]
    max_depth: u32,
    /// Certify the drawing: every segment within this distance of the true curve, relative to
    /// the bounding-box diagonal (absolute with --abs-tol). Without it the topology is
    /// certified but the chords are not bounded (and `certified` is false).
    #[arg(long, allow_hyphen_values = true)]
    tol: Option<f64>,
    /// Read --tol as an absolute distance in model units.
    #[arg(long)]
    abs_tol: bool,
    /// Stop subdividing after this many seconds of wall time: what is not decided by then is
    /// reported unresolved, and arcs not yet traced are drawn uncertified. Without it the run
    /// is bounded by the box and depth budgets only, and its output does not depend on the
    /// machine's speed.
    #[arg(long, allow_hyphen_values = true)]
    time_limit: Option<f64>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Method {
    Certified,
    Mesh,
    SrfNode,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum CurveKind {
    Parabolic,
    Flecnodal,
    Bitangent,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum CurveFormat {
    Text,
    Json,
    Svg,
    Obj,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum HlrFormat {
    Text,
    Json,
    Svg,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum OutputFormat {
    Text,
    Json,
}

/// A failure of a command: the message, and the exit code (2 for bad input or arguments).
#[derive(Debug)]
pub struct CliError {
    /// One line: the file, the place and what is wrong.
    pub message: String,
    /// The process exit code.
    pub code: u8,
}

impl CliError {
    fn input(message: impl Into<String>) -> CliError {
        CliError {
            message: message.into(),
            code: 2,
        }
    }
}

fn parse_weld(s: &str) -> Result<WeldTolerance, CliError> {
    if s.eq_ignore_ascii_case("exact") {
        return Ok(WeldTolerance::Exact);
    }
    match s.parse::<f64>() {
        Ok(t) if t.is_finite() && t > 0.0 => Ok(WeldTolerance::Absolute(t)),
        _ => Err(CliError::input(format!(
            "--weld: expected \"exact\" or a positive distance, found {s:?}"
        ))),
    }
}

/// Runs the command line `args` (including the program name), writing results to `out`.
///
/// # Errors
/// [`CliError`] with exit code 2 on bad arguments or bad input files.
pub fn run<I, T>(args: I, out: &mut dyn Write) -> Result<(), CliError>
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let cli = Cli::try_parse_from(args).map_err(|e| {
        use clap::error::ErrorKind;
        match e.kind() {
            // --help and --version: the full text, on stdout, success.
            ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => CliError {
                message: e.render().to_string().trim_end().to_string(),
                code: 0,
            },
            ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => CliError::input(
                "no command given: try `limn demo`, `limn info MODEL`, or `limn --help`",
            ),
            // Anything else: clap's first line ("error: ..."), as one line, exit 2.
            _ => {
                // clap's message up to the usage block, joined into one line.
                let text = e.render().to_string();
                let message: Vec<&str> = text
                    .lines()
                    .map(str::trim)
                    .take_while(|l| {
                        !l.starts_with("Usage:")
                            && !l.starts_with("tip:")
                            && !l.starts_with("For more")
                    })
                    .filter(|l| !l.is_empty())
                    .collect();
                let joined = message.join(" ");
                let first = joined.strip_prefix("error: ").unwrap_or(&joined);
                CliError::input(format!("{first} (see `limn --help`)"))
            }
        }
    })?;
    match cli.command {
        Command::Info {
            model,
            format,
            weld,
        } => {
            let name = model.display().to_string();
            let m = read_model(&model).map_err(|e| CliError::input(e.to_string()))?;
            let weld = match weld {
                Some(s) => parse_weld(&s)?,
                None => default_weld(&m),
            };
            let info = ModelInfo::of(&name, &m, weld);
            w(print_info(&info, format, out))
        }
        Command::Silhouette {
            model,
            view,
            format,
            run,
            method,
            certificate,
        } => {
            check_run_arguments(&run)?;
            let view = parse_view(view)?;
            refuse_overwrite(run.output.iter().chain(&certificate), run.force)?;
            if certificate.is_some() && method != Method::Certified {
                return Err(CliError::input(
                    "--certificate: only the certified method proves anything",
                ));
            }
            if run.output.is_some() && run.output == certificate {
                return Err(CliError::input("-o and --certificate name the same file"));
            }
            let Loaded {
                name,
                model: m,
                weld,
                opts,
                pool,
                tol_abs,
            } = load(&model, &run)?;
            let start = std::time::Instant::now();
            let (s, report) = match method {
                Method::Certified => {
                    let s = pool
                        .install(|| {
                            silhouette(&m, &view, &ContourOptions::new(opts.clone(), weld, tol_abs))
                        })
                        .map_err(|e| CliError::input(e.to_string()))?;
                    let ms = start.elapsed().as_secs_f64() * 1e3;
                    let r = SilhouetteReport::new(&name, &view, &s, ms, pool.current_num_threads());
                    (s, r)
                }
                Method::Mesh | Method::SrfNode => {
                    let bm = if method == Method::Mesh {
                        BaselineMethod::Mesh
                    } else {
                        BaselineMethod::SrfNode
                    };
                    let curves = baseline_silhouette(&m, &view, bm);
                    let ms = start.elapsed().as_secs_f64() * 1e3;
                    let r = SilhouetteReport::baseline(&name, &view, bm, curves.clone(), ms);
                    (Silhouette::from_curves(curves), r)
                }
            };
            if let Some(path) = &certificate {
                let cert = pool.install(|| SilhouetteCertificate::new(&name, &view, &s));
                let json = serde_json::to_string(&cert).map_err(|e| CliError {
                    message: format!("cannot serialise the certificate: {e}"),
                    code: 1,
                })?;
                std::fs::write(path, json).map_err(|e| CliError {
                    message: format!("{}: cannot write: {e}", path.display()),
                    code: 1,
                })?;
            }
            let text = render_silhouette(format, &report, &m, &view, &s)?;
            write_output(run.output, &text, out)
        }
        Command::Curves {
            model,
            kind,
            format,
            dir,
            run,
        } => {
            check_run_arguments(&run)?;
            let projection = View::Direction(
                parse_vector(&dir).map_err(|e| CliError::input(format!("--dir: {e}")))?,
            );
            if projection.is_degenerate() {
                return Err(CliError::input(
                    "--dir: the direction must not be the zero vector",
                ));
            }
            refuse_overwrite(run.output.iter(), run.force)?;
            let Loaded {
                name,
                model: m,
                weld,
                opts,
                pool,
                tol_abs,
            } = load(&model, &run)?;
            let start = std::time::Instant::now();
            let threads = pool.current_num_threads();
            let document: Box<dyn CurveDocument> = match kind {
                CurveKind::Flecnodal => {
                    let o = FlecnodalOptions::with_tolerance(tol_abs).with_deadline(opts.deadline);
                    let r = pool
                        .install(|| flecnodal_curves(&m, &o))
                        .map_err(|e| CliError::input(e.to_string()))?;
                    let ms = start.elapsed().as_secs_f64() * 1e3;
                    Box::new(FlecnodalReport::new(&name, &r, tol_abs, ms, threads))
                }
                CurveKind::Bitangent => {
                    let o = BitangentOptions::with_tolerance(tol_abs).with_deadline(opts.deadline);
                    let r = pool
                        .install(|| bitangent_curves(&m, &o))
                        .map_err(|e| CliError::input(e.to_string()))?;
                    let ms = start.elapsed().as_secs_f64() * 1e3;
                    Box::new(BitangentReport::new(&name, &r, tol_abs, ms, threads))
                }
                CurveKind::Parabolic => {
                    let s = pool
                        .install(|| {
                            parabolic(&m, &ContourOptions::new(opts.clone(), weld, tol_abs))
                        })
                        .map_err(|e| CliError::input(e.to_string()))?;
                    let ms = start.elapsed().as_secs_f64() * 1e3;
                    let report = SilhouetteReport::of_curves(
                        &name,
                        "parabolic",
                        serde_json::Value::Null,
                        &s,
                        ms,
                        threads,
                    );
                    let text = render_silhouette(format, &report, &m, &projection, &s)?;
                    return write_output(run.output, &text, out);
                }
            };
            let text = match format {
                CurveFormat::Json => document.json().map_err(|e| CliError {
                    message: format!("cannot write JSON: {e}"),
                    code: 1,
                })?,
                CurveFormat::Text => document.text(),
                CurveFormat::Svg => document.svg(&m, &projection),
                CurveFormat::Obj => document.obj(),
            };
            write_output(run.output, &text, out)
        }
        Command::Events {
            model,
            kinds,
            format,
            run,
        } => {
            check_run_arguments(&run)?;
            if format == CurveFormat::Obj {
                return Err(CliError::input(
                    "--format: events are written as text, json or svg",
                ));
            }
            let mut wanted = [false; 3];
            for k in kinds.split(',').map(str::trim) {
                match k {
                    "parabolic" => wanted[0] = true,
                    "flecnodal" => wanted[1] = true,
                    "bitangent" => wanted[2] = true,
                    other => {
                        return Err(CliError::input(format!(
                            "--kinds: unknown family {other:?} (expected parabolic, flecnodal, bitangent)"
                        )))
                    }
                }
            }
            refuse_overwrite(run.output.iter(), run.force)?;
            let Loaded {
                name,
                model: m,
                weld,
                opts,
                pool,
                tol_abs,
            } = load(&model, &run)?;
            let start = std::time::Instant::now();
            let deadline = opts.deadline;
            let eopts = EventOptions {
                parabolic: wanted[0].then(|| (opts.clone(), weld, tol_abs)),
                flecnodal: wanted[1]
                    .then(|| FlecnodalOptions::with_tolerance(tol_abs).with_deadline(deadline)),
                bitangent: wanted[2]
                    .then(|| BitangentOptions::with_tolerance(tol_abs).with_deadline(deadline)),
            };
            let ev = pool
                .install(|| events(&m, &eopts))
                .map_err(|e| CliError::input(e.to_string()))?;
            let ms = start.elapsed().as_secs_f64() * 1e3;
            let report = EventsReport::new(&name, &ev, ms, pool.current_num_threads());
            let text = match format {
                CurveFormat::Json => pretty_json(&report)?,
                CurveFormat::Svg => events_svg(
                    &ev,
                    &format!(
                        "{name}: {} event curves on the viewing sphere (parabolic blue, flecnodal green, bitangent orange; dashed: not certified)",
                        ev.curves.len()
                    ),
                ),
                _ => report.text(),
            };
            write_output(run.output, &text, out)
        }
        Command::Hlr {
            model,
            view,
            format,
            run,
        } => {
            check_run_arguments(&run)?;
            let view = parse_view(view)?;
            refuse_overwrite(run.output.iter(), run.force)?;
            let Loaded {
                name,
                model: m,
                weld,
                opts,
                pool,
                tol_abs,
            } = load(&model, &run)?;
            let start = std::time::Instant::now();
            let hopts = HlrOptions {
                curve: opts,
                tol: tol_abs,
                ..HlrOptions::default()
            };
            let h = pool
                .install(|| hidden_lines(&m, &view, &hopts.clone().with_weld(weld)))
                .map_err(|e| CliError::input(format!("{name}: {e}")))?;
            let ms = start.elapsed().as_secs_f64() * 1e3;
            let report = HlrReport::new(&name, &view, &h, ms, pool.current_num_threads());
            let text = match format {
                HlrFormat::Text => report.text(),
                HlrFormat::Json => pretty_json(&report)?,
                HlrFormat::Svg => {
                    let title = format!(
                        "{}: hidden lines, {} pieces, {}",
                        name,
                        report.pieces.len(),
                        if report.certified {
                            "visibility certified".to_string()
                        } else {
                            format!("{} pieces unresolved (red)", report.unresolved.len())
                        }
                    );
                    hlr_svg(&m, &view, &h, &title)
                }
            };
            write_output(run.output, &text, out)
        }
        Command::Visible {
            model,
            view,
            format,
            cell_depth,
            cells,
            run,
        } => {
            if !(1..=14).contains(&cell_depth) {
                return Err(CliError::input(format!(
                    "--cell-depth: expected 1..=14, found {cell_depth}"
                )));
            }
            check_run_arguments(&run)?;
            let view = parse_view(view)?;
            refuse_overwrite(run.output.iter(), run.force)?;
            let Loaded {
                name,
                model: m,
                weld,
                opts,
                pool,
                tol_abs,
            } = load(&model, &run)?;
            let start = std::time::Instant::now();
            let vopts = VisibleOptions {
                curve: opts,
                max_depth: cell_depth,
                tol: tol_abs,
                ..VisibleOptions::default()
            };
            let r = pool
                .install(|| visible_regions(&m, &view, &vopts.clone().with_weld(weld)))
                .map_err(|e| CliError::input(format!("{name}: {e}")))?;
            let ms = start.elapsed().as_secs_f64() * 1e3;
            let report =
                VisibleReport::new(&name, &view, &r, cells, ms, pool.current_num_threads());
            let text = match format {
                HlrFormat::Text => report.text(),
                HlrFormat::Json => pretty_json(&report)?,
                HlrFormat::Svg => {
                    let title = format!(
                        "{}: visible regions, area share [{:.4}, {:.4}]{}",
                        name,
                        r.area_fraction[0],
                        r.area_fraction[1],
                        if report.certified {
                            ""
                        } else {
                            ", unresolved cells red"
                        }
                    );
                    visible_svg(&m, &view, &r, &title)
                }
            };
            write_output(run.output, &text, out)
        }
        Command::Check {
            model,
            certificate,
            format,
            threads,
        } => {
            if threads == Some(0) {
                return Err(CliError::input("--threads: expected at least 1"));
            }
            let m = read_model(&model).map_err(|e| CliError::input(e.to_string()))?;
            let text = std::fs::read_to_string(&certificate).map_err(|e| {
                CliError::input(format!("{}: cannot read: {e}", certificate.display()))
            })?;
            let cert: SilhouetteCertificate = serde_json::from_str(&text).map_err(|e| {
                CliError::input(format!(
                    "{}: line {}, column {}: not a silhouette certificate: {e}",
                    certificate.display(),
                    e.line(),
                    e.column()
                ))
            })?;
            let pool = thread_pool(threads)?;
            let start = std::time::Instant::now();
            let verdict = pool.install(|| check_silhouette(&m, &cert));
            let ms = start.elapsed().as_secs_f64() * 1e3;
            let line = match (&verdict, format) {
                (Ok(v), OutputFormat::Text) => format!(
                    "valid: {} patches, {} cells, {} crossings, {} arcs, {} branches re-verified \
                     in exact arithmetic; {} ({ms:.1} ms)\n",
                    v.patches,
                    v.cells,
                    v.crossings,
                    v.arcs,
                    v.branches,
                    if v.certified {
                        "the whole model is decided".to_string()
                    } else {
                        format!("{} cells unresolved (nothing claimed there)", v.unresolved)
                    }
                ),
                (Err(e), OutputFormat::Text) => format!("invalid: {e}\n"),
                (Ok(v), OutputFormat::Json) => format!(
                    "{}\n",
                    serde_json::json!({"valid": true, "summary": v, "time_ms": ms})
                ),
                (Err(e), OutputFormat::Json) => format!(
                    "{}\n",
                    serde_json::json!({"valid": false, "item": e.item, "reason": e.reason, "time_ms": ms})
                ),
            };
            w(out.write_all(line.as_bytes()))?;
            match verdict {
                Ok(_) => Ok(()),
                Err(_) => Err(CliError {
                    message: format!("{}: invalid certificate", certificate.display()),
                    code: 1,
                }),
            }
        }
        Command::Demo { format } => {
            let name = "embedded teapot (Newell, 32 bicubic patches)";
            let m = read_model_bytes(
                "embedded teapot",
                EMBEDDED_TEAPOT.as_bytes(),
                Some(Format::Bpt),
            )
            .map_err(|e| CliError::input(e.to_string()))?;
            if format == CurveFormat::Svg {
                let view =
                    View::Direction(parse_vector(DEMO_HLR_DIRECTION).map_err(CliError::input)?);
                let h = hidden_lines(
                    &m,
                    &view,
                    &HlrOptions::default().with_weld(WeldTolerance::Exact),
                )
                .map_err(|e| CliError::input(e.to_string()))?;
                let unresolved = h.pieces.iter().filter(|p| !p.certified).count();
                let title = format!(
                    "{name}: hidden lines from ({DEMO_HLR_DIRECTION}), {} pieces, {unresolved} unresolved (red)",
                    h.pieces.len()
                );
                return w(out.write_all(hlr_svg(&m, &view, &h, &title).as_bytes()));
            }
            let view = View::Direction(parse_vector(DEMO_DIRECTION).map_err(CliError::input)?);
            let start = std::time::Instant::now();
            let tol = DEMO_TOLERANCE * m.diagonal();
            let s = silhouette(
                &m,
                &view,
                &ContourOptions::new(CurveOptions::default(), WeldTolerance::Exact, Some(tol)),
            )
            .map_err(|e| CliError::input(e.to_string()))?;
            let ms = start.elapsed().as_secs_f64() * 1e3;
            let report = SilhouetteReport::new(name, &view, &s, ms, rayon::current_num_threads());
            let text = match format {
                CurveFormat::Text => {
                    let mut info = Vec::new();
                    w(print_info(
                        &ModelInfo::of(name, &m, WeldTolerance::Exact),
                        OutputFormat::Text,
                        &mut info,
                    ))?;
                    String::from_utf8_lossy(&info).into_owned()
                        + "\nsilhouette from ("
                        + DEMO_DIRECTION
                        + "):\n"
                        + &silhouette_text(&report)
                }
                _ => render_silhouette(format, &report, &m, &view, &s)?,
            };
            w(out.write_all(text.as_bytes()))
        }
    }
}

/// A model read for a curve command, with what the run needs.
struct Loaded {
    name: String,
    model: crate::model::Model,
    weld: WeldTolerance,
    opts: CurveOptions,
    pool: rayon::ThreadPool,
    /// The tolerance in model units.
    tol_abs: Option<f64>,
}

/// Reads the model of a curve command and sets up the run (arguments already checked).
fn load(path: &std::path::Path, run: &RunArgs) -> Result<Loaded, CliError> {
    let model = read_model(path).map_err(|e| CliError::input(e.to_string()))?;
    if model.patches.is_empty() {
        let faces: usize = model.meshes.iter().map(|m| m.faces.len()).sum();
        return Err(CliError::input(if faces > 0 {
            format!(
                "{}: a polygon mesh ({faces} faces): silhouettes and curves are computed on Bézier / NURBS patch models only (meshes are not supported yet)",
                path.display()
            )
        } else {
            format!(
                "{}: the model has no surface patches to analyse",
                path.display()
            )
        }));
    }
    let weld = match &run.weld {
        Some(s) => parse_weld(s)?,
        None => default_weld(&model),
    };
    let tol_abs = run
        .tol
        .map(|t| if run.abs_tol { t } else { t * model.diagonal() });
    Ok(Loaded {
        name: path.display().to_string(),
        model,
        weld,
        opts: CurveOptions {
            max_depth: run.max_depth,
            deadline: run
                .time_limit
                .map(|t| std::time::Instant::now() + std::time::Duration::from_secs_f64(t)),
            ..CurveOptions::default()
        },
        pool: thread_pool(run.threads)?,
        tol_abs,
    })
}

/// An output error (exit code 1).
fn w(r: std::io::Result<()>) -> Result<(), CliError> {
    r.map_err(|e| CliError {
        message: format!("cannot write the output: {e}"),
        code: 1,
    })
}

/// The checks shared by the commands that solve curves.
fn check_run_arguments(run: &RunArgs) -> Result<(), CliError> {
    let (tol, max_depth, threads) = (run.tol, run.max_depth, run.threads);
    if let Some(t) = run.time_limit {
        if !(0.0..1e9).contains(&t) {
            return Err(CliError::input(format!(
                "--time-limit: expected a number of seconds, 0 or more, found {t}"
            )));
        }
    }
    if let Some(t) = tol {
        if !(t.is_finite() && t > 0.0) {
            return Err(CliError::input(format!(
                "--tol: expected a positive number, found {t}"
            )));
        }
    }
    if !(1..=40).contains(&max_depth) {
        return Err(CliError::input(format!(
            "--max-depth: expected 1..=40, found {max_depth}"
        )));
    }
    if threads == Some(0) {
        return Err(CliError::input("--threads: expected at least 1"));
    }
    Ok(())
}

/// Refuses to overwrite an existing file unless asked.
fn refuse_overwrite<'a>(
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
fn pretty_json(report: &impl serde::Serialize) -> Result<String, CliError> {
    serde_json::to_string_pretty(report)
        .map(|t| t + "\n")
        .map_err(|e| CliError {
            message: e.to_string(),
            code: 1,
        })
}

fn write_output(output: Option<PathBuf>, text: &str, out: &mut dyn Write) -> Result<(), CliError> {
    match output {
        Some(path) => std::fs::write(&path, text).map_err(|e| CliError {
            message: format!("{}: cannot write: {e}", path.display()),
            code: 1,
        }),
        None => w(out.write_all(text.as_bytes())),
    }
}

fn thread_pool(threads: Option<usize>) -> Result<rayon::ThreadPool, CliError> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .build()
        .map_err(|e| CliError {
            message: format!("cannot start threads: {e}"),
            code: 1,
        })
}

/// The view from `--dir` or `--eye`.
fn parse_view(args: ViewArgs) -> Result<View, CliError> {
    let view = match (args.dir, args.eye) {
        (Some(d), _) => {
            View::Direction(parse_vector(&d).map_err(|e| CliError::input(format!("--dir: {e}")))?)
        }
        (None, Some(e)) => {
            View::Eye(parse_vector(&e).map_err(|e| CliError::input(format!("--eye: {e}")))?)
        }
        (None, None) => return Err(CliError::input("give --dir X,Y,Z or --eye X,Y,Z")),
    };
    if view.is_degenerate() {
        return Err(CliError::input(
            "--dir: the view direction must not be the zero vector",
        ));
    }
    Ok(view)
}

fn render_silhouette(
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

fn silhouette_text(r: &SilhouetteReport) -> String {
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

fn print_info(info: &ModelInfo, format: OutputFormat, out: &mut dyn Write) -> std::io::Result<()> {
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

/// The entry point of the `limn` binary: runs, prints errors on stderr as one line, and
/// returns the exit code (2 for bad input or arguments).
pub fn main() -> ExitCode {
    let mut stdout = std::io::stdout().lock();
    match run(std::env::args_os(), &mut stdout) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) if e.code == 0 => {
            let _ = writeln!(stdout, "{}", e.message);
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("limn: {}", e.message);
            ExitCode::from(e.code)
        }
    }
}
