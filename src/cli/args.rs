//! The command line's arguments (clap): one struct per command, the shared view and run
//! options, and their checks (a bad argument is exit code 2 with one line).

use crate::analysis::view::{parse_vector, View};
use crate::cli::{CliError, DEMO_DIRECTION};
use crate::model::WeldTolerance;
use clap::{Parser, Subcommand, ValueEnum};
use std::path::PathBuf;

#[derive(Parser, Debug)]
#[command(
    name = "limn",
    version,
    about = "Certified visibility analysis of free-form surfaces"
)]
pub(crate) struct Cli {
    #[command(subcommand)]
    pub(crate) command: Command,
}
#[derive(Subcommand, Debug)]
pub(crate) enum Command {
    /// Patch count and degrees, bounding box, shared / boundary / collapsed edges, closedness,
    /// Euler characteristic and genus of a model.
    Info(InfoArgs),
    /// The silhouette (contour generator) of a model for a view: curves with certified
    /// topology, and with --tol every drawn segment proven within the tolerance.
    Silhouette(SilhouetteArgs),
    /// Curves on a model that do not depend on a view, with certified topology (and accuracy
    /// with --tol): `parabolic` (Gaussian curvature zero), `flecnodal` (an asymptotic tangent
    /// line with 4-point contact), `bitangent` (pairs of points with one tangent plane).
    Curves(CurvesArgs),
    /// Visual events on the viewing sphere: the view directions of the events of the parabolic
    /// (lip, beak-to-beak), flecnodal (swallowtail) and bitangent curves, each with its
    /// antipode, as JSON or as an SVG map of the sphere (cylindrical equal-area).
    Events(EventsArgs),
    /// The hidden-line drawing of a model for a view: its silhouettes and patch boundaries,
    /// each piece with its proven number of surface layers in front (QI: 0 = visible); with
    /// --tol, each piece drawn provably within the tolerance of the true line.
    Hlr(HlrArgs),
    /// The visible regions of each patch for a view: the parameter cells proven visible,
    /// hidden (with their QI) or unresolved, the loops around the proven-visible and the
    /// possibly-visible cells, bounds on each patch's visible share of its area, and the
    /// trimming curves that bound its visible region (silhouette, boundary and occlusion
    /// curves, each within a proven distance with --tol), chained into loops.
    Visible(VisibleArgs),
    /// Re-verifies a silhouette certificate against its model, independently of the solver, in
    /// exact arithmetic. Exit 0: valid; 1: invalid (the first failing item is named).
    Check(CheckArgs),
    /// Runs the main job on the embedded Newell teapot (no files needed).
    Demo(DemoArgs),
}
/// The view of the commands that depend on one.
#[derive(clap::Args, Debug)]
pub(crate) struct ViewArgs {
    /// Parallel view direction x,y,z (from the viewer into the scene).
    #[arg(
        long,
        allow_hyphen_values = true,
        conflicts_with = "eye",
        required_unless_present = "eye"
    )]
    pub(crate) dir: Option<String>,
    /// Perspective eye point x,y,z.
    #[arg(long, allow_hyphen_values = true)]
    pub(crate) eye: Option<String>,
}
/// The options shared by the commands that solve curves on a model.
#[derive(clap::Args, Debug)]
pub(crate) struct RunArgs {
    /// Write to this file instead of standard output (refused if it exists, unless --force).
    #[arg(short = 'o', long = "output")]
    pub(crate) output: Option<PathBuf>,
    /// Overwrite the output file if it exists.
    #[arg(long)]
    pub(crate) force: bool,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub(crate) threads: Option<usize>,
    /// How patch boundaries are matched: "exact" or a distance (default as for `info`).
    #[arg(long, allow_hyphen_values = true)]
    pub(crate) weld: Option<String>,
    /// The deepest subdivision (the box side is 2^-depth), 1..=40.
    #[arg(long, default_value_t = 24)]
    pub(crate) max_depth: u32,
    /// Certify the drawing: every segment within this distance of the true curve, relative to
    /// the bounding-box diagonal (absolute with --abs-tol). Without it the topology is
    /// certified but the chords are not bounded (and `certified` is false).
    #[arg(long, allow_hyphen_values = true)]
    pub(crate) tol: Option<f64>,
    /// Read --tol as an absolute distance in model units.
    #[arg(long)]
    pub(crate) abs_tol: bool,
    /// Stop subdividing after this many seconds of wall time: what is not decided by then is
    /// reported unresolved, and arcs not yet traced are drawn uncertified. Without it the run
    /// is bounded by the box and depth budgets only, and its output does not depend on the
    /// machine's speed.
    #[arg(long, allow_hyphen_values = true)]
    pub(crate) time_limit: Option<f64>,
}
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum Method {
    Certified,
    Mesh,
    SrfNode,
}
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum CurveKind {
    Parabolic,
    Flecnodal,
    Bitangent,
}
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum CurveFormat {
    Text,
    Json,
    Svg,
    Obj,
}
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum HlrFormat {
    Text,
    Json,
    Svg,
}
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum OutputFormat {
    Text,
    Json,
}
pub(crate) fn parse_weld(s: &str) -> Result<WeldTolerance, CliError> {
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
/// The checks shared by the commands that solve curves.
pub(crate) fn check_run_arguments(run: &RunArgs) -> Result<(), CliError> {
    let (tol, max_depth, threads) = (run.tol, run.max_depth, run.threads);
    if let Some(t) = run.time_limit {
        if !(0.0..1e9).contains(&t) {
            return Err(CliError::input(format!(
                "--time-limit: expected a number of seconds from 0 to below 1e9, found {t}"
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
/// The view from `--dir` or `--eye`.
pub(crate) fn parse_view(args: ViewArgs) -> Result<View, CliError> {
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
/// The arguments of `limn info`.
#[derive(clap::Args, Debug)]
pub(crate) struct InfoArgs {
    /// The model file (.json, .bpt, teaset, .igs/.iges, .stp/.step, .obj).
    pub(crate) model: PathBuf,
    /// Output format.
    #[arg(long, value_enum, default_value_t = OutputFormat::Text)]
    pub(crate) format: OutputFormat,
    /// How patch boundaries are matched: "exact", or an absolute distance. Default: exact,
    /// except for IGES (the file's minimum resolution) and STEP (10⁻⁶ of the model's diagonal).
    #[arg(long, allow_hyphen_values = true)]
    pub(crate) weld: Option<String>,
}
/// The arguments of `limn silhouette`.
#[derive(clap::Args, Debug)]
pub(crate) struct SilhouetteArgs {
    /// The model file.
    pub(crate) model: PathBuf,
    #[command(flatten)]
    pub(crate) view: ViewArgs,
    /// Output format.
    #[arg(long, value_enum, default_value_t = CurveFormat::Text)]
    pub(crate) format: CurveFormat,
    #[command(flatten)]
    pub(crate) run: RunArgs,
    /// "certified" (limn), or an uncertified float baseline of paper 002 for comparison:
    /// "mesh" (control-mesh normals) or "srf-node" (signs at the control points' parameters).
    #[arg(long, value_enum, default_value_t = Method::Certified)]
    pub(crate) method: Method,
    /// Also write the certificate of what was proven (JSON; see README) to this file, for
    /// `limn check` (refused if it exists, unless --force; certified method only).
    #[arg(long)]
    pub(crate) certificate: Option<PathBuf>,
}
/// The arguments of `limn curves`.
#[derive(clap::Args, Debug)]
pub(crate) struct CurvesArgs {
    /// The model file.
    pub(crate) model: PathBuf,
    /// The curve family.
    #[arg(long, value_enum)]
    pub(crate) kind: CurveKind,
    /// Output format.
    #[arg(long, value_enum, default_value_t = CurveFormat::Text)]
    pub(crate) format: CurveFormat,
    /// The direction along which the SVG drawing is projected, x,y,z.
    #[arg(long, allow_hyphen_values = true, default_value = DEMO_DIRECTION)]
    pub(crate) dir: String,
    #[command(flatten)]
    pub(crate) run: RunArgs,
}
/// The arguments of `limn events`.
#[derive(clap::Args, Debug)]
pub(crate) struct EventsArgs {
    /// The model file.
    pub(crate) model: PathBuf,
    /// The families, comma separated: parabolic, flecnodal, bitangent.
    #[arg(long, default_value = "parabolic,flecnodal,bitangent")]
    pub(crate) kinds: String,
    /// Output format.
    #[arg(long, value_enum, default_value_t = CurveFormat::Text)]
    pub(crate) format: CurveFormat,
    #[command(flatten)]
    pub(crate) run: RunArgs,
}
/// The arguments of `limn hlr`.
#[derive(clap::Args, Debug)]
pub(crate) struct HlrArgs {
    /// The model file.
    pub(crate) model: PathBuf,
    #[command(flatten)]
    pub(crate) view: ViewArgs,
    /// Output format.
    #[arg(long, value_enum, default_value_t = HlrFormat::Text)]
    pub(crate) format: HlrFormat,
    /// Do not search the curves where patches that share no corner pass through each other
    /// (they are then not drawn; faster on models with many overlapping patches)
    #[arg(long)]
    pub(crate) no_intersections: bool,
    #[command(flatten)]
    pub(crate) run: RunArgs,
}
/// The arguments of `limn visible`.
#[derive(clap::Args, Debug)]
pub(crate) struct VisibleArgs {
    /// The model file.
    pub(crate) model: PathBuf,
    #[command(flatten)]
    pub(crate) view: ViewArgs,
    /// Output format (svg: the visible cells drawn in the view plane, unresolved in red,
    /// the trimming curves on top).
    #[arg(long, value_enum, default_value_t = HlrFormat::Text)]
    pub(crate) format: HlrFormat,
    /// The deepest cell level: cells of side 2^-depth in the parameter square, 1..=14.
    #[arg(long, default_value_t = 8)]
    pub(crate) cell_depth: u32,
    /// Include every leaf cell with its QI in the JSON (the certificate of the result).
    #[arg(long)]
    pub(crate) cells: bool,
    #[command(flatten)]
    pub(crate) run: RunArgs,
}
/// The arguments of `limn check`.
#[derive(clap::Args, Debug)]
pub(crate) struct CheckArgs {
    /// The model file the certificate was written for.
    pub(crate) model: PathBuf,
    /// The certificate (from `limn silhouette --certificate`).
    pub(crate) certificate: PathBuf,
    /// Output format.
    #[arg(long, value_enum, default_value_t = OutputFormat::Text)]
    pub(crate) format: OutputFormat,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub(crate) threads: Option<usize>,
}
/// The arguments of `limn demo`.
#[derive(clap::Args, Debug)]
pub(crate) struct DemoArgs {
    /// Output format: a text summary and the silhouette report (JSON, OBJ), or the
    /// hidden-line drawing (SVG, from 2,3,-2: silhouettes and patch boundaries, hidden
    /// lines dashed; it takes some seconds).
    #[arg(long, value_enum, default_value_t = CurveFormat::Text)]
    pub(crate) format: CurveFormat,
}
