//! Named relative margins that make an f64 bound computed with round-to-nearest an upper (or
//! lower) bound of the exact value, each covering a stated number of roundings
//! (`proofs/rounding-margins.md`).
//!
//! A bound such as `L · (δ + h)` or `√(Σ xᵢ²)` is computed in f64 from nonnegative inputs that
//! are exact (f64 data, the ends of proven intervals, or differences of two exact f64 numbers,
//! each rounded once). Each operation (+, ×, ÷, √) rounds to nearest with relative error at
//! most `u = 2⁻⁵³`, so after `n` roundings the computed `x̃` satisfies `x ≤ x̃ / (1 − γₙ)`,
//! `γₙ = nu / (1 − nu)`; multiplying by `1 + m` in f64 (one more rounding) is an upper bound of
//! `x` as long as `(1 + m)(1 − u)(1 − γₙ) ≥ 1`. Each margin below states the largest `n` it
//! covers; a call site's chain must be within it (its count is in a comment where it is not
//! plain), and a chain whose length depends on the data uses [`covering`].

/// The unit roundoff of f64, `2⁻⁵³`.
pub const UNIT_ROUNDOFF: f64 = f64::EPSILON / 2.0;

/// Covers up to 3 roundings (a square root of an enclosure's end, say).
pub const TIGHT: f64 = 1e-15;

/// Covers up to 900 roundings: the short chains of the drawing and accuracy bounds.
pub const FEW: f64 = 1e-12;

/// Covers up to 900,000 roundings: bounds accumulated over many pieces or cells.
pub const MANY: f64 = 1e-9;

/// `x (1 + margin)`: an upper bound of the exact value of which `x` is the computed value,
/// when the computation is within what `margin` covers.
#[inline]
pub fn up(x: f64, margin: f64) -> f64 {
    x * (1.0 + margin)
}

/// `x (1 − margin)`: the matching lower bound (of a nonnegative value).
#[inline]
pub fn down(x: f64, margin: f64) -> f64 {
    x * (1.0 - margin)
}

/// `margin`, or larger if `n` roundings need more: `max(margin, 3 (n + 1) u)`, which covers `n`
/// roundings for every `n ≤ 10¹³` (`proofs/rounding-margins.md`, the count-dependent margin).
pub fn covering(n: usize, margin: f64) -> f64 {
    margin.max(3.0 * (n as f64 + 1.0) * UNIT_ROUNDOFF)
}

/// The largest number of roundings a margin covers: the largest `n` with
/// `(1 + m)(1 − u)(1 − γₙ) ≥ 1`, evaluated with a safety factor of 2 on `γₙ` (used by the tests
/// that check the constants' documented covers).
pub fn covers(margin: f64) -> usize {
    let u = UNIT_ROUNDOFF;
    // (1 + m)(1 − u)(1 − g) ≥ 1  ⟸  g ≤ (m − u − mu) / (1 + m) / 2 (the factor 2: slack for
    // the f64 evaluation of this very test).
    let g = (margin - u - margin * u) / (1.0 + margin) / 2.0;
    if g <= 0.0 {
        return 0;
    }
    // γₙ ≤ g  ⟺  n ≤ g / (u (1 + g)).
    (g / (u * (1.0 + g))).floor() as usize
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_named_margins_cover_what_they_say() {
        assert!(covers(TIGHT) >= 3, "{}", covers(TIGHT));
        assert!(covers(FEW) >= 900, "{}", covers(FEW));
        assert!(covers(MANY) >= 900_000, "{}", covers(MANY));
        for n in [0usize, 1, 10, 1_000, 10_000_000, 1 << 40] {
            assert!(covers(covering(n, FEW)) >= n, "{n}");
        }
    }

    #[test]
    fn a_long_sum_is_bounded_by_its_margin() {
        // 10⁶ terms of 0.1 (inexact in f64): the exact sum of the f64 terms lies within
        // the margin (checked in exact rationals).
        let x = 0.1f64;
        let n = 1_000_000usize;
        let s: f64 = (0..n).map(|_| x).sum();
        let exact = crate::number::Rational::from_f64(x).unwrap() * n as u64;
        let m = covering(n, MANY);
        assert!(crate::number::Rational::from_f64(up(s, m)).unwrap() >= exact);
        assert!(crate::number::Rational::from_f64(down(s, m)).unwrap() <= exact);
    }
}
