//! Packed exponent vectors for the inner loops of multiplication and exact division.
//!
//! A [`Packing`] gives each atom of the operands a bit field of a `u128`, lowest atom
//! id in the lowest bits, each field wide enough for the largest exponent the
//! operation can produce. Multiplying monomials is then one integer addition, and
//! comparing them one integer comparison: with the highest atom id most significant,
//! the integer order is exactly [`Mono`]'s lexicographic order. When the fields do not
//! fit in 128 bits the callers keep to the general [`Mono`] path.

use super::atom::AtomId;
use super::mono::Mono;
use super::poly::Poly;
use super::Limit;

/// The bit fields of a set of atoms.
pub struct Packing {
    /// `(atom, shift, width)`, ascending by atom id.
    fields: Vec<(AtomId, u32, u32)>,
}

impl Packing {
    /// A packing whose field for atom `a` holds exponents up to `max(a)`, for the atoms
    /// listed (ascending, distinct); `None` when the fields need more than 128 bits.
    pub fn new(atoms: &[(AtomId, u64)]) -> Option<Packing> {
        let mut fields = Vec::with_capacity(atoms.len());
        let mut shift = 0u32;
        for &(a, max) in atoms {
            let width = (u64::BITS - max.leading_zeros()).max(1);
            fields.push((a, shift, width));
            shift = shift.checked_add(width)?;
        }
        (shift <= 128).then_some(Packing { fields })
    }

    /// A packing for the product of `a` and `b`: each field holds the sum of the two
    /// degrees.
    pub fn for_product(a: &Poly, b: &Poly) -> Option<Packing> {
        Packing::new(&merge_degrees(&degrees(a), &degrees(b), |x, y| x + y))
    }

    /// A packing for dividing `a` by `b`: each field holds the larger of the two degrees
    /// (an exact quotient never needs more, see [`super::gcd::div_exact`]).
    pub fn for_quotient(a: &Poly, b: &Poly) -> Option<Packing> {
        Packing::new(&merge_degrees(&degrees(a), &degrees(b), u64::max))
    }

    /// The packed form of `m`, `None` if an atom has no field or its exponent does
    /// not fit.
    pub fn pack(&self, m: &Mono) -> Option<u128> {
        let mut out = 0u128;
        let mut i = 0;
        for &(a, e) in m.pairs() {
            while self.fields.get(i)?.0 < a {
                i += 1;
            }
            let &(b, shift, width) = self.fields.get(i)?;
            if b != a || (width < 32 && e >> width != 0) {
                return None;
            }
            out |= u128::from(e) << shift;
        }
        Some(out)
    }

    /// The monomial of a packed value.
    pub fn unpack(&self, mut v: u128) -> Mono {
        // At most 128 fields (each at least one bit wide): collect on the stack, then
        // allocate once, at the right size.
        let mut buf = [(AtomId::default(), 0u32); 128];
        let mut n = 0;
        for &(a, _, width) in &self.fields {
            let mask = (1u128 << width) - 1;
            let e = (v & mask) as u32;
            if e != 0 {
                if let Some(slot) = buf.get_mut(n) {
                    *slot = (a, e);
                    n += 1;
                }
            }
            v >>= width;
            if v == 0 {
                break;
            }
        }
        Mono::from_sorted_pairs(buf.get(..n).unwrap_or(&[]).to_vec())
    }

    /// `a / b` when `b` divides `a` and every exponent of the quotient is at most the
    /// matching one of `limit`.
    pub fn div(&self, a: u128, b: u128, limit: u128) -> Option<u128> {
        let mut q = 0u128;
        for &(_, shift, width) in &self.fields {
            let mask = ((1u128 << width) - 1) << shift;
            let (x, y, l) = (a & mask, b & mask, limit & mask);
            if y > x || x - y > l {
                return None;
            }
            q |= x - y;
        }
        Some(q)
    }
}

/// The largest exponent of every atom of `p`, ascending by atom id.
pub(crate) fn degrees(p: &Poly) -> Vec<(AtomId, u64)> {
    let (mut lo, mut hi) = (u32::MAX, 0);
    for (m, _) in p.terms() {
        if let (Some(first), Some(last)) = (m.pairs().first(), m.pairs().last()) {
            lo = lo.min(first.0.index());
            hi = hi.max(last.0.index());
        }
    }
    if lo > hi {
        return Vec::new();
    }
    if hi - lo < 4096 {
        // A direct table over the atom ids in use.
        let mut table = vec![0u32; (hi - lo) as usize + 1];
        for (m, _) in p.terms() {
            for &(a, e) in m.pairs() {
                if let Some(t) = table.get_mut((a.index() - lo) as usize) {
                    *t = (*t).max(e);
                }
            }
        }
        return (lo..=hi)
            .zip(table)
            .filter(|t| t.1 > 0)
            .map(|(a, e)| (AtomId::from_index(a), u64::from(e)))
            .collect();
    }
    let mut out: Vec<(AtomId, u64)> = Vec::new();
    for (m, _) in p.terms() {
        for &(a, e) in m.pairs() {
            match out.binary_search_by_key(&a, |t| t.0) {
                Ok(i) => {
                    if let Some(t) = out.get_mut(i) {
                        t.1 = t.1.max(u64::from(e));
                    }
                }
                Err(i) => out.insert(i, (a, u64::from(e))),
            }
        }
    }
    out
}

/// The union of two degree lists, combining the degrees of shared atoms with `f`.
fn merge_degrees(
    a: &[(AtomId, u64)],
    b: &[(AtomId, u64)],
    f: impl Fn(u64, u64) -> u64,
) -> Vec<(AtomId, u64)> {
    let mut out = Vec::with_capacity(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    while i < a.len() || j < b.len() {
        match (a.get(i), b.get(j)) {
            (Some(x), Some(y)) if x.0 == y.0 => {
                out.push((x.0, f(x.1, y.1)));
                i += 1;
                j += 1;
            }
            (Some(x), Some(y)) if x.0 < y.0 => {
                out.push((x.0, f(x.1, 0)));
                i += 1;
            }
            (Some(x), None) => {
                out.push((x.0, f(x.1, 0)));
                i += 1;
            }
            (_, Some(y)) => {
                out.push((y.0, f(0, y.1)));
                j += 1;
            }
            (None, None) => break,
        }
    }
    out
}

/// `p^k` by the multinomial theorem, when no two terms of `p` share an atom (a constant
/// term shares none): then every choice of exponents `α` with `|α| = k` gives a
/// different monomial `Π mᵢ^αᵢ`, with coefficient `k!/Π αᵢ! · Π cᵢ^αᵢ`, so each term of
/// the power is made once, with no products to merge, and the terms are sorted once.
/// `None` when terms share an atom, the monomials do not pack, or a coefficient (over
/// the common denominator) leaves `i128`: the callers multiply instead.
pub(crate) fn pow_multinomial(p: &Poly, k: u64) -> Result<Option<Poly>, Limit> {
    use num_bigint::BigInt;
    use num_integer::Integer;
    use num_traits::{One, ToPrimitive};
    let mut ids: Vec<AtomId> = p
        .terms()
        .iter()
        .flat_map(|(m, _)| m.pairs().iter().map(|t| t.0))
        .collect();
    let all = ids.len();
    ids.sort_unstable();
    ids.dedup();
    let Ok(k32) = u32::try_from(k) else {
        return Ok(None);
    };
    if ids.len() != all || p.len() < 2 || k < 2 {
        return Ok(None);
    }
    let fields: Vec<(AtomId, u64)> = degrees(p)
        .into_iter()
        .map(|(a, d)| (a, d.saturating_mul(k)))
        .collect();
    let Some(pk) = Packing::new(&fields) else {
        return Ok(None);
    };
    // Integer coefficients over the common denominator `l`: p = (1/l) Σ cᵢ mᵢ.
    let mut l = BigInt::one();
    for (_, q) in p.terms() {
        l = l.lcm(q.denom());
    }
    let mut base: Vec<(u128, i128)> = Vec::with_capacity(p.len());
    for (m, q) in p.terms() {
        let c = (q.numer() * (&l / q.denom())).to_i128();
        match (pk.pack(m), c) {
            (Some(x), Some(c)) => base.push((x, c)),
            _ => return Ok(None),
        }
    }
    let mut out: Vec<(u128, i128)> = Vec::new();
    if !multinomial_terms(&base, k32, 0, 1, &mut out) {
        return Ok(None);
    }
    if out.len() > super::poly::max_terms() {
        return Err(Limit::terms());
    }
    super::poly::check_deadline()?;
    out.sort_unstable_by_key(|t| t.0);
    let scale = super::poly::pow_q_checked(&super::poly::Q::new(BigInt::one(), l), k32)?;
    let terms = out
        .into_iter()
        .map(|(x, c)| {
            let c = super::poly::Q::from_integer(BigInt::from(c));
            (pk.unpack(x), super::qops::mul(&c, &scale))
        })
        .collect();
    Ok(Some(Poly::from_sorted_terms(terms)))
}

/// The terms `(Σ αᵢ mᵢ, coeff · Π C(rᵢ, αᵢ) cᵢ^αᵢ)` of the multinomial expansion of the
/// packed terms `base` to the power `left`, pushed onto `out`; `false` on overflow.
fn multinomial_terms(
    base: &[(u128, i128)],
    left: u32,
    mono: u128,
    coeff: i128,
    out: &mut Vec<(u128, i128)>,
) -> bool {
    let Some((&(m, c), rest)) = base.split_first() else {
        return true;
    };
    if rest.is_empty() {
        // The last term takes the exponent that is left.
        let Some(cp) = c.checked_pow(left) else {
            return false;
        };
        let Some(coeff) = coeff.checked_mul(cp) else {
            return false;
        };
        out.push((mono + m * u128::from(left), coeff));
        return true;
    }
    // binom = C(left, a), power = c^a.
    let (mut binom, mut power) = (1i128, 1i128);
    for a in 0..=left {
        let Some(t) = coeff.checked_mul(binom).and_then(|t| t.checked_mul(power)) else {
            return false;
        };
        if !multinomial_terms(rest, left - a, mono + m * u128::from(a), t, out) {
            return false;
        }
        if a < left {
            let Some(b) = binom.checked_mul(i128::from(left - a)) else {
                return false;
            };
            binom = b / i128::from(a + 1);
            let Some(pw) = power.checked_mul(c) else {
                return false;
            };
            power = pw;
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_bigint::BigInt;
    use num_traits::{One, Pow};
    use proptest::prelude::*;

    fn mono(pairs: &[(u32, u32)]) -> Mono {
        let pairs = pairs.iter().map(|&(a, e)| (AtomId::from_index(a), e));
        Mono::from_pairs(pairs.collect()).unwrap_or_else(Mono::one)
    }

    /// Atoms numbered as written, with their degrees.
    fn ids(pairs: &[(u32, u64)]) -> Vec<(AtomId, u64)> {
        pairs
            .iter()
            .map(|&(a, e)| (AtomId::from_index(a), e))
            .collect()
    }

    fn any_mono() -> impl Strategy<Value = Mono> {
        proptest::collection::vec((0u32..6, 0u32..9), 0..5).prop_map(|v| mono(&v))
    }

    /// A sum of terms without a common atom: term `i` uses atoms `3i`, `3i + 1`, `3i + 2`
    /// (a term with no exponents is the constant).
    fn disjoint_sum() -> impl Strategy<Value = Poly> {
        proptest::collection::vec(
            (proptest::collection::vec(0u32..4, 3), -9i64..10, 1i64..5),
            1..5,
        )
        .prop_map(|ts| {
            let terms = ts
                .into_iter()
                .enumerate()
                .map(|(i, (es, n, d))| {
                    let i = i as u32;
                    let pairs: Vec<(u32, u32)> = es
                        .iter()
                        .enumerate()
                        .map(|(j, &e)| (3 * i + j as u32, e))
                        .collect();
                    let q = super::super::poly::Q::new(n.into(), d.into());
                    (mono(&pairs), q)
                })
                .collect();
            Poly::from_terms(terms)
        })
    }

    proptest! {
        /// The multinomial expansion is the repeated product, term for term.
        #[test]
        fn multinomial_power_is_the_repeated_product(p in disjoint_sum(), k in 0u64..9) {
            let mut want = Poly::one();
            for _ in 0..k {
                want = want.mul(&p).unwrap_or_else(|_| unreachable!());
            }
            if let Some(got) = pow_multinomial(&p, k).unwrap_or_else(|_| unreachable!()) {
                prop_assert_eq!(&got, &want);
            } else {
                // Refused only when the expansion does not apply.
                let atoms: usize = p.terms().iter().map(|t| t.0.pairs().len()).sum();
                prop_assert!(k < 2 || p.len() < 2 || atoms != p.atoms().len());
            }
            prop_assert_eq!(p.pow(k).unwrap_or_else(|_| unreachable!()), want);
        }
    }

    #[test]
    fn multinomial_power_needs_terms_without_a_common_atom() {
        let q = super::super::poly::Q::one();
        let shared = Poly::from_terms(vec![
            (mono(&[(1, 1)]), q.clone()),
            (mono(&[(1, 2), (2, 1)]), q.clone()),
        ]);
        assert!(matches!(pow_multinomial(&shared, 3), Ok(None)));
        let big = Poly::from_terms(vec![
            (mono(&[]), q.clone()),
            (
                mono(&[(1, 1)]),
                super::super::poly::Q::from_integer(10i64.pow(15).into()),
            ),
        ]);
        // (1 + 10^15 x)^9 has a coefficient beyond i128: the caller multiplies instead.
        assert!(matches!(pow_multinomial(&big, 9), Ok(None)));
        assert_eq!(
            big.pow(9).ok().and_then(|p| p.lead().map(|t| t.1.clone())),
            Some(super::super::poly::Q::from_integer(
                BigInt::from(10).pow(135u32)
            ))
        );
    }

    #[test]
    fn too_wide_is_refused() {
        let atoms: Vec<(AtomId, u64)> = (0..70).map(|a| (AtomId::from_index(a), 3)).collect();
        assert!(Packing::new(&atoms).is_none());
        assert!(Packing::new(&atoms[..64]).is_some());
    }

    #[test]
    fn exponents_that_do_not_fit_are_refused() {
        let p = Packing::new(&ids(&[(1, 3), (4, 1)])).unwrap_or_else(|| unreachable!());
        assert!(p.pack(&mono(&[(1, 3), (4, 1)])).is_some());
        assert!(p.pack(&mono(&[(1, 4)])).is_none());
        assert!(p.pack(&mono(&[(2, 1)])).is_none());
        assert!(p.pack(&mono(&[(9, 1)])).is_none());
    }

    #[test]
    fn degrees_near_and_far_apart() {
        let q = super::super::poly::Q::one();
        for far in [7, 100_000] {
            let p = Poly::from_terms(vec![
                (mono(&[(3, 2), (far, 1)]), q.clone()),
                (mono(&[(3, 5)]), q.clone()),
                (mono(&[(far, 4)]), q.clone()),
            ]);
            assert_eq!(degrees(&p), ids(&[(3, 5), (far, 4)]));
        }
        assert!(degrees(&Poly::one()).is_empty());
    }

    proptest! {
        #[test]
        fn packing_keeps_products_order_and_quotients(a in any_mono(), b in any_mono()) {
            let pa = Poly::term(a.clone(), super::super::poly::Q::one());
            let pb = Poly::term(b.clone(), super::super::poly::Q::one());
            let Some(p) = Packing::for_product(&pa, &pb) else {
                return Ok(());
            };
            let (Some(x), Some(y)) = (p.pack(&a), p.pack(&b)) else {
                return Err(TestCaseError::fail("operands must pack"));
            };
            prop_assert_eq!(p.unpack(x), a.clone());
            let ab = a.mul(&b).unwrap_or_else(Mono::one);
            prop_assert_eq!(p.unpack(x + y), ab.clone());
            prop_assert_eq!(x.cmp(&y), a.cmp(&b));
            prop_assert_eq!(p.div(x + y, y, u128::MAX).map(|q| p.unpack(q)), Some(a.clone()));
            prop_assert_eq!(p.div(x, y, u128::MAX).map(|q| p.unpack(q)), a.div(&b));
        }
    }
}
