//! IGES trimmed surfaces (144) and their curves on the surface (142): faces whose loops are
//! the parameter-space curves the file gives. A 142 without a parameter-space curve would need
//! its model-space curve inverted onto the surface, which limn does not do yet: that face is
//! used untrimmed and the reason reported.

use super::curve::CurveFailure;
use super::Reader;
use crate::io::trimmed::SurfaceInfo;
use crate::io::ReadError;
use crate::model::{Closing, Face, TrimLoop};
use crate::surface::ParameterCurve;

impl Reader<'_> {
    /// The parameter-space curves of a 142 entity (its type checked by the caller) on surface
    /// `surface`.
    fn curve_on_surface(
        &mut self,
        de: usize,
        surface: usize,
    ) -> Result<Vec<ParameterCurve>, CurveFailure> {
        let f = self.fields(de)?;
        let s = self
            .pointer_at(de, &f, 1, "SPTR (surface)", false)?
            .expect("required");
        if s != surface {
            return Err(self
                .entity_err(
                    de,
                    format!("the curve lies on the surface at directory entry {s}, not on the trimmed surface at {surface}"),
                )
                .into());
        }
        match self.pointer_at(de, &f, 2, "BPTR (parameter-space curve)", true)? {
            Some(b) => self.read_parameter_curve(b),
            None => Err(CurveFailure::Unsupported(format!(
                "the curve on surface at directory entry {de} has no parameter-space curve, and inverting its model-space curve onto the surface is not built yet"
            ))),
        }
    }

    /// A loop of the 142 entity `de`, closed as `closing` allows.
    pub(super) fn trim_loop(
        &mut self,
        de: usize,
        surface: usize,
        closing: &Closing,
    ) -> Result<TrimLoop, CurveFailure> {
        let curves = self.curve_on_surface(de, surface)?;
        TrimLoop::close(
            curves.into_iter().map(|c| (c, None)).collect(),
            closing,
            Some(de),
        )
        .map_err(|e| self.entity_err(de, format!("trimming loop: {e}")).into())
    }

    /// The face of a 144 entity on the surface at directory entry `surface`: `Ok(Err(why))`
    /// when a loop uses curves limn does not read.
    pub(super) fn trimmed_surface(
        &mut self,
        de: usize,
        surface: usize,
        info: &SurfaceInfo,
    ) -> Result<Result<Face, String>, ReadError> {
        let f = self.fields(de)?;
        let n1 = self.count(de, &f, 1, "N1 (outer boundary flag)", 1)?;
        let n2 = self.count(de, &f, 2, "N2 (number of inner boundaries)", 100_000)?;
        let closing = info.closing();
        let read = |r: &mut Self, k: usize, what: &str| -> Result<Option<TrimLoop>, CurveFailure> {
            match r.pointer_at(de, &f, k, what, n1 == 0 && k == 3)? {
                None => Ok(None),
                Some(p) => {
                    r.expect_kind(de, p, 142, what, "a curve on a surface")?;
                    r.trim_loop(p, surface, &closing).map(Some)
                }
            }
        };
        let mut loops = Vec::with_capacity(n2 + 1);
        for k in 3..4 + n2 {
            let what = if k == 3 {
                "PTO (outer boundary)".to_string()
            } else {
                format!("PTI{} (inner boundary)", k - 3)
            };
            match read(self, k, &what) {
                Ok(l) => loops.push(l),
                Err(CurveFailure::Malformed(e)) => return Err(e),
                Err(CurveFailure::Unsupported(why)) => return Ok(Err(why)),
            }
        }
        let mut loops = loops.into_iter();
        let outer = if n1 == 0 {
            loops.next();
            None
        } else {
            loops.next().flatten()
        };
        Ok(Ok(Face {
            surface: info.index,
            entity: Some(de),
            domain: info.domain.clone(),
            outer,
            inner: loops.flatten().collect(),
        }))
    }
}
