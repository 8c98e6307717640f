//! The view every view-dependent analysis takes: a parallel direction or a perspective eye,
//! with exact rational coordinates (the input is exact).

use crate::number::{Number, Rational};

/// A view: parallel direction (from the viewer into the scene) or perspective eye point.
///
/// A point of a solid is front-facing (on the visible side) when `n·V < 0` for a direction `V`,
/// or `n·(E − S) > 0` for an eye `E`, with `n` the outward normal `S_u × S_v`.
///
/// # Examples
/// ```
/// use limn::View;
/// let v = View::direction([1, 2, 3]);
/// assert_eq!(v, View::parse_direction("1,2,3").unwrap());
/// assert_eq!(v.to_json().to_string(), r#"{"dir":[1.0,2.0,3.0]}"#);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub enum View {
    /// Parallel projection along this direction.
    Direction([Rational; 3]),
    /// Perspective from this eye point.
    Eye([Rational; 3]),
}

impl View {
    /// The parallel view along an integer direction.
    pub fn direction(d: [i64; 3]) -> View {
        View::Direction(d.map(Rational::from))
    }

    /// The perspective view from an integer eye point.
    pub fn eye(e: [i64; 3]) -> View {
        View::Eye(e.map(Rational::from))
    }

    /// The parallel view along `"x,y,z"` (each number read exactly, as the model's are).
    ///
    /// # Errors
    /// A message if the text is not three numbers.
    pub fn parse_direction(text: &str) -> Result<View, String> {
        parse_vector(text).map(View::Direction)
    }

    /// The perspective view from `"x,y,z"`.
    ///
    /// # Errors
    /// A message if the text is not three numbers.
    pub fn parse_eye(text: &str) -> Result<View, String> {
        parse_vector(text).map(View::Eye)
    }

    /// The view as JSON: `{"dir": [x, y, z]}` or `{"eye": [x, y, z]}` (f64).
    pub fn to_json(&self) -> serde_json::Value {
        let v = |x: &[Rational; 3]| x.clone().map(|c| c.to_f64());
        match self {
            View::Direction(d) => serde_json::json!({ "dir": v(d) }),
            View::Eye(e) => serde_json::json!({ "eye": v(e) }),
        }
    }

    /// The direction an analysis works with: a direction's length does not matter, so one
    /// whose largest component lies outside `[2⁻⁸, 2⁸]` is scaled exactly by a power of two
    /// until it lies in `[1, 2)` (so that `--dir 1e308,1e308,1e308` and `--dir 1,1,1` give
    /// the same answer: f64 enclosures of the functions built from it stay in range); others,
    /// and eyes, unchanged (their results are then bit for bit those of the direction as
    /// written).
    pub fn working(&self) -> View {
        match self {
            View::Direction(d) => View::Direction(working_direction(d)),
            View::Eye(_) => self.clone(),
        }
    }

    /// Whether a direction view is the zero vector (meaningless).
    pub fn is_degenerate(&self) -> bool {
        match self {
            View::Direction(d) => d.iter().all(|c| c.sign().is_zero()),
            View::Eye(_) => false,
        }
    }
}

/// [`View::working`] of a direction.
pub fn working_direction(d: &[Rational; 3]) -> [Rational; 3] {
    let Some(m) = d.iter().map(|c| c.clone().abs()).max() else {
        return d.clone();
    };
    if m.cmp0() == std::cmp::Ordering::Equal {
        return d.clone();
    }
    let pow2 = |k: i64| {
        let mut p = Rational::from(1);
        if k >= 0 {
            p <<= k as u32;
        } else {
            p >>= (-k) as u32;
        }
        p
    };
    if pow2(-8) <= m && m <= pow2(8) {
        return d.clone();
    }
    // k with 2^k ≤ m < 2^(k+1): estimated from the bit lengths, then corrected exactly.
    let bits = |i: &rug::Integer| i64::from(i.significant_bits());
    let mut k = bits(m.numer()) - bits(m.denom());
    while pow2(k) > m {
        k -= 1;
    }
    while pow2(k + 1) <= m {
        k += 1;
    }
    let scale = pow2(-k);
    d.clone().map(|c| c * &scale)
}

/// Parses "x,y,z" into an exact vector.
///
/// # Errors
/// A message if the text is not three numbers.
pub fn parse_vector(text: &str) -> Result<[Rational; 3], String> {
    let parts: Vec<&str> = text.split(',').collect();
    if parts.len() != 3 {
        return Err(format!(
            "expected three numbers x,y,z, found {:?}",
            crate::io::shortened(text)
        ));
    }
    let mut v = Vec::with_capacity(3);
    for p in parts {
        v.push(
            crate::number::parse_exact(p)
                .map_err(|e| format!("{:?}: {e}", crate::io::shortened(text)))?,
        );
    }
    let v: [Rational; 3] = v.try_into().map_err(|_| "three numbers".to_string())?;
    Ok(v)
}
