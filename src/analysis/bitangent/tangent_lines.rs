//! Lines of a patch along which one plane is tangent (the top circle of a surface of
//! revolution, a flat side), checked in exact arithmetic. Two such lines with the same plane
//! make every pair of their points a bitangent pair: a 2-dimensional set of solutions of the
//! bitangent system, on which no Jacobian minor is regular (`proofs/bitangent.md`, Lemma 6).

use crate::bernstein::Bernstein;
use crate::number::Rational;
use crate::surface::RationalPatch;

/// A plane `normal · x = offset` tangent to a patch along the whole line where its variable
/// `axis` (0: u, 1: v) equals `at`.
#[derive(Clone, Debug, PartialEq)]
pub struct TangentLine {
    /// The variable held fixed (0: u, 1: v).
    pub axis: usize,
    /// Its value.
    pub at: Rational,
    /// A normal of the plane (exact: the patch's unnormalized normal at a point of the line).
    pub normal: [Rational; 3],
    /// The plane's offset along `normal`.
    pub offset: Rational,
}

impl TangentLine {
    /// `"u = 1/2"`.
    pub fn name(&self) -> String {
        format!("{} = {}", ["u", "v"][self.axis], self.at)
    }

    /// Whether `other` lies along the same plane.
    pub fn same_plane(&self, other: &TangentLine) -> bool {
        let (a, b) = (&self.normal, &other.normal);
        let cross =
            |i: usize, j: usize| Rational::from(&a[i] * &b[j]) - Rational::from(&a[j] * &b[i]);
        if cross(1, 2) != 0 || cross(2, 0) != 0 || cross(0, 1) != 0 {
            return false;
        }
        // b = λ a: the offsets scale alike.
        let k = (0..3).find(|&k| a[k] != 0).expect("a nonzero normal");
        let lambda = Rational::from(&b[k] / &a[k]);
        Rational::from(&lambda * &self.offset) == other.offset
    }
}

/// The polynomial on the line `x_axis = at`, as a polynomial constant along `axis`.
fn on_line(p: &Bernstein<Rational>, axis: usize, at: &Rational) -> Bernstein<Rational> {
    p.restrict_rational(axis, at, at)
}

/// The plane tangent to `patch` all along the line `x_axis = at`, if there is one: the patch's
/// normal there is parallel to one fixed vector, and the patch's points on the line lie in one
/// plane normal to it (both checked as identities of exact polynomials).
pub fn tangent_plane_along(
    patch: &RationalPatch,
    axis: usize,
    at: &Rational,
) -> Option<TangentLine> {
    if axis > 1 || *at < 0 || *at > 1 {
        return None;
    }
    let normal = patch.normal().map(|n| on_line(&n, axis, at));
    let [x, y, z, w] = patch.homogeneous().map(|c| on_line(&c, axis, at));
    // A point of the line where the normal does not vanish.
    let point = |t: &Rational| -> [Rational; 2] {
        if axis == 0 {
            [at.clone(), t.clone()]
        } else {
            [t.clone(), at.clone()]
        }
    };
    let samples = [(1, 2), (1, 3), (2, 3), (1, 5), (4, 5), (1, 7)];
    let (e, p) = samples.iter().find_map(|&(a, b)| {
        let p = point(&Rational::from((a, b)));
        let e = normal.clone().map(|n| n.eval(&p));
        e.iter().any(|c| *c != 0).then_some((e, p))
    })?;
    // N × e ≡ 0 on the line.
    let cross = |i: usize, j: usize| -> Option<bool> {
        let d = normal[i]
            .scale(&e[j])
            .try_sub(&normal[j].scale(&e[i]))
            .ok()?;
        Some(d.is_zero())
    };
    if !(cross(1, 2)? && cross(2, 0)? && cross(0, 1)?) {
        return None;
    }
    // e · X − k W ≡ 0 on the line, with k = e · S at the sample point.
    let wp = w.eval(&p);
    if wp == 0 {
        return None;
    }
    let dot_at = Rational::from(&e[0] * &x.eval(&p))
        + Rational::from(&e[1] * &y.eval(&p))
        + Rational::from(&e[2] * &z.eval(&p));
    let offset = dot_at / &wp;
    let plane = x
        .scale(&e[0])
        .try_add(&y.scale(&e[1]))
        .ok()?
        .try_add(&z.scale(&e[2]))
        .ok()?
        .try_sub(&w.scale(&offset))
        .ok()?;
    plane.is_zero().then_some(TangentLine {
        axis,
        at: at.clone(),
        normal: e,
        offset,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::shapes;

    #[test]
    fn the_plane_tangent_along_the_teapots_rim_and_nowhere_else() {
        let q = |a: i64, b: i64| Rational::from((a, b));
        let teapot = crate::testing::teapot();
        // The rim's top (patch 0, u = 1/2 in the teapot's parameterization): the horizontal
        // plane z = 2.4984375, the same on the neighbouring patch 1.
        let a = tangent_plane_along(&teapot.patches[0].surface, 0, &q(1, 2)).expect("a plane");
        let b = tangent_plane_along(&teapot.patches[1].surface, 0, &q(1, 2)).expect("a plane");
        assert!(a.normal[0] == 0 && a.normal[1] == 0 && a.normal[2] != 0);
        let height = Rational::from(&a.offset / &a.normal[2]).to_f64();
        assert!((height - 2.4984375).abs() < 1e-12, "{height}");
        assert!(a.same_plane(&b));
        assert_eq!(a.name(), "u = 1/2");
        // Not along u = 1/3 of the rim, nor along any line of a sphere.
        assert!(tangent_plane_along(&teapot.patches[0].surface, 0, &q(1, 3)).is_none());
        let sphere = &shapes::sphere(&Rational::from(1))[0];
        for c in [q(0, 1), q(1, 2), q(1, 1)] {
            for axis in 0..2 {
                assert!(tangent_plane_along(sphere, axis, &c).is_none());
            }
        }
    }
}
