//! quickcheck `Arbitrary` for patches, drawing from the same families as the proptest
//! strategies.

use super::shapes;
use crate::number::Rational;
use crate::surface::RationalPatch;
use quickcheck::{Arbitrary, Gen};

/// A random patch (generic, planar, collapsed edge or cylinder), for quickcheck properties.
#[derive(Clone, Debug)]
pub struct ArbitraryPatch(pub RationalPatch);

fn small(g: &mut Gen) -> Rational {
    let p = i64::from(i8::arbitrary(g) % 65);
    let q = i64::from(u8::arbitrary(g) % 16) + 1;
    Rational::from((p, q))
}

impl Arbitrary for ArbitraryPatch {
    fn arbitrary(g: &mut Gen) -> Self {
        let family = u8::arbitrary(g) % 4;
        if family == 3 {
            let r = Rational::from((i64::from(u8::arbitrary(g) % 8) + 1, 2));
            return ArbitraryPatch(shapes::cylinder_quarter(&r, &Rational::from(1)));
        }
        let m = usize::from(u8::arbitrary(g) % 3) + 1;
        let n = usize::from(u8::arbitrary(g) % 3) + 1;
        let count = (m + 1) * (n + 1);
        let mut pts: Vec<_> = (0..count).map(|_| [small(g), small(g), small(g)]).collect();
        match family {
            1 => pts.iter_mut().for_each(|p| p[2] = Rational::new()),
            2 => {
                let apex = pts[0].clone();
                for i in 0..=m {
                    pts[i * (n + 1)] = apex.clone();
                }
            }
            _ => {}
        }
        let ws = (0..count)
            .map(|_| Rational::from((i64::from(u8::arbitrary(g) % 15) + 1, 4)))
            .collect();
        ArbitraryPatch(RationalPatch::new([m, n], pts, ws).expect("valid by construction"))
    }
}
