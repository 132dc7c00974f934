//! Cramer's quotients `x_k = num_k / (det · c_k)`, which all share the determinant,
//! brought to lowest terms with one proof about `det` instead of one gcd per unknown.
//!
//! Write `det = κ · M · P`: `κ` its leading coefficient, `M` its monomial content and
//! `P` monic with no monomial factor. When `P` is 1, or has degree 1 in some atom `v`
//! with coprime coefficients (`P = a·v + b`, `gcd(a, b) = 1`), `P` is irreducible: in a
//! factorisation one factor is free of `v`, so it divides `a` and `b` and is a
//! constant. Atoms are primes and `P` is prime to every monomial, so
//! `gcd(num_k, M·c_k·P)` is the monomial `gcd(content(num_k), M·c_k)` times `P` when `P`
//! divides `num_k`, and each quotient needs only its monomial content, one
//! divisibility test (evaluation proves most non-divisibility, an exact division
//! decides the rest) and one scaling. Everything here assumes atoms without rewrite
//! rules, which the caller checks.

use super::packed::{Ring, P};
use crate::normal::gcd::{div_exact, gcd, LinearFactor};
use crate::normal::mono::Mono;
use crate::normal::{AtomId, Limit, Poly, Rat, Q};
use num_traits::One;

/// What is proved about a nonzero determinant: `det = κ · mono · P`, `P` monic,
/// without a monomial factor, and irreducible (or 1).
pub(super) struct Denominator {
    kappa: Q,
    /// `1/κ`: the scaling that makes every quotient's denominator monic.
    inv: Q,
    mono: Mono,
    /// `P`, with an atom in which it has degree 1 with coprime coefficients; `None`
    /// when `P` is 1.
    prime: Option<LinearFactor>,
    /// `P`'s atoms (ascending) and its total degree in them: a polynomial of lower
    /// degree in them is not a multiple of `P`.
    atoms: Vec<AtomId>,
    degree: u64,
}

impl Denominator {
    /// The proof about `det`, `None` when it is not shown (zero, a reducible `P`, or
    /// no atom of degree 1): the caller then reduces each quotient on its own.
    pub(super) fn new(det: &Poly) -> Result<Option<Denominator>, Limit> {
        let Some((_, kappa)) = det.lead() else {
            return Ok(None);
        };
        let inv = kappa.recip();
        let mono = det.mono_content();
        // Dividing by a monomial keeps the order: P's leading coefficient is κ's.
        let p = det
            .div_mono(&mono)
            .ok_or(Limit::Exponent)?
            .into_scaled(&inv);
        let atoms = p.atoms();
        let degree = degree_in(&p, &atoms);
        let mut out = Denominator {
            kappa: kappa.clone(),
            inv,
            mono,
            prime: None,
            atoms,
            degree,
        };
        if p.is_one() {
            return Ok(Some(out));
        }
        let Some(&v) = out.atoms.iter().find(|&&v| p.degree_in(v) == 1) else {
            return Ok(None);
        };
        let coeffs = p.coeffs_in(v);
        let [(0, b), (1, a)] = coeffs.as_slice() else {
            return Ok(None);
        };
        if !gcd(a, b)?.is_one() {
            // P is reducible: a factor free of v divides both coefficients.
            return Ok(None);
        }
        out.prime = LinearFactor::new(p, v);
        Ok(out.prime.is_some().then_some(out))
    }

    /// `num / (det · c)` in lowest terms, with a monic denominator: the value of
    /// `Rat::new(num, det · c)`.
    pub(super) fn quotient(&self, num: Poly, c: &Mono) -> Result<Rat, Limit> {
        if num.is_zero() {
            return Ok(Rat::zero());
        }
        let full = self.mono.mul(c).ok_or(Limit::Exponent)?;
        let g = common_content(&num, &full).ok_or(Limit::Exponent)?;
        let num = if g.is_one() {
            num
        } else {
            num.div_mono(&g).ok_or(Limit::Exponent)?
        };
        let rest = full.div(&g).ok_or(Limit::Exponent)?;
        self.finish(num.into_scaled(&self.inv), rest)
    }

    /// [`Denominator::quotient`] of a packed numerator (integer coefficients): the
    /// monomial content found and divided out, and the scaling by `1/κ` done, while
    /// unpacking. `None` when the packed form does not serve (the caller unpacks).
    pub(super) fn quotient_packed(
        &self,
        ring: &Ring,
        num: &P,
        c: &Mono,
    ) -> Result<Option<Rat>, Limit> {
        if num.is_empty() {
            return Ok(Some(Rat::zero()));
        }
        let full = self.mono.mul(c).ok_or(Limit::Exponent)?;
        let Some((g, packed)) = ring.common_content(num, &full) else {
            return Ok(None);
        };
        let (kappa, true) = (self.kappa.numer(), self.kappa.denom().is_one()) else {
            return Ok(None);
        };
        let Some(num) = ring.unpack_over(num, packed, kappa) else {
            return Ok(None);
        };
        let rest = full.div(&g).ok_or(Limit::Exponent)?;
        self.finish(num, rest).map(Some)
    }

    /// `num / (rest · P)` for `num` already over `κ` and sharing no atom with `rest`
    /// that both can spare: `P` cancelled when it divides `num`.
    fn finish(&self, mut num: Poly, rest: Mono) -> Result<Rat, Limit> {
        let den = match &self.prime {
            None => Poly::term(rest, Q::one()),
            Some(p) => {
                let quotient =
                    if degree_in(&num, &self.atoms) < self.degree || p.shown_not_to_divide(&num) {
                        None
                    } else {
                        div_exact(&num, p.poly())?
                    };
                match quotient {
                    // P divides num (once is all det has).
                    Some(q) => {
                        num = q;
                        Poly::term(rest, Q::one())
                    }
                    None => p.poly().mul_term(&rest, &Q::one())?,
                }
            }
        };
        // num and den are coprime: the monomial parts by the choice of g (P has no
        // monomial factor, so num/P has num's monomial content), and P, irreducible,
        // is in den only when it does not divide num. den is monic: a monomial times
        // the monic P, whose leading term a monomial factor keeps leading.
        Ok(Rat::from_coprime(num, den))
    }
}

/// The total degree of `p` in `atoms` (ascending): the most any term has. A multiple
/// of `q` has at least `q`'s (the terms of highest degree in `atoms` multiply, over a
/// domain, to terms of the product's).
fn degree_in(p: &Poly, atoms: &[AtomId]) -> u64 {
    let mut most = 0u64;
    for (m, _) in p.terms() {
        let (mut d, mut i) = (0u64, 0);
        for &(x, e) in m.pairs() {
            while atoms.get(i).is_some_and(|&a| a < x) {
                i += 1;
            }
            if atoms.get(i) == Some(&x) {
                d += u64::from(e);
            }
        }
        most = most.max(d);
    }
    most
}

/// The largest monomial dividing `full` and every term of `p`: `gcd(content(p), full)`,
/// found by lowering `full`'s exponents term by term (no monomial is built per term).
fn common_content(p: &Poly, full: &Mono) -> Option<Mono> {
    let mut g: Vec<(AtomId, u32)> = full.pairs().to_vec();
    for (m, _) in p.terms() {
        if g.is_empty() {
            break;
        }
        for slot in &mut g {
            slot.1 = slot.1.min(m.exp(slot.0));
        }
        g.retain(|s| s.1 > 0);
    }
    Mono::from_pairs(g)
}

#[cfg(test)]
mod tests {
    use super::super::linear::tests::{poly, var};
    use super::*;
    use num_bigint::BigInt;
    use proptest::prelude::*;

    /// A polynomial in atoms `from..4`.
    fn any_poly(from: u32) -> impl Strategy<Value = Poly> {
        let term = (
            proptest::collection::vec((from..4, 1u32..3), 0..3),
            -4i64..=4,
        );
        proptest::collection::vec(term, 1..4).prop_map(|t| poly(&t))
    }

    fn any_mono() -> impl Strategy<Value = Mono> {
        proptest::collection::vec((0u32..4, 1u32..3), 0..3).prop_map(|p| {
            Mono::from_pairs(p.into_iter().map(|(a, e)| (var(a), e)).collect())
                .unwrap_or_else(Mono::one)
        })
    }

    /// `κ · M · (a·x₀ + b)` and a numerator: random, or a multiple of the linear factor.
    fn any_case() -> impl Strategy<Value = (Poly, Poly, Mono)> {
        (
            any_poly(1),
            any_poly(1),
            any_poly(1),
            -3i64..=3,
            any_mono(),
            any_mono(),
            any_poly(0),
            any::<bool>(),
        )
            .prop_map(|(a, b, second, kappa, m, c, r, multiple)| {
                let x = Poly::atom(var(0));
                let ok = |p: Result<Poly, Limit>| p.unwrap_or_else(|_| Poly::zero());
                let mut p = ok(a.mul(&x)).add(&b);
                if kappa == 0 {
                    // A reducible determinant now and then: the factor twice over.
                    p = ok(p.mul(&second.add(&x)));
                }
                let det = ok(p.mul_term(&m, &Q::from_integer(BigInt::from(kappa.max(1)))));
                let num = if multiple { ok(r.mul(&p)) } else { r };
                (det, num, c)
            })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(400))]

        /// Whenever the proof about the determinant is made, each quotient is the
        /// canonical form `Rat::new` gives.
        #[test]
        fn quotient_is_rat_new((det, num, c) in any_case()) {
            if det.is_zero() {
                return Ok(());
            }
            let Ok(Some(d)) = Denominator::new(&det) else {
                return Ok(());
            };
            let want = det
                .mul_term(&c, &Q::from_integer(BigInt::from(1)))
                .map_err(|e| TestCaseError::fail(format!("{e}")))
                .and_then(|den| {
                    Rat::new(num.clone(), den).map_err(|e| TestCaseError::fail(format!("{e}")))
                })?;
            let got = d.quotient(num, &c).map_err(|e| TestCaseError::fail(format!("{e}")))?;
            prop_assert_eq!(got, want);
        }
    }

    /// The proof is made for a determinant linear in an atom with coprime
    /// coefficients, and refused for one with a repeated factor; a multiple of the
    /// factor cancels it.
    #[test]
    fn irreducible_and_reducible_determinants() {
        let x = |i: u32| Poly::atom(var(i));
        let ok = |p: Result<Poly, Limit>| p.unwrap_or_else(|e| panic!("{e}"));
        // 2·x₁·(x₀ x₂ + x₃): linear in x₀, coefficients x₂ and x₃ coprime.
        let p = ok(x(0).mul(&x(2))).add(&x(3));
        let det = ok(ok(p.mul(&x(1))).mul(&Poly::int(2)));
        let d = match Denominator::new(&det) {
            Ok(Some(d)) => d,
            _ => panic!("the proof about an irreducible determinant"),
        };
        let num = ok(p.mul(&x(1)));
        let r = d
            .quotient(num, &Mono::one())
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(r, Rat::constant(Q::new(BigInt::from(1), BigInt::from(2))));
        // (x₀ + x₁)²: every atom of degree 2, no proof.
        let sq = ok(x(0).add(&x(1)).mul(&x(0).add(&x(1))));
        assert!(matches!(Denominator::new(&sq), Ok(None)));
        // x₀ x₂ + x₁ x₂ = x₂ (x₀ + x₁): the monomial factor leaves P = x₀ + x₁.
        let det = ok(x(0).mul(&x(2))).add(&ok(x(1).mul(&x(2))));
        assert!(matches!(Denominator::new(&det), Ok(Some(_))));
        // (x₀ x₂ + x₁ x₂ + x₀ + x₁) = (x₂ + 1)(x₀ + x₁): linear in x₀ with coefficients
        // x₂ + 1 and x₁ x₂ + x₁, which share x₂ + 1.
        let det = ok(x(2).add(&Poly::one()).mul(&x(0).add(&x(1))));
        assert!(matches!(Denominator::new(&det), Ok(None)));
    }
}
