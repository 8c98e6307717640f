//! The document of `limn events` (JSON, text) and its SVG map of the viewing sphere.

use crate::analysis::events::{EventKind, Events, SphereCurve};
use crate::report::render::{svg_document, Layer};

/// The point of the cylindrical equal-area map of the sphere: longitude in `[−π, π]`, `z`.
fn equal_area(d: [f64; 3]) -> [f64; 2] {
    [d[1].atan2(d[0]), d[2].clamp(-1.0, 1.0)]
}

/// The viewing sphere as an SVG map (Lambert's cylindrical equal-area projection: longitude
/// across, `z` up), each event curve drawn with its antipode, parabolic events blue,
/// flecnodal green, bitangent orange; curves not certified (source or error bound) dashed.
pub fn events_svg(ev: &Events, title: &str) -> String {
    let style = |k: EventKind, certified: bool| match (k, certified) {
        (EventKind::Parabolic, true) => r##"stroke="#04c" stroke-width="1.4""##,
        (EventKind::Parabolic, false) => {
            r##"stroke="#04c" stroke-width="1.4" stroke-dasharray="5,3""##
        }
        (EventKind::Flecnodal, true) => r##"stroke="#0a4" stroke-width="1.4""##,
        (EventKind::Flecnodal, false) => {
            r##"stroke="#0a4" stroke-width="1.4" stroke-dasharray="5,3""##
        }
        (EventKind::Bitangent, true) => r##"stroke="#e80" stroke-width="1.4""##,
        (EventKind::Bitangent, false) => {
            r##"stroke="#e80" stroke-width="1.4" stroke-dasharray="5,3""##
        }
    };
    let pi = std::f64::consts::PI;
    let mut layers = vec![Layer {
        style: r##"stroke="#bbb" stroke-width="0.8""##,
        paths: vec![
            vec![[-pi, -1.0], [pi, -1.0], [pi, 1.0], [-pi, 1.0], [-pi, -1.0]],
            vec![[-pi, 0.0], [pi, 0.0]],
            vec![[0.0, -1.0], [0.0, 1.0]],
        ],
        filled: false,
    }];
    for kind in [
        EventKind::Parabolic,
        EventKind::Flecnodal,
        EventKind::Bitangent,
    ] {
        for certified in [true, false] {
            let mut paths = Vec::new();
            for c in ev
                .curves
                .iter()
                .filter(|c| c.kind == kind && c.certified == certified)
            {
                for sign in [1.0, -1.0] {
                    let mut pts: Vec<[f64; 3]> =
                        c.directions.iter().map(|d| d.map(|x| sign * x)).collect();
                    if c.closed {
                        // Around a loop the line may come back with the opposite sign (a loop
                        // of lines need not lift to a loop of vectors): close to whichever of
                        // ± the first direction is within 90° of the last.
                        if let (Some(f), Some(l)) = (pts.first().copied(), pts.last().copied()) {
                            let same = f[0] * l[0] + f[1] * l[1] + f[2] * l[2] >= 0.0;
                            pts.push(if same { f } else { f.map(|x| -x) });
                        }
                    }
                    // Split where the curve crosses the map's seam (longitude ±π).
                    let mut piece: Vec<[f64; 2]> = Vec::new();
                    for d in pts {
                        let p = equal_area(d);
                        if let Some(last) = piece.last() {
                            if (p[0] - last[0]).abs() > pi {
                                paths.push(std::mem::take(&mut piece));
                            }
                        }
                        piece.push(p);
                    }
                    paths.push(piece);
                }
            }
            layers.push(Layer {
                style: style(kind, certified),
                paths,
                filled: false,
            });
        }
    }
    svg_document(title, &layers, &[])
}

/// Counts per family in [`EventsReport`].
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct FamilySummary {
    /// The family.
    pub kind: EventKind,
    /// Its curves on the sphere.
    pub curves: usize,
    /// Source curves whose topology is not certified.
    pub uncertified_curves: usize,
    /// Unresolved boxes (and degenerate patches) of the source computation.
    pub unresolved: usize,
    /// Curves whose error on the sphere could not be bounded.
    pub unbounded: usize,
}

/// The document of `limn events`.
#[derive(Clone, Debug, serde::Serialize)]
#[non_exhaustive]
pub struct EventsReport {
    /// The model file.
    pub model: String,
    /// Every source curve's topology certified and nothing unresolved.
    pub sources_certified: bool,
    /// Sources certified and every curve's error on the sphere bounded.
    pub certified: bool,
    /// The largest error bound on the sphere, radians (`null` if a curve has none).
    pub largest_error: Option<f64>,
    /// Per family.
    pub families: Vec<FamilySummary>,
    /// The curves.
    pub curves: Vec<SphereCurve>,
    /// Wall-clock milliseconds.
    pub ms: f64,
    /// Threads.
    pub threads: usize,
}

impl EventsReport {
    /// The report of a run.
    pub fn new(model: &str, ev: &Events, ms: f64, threads: usize) -> EventsReport {
        EventsReport {
            model: model.to_string(),
            sources_certified: ev.sources_certified(),
            certified: ev.certified(),
            largest_error: ev.largest_error(),
            families: ev
                .uncertified
                .iter()
                .map(|&(kind, c, u)| FamilySummary {
                    kind,
                    curves: ev.curves.iter().filter(|x| x.kind == kind).count(),
                    uncertified_curves: c,
                    unresolved: u,
                    unbounded: ev
                        .curves
                        .iter()
                        .filter(|x| x.kind == kind && x.error.is_none())
                        .count(),
                })
                .collect(),
            curves: ev.curves.clone(),
            ms,
            threads,
        }
    }

    /// A short human-readable summary.
    pub fn text(&self) -> String {
        let mut out = format!(
            "{}: {} event curves on the viewing sphere (each with its antipode): {}, sources {}, \
             largest error {}\n",
            self.model,
            self.curves.len(),
            if self.certified {
                "certified"
            } else {
                "NOT certified"
            },
            if self.sources_certified {
                "certified"
            } else {
                "NOT all certified"
            },
            match self.largest_error {
                Some(e) => format!("{e:.3e} rad"),
                None => "not bounded".to_string(),
            }
        );
        for f in &self.families {
            out += &format!(
                "  {:?}: {} curves, {} with uncertified source, {} unresolved boxes in the source, \
                 {} without an error bound\n",
                f.kind, f.curves, f.uncertified_curves, f.unresolved, f.unbounded
            );
        }
        out += &format!("{:.1} ms on {} threads\n", self.ms, self.threads);
        out
    }
}
