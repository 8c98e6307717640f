//! Wavefront OBJ meshes: `v x y z [w]` and `f i j k ...` (indices `i`, `i/t`, `i//n`, `i/t/n`,
//! one-based, negative meaning relative to the end). Other statements (`vt`, `vn`, `g`, `o`,
//! `s`, `usemtl`, `mtllib`, `l`, `#`) are ignored.

use super::{Place, ReadError};
use crate::model::{Format, Model};
use crate::number::parse_exact;
use crate::surface::Mesh;

pub(super) fn read(name: &str, text: &str) -> Result<Model, ReadError> {
    let err = |line: usize, msg: String| ReadError::new(name, Place::Line(line), msg);
    let mut mesh = Mesh::default();
    let mut face_lines = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let content = raw.split('#').next().unwrap_or("");
        let mut words = content.split_whitespace();
        match words.next() {
            Some("v") => {
                let coords: Vec<&str> = words.collect();
                if coords.len() < 3 || coords.len() > 4 {
                    return Err(err(
                        line,
                        format!(
                            "a vertex needs 3 coordinates (4 with w), found {}",
                            coords.len()
                        ),
                    ));
                }
                let mut p = Vec::with_capacity(3);
                for c in &coords {
                    p.push(
                        parse_exact(c).map_err(|e| err(line, format!("vertex coordinate: {e}")))?,
                    );
                }
                if coords.len() == 4 {
                    let w = p.pop().expect("four values");
                    if w.cmp0() != std::cmp::Ordering::Greater {
                        return Err(err(line, format!("vertex weight {w} must be positive")));
                    }
                    for c in &mut p {
                        *c /= &w;
                    }
                }
                let [x, y, z]: [_; 3] = p.try_into().expect("three values");
                mesh.vertices.push([x, y, z]);
            }
            Some("f") => {
                let mut face = Vec::new();
                for w in words {
                    let idx = w.split('/').next().unwrap_or("");
                    let k: i64 = idx
                        .parse()
                        .map_err(|_| err(line, format!("face vertex {w:?} is not an index")))?;
                    face.push(k);
                }
                if face.len() < 3 {
                    return Err(err(
                        line,
                        format!("a face needs at least 3 vertices, found {}", face.len()),
                    ));
                }
                // Negative indices count back from the vertices defined so far (OBJ spec).
                face_lines.push((line, face, mesh.vertices.len() as i64));
            }
            _ => {}
        }
    }
    let n = mesh.vertices.len() as i64;
    for (line, face, so_far) in face_lines {
        let mut f = Vec::with_capacity(face.len());
        for k in face {
            let i = if k > 0 { k - 1 } else { so_far + k };
            if k == 0 || i < 0 || i >= n {
                return Err(err(
                    line,
                    format!("face vertex index {k} is out of range (the file has {n} vertices)"),
                ));
            }
            f.push(i as usize);
        }
        mesh.faces.push(f);
    }
    if mesh.faces.is_empty() {
        return Err(ReadError::new(
            name,
            Place::File,
            "no faces: an OBJ model needs `f` lines",
        ));
    }
    let mut model = Model::from_patches(Format::Obj, Vec::new());
    model.meshes.push(mesh);
    Ok(model)
}
