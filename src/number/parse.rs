//! Exact parsing of decimal and rational numerals, as model files write them.

use super::Rational;
use rug::Integer;

/// Why a numeral could not be read.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ParseNumberError {
    /// Nothing to read.
    #[error("empty number")]
    Empty,
    /// Not a decimal numeral `[+-]digits[.digits][(e|E|d|D)[+-]digits]` or `p/q`.
    #[error("not a number: {0:?}")]
    Invalid(String),
    /// A denominator of zero in `p/q`.
    #[error("zero denominator in {0:?}")]
    ZeroDenominator(String),
    /// An exponent beyond ±10000 (almost certainly corrupt data; it would build huge integers).
    #[error("exponent out of range (at most ±10000) in {0:?}")]
    ExponentRange(String),
    /// More digits than a numeral may have (2,000): the count, and the numeral's first
    /// characters.
    #[error("a numeral of {1} digits, more than the 2000 limn reads: {0}…")]
    TooManyDigits(String, usize),
}

/// The largest decimal exponent accepted.
const MAX_EXPONENT: i64 = 10_000;
/// The most digits accepted in one numeral.
const MAX_DIGITS: usize = 2_000;

/// Reads a numeral exactly: `"0.125"`, `"-1.5e-3"`, `"1.0D0"` (Fortran), `".5"`, `"7"`,
/// `"1/3"`, `"-2/6"`. Leading and trailing spaces are ignored. `inf` and `nan` are refused.
///
/// The result is the exact rational the text denotes, never a rounded float.
///
/// # Errors
/// [`ParseNumberError`] when the text is not such a numeral.
///
/// # Examples
/// ```
/// use limn::number::{parse_exact, Rational};
/// assert_eq!(parse_exact("0.1").unwrap(), Rational::from((1, 10)));
/// assert_eq!(parse_exact("2.5D-1").unwrap(), Rational::from((1, 4)));
/// assert_eq!(parse_exact("-4/6").unwrap(), Rational::from((-2, 3)));
/// assert!(parse_exact("nan").is_err());
/// ```
pub fn parse_exact(text: &str) -> Result<Rational, ParseNumberError> {
    let t = text.trim();
    if t.is_empty() {
        return Err(ParseNumberError::Empty);
    }
    if let Some((p, q)) = t.split_once('/') {
        let num = parse_decimal(p.trim(), t)?;
        let den = parse_decimal(q.trim(), t)?;
        if den.cmp0() == std::cmp::Ordering::Equal {
            return Err(ParseNumberError::ZeroDenominator(t.to_string()));
        }
        return Ok(num / den);
    }
    parse_decimal(t, t)
}

fn parse_decimal(t: &str, whole: &str) -> Result<Rational, ParseNumberError> {
    let invalid = || ParseNumberError::Invalid(whole.to_string());
    let bytes = t.as_bytes();
    let mut i = 0;
    let negative = match bytes.first() {
        Some(b'-') => {
            i += 1;
            true
        }
        Some(b'+') => {
            i += 1;
            false
        }
        _ => false,
    };
    let mut digits = String::new();
    let mut frac_digits: i64 = 0;
    let mut seen_digit = false;
    while i < bytes.len() && bytes[i].is_ascii_digit() {
        digits.push(bytes[i] as char);
        seen_digit = true;
        i += 1;
    }
    if i < bytes.len() && bytes[i] == b'.' {
        i += 1;
        while i < bytes.len() && bytes[i].is_ascii_digit() {
            digits.push(bytes[i] as char);
            frac_digits += 1;
            seen_digit = true;
            i += 1;
        }
    }
    if !seen_digit {
        return Err(invalid());
    }
    if digits.len() > MAX_DIGITS {
        let preview: String = whole.chars().take(24).collect();
        return Err(ParseNumberError::TooManyDigits(preview, digits.len()));
    }
    let mut exponent: i64 = 0;
    if i < bytes.len() && matches!(bytes[i], b'e' | b'E' | b'd' | b'D') {
        i += 1;
        let mut exp_neg = false;
        if i < bytes.len() && (bytes[i] == b'-' || bytes[i] == b'+') {
            exp_neg = bytes[i] == b'-';
            i += 1;
        }
        let start = i;
        while i < bytes.len() && bytes[i].is_ascii_digit() {
            if i - start > 8 {
                return Err(ParseNumberError::ExponentRange(whole.to_string()));
            }
            exponent = exponent * 10 + i64::from(bytes[i] - b'0');
            i += 1;
        }
        if i == start {
            return Err(invalid());
        }
        if exp_neg {
            exponent = -exponent;
        }
    }
    if i != bytes.len() {
        return Err(invalid());
    }
    let scale = exponent - frac_digits;
    if scale.abs() > MAX_EXPONENT {
        return Err(ParseNumberError::ExponentRange(whole.to_string()));
    }
    let mantissa = Integer::from_str_radix(&digits, 10).map_err(|_| invalid())?;
    let mantissa = if negative { -mantissa } else { mantissa };
    let pow = Integer::from(Integer::u_pow_u(10, scale.unsigned_abs() as u32));
    Ok(if scale >= 0 {
        Rational::from(mantissa * pow)
    } else {
        Rational::from((mantissa, pow))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_exactly() {
        let q = |a: i64, b: i64| Rational::from((a, b));
        assert_eq!(parse_exact("0.125").unwrap(), q(1, 8));
        assert_eq!(parse_exact("  -3 ").unwrap(), q(-3, 1));
        assert_eq!(parse_exact("1.E-3").unwrap(), q(1, 1000));
        assert_eq!(parse_exact("-.5").unwrap(), q(-1, 2));
        assert_eq!(parse_exact("+2.50d+2").unwrap(), q(250, 1));
        assert_eq!(parse_exact("1/3").unwrap(), q(1, 3));
        assert_eq!(parse_exact("0.5/0.25").unwrap(), q(2, 1));
        // 0.1 is not the double 0.1.
        assert_ne!(
            parse_exact("0.1").unwrap(),
            Rational::from_f64(0.1).unwrap()
        );
    }

    #[test]
    fn refuses_garbage() {
        for bad in [
            "", "nan", "inf", "-", ".", "1e", "1.2.3", "1e5x", "0x10", "1/0", "1e99999", "--1",
            "1 2",
        ] {
            assert!(parse_exact(bad).is_err(), "{bad:?} should be refused");
        }
    }
}
