//! The 1991 teaset archive format (Juhana Kouhia): a patch count; per patch one line of 16
//! one-based vertex indices (a bicubic patch, row by row); a vertex count; per vertex a line
//! `x,y,z`.

use super::text::Tokens;
use super::ReadError;
use crate::model::{Format, Model};
use crate::number::Rational;
use crate::surface::RationalPatch;

pub(super) fn read(name: &str, text: &str) -> Result<Model, ReadError> {
    let mut t = Tokens::new(name, text, &[',']);
    let count = t.count("the patch count", super::bpt::MAX_PATCHES)?;
    let mut indices = Vec::with_capacity(count.min(4096));
    for k in 0..count {
        let line = t.line();
        let mut idx = [0usize; 16];
        for (p, slot) in idx.iter_mut().enumerate() {
            if !t.at_end() && t.line() != line {
                return Err(t.error(
                    line,
                    format!("patch {k}: the line has {p} vertex indices, expected 16"),
                ));
            }
            *slot = t.count(&format!("patch {k}: vertex index {p}"), usize::MAX)?;
        }
        if !t.at_end() && t.line() == line {
            return Err(t.error(
                line,
                format!("patch {k}: the line has more than 16 vertex indices"),
            ));
        }
        indices.push((line, idx));
    }
    let nv = t.count("the vertex count", 100_000_000)?;
    let mut vertices = Vec::with_capacity(nv.min(1 << 16));
    for v in 0..nv {
        let what = format!("vertex {}", v + 1);
        let line = t.line();
        let mut xyz: [Rational; 3] = Default::default();
        for (c, slot) in xyz.iter_mut().enumerate() {
            if !t.at_end() && t.line() != line {
                return Err(t.error(
                    line,
                    format!("{what}: the line has {c} coordinates, expected 3 (x,y,z)"),
                ));
            }
            *slot = t.number(&what)?;
        }
        if !t.at_end() && t.line() == line {
            return Err(t.error(
                line,
                format!("{what}: the line has more than 3 coordinates (x,y,z)"),
            ));
        }
        vertices.push(xyz);
    }
    t.finish(&format!("the {nv} vertices the file declares"))?;
    let mut patches = Vec::with_capacity(count);
    for (k, (line, idx)) in indices.into_iter().enumerate() {
        let mut pts = Vec::with_capacity(16);
        for &i in &idx {
            if i == 0 || i > nv {
                return Err(t.error(
                    line,
                    format!("patch {k}: vertex index {i} is out of range 1..={nv}"),
                ));
            }
            pts.push(vertices[i - 1].clone());
        }
        patches.push(
            RationalPatch::polynomial([3, 3], pts)
                .map_err(|e| t.error(line, format!("patch {k}: {e}")))?,
        );
    }
    Ok(Model::from_patches(Format::Teaset, patches))
}
