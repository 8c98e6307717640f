//! The subdivision: boxes excluded, proven to hold graph arcs between their face crossings, or
//! split, within the depth, box and time budgets.

use crate::bernstein::Bernstein;
use crate::number::{Interval, Number, Precision, Rational};
use crate::reason::Reason;
use crate::solver::dyadic::Dyadic;
use crate::solver::space_curve::faces::{
    face_roots, face_slice, to_global, to_global_inward, FaceRoot,
};
use crate::solver::space_curve::regular_minor::{
    det, excludes, magnitude, over_one_minus, regular, slack, times_norm,
};
use crate::solver::space_curve::singular_branches::{
    star_branches, HigherPartials, SingularPoint, StarBranch,
};
use crate::solver::space_curve::singular_search::Leaves;
use crate::solver::space_curve::topology::{SpaceCurve, SpaceUnresolved};
use crate::solver::space_curve::{BoxVerdict, SpaceCurveOptions};
use crate::solver::system::{f64_box, split_box, DyadicBoxN};
use std::collections::HashMap;

/// A crossing as one box found it.
pub(crate) struct RawCrossing {
    pub(crate) axis: usize,
    pub(crate) at: Dyadic,
    pub(crate) enclosure: Vec<[f64; 2]>,
    /// Where it is the only root of the face system (face coordinates: `axis` left out).
    pub(crate) unique_in: Vec<[f64; 2]>,
    pub(crate) on_boundary: bool,
    /// The centre of a star: this singular point (index into the solver's list).
    pub(crate) singular: Option<usize>,
}
pub(crate) struct RawArc {
    pub(crate) from: usize,
    pub(crate) to: usize,
    pub(crate) cell: Vec<[f64; 2]>,
    pub(crate) monotone_in: usize,
    pub(crate) deviation: Option<Vec<f64>>,
}
/// How a box was decided.
pub(crate) enum Settled {
    /// Its crossings (sorted along the monotone variable), paired into arcs in that order,
    /// and whether every arc is within the tolerance. With a `center` (a singular point, §6),
    /// every crossing is joined to it instead.
    Arcs {
        center: Option<RawCrossing>,
        monotone_in: usize,
        crossings: Vec<RawCrossing>,
        deviations: Vec<Option<Vec<f64>>>,
        accurate: bool,
    },
    /// Not decided on this box (why).
    Open(Reason),
}
pub(crate) struct Item {
    pub(crate) cell: DyadicBoxN,
    pub(crate) depth: u32,
    pub(crate) polys: Vec<Bernstein<Interval>>,
    pub(crate) exact: bool,
}
/// A face of a box: the fixed variable, its value, and the other sides.
pub(crate) type FaceKey = (usize, Dyadic, DyadicBoxN);
pub(crate) struct Solver<'a> {
    /// The crossings found on each face solved so far (`None`: not decided).
    pub(crate) faces: HashMap<FaceKey, Option<Vec<FaceRoot>>>,
    pub(crate) n: usize,
    pub(crate) opts: &'a SpaceCurveOptions,
    /// The exact singular points known (§6), and the partials their star tests use.
    pub(crate) singular: Vec<SingularPoint>,
    pub(crate) partials: Option<HigherPartials>,
}
impl Solver<'_> {
    /// Decides one box from its polynomials (local coordinates).
    pub(crate) fn settle(&mut self, cell: &DyadicBoxN, polys: &[Bernstein<Interval>]) -> Settled {
        let n = self.n;
        // The first partials, kept for the accuracy bounds.
        let partials: Vec<Vec<Bernstein<Interval>>> = polys
            .iter()
            .map(|f| (0..n).map(|k| f.deriv(k)).collect())
            .collect();
        let jac: Vec<Vec<Interval>> = partials
            .iter()
            .map(|row| row.iter().map(Bernstein::hull).collect())
            .collect();
        let minor = |skip: usize| -> Vec<Vec<Interval>> {
            jac.iter()
                .map(|r| {
                    r.iter()
                        .enumerate()
                        .filter(|&(k, _)| k != skip)
                        .map(|(_, x)| *x)
                        .collect()
                })
                .collect()
        };
        let mid = |m: &[Vec<Interval>]| -> Vec<Vec<f64>> {
            m.iter()
                .map(|r| r.iter().map(|x| 0.5 * (x.lo() + x.hi())).collect())
                .collect()
        };
        let mut order: Vec<(usize, f64)> =
            (0..n).map(|i| (i, det(&mid(&minor(i))).abs())).collect();
        order.sort_by(|a, b| b.1.total_cmp(&a.1));
        let Some((i, c, beta)) = order
            .iter()
            .find_map(|&(i, _)| regular(&minor(i)).map(|(c, b)| (i, c, b)))
        else {
            return Settled::Open(Reason::NoRegularMinor);
        };
        let mut crossings = match self.face_crossings(cell, polys, &|_, _| false) {
            Ok(c) => c,
            Err(reason) => return Settled::Open(reason),
        };
        if crossings.len() % 2 == 1 {
            return Settled::Open(Reason::OddFaceCrossings);
        }
        crossings.sort_by(|a, b| {
            (a.enclosure[i][0] + a.enclosure[i][1])
                .total_cmp(&(b.enclosure[i][0] + b.enclosure[i][1]))
        });
        if crossings
            .windows(2)
            .any(|w| w[0].enclosure[i][1] >= w[1].enclosure[i][0])
        {
            return Settled::Open(Reason::CrossingsNotSeparated);
        }
        let (deviations, accurate) =
            self.deviations(cell, &partials, &jac, i, &c, beta, &crossings);
        Settled::Arcs {
            center: None,
            monotone_in: i,
            crossings,
            deviations,
            accurate,
        }
    }

    /// Decides a box around the singular point `index` by the star test (§6): its branches,
    /// each joined to the face crossing it ends at.
    pub(crate) fn star(
        &mut self,
        cell: &DyadicBoxN,
        polys: &dyn Fn() -> Vec<Bernstein<Interval>>,
        index: usize,
    ) -> Settled {
        let sp = &self.singular[index];
        let lo: Vec<f64> = cell.iter().map(|d| d.0.to_f64()).collect();
        let hi: Vec<f64> = cell.iter().map(|d| d.1.to_f64()).collect();
        let partials = self
            .partials
            .as_ref()
            .expect("partials with singular points");
        let branches = match star_branches(sp, partials, &lo, &hi) {
            Ok(b) => b,
            Err(reason) => return Settled::Open(reason),
        };
        // The faces through the singular point (sides of the unit box) hold no crossing but
        // it: the branches end on the other faces.
        let exact = sp.exact.clone();
        let on_side = move |axis: usize, side: bool| {
            let at = if side { cell[axis].1 } else { cell[axis].0 };
            exact[axis] == at.to_rational()
        };
        let crossings = match self.face_crossings(cell, &polys(), &on_side) {
            Ok(c) => c,
            Err(reason) => return Settled::Open(reason),
        };
        let sp = &self.singular[index];
        // Each crossing is the end of exactly one branch: its enclosure lies in the region of
        // the facet where that branch's end is the only point of the curve on the face.
        if crossings.len() != branches.len() {
            return Settled::Open(Reason::BranchesMismatch);
        }
        let mut used = vec![false; branches.len()];
        let mut order = Vec::with_capacity(branches.len());
        for c in &crossings {
            let upper = c.at == cell[c.axis].1;
            let matches: Vec<usize> = (0..branches.len())
                .filter(|&b| {
                    let br = &branches[b];
                    br.axis == c.axis
                        && br.upper == upper
                        && (0..self.n).filter(|&k| k != c.axis).all(|k| {
                            let region = sp.at[k].add(&br.region[k]);
                            region.lo() <= c.enclosure[k][0] && c.enclosure[k][1] <= region.hi()
                        })
                })
                .collect();
            match matches.as_slice() {
                [b] if !used[*b] => {
                    used[*b] = true;
                    order.push(*b);
                }
                _ => return Settled::Open(Reason::BranchesMismatch),
            }
        }
        let center = RawCrossing {
            axis: self.n,
            at: Dyadic::ZERO,
            enclosure: sp.at.iter().map(|x| [x.lo(), x.hi()]).collect(),
            unique_in: sp.at.iter().map(|x| [x.lo(), x.hi()]).collect(),
            on_boundary: sp.exact.iter().any(|x| *x == 0 || *x == 1),
            singular: Some(index),
        };
        let (deviations, accurate) =
            self.star_deviations(sp, &center, &branches, &order, &crossings);
        Settled::Arcs {
            center: Some(center),
            monotone_in: self.n,
            crossings,
            deviations,
            accurate,
        }
    }

    /// Per branch of a star, a bound per variable on the distance between the branch and the
    /// segment from the singular point to its crossing (§6: every point `p + r w(r)` is within
    /// `|w(r) − (c − p)|` of `p + r (c − p)`, and `w(r)` lies in the branch's image).
    pub(crate) fn star_deviations(
        &self,
        sp: &SingularPoint,
        center: &RawCrossing,
        branches: &[StarBranch],
        order: &[usize],
        crossings: &[RawCrossing],
    ) -> (Vec<Option<Vec<f64>>>, bool) {
        if self.opts.tolerance.is_none() {
            return (vec![None; crossings.len()], true);
        }
        let mut accurate = true;
        let devs = crossings
            .iter()
            .zip(order)
            .map(|(c, &b)| {
                let br = &branches[b];
                let dev: Vec<f64> = (0..self.n)
                    .map(|k| {
                        let mid = |e: &[f64; 2]| 0.5 * (e[0] + e[1]);
                        let drawn_p = mid(&center.enclosure[k]);
                        // c̃ − p and the image of w(r) (the facet value on the face's axis).
                        let to_end = Interval::point(mid(&c.enclosure[k])).sub(&sp.at[k]);
                        let w = if k == br.axis {
                            br.region[k]
                        } else {
                            br.image[k]
                        };
                        let spread = magnitude(&w.sub(&to_end));
                        let start = magnitude(&sp.at[k].sub(&Interval::point(drawn_p)));
                        Interval::point(spread).add(&Interval::point(start)).hi()
                    })
                    .collect();
                if let Some(accept) = &self.opts.accept {
                    accurate &= (accept.0)(&center.enclosure, &c.enclosure, &dev);
                } else if let Some(tol) = &self.opts.tolerance {
                    accurate &= dev.iter().zip(tol).all(|(d, t)| d <= t);
                    if let Some(chord) = &self.opts.max_chord {
                        let (a, e) = (&center.enclosure, &c.enclosure);
                        accurate &= chord
                            .iter()
                            .enumerate()
                            .all(|(k, l)| a[k][1].max(e[k][1]) - a[k][0].min(e[k][0]) <= *l);
                    }
                }
                Some(dev)
            })
            .collect();
        (devs, accurate)
    }

    /// The crossings of the curve with the faces of the box (all faces but those `skip`
    /// names, by axis and side), each strictly inside its face (§3); `Err` if some face was
    /// not decided.
    pub(crate) fn face_crossings(
        &mut self,
        cell: &DyadicBoxN,
        polys: &[Bernstein<Interval>],
        skip: &dyn Fn(usize, bool) -> bool,
    ) -> Result<Vec<RawCrossing>, Reason> {
        let n = self.n;
        let mut crossings = Vec::new();
        for axis in 0..n {
            for (side, at) in [(false, cell[axis].0), (true, cell[axis].1)] {
                if skip(axis, side) {
                    continue;
                }
                // The box's own coefficients on the face are the face polynomials' (exactly
                // the Bernstein coefficients with that index at 0 or at the degree): where
                // one equation has a strict sign there, the face holds no crossing.
                if polys.iter().any(|p| excludes(&face_slice(p, axis, side))) {
                    continue;
                }
                let domain: DyadicBoxN = (0..n).filter(|&k| k != axis).map(|k| cell[k]).collect();
                // A face shared with a neighbour of the same size is solved once: both boxes
                // enclose the same exact system on it (`proofs/space-curves.md` §4).
                let key = (axis, at, domain.clone());
                let roots = match self.faces.get(&key) {
                    Some(known) => known.clone(),
                    None => {
                        let face: Vec<Bernstein<Interval>> =
                            polys.iter().map(|p| face_slice(p, axis, side)).collect();
                        let dlo: Vec<f64> = domain.iter().map(|d| d.0.to_f64()).collect();
                        let dhi: Vec<f64> = domain.iter().map(|d| d.1.to_f64()).collect();
                        let found = face_roots(face, &self.opts.face).map(|roots| {
                            roots
                                .into_iter()
                                .map(|r| FaceRoot {
                                    enclosure: to_global(&r.enclosure, &dlo, &dhi),
                                    unique_in: to_global_inward(&r.unique_in, &dlo, &dhi),
                                })
                                .collect::<Vec<_>>()
                        });
                        self.faces.insert(key, found.clone());
                        found
                    }
                };
                let Some(roots) = roots else {
                    return Err(Reason::FaceCrossing);
                };
                for r in roots {
                    let strictly_inside = r
                        .enclosure
                        .iter()
                        .zip(&domain)
                        .all(|(e, d)| d.0.to_f64() < e[0] && e[1] < d.1.to_f64());
                    if !strictly_inside {
                        return Err(Reason::NearBoxEdge);
                    }
                    let a = at.to_f64();
                    let mut enclosure = r.enclosure.clone();
                    enclosure.insert(axis, [a, a]);
                    crossings.push(RawCrossing {
                        axis,
                        at,
                        enclosure,
                        unique_in: r.unique_in,
                        on_boundary: at == Dyadic::ZERO || at == Dyadic::ONE,
                        singular: None,
                    });
                }
            }
        }
        Ok(crossings)
    }

    /// Per arc (consecutive pairs of crossings) and variable, a bound on the distance between
    /// the arc and its chord (`proofs/space-curves.md`, Claim 3), and whether all are within
    /// the tolerance.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn deviations(
        &self,
        cell: &DyadicBoxN,
        partials: &[Vec<Bernstein<Interval>>],
        jac: &[Vec<Interval>],
        i: usize,
        c: &[Vec<f64>],
        beta: f64,
        crossings: &[RawCrossing],
    ) -> (Vec<Option<Vec<f64>>>, bool) {
        let Some(tol) = &self.opts.tolerance else {
            return (vec![None; crossings.len() / 2], true);
        };
        let n = self.n;
        let width: Vec<f64> = cell.iter().map(|d| d.1.to_f64() - d.0.to_f64()).collect();
        // |η'|∞ ≤ ‖C J_x‖∞ / (1 − β) in local coordinates.
        let jx: Vec<Interval> = jac.iter().map(|r| r[i]).collect();
        let slope = over_one_minus(times_norm(c, &jx), beta);
        let t: Vec<Interval> = (0..n)
            .map(|k| {
                if k == i {
                    Interval::point(1.0)
                } else {
                    Interval::new(-slope, slope)
                }
            })
            .collect();
        // r_j = D²F_j(t, t) over the box: the Hessian is symmetric, so each mixed partial is
        // taken once and counted twice.
        let r: Vec<Interval> = partials
            .iter()
            .map(|row| {
                let mut s = Interval::point(0.0);
                for a in 0..n {
                    for b in a..n {
                        let h = row[a].deriv_hull(b);
                        let term = h.mul(&t[a]).mul(&t[b]);
                        s = s.add(&if a == b { term } else { term.add(&term) });
                    }
                }
                s
            })
            .collect();
        let curvature = over_one_minus(times_norm(c, &r), beta);
        let mut accurate = true;
        let devs = crossings
            .chunks_exact(2)
            .map(|pair| {
                // The arc's extent along x_i in box units (an upper bound).
                let span = Interval::point(pair[1].enclosure[i][1])
                    .sub(&Interval::point(pair[0].enclosure[i][0]))
                    .mul(
                        &Interval::point(width[i])
                            .recip()
                            .unwrap_or(Interval::new(0.0, f64::INFINITY)),
                    )
                    .hi()
                    .clamp(0.0, 1.0);
                let span = Interval::point(span);
                let dev: Vec<f64> = (0..n)
                    .map(|k| {
                        // In local coordinates the arc deviates from the chord between its true
                        // ends, at equal x_i, by at most span² |η''| / 8; back to global: times
                        // the width (and never more than the box's width).
                        let bulge = if k == i {
                            0.0
                        } else {
                            span.mul(&span)
                                .mul(&Interval::point(0.125))
                                .mul(&Interval::point(curvature))
                                .mul(&Interval::point(width[k]))
                                .hi()
                                .min(width[k])
                        };
                        // The drawn chord joins the enclosures' centres: moving each end by at
                        // most its half-width moves every point of the chord (at equal chord
                        // parameter) by at most the larger one, in every coordinate.
                        let half = |c: &RawCrossing| {
                            Interval::point(c.enclosure[k][1])
                                .sub(&Interval::point(c.enclosure[k][0]))
                                .mul(&Interval::point(0.5))
                                .hi()
                        };
                        let slack = half(&pair[0]).max(half(&pair[1]));
                        Interval::point(bulge).add(&Interval::point(slack)).hi()
                    })
                    .collect();
                if let Some(accept) = &self.opts.accept {
                    accurate &= (accept.0)(&pair[0].enclosure, &pair[1].enclosure, &dev);
                } else {
                    accurate &= dev.iter().zip(tol).all(|(d, t)| d <= t);
                    if let Some(chord) = &self.opts.max_chord {
                        let extent = |k: usize| {
                            let (a, b) = (&pair[0].enclosure[k], &pair[1].enclosure[k]);
                            a[1].max(b[1]) - a[0].min(b[0])
                        };
                        accurate &= chord.iter().enumerate().all(|(k, c)| extent(k) <= *c);
                    }
                }
                Some(dev)
            })
            .collect();
        (devs, accurate)
    }
}
/// The subdivision: every box excluded, settled (its crossings and arcs added to `leaves`),
/// dropped by the caller, or unresolved (added to `out`).
pub(crate) fn subdivide(
    solver: &mut Solver,
    eqs: &[Bernstein<Rational>],
    filters: &[Bernstein<Rational>],
    verdict: &dyn Fn(&[[f64; 2]], u32) -> BoxVerdict,
    out: &mut SpaceCurve,
    leaves: &mut Leaves,
) {
    let (n, opts) = (solver.n, solver.opts);
    let all_exact: Vec<Bernstein<Rational>> = eqs.iter().chain(filters).cloned().collect();
    let all_exact = &all_exact[..];
    // Each box carries the equations, then the filters.
    let mut stack = vec![Item {
        cell: vec![(Dyadic::ZERO, Dyadic::ONE); n],
        depth: 0,
        polys: eqs
            .iter()
            .chain(filters)
            .map(|p| p.convert(Precision::F64))
            .collect(),
        exact: false,
    }];
    let positive = |p: &Bernstein<Interval>| p.coeffs().iter().all(|x| x.lo() > 0.0);
    while let Some(item) = stack.pop() {
        out.boxes += 1;
        let (equations, filter_polys) = item.polys.split_at(n - 1);
        if equations.iter().any(excludes) || filter_polys.iter().any(positive) {
            continue;
        }
        match verdict(&f64_box(&item.cell), item.depth) {
            BoxVerdict::Solve => {}
            BoxVerdict::Drop => {
                leaves.dropped.push(f64_box(&item.cell));
                continue;
            }
            BoxVerdict::Unresolved(reason) => {
                // Neither may a star box cover it: the caller's reason stands.
                leaves.dropped.push(f64_box(&item.cell));
                out.unresolved.push(SpaceUnresolved {
                    cell: f64_box(&item.cell),
                    reason: reason.clone(),
                });
                continue;
            }
        }
        let (reason, accurate_enough) = match solver.settle(&item.cell, equations) {
            Settled::Arcs {
                center: _,
                monotone_in,
                crossings,
                deviations,
                accurate,
            } => {
                let last_chance = item.depth >= opts.max_depth
                    || out.boxes + stack.len() >= opts.max_boxes
                    || opts
                        .deadline
                        .is_some_and(|d| std::time::Instant::now() >= d);
                if accurate || last_chance {
                    out.within_tolerance &= accurate;
                    let first = leaves.crossings.len();
                    leaves.crossings.extend(crossings);
                    for (k, deviation) in deviations.into_iter().enumerate() {
                        leaves.arcs.push(RawArc {
                            from: first + 2 * k,
                            to: first + 2 * k + 1,
                            cell: f64_box(&item.cell),
                            monotone_in,
                            deviation,
                        });
                    }
                    continue;
                }
                (Reason::ArcsNotWithinTolerance, false)
            }
            Settled::Open(reason) => (reason, true),
        };
        // Undecided: recompute the polynomials from the exact input once, at the ladder's
        // tightest level, if the enclosures have spread.
        if accurate_enough && !item.exact && item.depth >= 3 && slack(equations) > 1e-9 {
            let lo: Vec<Rational> = item.cell.iter().map(|d| d.0.to_rational()).collect();
            let hi: Vec<Rational> = item.cell.iter().map(|d| d.1.to_rational()).collect();
            let (polys, level) = opts.ladder.restricted_enclosures(all_exact, &lo, &hi);
            out.escalations.record(Some(level));
            out.boxes -= 1;
            stack.push(Item {
                polys,
                exact: true,
                ..item
            });
            continue;
        }
        if opts
            .deadline
            .is_some_and(|d| std::time::Instant::now() >= d)
        {
            out.unresolved.push(SpaceUnresolved {
                cell: f64_box(&item.cell),
                reason: Reason::TimeLimit,
            });
            continue;
        }
        if item.depth >= opts.max_depth || out.boxes + stack.len() >= opts.max_boxes {
            out.unresolved.push(SpaceUnresolved {
                cell: f64_box(&item.cell),
                reason,
            });
            continue;
        }
        let axes: Vec<usize> = (0..n).collect();
        let Some(children) = split_box(&item.cell, item.polys, &axes) else {
            out.unresolved.push(SpaceUnresolved {
                cell: f64_box(&item.cell),
                reason: Reason::FinestSubdivision,
            });
            continue;
        };
        for (cell, polys) in children.into_iter().rev() {
            stack.push(Item {
                cell,
                depth: item.depth + 1,
                polys,
                exact: false,
            });
        }
    }
}
