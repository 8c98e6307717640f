//! SVG drawings of curves on a model, projected on the view plane.

use crate::analysis::contour::curves::Silhouette;
use crate::analysis::view::View;
use crate::analysis::visibility::hlr::{HiddenLines, HlrPiece, LineKind};
use crate::analysis::visibility::visible::VisibleRegions;
use crate::geometry::vec3::{cross, dot, normalize};
use crate::model::Model;
use crate::solver::precision::Escalations;
use crate::surface::DrawPatch;
use std::fmt::Write;

/// A projection of space onto the view plane: orthographic along a direction, or central from
/// an eye towards the model's centre.
pub struct Projection {
    eye: Option<[f64; 3]>,
    forward: [f64; 3],
    right: [f64; 3],
    up: [f64; 3],
}

impl Projection {
    /// The projection for a view of a model.
    pub fn new(view: &View, model: &Model) -> Projection {
        let center = model.bounding_box().map_or([0.0; 3], |[lo, hi]| {
            [0, 1, 2].map(|k| 0.5 * (lo[k].to_f64() + hi[k].to_f64()))
        });
        let (eye, forward) = match view {
            View::Direction(d) => (None, normalize(d.clone().map(|c| c.to_f64()))),
            View::Eye(e) => {
                let e = e.clone().map(|c| c.to_f64());
                (
                    Some(e),
                    normalize([center[0] - e[0], center[1] - e[1], center[2] - e[2]]),
                )
            }
        };
        // "Up" is the z axis unless the view is along it.
        let helper = if forward[2].abs() < 0.9 {
            [0.0, 0.0, 1.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        let right = normalize(cross(forward, helper));
        let up = cross(right, forward);
        Projection {
            eye,
            forward,
            right,
            up,
        }
    }

    /// The 2D image of a point (y up).
    pub fn project(&self, p: [f64; 3]) -> [f64; 2] {
        match self.eye {
            None => [dot(p, self.right), dot(p, self.up)],
            Some(e) => {
                let d = [p[0] - e[0], p[1] - e[1], p[2] - e[2]];
                let depth = dot(d, self.forward).max(1e-12);
                [dot(d, self.right) / depth, dot(d, self.up) / depth]
            }
        }
    }
}

/// The patches of a model, ready for f64 evaluation.
pub(crate) fn draw_patches(model: &Model) -> Vec<DrawPatch> {
    model
        .patches
        .iter()
        .map(|p| DrawPatch::new(&p.surface))
        .collect()
}

/// The patches' sides in light grey, for context.
pub(crate) fn outline_layer(draw: &[DrawPatch], proj: &Projection) -> Layer {
    let mut outlines: Vec<Vec<[f64; 2]>> = Vec::new();
    for d in draw {
        for side in 0..4 {
            let pts: Vec<[f64; 2]> = (0..=16)
                .map(|k| {
                    let t = k as f64 / 16.0;
                    let (u, v) = match side {
                        0 => (t, 0.0),
                        1 => (1.0, t),
                        2 => (1.0 - t, 1.0),
                        _ => (0.0, 1.0 - t),
                    };
                    proj.project(d.eval(u, v))
                })
                .collect();
            outlines.push(pts);
        }
    }
    Layer {
        style: r##"stroke="#c8c8c8" stroke-width="0.6""##,
        paths: outlines,
        filled: false,
    }
}

/// The silhouette over light patch outlines, as an SVG document. Curves whose topology is
/// certified are black; others red and dashed; unresolved boxes are marked in red.
pub fn silhouette_svg(model: &Model, view: &View, s: &Silhouette, title: &str) -> String {
    let proj = Projection::new(view, model);
    let draw = draw_patches(model);
    let curves: Vec<(bool, Vec<[f64; 2]>)> = s
        .curves
        .iter()
        .map(|c| {
            (
                c.certified_topology,
                c.points.iter().map(|&p| proj.project(p)).collect(),
            )
        })
        .collect();
    let marks: Vec<[f64; 2]> = s
        .unresolved
        .iter()
        .map(|(p, cell, _)| {
            let [u, v] = cell.to_f64().center();
            proj.project(draw[*p].eval(u, v))
        })
        .collect();
    let mut layers = vec![outline_layer(&draw, &proj)];
    let (good, bad): (Vec<_>, Vec<_>) = curves.into_iter().partition(|c| c.0);
    layers.push(Layer {
        style: r##"stroke="#000" stroke-width="1.8""##,
        paths: good.into_iter().map(|c| c.1).collect(),
        filled: false,
    });
    layers.push(Layer {
        style: r##"stroke="#d00" stroke-width="1.8" stroke-dasharray="6,3""##,
        paths: bad.into_iter().map(|c| c.1).collect(),
        filled: false,
    });
    svg_document(title, &layers, &marks)
}

/// A set of polylines drawn with one SVG style.
pub struct Layer {
    /// SVG attributes of the paths.
    pub style: &'static str,
    /// The polylines, in image coordinates (y up).
    pub paths: Vec<Vec<[f64; 2]>>,
    /// Closed and filled: the polylines are joined into one even-odd path (so loops inside
    /// loops are holes), and the style gives the fill.
    pub filled: bool,
}

/// An 800x800 SVG document of layers of polylines (fitted to the page, y up) and red marks,
/// with the title as a caption.
pub fn svg_document(title: &str, layers: &[Layer], marks: &[[f64; 2]]) -> String {
    let (mut x0, mut y0, mut x1, mut y1) = (
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    );
    for p in layers.iter().flat_map(|l| l.paths.iter().flatten()) {
        if p[0].is_finite() && p[1].is_finite() {
            x0 = x0.min(p[0]);
            y0 = y0.min(p[1]);
            x1 = x1.max(p[0]);
            y1 = y1.max(p[1]);
        }
    }
    if !x0.is_finite() {
        (x0, y0, x1, y1) = (0.0, 0.0, 1.0, 1.0);
    }
    // The longer side of the drawing spans 760 units; the canvas fits the drawing, with
    // margins of 20 and a band of 30 at the top for the title.
    let size = 800.0;
    let scale = (size - 40.0) / (x1 - x0).max(y1 - y0).max(1e-300);
    let width = (40.0 + (x1 - x0) * scale).ceil();
    let height = (50.0 + (y1 - y0) * scale).ceil();
    let map = |p: [f64; 2]| (20.0 + (p[0] - x0) * scale, 30.0 + (y1 - p[1]) * scale);
    let path = |pts: &[[f64; 2]]| -> String {
        let mut d = String::new();
        for (i, p) in pts.iter().enumerate() {
            let (x, y) = map(*p);
            let _ = write!(d, "{}{:.2},{:.2} ", if i == 0 { "M" } else { "L" }, x, y);
        }
        d
    };
    let mut svg = String::new();
    let _ = writeln!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}">"#
    );
    let _ = writeln!(
        svg,
        r#"<title>{}</title><rect width="100%" height="100%" fill="white"/>"#,
        escape(title)
    );
    for layer in layers {
        if layer.paths.is_empty() {
            continue;
        }
        if layer.filled {
            let d: String = layer.paths.iter().map(|o| path(o) + "Z ").collect();
            let _ = writeln!(
                svg,
                r#"<path fill-rule="evenodd" {} d="{}"/>"#,
                layer.style, d
            );
            continue;
        }
        let _ = writeln!(svg, r#"<g fill="none" {}>"#, layer.style);
        for o in &layer.paths {
            let _ = writeln!(svg, r#"<path d="{}"/>"#, path(o));
        }
        let _ = writeln!(svg, "</g>");
    }
    for m in marks.iter().take(2000) {
        let (x, y) = map(*m);
        let _ = writeln!(
            svg,
            r##"<circle cx="{x:.2}" cy="{y:.2}" r="2" fill="#d00"/>"##
        );
    }
    let _ = writeln!(
        svg,
        r##"<text x="10" y="16" font-family="sans-serif" font-size="12" fill="#333">{}</text>"##,
        escape(title)
    );
    svg.push_str("</svg>\n");
    svg
}

/// A hidden-line drawing as an SVG document: visible pieces solid black (silhouettes thicker
/// than boundaries), hidden pieces dashed grey, pieces whose visibility is not proven red.
pub fn hlr_svg(model: &Model, view: &View, h: &HiddenLines, title: &str) -> String {
    let proj = Projection::new(view, model);
    let image =
        |p: &HlrPiece| -> Vec<[f64; 2]> { p.points.iter().map(|&x| proj.project(x)).collect() };
    let pick = |f: &dyn Fn(&HlrPiece) -> bool| -> Vec<Vec<[f64; 2]>> {
        h.pieces.iter().filter(|p| f(p)).map(image).collect()
    };
    let layers = [
        Layer {
            style: r##"stroke="#9a9a9a" stroke-width="0.8" stroke-dasharray="4,3""##,
            paths: pick(&|p| p.qi.is_some_and(|q| q > 0)),
            filled: false,
        },
        Layer {
            style: r##"stroke="#000" stroke-width="1.0""##,
            paths: pick(&|p| {
                p.qi == Some(0) && !matches!(p.kind, LineKind::Silhouette | LineKind::Intersection)
            }),
            filled: false,
        },
        Layer {
            style: r##"stroke="#1a55c4" stroke-width="1.4""##,
            paths: pick(&|p| p.qi == Some(0) && p.kind == LineKind::Intersection),
            filled: false,
        },
        Layer {
            style: r##"stroke="#000" stroke-width="1.8""##,
            paths: pick(&|p| p.qi == Some(0) && p.kind == LineKind::Silhouette),
            filled: false,
        },
        Layer {
            style: r##"stroke="#d00" stroke-width="1.8""##,
            paths: pick(&|p| p.qi.is_none()),
            filled: false,
        },
    ];
    svg_document(title, &layers, &[])
}

/// Visible regions as an SVG document in the view plane: the proven-visible region of every
/// patch filled grey with its loops in black, and the unresolved cells filled red. (The
/// visible regions of different patches cannot overlap in the image.)
pub fn visible_svg(model: &Model, view: &View, r: &VisibleRegions, title: &str) -> String {
    let proj = Projection::new(view, model);
    let loops: Vec<Vec<[f64; 2]>> = r
        .patches
        .iter()
        .flat_map(|p| p.visible_loops.iter())
        .map(|l| l.xyz.iter().map(|&x| proj.project(x)).collect())
        .collect();
    let mut red = Vec::new();
    for p in &r.patches {
        let d = DrawPatch::new(&model.patches[p.patch].surface);
        for c in p.cells.iter().filter(|c| c.qi.is_none()) {
            let corners = [
                [c.lo[0], c.lo[1]],
                [c.hi[0], c.lo[1]],
                [c.hi[0], c.hi[1]],
                [c.lo[0], c.hi[1]],
            ];
            red.push(
                corners
                    .iter()
                    .map(|q| proj.project(d.eval(q[0], q[1])))
                    .collect(),
            );
        }
    }
    let closed = |mut v: Vec<[f64; 2]>| {
        if let Some(f) = v.first().copied() {
            v.push(f);
        }
        v
    };
    // The trimming curves, certified (blue) or not (orange, dashed).
    let trimming = |certified: bool| -> Vec<Vec<[f64; 2]>> {
        r.patches
            .iter()
            .flat_map(|p| &p.trimming)
            .filter(|c| c.certified == certified)
            .map(|c| c.xyz.iter().map(|&x| proj.project(x)).collect())
            .collect()
    };
    let layers = [
        Layer {
            style: r##"fill="#c9d3de" stroke="none""##,
            paths: loops.clone(),
            filled: true,
        },
        Layer {
            style: r##"fill="#e03030" stroke="none""##,
            paths: red,
            filled: true,
        },
        Layer {
            style: r##"stroke="#000" stroke-width="0.6""##,
            paths: loops.into_iter().map(closed).collect(),
            filled: false,
        },
        Layer {
            style: r##"stroke="#1f5fbf" stroke-width="1.1""##,
            paths: trimming(true),
            filled: false,
        },
        Layer {
            style: r##"stroke="#e08000" stroke-width="1.1" stroke-dasharray="3,2""##,
            paths: trimming(false),
            filled: false,
        },
    ];
    svg_document(title, &layers, &[])
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The silhouette curves as an OBJ polyline file: one `v x y z` per point and one `l` line per
/// curve (1-based indices; a closed curve repeats its first vertex at the end), with comment
/// lines stating what each curve's certification covers.
///
/// # Examples
/// ```
/// use limn::report::render::silhouette_obj;
/// use limn::analysis::contour::silhouette::silhouette;
/// use limn::analysis::view::View;
/// use limn::model::{Format, Model, WeldTolerance};
/// use limn::number::Rational;
/// use limn::solver::CurveOptions;
/// use limn::testing::shapes;
/// let m = Model::from_patches(Format::Json, shapes::sphere(&Rational::from(1)));
/// let view = View::Direction([1, 2, 3].map(Rational::from));
/// let s = silhouette(&m, &view, &limn::ContourOptions::new(CurveOptions::default(), WeldTolerance::Exact, Some(1e-3))).unwrap();
/// let obj = silhouette_obj(&s, "sphere");
/// assert_eq!(obj.lines().filter(|l| l.starts_with("l ")).count(), 1);
/// ```
pub fn silhouette_obj(s: &Silhouette, title: &str) -> String {
    let mut out = format!("# limn silhouette: {title}\n");
    if let Some(t) = s.tolerance {
        out += &format!("# tolerance {t} (model units)\n");
    }
    let mut next = 1usize;
    for (k, c) in s.curves.iter().enumerate() {
        out += &format!(
            "# curve {k}: {}, {}, patches {:?}{}\n",
            if c.closed { "closed" } else { "open" },
            if c.certified {
                "certified"
            } else if c.certified_topology {
                "topology certified"
            } else {
                "not certified"
            },
            c.patches,
            c.error_bound
                .map_or(String::new(), |e| format!(", error bound {e}")),
        );
        obj_polyline(&mut out, &mut next, &c.points, c.closed);
    }
    out
}

/// Appends one polyline to an OBJ text: its vertices (`next` is the index of the first one,
/// advanced past them) and, with two or more points, its `l` line (closed back to the first
/// point if `closed`).
pub(crate) fn obj_polyline(out: &mut String, next: &mut usize, points: &[[f64; 3]], closed: bool) {
    for p in points {
        *out += &format!("v {} {} {}\n", p[0], p[1], p[2]);
    }
    if points.len() > 1 {
        let mut line = String::from("l");
        for i in 0..points.len() {
            line += &format!(" {}", *next + i);
        }
        if closed {
            line += &format!(" {next}");
        }
        *out += &line;
        *out += "\n";
    }
    *next += points.len();
}

/// Unresolved items grouped by reason, one line each: how many, and on what (the first 12
/// keys, e.g. patches or pairs of patches).
pub(crate) fn reason_lines<'a, K: Ord + std::fmt::Display>(
    items: impl Iterator<Item = (&'a crate::Reason, K)>,
    what: &str,
) -> String {
    let mut reasons: std::collections::BTreeMap<String, (usize, std::collections::BTreeSet<K>)> =
        Default::default();
    for (reason, key) in items {
        let e = reasons.entry(reason.to_string()).or_default();
        e.0 += 1;
        e.1.insert(key);
    }
    let mut out = String::new();
    for (reason, (n, keys)) in reasons {
        let list: Vec<String> = keys.iter().take(12).map(|p| p.to_string()).collect();
        let more = if keys.len() > 12 {
            format!(" and {} more", keys.len() - 12)
        } else {
            String::new()
        };
        out += &format!(
            "  {n} boxes unresolved on {what} {}{more}: {reason}\n",
            list.join(", ")
        );
    }
    out
}

/// The work of a run of the curve solver, in the `stats` of the curve reports.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Work {
    /// Boxes examined by the curve solver.
    pub boxes: usize,
    /// Sign questions and box recomputations by the precision level that settled them (the
    /// same object in every report).
    pub escalations: Escalations,
    /// Unresolved boxes.
    pub unresolved: usize,
    /// Wall-clock milliseconds.
    pub ms: f64,
    /// Threads.
    pub threads: usize,
}

impl Work {
    /// The line that ends a report's text.
    pub fn line(&self) -> String {
        format!(
            "{} boxes, {} escalations, {:.1} ms on {} threads\n",
            self.boxes,
            self.escalations.escalated(),
            self.ms,
            self.threads
        )
    }
}

/// The verdict of a curve report's first line ("certified", or what is missing), and the
/// tolerance line that follows it when there is a bound (`extra`: more counts, each starting
/// with ", ").
pub(crate) fn verdict_lines(
    certified: bool,
    unresolved: usize,
    incomplete: usize,
    extra: &str,
    tolerance: Option<f64>,
    error_bound: Option<f64>,
) -> (String, String) {
    let verdict = if certified {
        "certified".to_string()
    } else {
        format!(
            "NOT fully certified: {unresolved} unresolved boxes, {incomplete} incomplete curves{extra}{}",
            match (tolerance, error_bound) {
                (Some(t), Some(e)) if e > t => format!(", error bound {e:.3e} above the tolerance"),
                (Some(_), None) => ", no error bound".to_string(),
                _ => String::new(),
            }
        )
    };
    let bound = match (tolerance, error_bound) {
        (Some(t), Some(e)) => format!("tolerance {t:.3e}, proven error bound {e:.3e}\n"),
        _ => String::new(),
    };
    (verdict, bound)
}

/// The dashed red style of curves that are not complete.
pub(crate) const INCOMPLETE_STYLE: &str =
    r##"stroke="#d00" stroke-width="1.6" stroke-dasharray="6,3""##;

/// Polylines in space, each with whether it is closed.
pub(crate) type SpaceLines<'a> = Vec<(&'a [[f64; 3]], bool)>;

/// Polylines in space drawn along a view direction over the patches' sides in grey: each layer
/// a style and its polylines (closed ones joined back to their first point), and red marks at
/// the given points.
pub(crate) fn curves_svg(
    model: &Model,
    view: &View,
    title: &str,
    layers: Vec<(&'static str, SpaceLines)>,
    marks: &[[f64; 3]],
) -> String {
    let proj = Projection::new(view, model);
    let draw = draw_patches(model);
    let mut all = vec![outline_layer(&draw, &proj)];
    for (style, lines) in layers {
        let paths = lines
            .into_iter()
            .map(|(points, closed)| {
                let mut p: Vec<[f64; 2]> = points.iter().map(|x| proj.project(*x)).collect();
                if closed {
                    if let Some(f) = p.first().copied() {
                        p.push(f);
                    }
                }
                p
            })
            .collect();
        all.push(Layer {
            style,
            paths,
            filled: false,
        });
    }
    let marks: Vec<[f64; 2]> = marks.iter().map(|m| proj.project(*m)).collect();
    svg_document(title, &all, &marks)
}

/// The items of one list field of every element, in order (the per-patch or per-pair lists of
/// a report, flattened).
pub(crate) fn gather<T, U: Clone>(items: &[T], field: impl Fn(&T) -> &[U]) -> Vec<U> {
    items
        .iter()
        .flat_map(|x| field(x).iter().cloned())
        .collect()
}
