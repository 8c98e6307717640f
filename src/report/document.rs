//! One trait for every report: the documents a command writes from it (JSON, text, SVG,
//! OBJ), so that each command is "run, report, write".

use crate::analysis::contour::curves::Silhouette;
use crate::analysis::events::Events;
use crate::analysis::view::View;
use crate::analysis::visibility::hlr::HiddenLines;
use crate::analysis::visibility::visible::VisibleRegions;
use crate::model::Model;
use crate::report::events::{events_svg, EventsReport};
use crate::report::hlr::HlrReport;
use crate::report::render::{hlr_svg, silhouette_obj, silhouette_svg, visible_svg};
use crate::report::silhouette::SilhouetteReport;
use crate::report::visible::VisibleReport;

/// The kinds of document.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// A human-readable summary.
    Text,
    /// The JSON report (pretty-printed, with a final newline).
    Json,
    /// A drawing along the view.
    Svg,
    /// Polylines in Wavefront OBJ.
    Obj,
}

/// A report as the documents it can be written as.
pub trait Document {
    /// The JSON document (pretty-printed, with a final newline).
    fn json(&self) -> serde_json::Result<String>;
    /// A short human-readable summary.
    fn text(&self) -> String;
    /// The drawing along `view`, if the report has one.
    fn svg(&self, model: &Model, view: &View) -> Option<String>;
    /// The curves as OBJ polylines, if the report has curves.
    fn obj(&self) -> Option<String> {
        None
    }
    /// The document in `format`; `None` if the report is not offered in it.
    fn render(
        &self,
        format: Format,
        model: &Model,
        view: &View,
    ) -> Option<serde_json::Result<String>> {
        match format {
            Format::Json => Some(self.json()),
            Format::Text => Some(Ok(self.text())),
            Format::Svg => self.svg(model, view).map(Ok),
            Format::Obj => self.obj().map(Ok),
        }
    }
}

/// Pretty JSON with a final newline.
pub fn pretty(report: &impl serde::Serialize) -> serde_json::Result<String> {
    serde_json::to_string_pretty(report).map(|s| s + "\n")
}

/// `json` and `text` of a [`WithResult`]: its report's.
macro_rules! report_parts {
    () => {
        fn json(&self) -> serde_json::Result<String> {
            pretty(&self.report)
        }
        fn text(&self) -> String {
            self.report.text()
        }
    };
}

/// A report with the result it was made from, which its drawing needs (every unresolved
/// box, every cell: more than the JSON holds).
#[derive(Debug)]
pub struct WithResult<'a, R, A> {
    /// The report.
    pub report: R,
    /// The result.
    pub result: &'a A,
}

impl Document for WithResult<'_, SilhouetteReport, Silhouette> {
    report_parts!();
    fn svg(&self, model: &Model, view: &View) -> Option<String> {
        let r = &self.report;
        let title = format!(
            "{}: {} {} curves ({}), {} unresolved regions",
            r.model,
            r.curves.len(),
            r.kind,
            if r.certified {
                "certified"
            } else if r.topology_certified {
                "topology certified"
            } else {
                "topology NOT fully certified"
            },
            r.unresolved.len()
        );
        Some(silhouette_svg(model, view, self.result, &title))
    }
    fn obj(&self) -> Option<String> {
        Some(silhouette_obj(self.result, &self.report.model))
    }
}

impl Document for WithResult<'_, HlrReport, HiddenLines> {
    report_parts!();
    fn svg(&self, model: &Model, view: &View) -> Option<String> {
        let r = &self.report;
        let mut caveats = Vec::new();
        if model.left_out > 0 {
            caveats.push(format!(
                "{} surfaces or faces of the file left out",
                model.left_out
            ));
        }
        if model.placements_ignored > 0 {
            caveats.push("an assembly, parts not placed".to_string());
        }
        let left_out = if caveats.is_empty() {
            String::new()
        } else {
            format!(" ({})", caveats.join("; "))
        };
        let title = format!(
            "{}{left_out}: hidden lines, {} pieces, {}",
            r.model,
            r.pieces.len(),
            if r.certified {
                "visibility certified".to_string()
            } else {
                format!("{} pieces unresolved (red)", r.unresolved.len())
            }
        );
        Some(hlr_svg(model, view, self.result, &title))
    }
}

impl Document for WithResult<'_, VisibleReport, VisibleRegions> {
    report_parts!();
    fn svg(&self, model: &Model, view: &View) -> Option<String> {
        let r = self.result;
        let title = format!(
            "{}: visible regions, area share [{:.4}, {:.4}]{}",
            self.report.model,
            r.area_fraction[0],
            r.area_fraction[1],
            if self.report.certified {
                ""
            } else {
                ", unresolved cells red"
            }
        );
        Some(visible_svg(model, view, r, &title))
    }
}

impl Document for WithResult<'_, EventsReport, Events> {
    report_parts!();
    /// On the viewing sphere: the view is not used.
    fn svg(&self, _: &Model, _: &View) -> Option<String> {
        let title = format!(
            "{}: {} event curves on the viewing sphere (parabolic blue, flecnodal green, bitangent orange; dashed: not certified)",
            self.report.model,
            self.result.curves.len()
        );
        Some(events_svg(self.result, &title))
    }
}

/// Implements [`Document`] by the report's own methods `text`, `svg` and `obj`.
macro_rules! curve_document {
    ($t:ty) => {
        impl $crate::report::document::Document for $t {
            fn json(&self) -> serde_json::Result<String> {
                $crate::report::document::pretty(self)
            }
            fn text(&self) -> String {
                <$t>::text(self)
            }
            fn svg(
                &self,
                model: &$crate::model::Model,
                view: &$crate::analysis::view::View,
            ) -> Option<String> {
                Some(<$t>::svg(self, model, view))
            }
            fn obj(&self) -> Option<String> {
                Some(<$t>::obj(self))
            }
        }
    };
}
pub(crate) use curve_document;
