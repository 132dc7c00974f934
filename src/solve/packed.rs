//! The solver's determinants on packed integer polynomials: every monomial one `u128`
//! (a [`Packing`] chosen once for the whole matrix), every coefficient one `i128`.
//!
//! Bareiss elimination over ℤ[atoms] keeps every entry a minor of the matrix, so one
//! packing whose fields hold twice the largest degree a minor can have serves every
//! product and every exact quotient of the elimination, and nothing is converted back
//! to [`Poly`] (with its allocated monomials and big rationals) until the end. Any
//! coefficient that would overflow `i128`, any monomial that does not fit, and any
//! division that is not exact make the whole attempt `None`: the caller then runs the
//! general path, which gives the same result (or the same refusal) more slowly.

use crate::normal::limits::{check_deadline, max_terms};
use crate::normal::mono::Mono;
use crate::normal::pack::{degrees, Packing};
use crate::normal::poly::FxBuild;
use crate::normal::{Poly, Q};
use num_bigint::BigInt;
use num_traits::{One, ToPrimitive};
use std::collections::btree_map::Entry;
use std::collections::{BTreeMap, HashMap};

/// A polynomial: `(packed monomial, coefficient)`, strictly ascending, no zero.
pub(super) type P = Vec<(u128, i128)>;

/// The packing of one matrix and the largest exponents a minor of it can have.
pub(super) struct Ring {
    pk: Packing,
    /// Each field holds the degree bound of its atom: the exponent limit of a quotient.
    limit: u128,
}

impl Ring {
    /// A ring for the minors of `m` (every row of the same length), `None` when its
    /// entries have non-integer coefficients or the degrees do not fit 128 bits.
    pub(super) fn new(m: &[Vec<Poly>]) -> Option<Ring> {
        // The degree of a minor in an atom is at most the sum over the rows of the
        // row's largest degree in it (a term of a minor takes one entry per row).
        let mut bound: BTreeMap<crate::normal::AtomId, u64> = BTreeMap::new();
        for row in m {
            let mut row_max: BTreeMap<crate::normal::AtomId, u64> = BTreeMap::new();
            for e in row {
                for (a, d) in degrees(e) {
                    let slot = row_max.entry(a).or_insert(0);
                    *slot = (*slot).max(d);
                }
            }
            for (a, d) in row_max {
                let slot = bound.entry(a).or_insert(0);
                *slot = slot.saturating_add(d);
            }
        }
        let fields: Vec<_> = bound
            .iter()
            .map(|(&a, &d)| (a, d.saturating_mul(2)))
            .collect();
        let pk = Packing::new(&fields)?;
        let limit = bound
            .iter()
            .map(|(&a, &d)| Some((a, u32::try_from(d).ok()?)))
            .collect::<Option<Vec<_>>>()?;
        let limit = pk.pack(&Mono::from_pairs(limit)?)?;
        Some(Ring { pk, limit })
    }

    /// `p` in packed form, `None` if a coefficient is not an integer of `i128`.
    pub(super) fn pack(&self, p: &Poly) -> Option<P> {
        p.terms()
            .iter()
            .map(|(m, q)| {
                if !q.denom().is_one() {
                    return None;
                }
                Some((self.pk.pack(m)?, q.numer().to_i128()?))
            })
            .collect()
    }

    /// The polynomial of a packed one.
    pub(super) fn unpack(&self, p: &P) -> Poly {
        Poly::from_sorted_terms(
            p.iter()
                .map(|&(k, c)| (self.pk.unpack(k), Q::from_integer(BigInt::from(c))))
                .collect(),
        )
    }

    /// `(a·b − c·d) / prev`, `None` on overflow, a term limit, or an inexact division.
    pub(super) fn bareiss_entry(&self, a: &P, b: &P, c: &P, d: &P, prev: &P) -> Option<P> {
        let t = if c.is_empty() || d.is_empty() {
            mul(a, b)?
        } else {
            sub(&mul(a, b)?, &mul(c, d)?)?
        };
        self.div_exact(&t, prev)
    }

    /// `a / b` when `b` divides `a` with every quotient exponent within the bound.
    fn div_exact(&self, a: &P, b: &P) -> Option<P> {
        if a.is_empty() {
            return Some(Vec::new());
        }
        let (&(mb, cb), rest) = b.split_last()?;
        if rest.is_empty() {
            // A monomial divisor (1 included): term by term.
            return a
                .iter()
                .map(|&(m, c)| {
                    // checked: i128::MIN / −1 overflows.
                    (c.checked_rem(cb)? == 0).then_some(())?;
                    Some((self.pk.div(m, mb, self.limit)?, c.checked_div(cb)?))
                })
                .collect();
        }
        let mut r: BTreeMap<u128, i128> = a.iter().copied().collect();
        let mut q: P = Vec::new();
        while let Some((mr, cr)) = r.pop_last() {
            let m = self.pk.div(mr, mb, self.limit)?;
            if cr.checked_rem(cb)? != 0 {
                return None;
            }
            let c = cr.checked_div(cb)?;
            for &(mt, ct) in rest {
                // mt ≤ deg b and m ≤ the bound: the fields (twice the bound) hold the sum.
                let v = ct.checked_mul(c)?;
                match r.entry(mt + m) {
                    Entry::Occupied(mut e) => {
                        let x = e.get().checked_sub(v)?;
                        if x == 0 {
                            e.remove();
                        } else {
                            *e.get_mut() = x;
                        }
                    }
                    Entry::Vacant(e) => {
                        e.insert(v.checked_neg()?);
                    }
                }
            }
            q.push((m, c));
            if q.len() > max_terms() {
                return None;
            }
        }
        q.reverse();
        Some(q)
    }
}

/// The product, `None` on overflow or past the term limit.
fn mul(a: &P, b: &P) -> Option<P> {
    if a.is_empty() || b.is_empty() {
        return Some(Vec::new());
    }
    let (small, big) = if a.len() <= b.len() { (a, b) } else { (b, a) };
    if let [(m, c)] = small.as_slice() {
        // The fields hold the sum of two bounded degrees: no carry, order kept.
        return big
            .iter()
            .map(|&(k, d)| Some((k + m, d.checked_mul(*c)?)))
            .collect();
    }
    let mut acc: HashMap<u128, i128, FxBuild> =
        HashMap::with_capacity_and_hasher((small.len() * big.len()).min(1 << 16), FxBuild);
    for &(x, c1) in small {
        for &(y, c2) in big {
            let slot = acc.entry(x + y).or_insert(0);
            *slot = slot.checked_add(c1.checked_mul(c2)?)?;
        }
        if acc.len() > max_terms() || check_deadline().is_err() {
            return None;
        }
    }
    let mut v: P = acc.into_iter().filter(|t| t.1 != 0).collect();
    v.sort_unstable_by_key(|t| t.0);
    Some(v)
}

/// `a − b`, `None` on overflow.
fn sub(a: &P, b: &P) -> Option<P> {
    let mut out = Vec::with_capacity(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    while i < a.len() || j < b.len() {
        match (a.get(i), b.get(j)) {
            (Some(&x), Some(&y)) if x.0 == y.0 => {
                let c = x.1.checked_sub(y.1)?;
                if c != 0 {
                    out.push((x.0, c));
                }
                i += 1;
                j += 1;
            }
            (Some(&x), Some(&y)) if x.0 < y.0 => {
                out.push(x);
                i += 1;
            }
            (Some(&x), None) => {
                out.push(x);
                i += 1;
            }
            (_, Some(&y)) => {
                out.push((y.0, y.1.checked_neg()?));
                j += 1;
            }
            (None, None) => break,
        }
    }
    Some(out)
}
