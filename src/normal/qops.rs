//! Rational arithmetic with a machine-word fast path.
//!
//! `num-rational` reduces every result with a big-integer gcd, which dominates the
//! cost of polynomial work whose coefficients are small (the usual case). These
//! functions compute in `i128` when every input fits in an `i64`, reduce with a
//! binary gcd on machine words, and build the result without a second reduction;
//! otherwise they fall back to `num-rational`. The result is the same canonical
//! `BigRational` either way (lowest terms, positive denominator).

use super::poly::Q;
use num_bigint::BigInt;
use num_traits::{ToPrimitive, Zero};

/// `(numerator, denominator)` as `i64`s when both fit.
fn small(q: &Q) -> Option<(i64, i64)> {
    Some((q.numer().to_i64()?, q.denom().to_i64()?))
}

/// Binary (Stein) gcd, one body for each word size.
macro_rules! binary_gcd {
    ($name:ident, $t:ty) => {
        /// Binary gcd of two unsigned integers.
        fn $name(mut a: $t, mut b: $t) -> $t {
            if a == 0 {
                return b;
            }
            if b == 0 {
                return a;
            }
            let shift = (a | b).trailing_zeros();
            a >>= a.trailing_zeros();
            loop {
                b >>= b.trailing_zeros();
                if a > b {
                    std::mem::swap(&mut a, &mut b);
                }
                b -= a;
                if b == 0 {
                    return a << shift;
                }
            }
        }
    };
}

binary_gcd!(gcd_u64, u64);
binary_gcd!(gcd_u128, u128);

/// `n` as a big integer (through `i64` when it fits: that conversion is cheaper).
fn big(n: i128) -> BigInt {
    match i64::try_from(n) {
        Ok(n) => BigInt::from(n),
        Err(_) => BigInt::from(n),
    }
}

/// The integer `n`.
fn int(n: i128) -> Q {
    Q::from_integer(big(n))
}

/// `n/d` in lowest terms from machine integers (`d ≠ 0`).
fn make(n: i128, d: i128) -> Q {
    if n == 0 {
        return Q::zero();
    }
    if d == 1 {
        return int(n);
    }
    if let (Ok(n64), Ok(d64)) = (i64::try_from(n), i64::try_from(d)) {
        // Word-sized gcd; the 128-bit division only when there is a common factor.
        let g = gcd_u64(n64.unsigned_abs(), d64.unsigned_abs());
        let (n, d) = if g == 1 {
            (n, d)
        } else {
            (n / i128::from(g), d / i128::from(g))
        };
        let (n, d) = if d < 0 { (-n, -d) } else { (n, d) };
        return Q::new_raw(big(n), big(d));
    }
    let g = gcd_u128(n.unsigned_abs(), d.unsigned_abs());
    // g ≤ |d| ≤ i128::MAX, so the cast is lossless; |n|, |d| < 2^127 by construction.
    let g = g as i128;
    let (mut n, mut d) = (n / g, d / g);
    if d < 0 {
        n = -n;
        d = -d;
    }
    Q::new_raw(big(n), big(d))
}

/// `a · b`.
pub fn mul(a: &Q, b: &Q) -> Q {
    match (small(a), small(b)) {
        (Some((an, 1)), Some((bn, 1))) => int(i128::from(an) * i128::from(bn)),
        (Some((an, ad)), Some((bn, bd))) => {
            // |an·bn|, |ad·bd| < 2^126.
            make(
                i128::from(an) * i128::from(bn),
                i128::from(ad) * i128::from(bd),
            )
        }
        _ => a * b,
    }
}

/// `a + b`.
pub fn add(a: &Q, b: &Q) -> Q {
    match (small(a), small(b)) {
        (Some((an, 1)), Some((bn, 1))) => int(i128::from(an) + i128::from(bn)),
        (Some((an, ad)), Some((bn, bd))) => {
            if ad == bd {
                return make(i128::from(an) + i128::from(bn), i128::from(ad));
            }
            // Each product is below 2^126 in magnitude, so the sum is below 2^127.
            let n = i128::from(an) * i128::from(bd) + i128::from(bn) * i128::from(ad);
            make(n, i128::from(ad) * i128::from(bd))
        }
        _ => a + b,
    }
}

/// `a − b`.
pub fn sub(a: &Q, b: &Q) -> Q {
    match (small(a), small(b)) {
        (Some((an, ad)), Some((bn, bd))) => {
            let n = i128::from(an) * i128::from(bd) - i128::from(bn) * i128::from(ad);
            make(n, i128::from(ad) * i128::from(bd))
        }
        _ => a - b,
    }
}

/// `a / b`, `b ≠ 0`.
pub fn div(a: &Q, b: &Q) -> Q {
    match (small(a), small(b)) {
        (Some((an, 1)), Some((bn, 1))) if an.checked_rem(bn) == Some(0) => {
            // An exact integer quotient needs no gcd (i64::MIN % -1 overflows, so
            // checked_rem sends it to the general path).
            int(i128::from(an) / i128::from(bn))
        }
        (Some((an, ad)), Some((bn, bd))) if bn != 0 => make(
            i128::from(an) * i128::from(bd),
            i128::from(ad) * i128::from(bn),
        ),
        _ => a / b,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn q(n: i64, d: i64) -> Q {
        Q::new(BigInt::from(n), BigInt::from(d))
    }

    fn any_q() -> impl Strategy<Value = Q> {
        let part = prop_oneof![
            -5i64..=5,
            any::<i64>(),
            Just(i64::MIN),
            Just(i64::MAX),
            Just(i64::MIN + 1)
        ];
        let den = prop_oneof![1i64..=6, any::<i64>(), Just(i64::MIN), Just(i64::MAX)];
        (part, den.prop_filter("nonzero", |d| *d != 0))
            .prop_map(|(n, d)| Q::new(BigInt::from(n), BigInt::from(d)))
    }

    #[test]
    fn small_cases() {
        assert_eq!(mul(&q(2, 3), &q(3, 4)), q(1, 2));
        assert_eq!(add(&q(1, 6), &q(1, 3)), q(1, 2));
        assert_eq!(add(&q(1, 2), &q(-1, 2)), q(0, 1));
        assert_eq!(div(&q(1, 2), &q(-3, 4)), q(-2, 3));
        assert_eq!(gcd_u128(0, 0), 0);
        assert_eq!(gcd_u128(12, 18), 6);
        assert_eq!(gcd_u64(0, 7), 7);
        assert_eq!(gcd_u64(1 << 40, 3 << 38), 1 << 38);
        assert_eq!(gcd_u128(1 << 100, 3 << 98), 1 << 98);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]
        #[test]
        fn agrees_with_num_rational(a in any_q(), b in any_q()) {
            prop_assert_eq!(mul(&a, &b), &a * &b);
            prop_assert_eq!(add(&a, &b), &a + &b);
            prop_assert_eq!(sub(&a, &b), &a - &b);
            if !b.is_zero() {
                prop_assert_eq!(div(&a, &b), &a / &b);
            }
        }
    }
}
