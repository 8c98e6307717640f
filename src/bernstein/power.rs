//! The power (monomial) basis, for the few exact operations that are simplest there.

use super::Bernstein;
use crate::number::Rational;

use crate::bernstein::Poly;

/// For univariate `a`, `b` (elevated to one degree n), the exact polynomial of degree
/// (n − 1, n − 1) in (t, s) with `(t − s) Q(t, s) = a(t) b(s) − a(s) b(t)` (the product is
/// antisymmetric, so `t − s` divides it): the self-crossings of a curve's image without its
/// trivial diagonal.
pub fn antisymmetric_quotient(a: &Poly, b: &Poly) -> Poly {
    let (a, b) = same_degree(a, b);
    let n = a.degrees()[0];
    let (ma, mb) = (to_power(&a), to_power(&b));
    let m = n.max(1) - 1;
    let mut q = vec![Rational::new(); (m + 1) * (m + 1)];
    for i in 0..=n {
        for j in i + 1..=n {
            let c = Rational::from(&ma[i] * &mb[j]) - Rational::from(&ma[j] * &mb[i]);
            if c == 0 {
                continue;
            }
            // (t^i s^j − t^j s^i) = −(ts)^i (t − s) Σ_{k<d} t^k s^{d−1−k}, d = j − i.
            for k in 0..j - i {
                q[(i + k) * (m + 1) + (j - 1 - k)] -= &c;
            }
        }
    }
    from_power_2d(&q, m)
}

fn same_degree(a: &Poly, b: &Poly) -> (Poly, Poly) {
    let n = a.degrees()[0].max(b.degrees()[0]);
    (a.elevate_to(&[n]), b.elevate_to(&[n]))
}

fn binom(n: usize, k: usize) -> Rational {
    let mut r = Rational::from(1);
    for i in 0..k {
        r *= Rational::from(((n - i) as i64, (i + 1) as i64));
    }
    r
}

/// Power-basis coefficients of a univariate Bernstein polynomial.
fn to_power(p: &Poly) -> Vec<Rational> {
    let n = p.degrees()[0];
    let b = p.coeffs();
    (0..=n)
        .map(|k| {
            let mut s = Rational::new();
            for (i, bi) in b.iter().enumerate().take(k + 1) {
                let t = Rational::from(bi * &binom(k, i));
                if (k - i) % 2 == 0 {
                    s += t;
                } else {
                    s -= t;
                }
            }
            s * binom(n, k)
        })
        .collect()
}

/// The Bernstein form of degree (m, m) of a power-basis polynomial `Σ q[i(m+1)+j] t^i s^j`.
fn from_power_2d(q: &[Rational], m: usize) -> Poly {
    // b_{ij} = Σ_{k≤i, l≤j} C(i,k) C(j,l) / (C(m,k) C(m,l)) q_{kl}.
    let w: Vec<Vec<Rational>> = (0..=m)
        .map(|i| {
            (0..=m)
                .map(|k| {
                    if k <= i {
                        binom(i, k) / binom(m, k)
                    } else {
                        Rational::new()
                    }
                })
                .collect()
        })
        .collect();
    let mut out = vec![Rational::new(); (m + 1) * (m + 1)];
    for i in 0..=m {
        for j in 0..=m {
            let mut s = Rational::new();
            for k in 0..=i {
                for l in 0..=j {
                    let c = &q[k * (m + 1) + l];
                    if *c != 0 {
                        s += Rational::from(&w[i][k] * &w[j][l]) * c;
                    }
                }
            }
            out[i * (m + 1) + j] = s;
        }
    }
    Bernstein::new(&[m, m], out).expect("degree (m, m)")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_quotient_times_t_minus_s_is_the_antisymmetric_product() {
        let r = |n: i64, d: i64| Rational::from((n, d));
        let a = Bernstein::new(&[3], vec![r(1, 2), r(-3, 1), r(5, 7), r(2, 1)]).unwrap();
        let b = Bernstein::new(&[2], vec![r(4, 1), r(1, 3), r(-1, 5)]).unwrap();
        let q = antisymmetric_quotient(&a, &b);
        assert_eq!(q.degrees(), &[2, 2]);
        for (t, s) in [(r(1, 3), r(5, 7)), (r(0, 1), r(1, 1)), (r(9, 10), r(1, 8))] {
            let lhs = q.eval(&[t.clone(), s.clone()]) * Rational::from(&t - &s);
            let ev = |p: &Poly, x: &Rational| p.eval(std::slice::from_ref(x));
            let rhs = ev(&a, &t) * ev(&b, &s) - ev(&a, &s) * ev(&b, &t);
            assert_eq!(lhs, rhs, "at ({t}, {s})");
        }
    }
}
