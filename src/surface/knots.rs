//! Knot insertion, Bézier extraction and de Boor evaluation on homogeneous control polygons
//! (`[w x_1, …, w x_d, w]`, `K = d + 1` entries), exact: the one mechanism behind NURBS
//! surfaces ([`super::NurbsSurface`]) and curves ([`super::NurbsCurve`]);
//! `proofs/knot-insertion.md`.

use crate::number::Rational;

/// Inserts `u` once into a B-spline of degree `p` with homogeneous points (Boehm's algorithm,
/// exact). `knots` has `points.len() + p + 1` entries; `u` must lie in the domain [t_p, t_n].
pub(super) fn insert_knot<const K: usize>(
    p: usize,
    knots: &mut Vec<Rational>,
    points: &mut Vec<[Rational; K]>,
    u: &Rational,
) {
    // The span k with t_k <= u < t_{k+1}, k in [p, n-1]; at the domain end use the last span.
    let n = points.len();
    let mut k = p;
    while k + 1 < n && knots[k + 1] <= *u {
        k += 1;
    }
    // Only Q_{k-p+1..=k} are new: Q_i = α_i P_i + (1 − α_i) P_{i−1},
    // α_i = (u − t_i) / (t_{i+p} − t_i). The rest of the polygon is moved, not copied.
    let fresh: Vec<[Rational; K]> = (k + 1 - p..=k)
        .map(|i| {
            let den = Rational::from(&knots[i + p] - &knots[i]);
            let alpha = Rational::from(u - &knots[i]) / den;
            let beta = Rational::from(1 - &alpha);
            std::array::from_fn(|c| {
                Rational::from(&alpha * &points[i][c]) + Rational::from(&beta * &points[i - 1][c])
            })
        })
        .collect();
    points.splice(k + 1 - p..k, fresh);
    knots.insert(k + 1, u.clone());
}

/// Splits a B-spline of degree `p` on `[a, b]` (inside its domain `[t_p, t_n]`, `a < b`) into
/// Bézier segments: for each span `[s, e]` of `[a, b]` with `s < e`, the span and its `p + 1`
/// homogeneous Bézier points. Every knot value in `[a, b]`, and `a` and `b` themselves, are
/// raised to multiplicity at least `p` by exact insertion; then the segment on
/// `[t_k, t_{k+1}]` has control points `P_{k-p..=k}` (the blossom argument in
/// `proofs/knot-insertion.md`).
pub(super) fn bezier_segments<const K: usize>(
    p: usize,
    knots: &[Rational],
    points: &[[Rational; K]],
    range: [&Rational; 2],
) -> Vec<([Rational; 2], Vec<[Rational; K]>)> {
    let [a, b] = range;
    let mut knots = knots.to_vec();
    let mut points = points.to_vec();
    let mut values: Vec<Rational> = knots.iter().filter(|t| *t > a && *t < b).cloned().collect();
    values.push(a.clone());
    values.push(b.clone());
    values.sort();
    values.dedup();
    for u in &values {
        let mult = knots.iter().filter(|t| *t == u).count();
        for _ in mult..p {
            insert_knot(p, &mut knots, &mut points, u);
        }
    }
    let mut segments = Vec::new();
    for k in p..points.len() {
        if knots[k] < knots[k + 1] && knots[k] >= *a && knots[k + 1] <= *b {
            segments.push((
                [knots[k].clone(), knots[k + 1].clone()],
                points[k - p..=k].to_vec(),
            ));
        }
    }
    segments
}

/// De Boor's algorithm in f64 (for float filters: the nearest parameter of a point, never a
/// certified answer): the point of degree `p` with `knots` and homogeneous `points` at `u`,
/// `u` clamped to the domain.
pub(crate) fn de_boor_f64<const K: usize>(
    p: usize,
    knots: &[f64],
    points: &[[f64; K]],
    u: f64,
) -> [f64; K] {
    let n = points.len();
    let u = u.clamp(knots[p], knots[n]);
    let mut k = p;
    while k + 1 < n && knots[k + 1] <= u {
        k += 1;
    }
    while k > p && knots[k] == knots[k + 1] {
        k -= 1;
    }
    let mut d: Vec<[f64; K]> = (0..=p).map(|j| points[j + k - p]).collect();
    for r in 1..=p {
        for j in (r..=p).rev() {
            let i = j + k - p;
            let span = knots[i + p + 1 - r] - knots[i];
            let alpha = if span > 0.0 {
                (u - knots[i]) / span
            } else {
                0.0
            };
            d[j] = std::array::from_fn(|c| alpha * d[j][c] + (1.0 - alpha) * d[j - 1][c]);
        }
    }
    d[p]
}

/// de Boor's algorithm on homogeneous points (exact); `u` in the domain `[t_p, t_n]`.
pub(super) fn de_boor<const K: usize>(
    p: usize,
    knots: &[Rational],
    points: &[[Rational; K]],
    u: &Rational,
) -> [Rational; K] {
    let n = points.len();
    let mut k = p;
    while k + 1 < n && knots[k + 1] <= *u {
        k += 1;
    }
    // At the end of the domain the span found may be empty: use the last nonempty one.
    while k > p && knots[k] == knots[k + 1] {
        k -= 1;
    }
    let mut d: Vec<[Rational; K]> = (0..=p).map(|j| points[j + k - p].clone()).collect();
    for r in 1..=p {
        for j in (r..=p).rev() {
            let i = j + k - p;
            let alpha =
                Rational::from(u - &knots[i]) / Rational::from(&knots[i + p + 1 - r] - &knots[i]);
            let beta = Rational::from(1 - &alpha);
            d[j] = std::array::from_fn(|c| {
                Rational::from(&alpha * &d[j][c]) + Rational::from(&beta * &d[j - 1][c])
            });
        }
    }
    d[p].clone()
}
