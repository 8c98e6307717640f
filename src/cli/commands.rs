//! One function per command: read the model, run the analysis through the library's front
//! door, hand the result to the output.

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
use crate::cli::args::{
    check_run_arguments, parse_view, parse_weld, CheckArgs, CurveFormat, CurveKind, CurvesArgs,
    DemoArgs, EventsArgs, HlrArgs, InfoArgs, Method, OutputFormat, RunArgs, SilhouetteArgs,
    VisibleArgs,
};
use crate::cli::output::{emit, print_info, refuse_overwrite, w};
use crate::cli::{CliError, DEMO_DIRECTION, DEMO_HLR_DIRECTION, DEMO_TOLERANCE, EMBEDDED_TEAPOT};
use crate::io::{read_model, read_model_bytes};
use crate::model::{default_weld, Format, ModelInfo, WeldTolerance};
use crate::report::bitangent::BitangentReport;
use crate::report::document::{Document, WithResult};
use crate::report::events::EventsReport;
use crate::report::flecnodal::FlecnodalReport;
use crate::report::hlr::HlrReport;
use crate::report::render::hlr_svg;
use crate::report::silhouette::SilhouetteReport;
use crate::report::visible::VisibleReport;
use crate::solver::CurveOptions;
use crate::ContourOptions;
use std::io::Write;

/// A model read for a curve command, with what the run needs.
pub(crate) struct Loaded {
    pub(crate) name: String,
    pub(crate) model: crate::model::Model,
    pub(crate) weld: WeldTolerance,
    pub(crate) opts: CurveOptions,
    pub(crate) pool: rayon::ThreadPool,
    /// The tolerance in model units.
    pub(crate) tol_abs: Option<f64>,
}
impl Loaded {
    /// Runs `f` on the run's threads: its value and the wall-clock milliseconds it took.
    pub(crate) fn timed<T: Send>(&self, f: impl FnOnce() -> T + Send) -> (T, f64) {
        let start = std::time::Instant::now();
        let value = self.pool.install(f);
        (value, start.elapsed().as_secs_f64() * 1e3)
    }
}
/// Checks the output files (before any work: [`refuse_overwrite`]), reads the model of a
/// command and sets up the run (its other arguments already checked).
pub(crate) fn load(
    path: &std::path::Path,
    run: &RunArgs,
    other_outputs: Option<&std::path::PathBuf>,
    clips: bool,
) -> Result<Loaded, CliError> {
    refuse_overwrite(run.output.iter().chain(other_outputs), run.force)?;
    let model = read_model(path).map_err(|e| CliError::input(e.to_string()))?;
    // What the file holds that the analysis does not honour (trims, skipped surfaces) is
    // said on stderr, so that a drawing of untrimmed faces is never taken for the part.
    const SHOWN: usize = 8;
    for w in model.warnings.iter().take(SHOWN) {
        eprintln!("limn: warning: {}: {w}", path.display());
    }
    if model.warnings.len() > SHOWN {
        eprintln!(
            "limn: warning: {}: {} more warnings (`limn info` lists them)",
            path.display(),
            model.warnings.len() - SHOWN
        );
    }
    if !clips && !model.faces.is_empty() {
        eprintln!(
            "limn: warning: {}: this analysis does not clip to the {} trimmed face(s) yet: every surface is used whole",
            path.display(),
            model.faces.len()
        );
    }
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
pub(crate) fn thread_pool(threads: Option<usize>) -> Result<rayon::ThreadPool, CliError> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .build()
        .map_err(|e| CliError {
            message: format!("cannot start threads: {e}"),
            code: 1,
        })
}
/// `limn info`.
pub(crate) fn info_command(args: InfoArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let InfoArgs {
        model,
        format,
        weld,
    } = args;
    let name = model.display().to_string();
    let m = read_model(&model).map_err(|e| CliError::input(e.to_string()))?;
    let weld = match weld {
        Some(s) => parse_weld(&s)?,
        None => default_weld(&m),
    };
    let info = ModelInfo::of(&name, &m, weld);
    w(print_info(&info, format, out))
}
/// `limn silhouette`.
pub(crate) fn silhouette_command(
    args: SilhouetteArgs,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    let SilhouetteArgs {
        model,
        view,
        format,
        run,
        method,
        certificate,
    } = args;
    check_run_arguments(&run)?;
    let view = parse_view(view)?;
    if certificate.is_some() && method != Method::Certified {
        return Err(CliError::input(
            "--certificate: only the certified method proves anything",
        ));
    }
    let loaded = load(
        &model,
        &run,
        certificate.as_ref(),
        method == Method::Certified,
    )?;
    let start = std::time::Instant::now();
    let Loaded {
        name,
        model: m,
        weld,
        opts,
        pool,
        tol_abs,
    } = loaded;
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
    let doc = WithResult { report, result: &s };
    emit(&doc, format.into(), &m, &view, run.output, out)
}
/// `limn curves`.
pub(crate) fn curves_command(args: CurvesArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let CurvesArgs {
        model,
        kind,
        format,
        dir,
        run,
    } = args;
    check_run_arguments(&run)?;
    let projection =
        View::Direction(parse_vector(&dir).map_err(|e| CliError::input(format!("--dir: {e}")))?);
    if projection.is_degenerate() {
        return Err(CliError::input(
            "--dir: the direction must not be the zero vector",
        ));
    }
    let Loaded {
        name,
        model: m,
        weld,
        opts,
        pool,
        tol_abs,
    } = load(&model, &run, None, kind == CurveKind::Parabolic)?;
    let start = std::time::Instant::now();
    let threads = pool.current_num_threads();
    let parabolic_curves: Silhouette;
    let document: Box<dyn Document + '_> = match kind {
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
            parabolic_curves = pool
                .install(|| parabolic(&m, &ContourOptions::new(opts.clone(), weld, tol_abs)))
                .map_err(|e| CliError::input(e.to_string()))?;
            let s = &parabolic_curves;
            let ms = start.elapsed().as_secs_f64() * 1e3;
            let report = SilhouetteReport::of_curves(
                &name,
                "parabolic",
                serde_json::Value::Null,
                s,
                ms,
                threads,
            );
            Box::new(WithResult { report, result: s })
        }
    };
    emit(&*document, format.into(), &m, &projection, run.output, out)
}
/// `limn events`.
pub(crate) fn events_command(args: EventsArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let EventsArgs {
        model,
        kinds,
        format,
        run,
    } = args;
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
    let Loaded {
        name,
        model: m,
        weld,
        opts,
        pool,
        tol_abs,
    } = load(&model, &run, None, false)?;
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
    // On the viewing sphere: no view is drawn along.
    let doc = WithResult {
        report,
        result: &ev,
    };
    emit(
        &doc,
        format.into(),
        &m,
        &View::Direction(Default::default()),
        run.output,
        out,
    )
}
/// `limn hlr`.
pub(crate) fn hlr_command(args: HlrArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let HlrArgs {
        model,
        view,
        format,
        no_intersections,
        run,
    } = args;
    check_run_arguments(&run)?;
    let view = parse_view(view)?;
    let l = load(&model, &run, None, true)?;
    let hopts = HlrOptions {
        curve: l.opts.clone(),
        tol: l.tol_abs,
        weld: Some(l.weld),
        intersections: !no_intersections,
        ..HlrOptions::default()
    };
    let (h, ms) = l.timed(|| hidden_lines(&l.model, &view, &hopts));
    let h = h.map_err(|e| CliError::input(format!("{}: {e}", l.name)))?;
    let (m, threads) = (&l.model, l.pool.current_num_threads());
    let report = HlrReport::new(&l.name, &view, &h, ms, threads);
    let doc = WithResult { report, result: &h };
    emit(&doc, format.into(), m, &view, run.output, out)
}
/// `limn visible`.
pub(crate) fn visible_command(args: VisibleArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let VisibleArgs {
        model,
        view,
        format,
        cell_depth,
        cells,
        run,
    } = args;
    if !(1..=14).contains(&cell_depth) {
        return Err(CliError::input(format!(
            "--cell-depth: expected 1..=14, found {cell_depth}"
        )));
    }
    check_run_arguments(&run)?;
    let view = parse_view(view)?;
    let l = load(&model, &run, None, false)?;
    let vopts = VisibleOptions {
        curve: l.opts.clone(),
        max_depth: cell_depth,
        tol: l.tol_abs,
        weld: Some(l.weld),
        ..VisibleOptions::default()
    };
    let (r, ms) = l.timed(|| visible_regions(&l.model, &view, &vopts));
    let r = r.map_err(|e| CliError::input(format!("{}: {e}", l.name)))?;
    let threads = l.pool.current_num_threads();
    let report = VisibleReport::new(&l.name, &view, &r, cells, ms, threads);
    let doc = WithResult { report, result: &r };
    emit(&doc, format.into(), &l.model, &view, run.output, out)
}
/// `limn check`.
pub(crate) fn check_command(args: CheckArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let CheckArgs {
        model,
        certificate,
        format,
        threads,
    } = args;
    if threads == Some(0) {
        return Err(CliError::input("--threads: expected at least 1"));
    }
    let m = read_model(&model).map_err(|e| CliError::input(e.to_string()))?;
    let text = std::fs::read_to_string(&certificate)
        .map_err(|e| CliError::input(format!("{}: cannot read: {e}", certificate.display())))?;
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
/// `limn demo`.
pub(crate) fn demo_command(args: DemoArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let DemoArgs { format } = args;
    let name = "embedded teapot (Newell, 32 bicubic patches)";
    let m = read_model_bytes(
        "embedded teapot",
        EMBEDDED_TEAPOT.as_bytes(),
        Some(Format::Bpt),
    )
    .map_err(|e| CliError::input(e.to_string()))?;
    if format == CurveFormat::Svg {
        let view = View::Direction(parse_vector(DEMO_HLR_DIRECTION).map_err(CliError::input)?);
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
                + &report.text()
        }
        _ => {
            let doc = WithResult { report, result: &s };
            return emit(&doc, format.into(), &m, &view, None, out);
        }
    };
    w(out.write_all(text.as_bytes()))
}
