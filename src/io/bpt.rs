//! Newell's `.bpt` format: a patch count; per patch a line `m n` (degrees) and then
//! (m+1)(n+1) points `x y z`, row by row (i along u, j along v).

use super::text::Tokens;
use super::ReadError;
use crate::model::{Format, Model};
use crate::surface::{RationalPatch, MAX_PATCH_DEGREE};

/// The most patches one file may declare.
pub(super) const MAX_PATCHES: usize = 1_000_000;

pub(super) fn read(name: &str, text: &str) -> Result<Model, ReadError> {
    let mut t = Tokens::new(name, text, &[]);
    let count = t.count("the patch count", MAX_PATCHES)?;
    let mut patches = Vec::with_capacity(count.min(4096));
    for k in 0..count {
        let line = t.line();
        let m = t.count(&format!("patch {k}: degree in u"), MAX_PATCH_DEGREE)?;
        let n = t.count(&format!("patch {k}: degree in v"), MAX_PATCH_DEGREE)?;
        let mut pts = Vec::with_capacity((m + 1) * (n + 1));
        for p in 0..(m + 1) * (n + 1) {
            let what = format!("patch {k}: point {p}");
            pts.push([t.number(&what)?, t.number(&what)?, t.number(&what)?]);
        }
        let patch = RationalPatch::polynomial([m, n], pts)
            .map_err(|e| t.error(line, format!("patch {k}: {e}")))?;
        patches.push(patch);
    }
    t.finish(&format!("the {count} patches the file declares"))?;
    Ok(Model::from_patches(Format::Bpt, patches))
}
