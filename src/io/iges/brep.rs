//! IGES B-rep entities: manifold solid (186), shell (514), face (510), loop (508), edge list
//! (504) and vertex list (502). The topology (which loops share which edges, the vertices,
//! the shells) is read whole; a face becomes a trimmed face when every edge of its loops has a
//! parameter-space curve in the loop (508's PSCPT) or its model-space curve (504's CURV) can be
//! inverted onto the surface within a proven bound (`proofs/edge-inversion.md`); otherwise it
//! is used untrimmed and the reason is reported.

use super::curve::CurveFailure;
use super::Reader;
use crate::io::trimmed::{inverted_edge, SurfaceInfo};
use crate::io::ReadError;
use crate::model::{BrepEdge, Face, TrimLoop};
use crate::surface::{ModelCurve, ParameterCurve, Point3};
use std::collections::{BTreeMap, BTreeSet};

/// A vertex: its vertex list (502) and its index in the list.
type VertexKey = (usize, usize);

/// The topology collected while faces are read.
#[derive(Default)]
pub(super) struct BrepBuilder {
    /// Edges by (edge list, index): their place in `uses`.
    edge_index: BTreeMap<(usize, usize), usize>,
    /// Per edge, in the order first met: (edge list, index), the uses and the end vertices.
    uses: Vec<((usize, usize), usize, [Point3; 2])>,
    /// Vertices by (vertex list, index).
    vertices: BTreeSet<VertexKey>,
    pub(super) faces: usize,
    pub(super) loops: usize,
    pub(super) inner_loops: usize,
}

impl BrepBuilder {
    /// The B-rep, given the number of shells.
    pub(super) fn finish(self, shells: usize) -> crate::model::Brep {
        crate::model::Brep {
            vertices: self.vertices.len(),
            edges: self
                .uses
                .into_iter()
                .map(|((list, index), uses, ends)| BrepEdge {
                    list,
                    index,
                    uses,
                    ends,
                })
                .collect(),
            faces: self.faces,
            loops: self.loops,
            inner_loops: self.inner_loops,
            shells,
        }
    }

    /// Counts a use of an edge with end vertices `ends`; its index in
    /// [`crate::model::Brep::edges`].
    fn use_edge(&mut self, key: (usize, usize), ends: [Point3; 2]) -> usize {
        let next = self.uses.len();
        let i = *self.edge_index.entry(key).or_insert(next);
        if i == next {
            self.uses.push((key, 0, ends));
        }
        self.uses[i].1 += 1;
        i
    }
}

impl Reader<'_> {
    /// Edge `index` (1-based) of the edge list `list`: its two vertices (list, index) and
    /// their points.
    fn edge_vertices(
        &self,
        from: usize,
        list: usize,
        index: usize,
    ) -> Result<[(VertexKey, Point3); 2], ReadError> {
        self.expect_kind(from, list, 504, "EDGE", "an edge list")?;
        let f = self.fields(list)?;
        let n = self.count(list, &f, 0, "N (number of edges)", 1_000_000)?;
        if index == 0 || index > n {
            return Err(self.entity_err(
                from,
                format!("edge {index} of the edge list at directory entry {list}, which has {n}"),
            ));
        }
        let at = 1 + 5 * (index - 1);
        let vertex = |k: usize, what: &str| -> Result<(VertexKey, Point3), ReadError> {
            let what = format!("edge {index}: {what}");
            let field = format!("{what} vertex list");
            let v = self
                .pointer_at(list, &f, at + k, &field, false)?
                .expect("required");
            self.expect_kind(list, v, 502, &field, "a vertex list")?;
            let i = self.count(
                list,
                &f,
                at + k + 1,
                &format!("{what} vertex index"),
                1_000_000,
            )?;
            let g = self.fields(v)?;
            let count = self.count(v, &g, 0, "N (number of vertices)", 1_000_000)?;
            if i == 0 || i > count {
                return Err(self.entity_err(
                    list,
                    format!("{what} vertex {i} of the vertex list at directory entry {v}, which has {count}"),
                ));
            }
            let mut at = 1 + 3 * (i - 1);
            let c = self.numbers(v, &g, &mut at, 3, &format!("vertex {i} coordinate"))?;
            Ok(((v, i), [c[0].clone(), c[1].clone(), c[2].clone()]))
        };
        Ok([vertex(1, "start")?, vertex(3, "end")?])
    }

    /// The model-space curve (CURV) of edge `index` of the edge list `list`, as exact Bézier
    /// pieces in its direction.
    fn edge_curve(
        &mut self,
        list: usize,
        index: usize,
    ) -> Result<Result<Vec<ModelCurve>, String>, ReadError> {
        let f = self.fields(list)?;
        let field = format!("edge {index}: CURV");
        let curve = self
            .pointer_at(list, &f, 1 + 5 * (index - 1), &field, false)?
            .expect("required");
        match self.read_curve(curve) {
            Ok(c) if !c.is_empty() => Ok(Ok(c)),
            Ok(_) => Ok(Err(format!("the curve of edge {index} of the edge list at directory entry {list} has no pieces"))),
            Err(CurveFailure::Malformed(e)) => Err(e),
            Err(CurveFailure::Unsupported(why)) => Ok(Err(why)),
        }
    }

    /// A loop (508) of a face: its edges counted in `brep`, and its
    /// parameter-space curves as a closed loop when every edge has one (read from the file,
    /// or inverted from its model-space curve).
    fn brep_loop(
        &mut self,
        de: usize,
        info: Option<&SurfaceInfo>,
        brep: &mut BrepBuilder,
    ) -> Result<Result<TrimLoop, String>, ReadError> {
        let closing = info.map(SurfaceInfo::closing);
        let closing = closing.as_ref();
        let mut inverted = 0;
        let mut inversion_distance: f64 = 0.0;
        let f = self.fields(de)?;
        let n = self.count(de, &f, 0, "N (number of edges)", 1_000_000)?;
        let mut at = 1;
        let mut curves: Vec<(ParameterCurve, Option<usize>)> = Vec::new();
        let mut missing: Option<String> = None;
        for e in 1..=n {
            let what = |s: &str| format!("edge {e}: {s}");
            let kind = self.count(de, &f, at, &what("TYPE"), 1)?;
            let list = self
                .pointer_at(de, &f, at + 1, &what("EDGE (list)"), false)?
                .expect("required");
            let index = self.count(de, &f, at + 2, &what("NDX"), 1_000_000)?;
            // OF orients the model-space edge in the loop; the parameter-space curves are
            // written in the loop's direction already (so the fixtures' loops close).
            let forward = self.count(de, &f, at + 3, &what("OF (orientation)"), 1)? == 1;
            let k = self.count(de, &f, at + 4, &what("K (parameter-space curves)"), 1_000)?;
            let pscpt: Vec<usize> = (0..k)
                .map(|j| {
                    self.pointer_at(de, &f, at + 6 + 2 * j, &what("PSCPT"), false)
                        .map(|p| p.expect("required"))
                })
                .collect::<Result<_, _>>()?;
            at += 5 + 2 * k;
            if kind == 1 {
                // A vertex loop (a degenerate edge): its vertex is the whole loop.
                continue;
            }
            let [a, b] = self.edge_vertices(de, list, index)?;
            brep.vertices.insert(a.0);
            brep.vertices.insert(b.0);
            let ends = [a.1.clone(), b.1.clone()];
            let edge = brep.use_edge((list, index), [a.1, b.1]);
            let Some(info) = info else {
                continue;
            };
            if k == 0 {
                if missing.is_some() {
                    continue;
                }
                let edge_curve = match self.edge_curve(list, index)? {
                    Ok(c) => match run_between(c, &ends) {
                        Ok(c) => c,
                        Err(why) => {
                            missing = Some(format!("the curve of edge {index} of the edge list at directory entry {list} {why}"));
                            continue;
                        }
                    },
                    Err(why) => {
                        missing = Some(why);
                        continue;
                    }
                };
                let name = format!("edge {index} of the edge list at directory entry {list}");
                match inverted_edge(info, &edge_curve, self.resolution.as_ref(), &name) {
                    Ok((mut pieces, d)) => {
                        if !forward {
                            pieces.reverse();
                            pieces = pieces.iter().map(ParameterCurve::reversed).collect();
                        }
                        inverted += pieces.len();
                        inversion_distance = inversion_distance.max(d);
                        curves.extend(pieces.into_iter().map(|c| (c, Some(edge))));
                    }
                    Err(why) => missing = Some(why),
                }
                continue;
            }
            let mut pieces = Vec::new();
            for p in pscpt {
                match self.read_parameter_curve(p) {
                    Ok(c) => pieces.extend(c),
                    Err(CurveFailure::Malformed(e)) => return Err(e),
                    Err(CurveFailure::Unsupported(why)) => {
                        missing.get_or_insert(why);
                    }
                }
            }
            curves.extend(pieces.into_iter().map(|c| (c, Some(edge))));
        }
        if let Some(why) = missing {
            return Ok(Err(why));
        }
        let Some(closing) = closing else {
            return Ok(Err("its surface is skipped".to_string()));
        };
        match TrimLoop::close(curves, closing, Some(de)) {
            Ok(mut l) => {
                l.inverted_curves = inverted;
                l.inversion_distance = inversion_distance;
                Ok(Ok(l))
            }
            // Inverted curves are limn's, not the file's: a loop of them that does not close
            // leaves the face untrimmed, it does not make the file unreadable.
            Err(e) if inverted > 0 => Ok(Err(format!(
                "the loop at directory entry {de}, with edges inverted onto the surface, does not close: {e}"
            ))),
            Err(e) => Err(self.entity_err(de, format!("loop: {e}"))),
        }
    }

    /// The face of a 510 entity on a surface; with none (a surface limn skips), its loops are
    /// only counted in `brep`.
    pub(super) fn brep_face(
        &mut self,
        de: usize,
        info: Option<&SurfaceInfo>,
        brep: &mut BrepBuilder,
    ) -> Result<Result<Face, String>, ReadError> {
        let f = self.fields(de)?;
        let n = self.count(de, &f, 1, "N (number of loops)", 100_000)?;
        let outer_flag = self.count(de, &f, 2, "OF (outer loop flag)", 1)? == 1;
        brep.faces += 1;
        let mut loops = Vec::with_capacity(n);
        let mut why = None;
        for k in 0..n {
            let what = format!("loop {}", k + 1);
            let l = self
                .pointer_at(de, &f, 3 + k, &what, false)?
                .expect("required");
            self.expect_kind(de, l, 508, &what, "a loop")?;
            brep.loops += 1;
            if k > 0 {
                brep.inner_loops += 1;
            }
            match self.brep_loop(l, info, brep)? {
                Ok(l) => loops.push(l),
                Err(w) => {
                    why.get_or_insert(w);
                }
            }
        }
        if let Some(w) = why {
            return Ok(Err(w));
        }
        let Some(info) = info else {
            return Ok(Err("its surface is skipped".to_string()));
        };
        let mut loops = loops.into_iter();
        let outer = if outer_flag { loops.next() } else { None };
        Ok(Ok(Face {
            surface: info.index,
            entity: Some(de),
            domain: info.domain.clone(),
            outer,
            inner: loops.collect(),
        }))
    }
}

/// The curve of an edge directed from its start vertex to its end vertex: IGES 504 defines the
/// edge as the part of its curve between them, and some writers give the curve the other way
/// round. `Err` when neither direction puts its ends within 1e-4 of the curve's size (the
/// box of its control points) of the vertices.
fn run_between(curve: Vec<ModelCurve>, ends: &[Point3; 2]) -> Result<Vec<ModelCurve>, String> {
    let f = |p: &[crate::number::Rational]| [p[0].to_f64(), p[1].to_f64(), p[2].to_f64()];
    let gap = |p: [f64; 3], q: &Point3| {
        let q = f(q);
        (0..3).map(|k| (p[k] - q[k]).abs()).fold(0.0, f64::max)
    };
    let (Some(first), Some(last)) = (curve.first(), curve.last()) else {
        return Err("has no pieces".into());
    };
    let (start, end) = (f(&first.start()), f(&last.end()));
    // The size of the curve: the largest side of the box of its control points.
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in curve.iter().flat_map(|c| c.points()) {
        for (k, x) in f(&p).into_iter().enumerate() {
            lo[k] = lo[k].min(x);
            hi[k] = hi[k].max(x);
        }
    }
    let size = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
    let forward = gap(start, &ends[0]).max(gap(end, &ends[1]));
    let backward = gap(start, &ends[1]).max(gap(end, &ends[0]));
    let tolerance = 1e-4 * size.max(f64::MIN_POSITIVE);
    if forward <= backward && forward <= tolerance {
        Ok(curve)
    } else if backward <= tolerance {
        Ok(curve.iter().rev().map(ModelCurve::reversed).collect())
    } else {
        Err(format!(
            "does not run between its vertices (its ends are {:.3e} from them)",
            forward.min(backward)
        ))
    }
}
