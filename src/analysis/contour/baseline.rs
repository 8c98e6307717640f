//! The uncertified float silhouettes of paper 002: the Mesh Method and the Srf-Node Method.
//!
//! Both classify the nodes of a grid in parameter space by a sign, run marching squares, place
//! a point on each grid edge whose ends differ in sign by linear interpolation, and refine it by
//! the secant method on the true silhouette function along that edge. They differ in the sign:
//!
//! - **Srf-Node**: the sign of `g` at the parameter values `(i/m, j/n)` of the control points.
//! - **Mesh**: the sign of `n·V` (or `n·(E − P)`) with `n` the control-mesh normal at control
//!   point (i, j), the sum of the up to four cross products of the adjacent mesh edges.
//!
//! Everything is f64 and nothing is proven: these are the fast pipelines limn is an oracle
//! for. A loop smaller than a grid cell is missed, and a saddle cell is connected by guess.

use crate::analysis::contour::silhouette::silhouette_function;

use crate::surface::DrawPatch;

use crate::analysis::contour::curves::SilhouetteCurve;

use crate::analysis::view::View;
use crate::bernstein::Bernstein;
use crate::geometry::vec3::{cross, dot, sub};
use crate::model::Model;
use crate::number::Precision;
use crate::surface::RationalPatch;
use std::collections::BTreeMap;

/// A grid node (i, j).
type Node = (usize, usize);

/// Which float method.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum BaselineMethod {
    /// Signs from control-mesh normals.
    Mesh,
    /// Signs of the silhouette function at the control points' parameter values.
    SrfNode,
}

/// The node values of the grid (m+1) × (n+1) for one patch.
fn node_values(
    patch: &RationalPatch,
    g: &Bernstein<f64>,
    view: &View,
    method: BaselineMethod,
) -> Vec<Vec<f64>> {
    let [m, n] = patch.degree();
    let pt = |i: usize, j: usize| -> [f64; 3] { patch.point(i, j).clone().map(|c| c.to_f64()) };
    (0..=m)
        .map(|i| {
            (0..=n)
                .map(|j| match method {
                    BaselineMethod::SrfNode => {
                        g.eval(&[i as f64 / m.max(1) as f64, j as f64 / n.max(1) as f64])
                    }
                    BaselineMethod::Mesh => {
                        // Sum of the cross products of consecutive mesh edges around (i, j),
                        // oriented like S_u × S_v.
                        let p = pt(i, j);
                        let mut normal = [0.0; 3];
                        for (di, dj) in [(1i64, 1i64), (-1, 1), (-1, -1), (1, -1)] {
                            let (a, b) = (i as i64 + di, j as i64 + dj);
                            if a < 0 || b < 0 || a > m as i64 || b > n as i64 {
                                continue;
                            }
                            let eu = sub(pt(a as usize, j), p);
                            let ev = sub(pt(i, b as usize), p);
                            let c = cross(eu, ev);
                            // (di, dj) flips the orientation once per negative step.
                            let s = (di * dj) as f64;
                            normal = [
                                normal[0] + s * c[0],
                                normal[1] + s * c[1],
                                normal[2] + s * c[2],
                            ];
                        }
                        match view {
                            View::Direction(d) => dot(
                                normal,
                                crate::analysis::view::working_direction(d).map(|c| c.to_f64()),
                            ),
                            View::Eye(e) => dot(normal, sub(e.clone().map(|c| c.to_f64()), p)),
                        }
                    }
                })
                .collect()
        })
        .collect()
}

/// The silhouette of a model by a float method, patch by patch (curves are not joined across
/// patches, as in the paper).
pub fn baseline_silhouette(
    model: &Model,
    view: &View,
    method: BaselineMethod,
) -> Vec<SilhouetteCurve> {
    let mut curves = Vec::new();
    for (pi, mp) in model.patches.iter().enumerate() {
        let patch = &mp.surface;
        let g: Bernstein<f64> = silhouette_function(patch, view).convert(Precision::F64);
        let vals = node_values(patch, &g, view, method);
        let [m, n] = patch.degree();
        let (m, n) = (m.max(1), n.max(1));
        let uv = |i: usize, j: usize| [i as f64 / m as f64, j as f64 / n as f64];
        // A point on each grid edge whose end values differ in sign, keyed by the edge.
        let mut edge_point: BTreeMap<(Node, Node), [f64; 2]> = BTreeMap::new();
        let mut point_on = |a: (usize, usize), b: (usize, usize)| -> Option<[f64; 2]> {
            let (va, vb) = (vals[a.0][a.1], vals[b.0][b.1]);
            if (va > 0.0) == (vb > 0.0) {
                return None;
            }
            let key = if a < b { (a, b) } else { (b, a) };
            Some(*edge_point.entry(key).or_insert_with(|| {
                let (pa, pb) = (uv(a.0, a.1), uv(b.0, b.1));
                let lerp = |t: f64| [pa[0] + (pb[0] - pa[0]) * t, pa[1] + (pb[1] - pa[1]) * t];
                let t0 = va / (va - vb);
                // Secant refinement on the true g along the edge, when g changes sign on it.
                let (ga, gb) = (g.eval(&pa), g.eval(&pb));
                if (ga > 0.0) == (gb > 0.0) {
                    return lerp(t0);
                }
                let (mut x0, mut x1, mut f0, mut f1) = (0.0, 1.0, ga, gb);
                for _ in 0..30 {
                    let x = (x0 * f1 - x1 * f0) / (f1 - f0);
                    let fx = g.eval(&lerp(x));
                    if fx == 0.0 || (x1 - x0).abs() < 1e-13 {
                        return lerp(x);
                    }
                    if (fx > 0.0) == (f0 > 0.0) {
                        (x0, f0) = (x, fx);
                    } else {
                        (x1, f1) = (x, fx);
                    }
                }
                lerp(0.5 * (x0 + x1))
            }))
        };
        // Marching squares: segments in each cell.
        let mut segments: Vec<([f64; 2], [f64; 2])> = Vec::new();
        for i in 0..m {
            for j in 0..n {
                let corners = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)];
                let pts: Vec<[f64; 2]> = (0..4)
                    .filter_map(|k| point_on(corners[k], corners[(k + 1) % 4]))
                    .collect();
                match pts.len() {
                    2 => segments.push((pts[0], pts[1])),
                    4 => {
                        // Saddle: decided by the mean of the corner values (a guess).
                        let mean: f64 = corners.iter().map(|c| vals[c.0][c.1]).sum::<f64>() / 4.0;
                        if (mean > 0.0) == (vals[i][j] > 0.0) {
                            segments.push((pts[0], pts[3]));
                            segments.push((pts[1], pts[2]));
                        } else {
                            segments.push((pts[0], pts[1]));
                            segments.push((pts[2], pts[3]));
                        }
                    }
                    _ => {}
                }
            }
        }
        // Chain segments into polylines through shared points.
        let key = |p: [f64; 2]| (p[0].to_bits(), p[1].to_bits());
        let mut used = vec![false; segments.len()];
        let draw = DrawPatch::new(patch);
        for s in 0..segments.len() {
            if used[s] {
                continue;
            }
            used[s] = true;
            let mut line = vec![segments[s].0, segments[s].1];
            for forward in [true, false] {
                loop {
                    let end = if forward {
                        *line.last().expect("nonempty")
                    } else {
                        line[0]
                    };
                    let next = (0..segments.len()).find(|&k| {
                        !used[k]
                            && (key(segments[k].0) == key(end) || key(segments[k].1) == key(end))
                    });
                    let Some(k) = next else { break };
                    used[k] = true;
                    let other = if key(segments[k].0) == key(end) {
                        segments[k].1
                    } else {
                        segments[k].0
                    };
                    if forward {
                        line.push(other);
                    } else {
                        line.insert(0, other);
                    }
                }
            }
            let closed = line.len() > 2 && key(line[0]) == key(*line.last().expect("nonempty"));
            curves.push(SilhouetteCurve {
                patches: vec![pi],
                closed,
                certified_topology: false,
                certified: false,
                error_bound: None,
                points: line.iter().map(|p| draw.eval(p[0], p[1])).collect(),
                points_uv: line.iter().map(|p| (pi, p[0], p[1])).collect(),
                pieces: Vec::new(),
                cubics: Vec::new(),
                cubic_bound: None,
            });
        }
    }
    curves
}
