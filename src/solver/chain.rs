//! Chaining the arcs of a curve into its connected pieces: a graph whose vertices are the
//! crossings and whose edges are the arcs, walked through vertices of degree 2.

/// A chain of vertices joined by edges.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Chain {
    /// The vertices in order (a closed chain does not repeat its first vertex).
    pub vertices: Vec<usize>,
    /// The edges walked, in order: edge `i` joins vertices `i` and `i + 1` (for a closed
    /// chain, the last joins the last vertex to the first).
    pub edges: Vec<usize>,
    /// The last vertex joins the first.
    pub closed: bool,
    /// Closed with every vertex of degree 2 or a branch point, or open with both ends on the
    /// boundary (of degree 1) or at branch points: nothing of the curve is missing at its ends.
    pub complete: bool,
}

/// Chains the edges (vertex pairs, vertices `0..vertices`) through vertices of degree 2:
/// open chains first, from the vertices of degree 1 and the branch points of degree other
/// than 2, in increasing order (a chain from a branch point may come back to it: closed), then
/// the closed ones. `boundary` says which vertices lie on the domain's boundary (an end of
/// degree 1 there is complete), `branch_point` which are proven points where several chains
/// meet (a singular point whose branches are decided: an end there is complete).
pub(crate) fn chain(
    edges: &[(usize, usize)],
    vertices: usize,
    boundary: &dyn Fn(usize) -> bool,
    branch_point: &dyn Fn(usize) -> bool,
) -> Vec<Chain> {
    let mut incident: Vec<Vec<usize>> = vec![Vec::new(); vertices];
    for (i, &(a, b)) in edges.iter().enumerate() {
        incident[a].push(i);
        incident[b].push(i);
    }
    let degree = |v: usize| incident[v].len();
    let end_complete =
        |v: usize| (boundary(v) && degree(v) == 1) || (branch_point(v) && degree(v) != 2);
    let mut used = vec![false; edges.len()];
    let mut chains = Vec::new();
    let starts = (0..vertices).filter(|&v| degree(v) == 1 || (branch_point(v) && degree(v) > 2));
    for end in starts {
        for k in 0..incident[end].len() {
            let first = incident[end][k];
            if used[first] {
                continue;
            }
            let (vertices, walked, last) = walk(edges, &incident, &mut used, end, first);
            let closed = last == end;
            let complete = end_complete(end) && end_complete(last);
            chains.push(Chain {
                vertices,
                edges: walked,
                closed,
                complete,
            });
        }
    }
    for i in 0..edges.len() {
        if used[i] {
            continue;
        }
        let start = edges[i].0;
        let (vertices, walked, last) = walk(edges, &incident, &mut used, start, i);
        let closed = last == start;
        let complete = closed && vertices.iter().all(|&v| degree(v) == 2 || branch_point(v));
        chains.push(Chain {
            vertices,
            edges: walked,
            closed,
            complete,
        });
    }
    chains
}

fn walk(
    edges: &[(usize, usize)],
    incident: &[Vec<usize>],
    used: &mut [bool],
    start: usize,
    first: usize,
) -> (Vec<usize>, Vec<usize>, usize) {
    let mut vertices = vec![start];
    let mut walked = Vec::new();
    let mut at = start;
    let mut edge = first;
    loop {
        used[edge] = true;
        walked.push(edge);
        let (a, b) = edges[edge];
        let next = if a == at { b } else { a };
        if next == start {
            return (vertices, walked, next);
        }
        vertices.push(next);
        at = next;
        // Continue only through a vertex of degree exactly 2 (anything else ends the walk).
        let inc = &incident[at];
        if inc.len() != 2 {
            return (vertices, walked, at);
        }
        match inc.iter().find(|&&j| !used[j]) {
            Some(&j) => edge = j,
            None => return (vertices, walked, at),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_path_a_loop_and_a_dangling_end() {
        // 0-1-2 with 0 and 2 on the boundary; 3-4-5-3 a triangle; 6-7 with 7 not on it.
        let edges = [(0, 1), (1, 2), (3, 4), (4, 5), (5, 3), (6, 7)];
        let boundary = |v: usize| v != 7;
        let c = chain(&edges, 8, &boundary, &|_| false);
        assert_eq!(c.len(), 3);
        assert_eq!(
            (c[0].vertices.clone(), c[0].closed, c[0].complete),
            (vec![0, 1, 2], false, true)
        );
        assert_eq!(c[0].edges, vec![0, 1]);
        assert_eq!(c[1].edges, vec![5]);
        assert_eq!(c[2].edges, vec![2, 3, 4]);
        assert_eq!((c[1].vertices.clone(), c[1].complete), (vec![6, 7], false));
        assert_eq!(
            (c[2].vertices.clone(), c[2].closed, c[2].complete),
            (vec![3, 4, 5], true, true)
        );
    }

    #[test]
    fn chains_meet_at_a_branch_point() {
        // A node 0 with four arms to the boundary vertices 1-4 (through 5 on the first arm),
        // and a loop 0-6-7-0 through it.
        let edges = [
            (0, 5),
            (5, 1),
            (0, 2),
            (3, 0),
            (0, 4),
            (0, 6),
            (6, 7),
            (7, 0),
        ];
        let boundary = |v: usize| (1..=4).contains(&v);
        let c = chain(&edges, 8, &boundary, &|v| v == 0);
        assert_eq!(c.len(), 5);
        assert!(c.iter().all(|x| x.complete), "{c:?}");
        assert_eq!(c[0].vertices, vec![0, 5, 1]);
        let lp = c.iter().find(|x| x.closed).unwrap();
        assert_eq!(lp.vertices, vec![0, 6, 7]);
        // Not a branch point (even on the boundary): the arms are not complete there.
        let c = chain(&edges, 8, &|v: usize| v <= 4, &|_| false);
        assert!(c.iter().all(|x| !x.complete));
    }
}
