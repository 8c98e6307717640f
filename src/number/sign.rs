//! Three-valued signs plus "unknown".

use std::cmp::Ordering;

/// The sign of a number as far as it is proven.
///
/// `Unknown` means the number type could not decide (an interval that straddles zero, say).
/// It is never silently turned into one of the other three: callers that need a decision must
/// escalate precision or report the case as unresolved.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Sign {
    /// Certainly < 0.
    Negative,
    /// Certainly exactly 0.
    Zero,
    /// Certainly > 0.
    Positive,
    /// Not decided.
    Unknown,
}

impl Sign {
    /// The sign of an exactly known ordering against zero.
    pub fn from_ordering(o: Ordering) -> Sign {
        match o {
            Ordering::Less => Sign::Negative,
            Ordering::Equal => Sign::Zero,
            Ordering::Greater => Sign::Positive,
        }
    }

    /// Certainly positive.
    pub fn is_positive(self) -> bool {
        self == Sign::Positive
    }

    /// Certainly negative.
    pub fn is_negative(self) -> bool {
        self == Sign::Negative
    }

    /// Certainly zero.
    pub fn is_zero(self) -> bool {
        self == Sign::Zero
    }

    /// Certainly nonzero (positive or negative).
    pub fn is_nonzero(self) -> bool {
        matches!(self, Sign::Positive | Sign::Negative)
    }

    /// Zero is not excluded (zero or unknown).
    pub fn may_be_zero(self) -> bool {
        matches!(self, Sign::Zero | Sign::Unknown)
    }

    /// The sign is decided (not `Unknown`).
    pub fn is_known(self) -> bool {
        self != Sign::Unknown
    }
}

impl std::ops::Mul for Sign {
    type Output = Sign;

    /// The sign of a product of two numbers with these signs.
    ///
    /// | × | − | 0 | + | ? |
    /// |---|---|---|---|---|
    /// | − | + | 0 | − | ? |
    /// | 0 | 0 | 0 | 0 | 0 |
    /// | + | − | 0 | + | ? |
    /// | ? | ? | 0 | ? | ? |
    fn mul(self, other: Sign) -> Sign {
        use Sign::*;
        match (self, other) {
            (Zero, _) | (_, Zero) => Zero,
            (Unknown, _) | (_, Unknown) => Unknown,
            (a, b) if a == b => Positive,
            _ => Negative,
        }
    }
}

impl std::ops::Neg for Sign {
    type Output = Sign;

    /// The sign of the negated number.
    fn neg(self) -> Sign {
        match self {
            Sign::Negative => Sign::Positive,
            Sign::Positive => Sign::Negative,
            s => s,
        }
    }
}

impl Sign {
    /// The common sign of a set of numbers with these signs, when all agree strictly.
    ///
    /// Returns `Positive` (`Negative`) when every sign is `Positive` (`Negative`), `Zero` when
    /// every sign is `Zero`, and `Unknown` otherwise (mixed, or any unknown, or no signs).
    pub fn common<I: IntoIterator<Item = Sign>>(signs: I) -> Sign {
        let mut it = signs.into_iter();
        let Some(first) = it.next() else {
            return Sign::Unknown;
        };
        if first == Sign::Unknown {
            return Sign::Unknown;
        }
        for s in it {
            if s != first {
                return Sign::Unknown;
            }
        }
        first
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn product_table() {
        use Sign::*;
        let all = [Negative, Zero, Positive, Unknown];
        for a in all {
            for b in all {
                assert_eq!(a * b, b * a);
            }
            assert_eq!(a * Zero, Zero);
        }
        assert_eq!(Negative * Negative, Positive);
        assert_eq!(Negative * Positive, Negative);
        assert_eq!(Unknown * Positive, Unknown);
        assert_eq!(-Negative, Positive);
        assert_eq!(-Unknown, Unknown);
    }

    #[test]
    fn common_needs_agreement() {
        use Sign::*;
        assert_eq!(Sign::common([Positive, Positive]), Positive);
        assert_eq!(Sign::common([Positive, Zero]), Unknown);
        assert_eq!(Sign::common([Zero, Zero]), Zero);
        assert_eq!(Sign::common([]), Unknown);
        assert_eq!(Sign::common([Unknown]), Unknown);
    }
}
