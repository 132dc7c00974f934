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
use crate::normal::{AtomId, Poly, Q};
use num_bigint::BigInt;
use num_traits::{One, ToPrimitive};
use std::collections::btree_map::Entry;
use std::collections::BTreeMap;

/// A polynomial: `(packed monomial, coefficient)`, strictly ascending, no zero.
pub(super) type P = Vec<(u128, i128)>;

/// The packing of one matrix and the largest exponents a minor of it can have.
pub(super) struct Ring {
    pk: Packing,
    /// Each field holds the degree bound of its atom: the exponent limit of a quotient.
    limit: u128,
    /// The lowest bit of every field: a subtraction that borrows into one of these bits
    /// took a larger exponent from a smaller one in the field below.
    low: u128,
    /// `(atom, shift, mask)` of every field, ascending (read off the packing; the
    /// mask in place).
    fields: Vec<(AtomId, u32, u128)>,
    /// The field each bit belongs to.
    field_of_bit: [u8; 128],
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
        let mut low = 0u128;
        let mut fields = Vec::with_capacity(bound.len());
        for &a in bound.keys() {
            let bit = pk.pack(&Mono::atom(a, 1))?;
            low |= bit;
            fields.push((a, bit.trailing_zeros(), 0));
        }
        // A field reaches the next one's lowest bit (the last, the top of the word).
        let mut field_of_bit = [0u8; 128];
        for i in 0..fields.len() {
            let end = fields.get(i + 1).map_or(128, |f| f.1);
            let start = fields.get(i)?.1;
            let width = end.checked_sub(start)?;
            fields.get_mut(i)?.2 = (u128::MAX >> (128 - width)) << start;
            for slot in field_of_bit.get_mut(start as usize..end as usize)? {
                *slot = u8::try_from(i).ok()?;
            }
        }
        Some(Ring {
            pk,
            limit,
            low,
            fields,
            field_of_bit,
        })
    }

    /// The monomial of a packed one: only its nonzero fields are visited.
    fn unpack_mono(&self, k: u128) -> Mono {
        // At most one pair per set bit: no reallocation.
        let mut pairs = Vec::with_capacity(k.count_ones() as usize);
        let mut rest = k;
        while rest != 0 {
            let bit = rest.trailing_zeros();
            let f = self.field_of_bit.get(bit as usize).copied().unwrap_or(0);
            let Some(&(a, shift, mask)) = self.fields.get(usize::from(f)) else {
                break;
            };
            // An exponent of a minor is within its atom's degree bound, a u32.
            pairs.push((a, ((k & mask) >> shift) as u32));
            rest &= !mask;
        }
        Mono::from_sorted_pairs(pairs)
    }

    /// The largest monomial dividing `full` and every term of `p` (nonzero), and its
    /// packed form.
    pub(super) fn common_content(&self, p: &P, full: &Mono) -> Option<(Mono, u128)> {
        let mut g: Vec<(AtomId, u32)> = full
            .pairs()
            .iter()
            .filter(|t| self.fields.binary_search_by_key(&t.0, |f| f.0).is_ok())
            .copied()
            .collect();
        // Each atom's field: (shift, mask), found once.
        let mut at: Vec<(u32, u128)> = g
            .iter()
            .filter_map(|t| {
                let i = self.fields.binary_search_by_key(&t.0, |f| f.0).ok()?;
                let &(_, shift, mask) = self.fields.get(i)?;
                Some((shift, mask))
            })
            .collect();
        for &(k, _) in p {
            if g.is_empty() {
                break;
            }
            for (slot, &(shift, mask)) in g.iter_mut().zip(&at) {
                slot.1 = slot.1.min(((k & mask) >> shift) as u32);
            }
            if g.iter().any(|t| t.1 == 0) {
                let keep: Vec<bool> = g.iter().map(|t| t.1 > 0).collect();
                let mut it = keep.iter();
                at.retain(|_| it.next().copied().unwrap_or(false));
                g.retain(|t| t.1 > 0);
            }
        }
        let g = Mono::from_pairs(g)?;
        let packed = self.pk.pack(&g)?;
        Some((g, packed))
    }

    /// `p / (g · kappa)` as a polynomial, for a monomial `g` (packed) dividing every
    /// term and a nonzero `kappa`: each coefficient reduced in machine words when
    /// they suffice. `None` when `g` does not divide a term.
    pub(super) fn unpack_over(&self, p: &P, g: u128, kappa: &BigInt) -> Option<Poly> {
        let small = kappa.to_i128().filter(|k| *k != i128::MIN);
        let mut terms = Vec::with_capacity(p.len());
        for &(k, c) in p {
            let m = self.unpack_mono(self.div_mono(k, g)?);
            let q = match small {
                Some(kp) => {
                    let d = gcd_i128(c, kp);
                    let (mut n, mut den) = (c / d, kp / d);
                    if den < 0 {
                        (n, den) = (n.checked_neg()?, -den);
                    }
                    Q::new_raw(big(n), big(den))
                }
                None => Q::new(big(c), kappa.clone()),
            };
            terms.push((m, q));
        }
        Some(Poly::from_sorted_terms(terms))
    }

    /// The monomial `a / b` when `b` divides `a` and every exponent of the quotient is
    /// within the bound: two word subtractions, whose borrows between fields show a
    /// field that went negative (SWAR). Without a borrow out of any field the
    /// difference of the words is the difference of every field; a borrow out of the
    /// highest field makes the subtraction itself overflow.
    fn div_mono(&self, a: u128, b: u128) -> Option<u128> {
        let q = a.checked_sub(b)?;
        // Bit i of a ^ b ^ (a − b) is the borrow into bit i.
        if (a ^ b ^ q) & self.low != 0 {
            return None;
        }
        let room = self.limit.checked_sub(q)?;
        if (self.limit ^ q ^ room) & self.low != 0 {
            return None;
        }
        Some(q)
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
                .map(|&(k, c)| (self.unpack_mono(k), Q::from_integer(big(c))))
                .collect(),
        )
    }

    /// `(a·b − c·d) / prev`, `None` on overflow, a term limit, or an inexact division.
    pub(super) fn bareiss_entry(&self, a: &P, b: &P, c: &P, d: &P, prev: &P) -> Option<P> {
        let t = mul_sub(a, b, c, d)?;
        self.div_exact(t, prev)
    }

    /// `(b·d − Σ u·x) / p` over the pairs `(u, x)` of `rest`: a step of fraction-free
    /// back substitution, exact when `p` is the row's pivot and `d` the determinant
    /// (Bareiss); `None` when a division is not exact, on overflow or past the term
    /// limit.
    pub(super) fn back_substitute(&self, b: &P, d: &P, rest: &[(&P, &P)], p: &P) -> Option<P> {
        // Past this many term products the sum is taken pairwise by merges (as in
        // `mul_sub`), where a table would leave the cache.
        const TABLE_PRODUCTS: usize = 1 << 17;
        let mut pairs: Vec<(Terms<'_>, Terms<'_>, bool)> = vec![(b, d, false)];
        pairs.extend(rest.iter().map(|(u, x)| (u.as_slice(), x.as_slice(), true)));
        let products = pairs
            .iter()
            .map(|t| t.0.len().saturating_mul(t.1.len()))
            .fold(0usize, usize::saturating_add);
        let t = if products <= TABLE_PRODUCTS {
            sum_of_products(&pairs, d.len().saturating_mul(p.len()).min(products))?
        } else {
            let mut t = mul_sub(b, d, &[], &[])?;
            for (u, x) in rest {
                t = mul_sub(&t, &[(0, 1)], u, x)?;
            }
            t
        };
        self.div_exact(t, p)
    }

    /// `a / (cb·mb)` in place, `None` when a term is not divisible; the coefficients are
    /// divided in machine words when they fit.
    fn div_by_term(&self, mut a: P, mb: u128, cb: i128) -> Option<P> {
        if mb != 0 {
            for t in &mut a {
                t.0 = self.div_mono(t.0, mb)?;
            }
        }
        match cb {
            1 => {}
            -1 => {
                for t in &mut a {
                    t.1 = t.1.checked_neg()?;
                }
            }
            _ => {
                let words = i64::try_from(cb)
                    .ok()
                    .filter(|_| a.iter().all(|t| i64::try_from(t.1).is_ok()));
                for t in &mut a {
                    t.1 = match words {
                        // checked: i64::MIN / −1 overflows.
                        Some(w) => {
                            let c = t.1 as i64;
                            (c.checked_rem(w)? == 0).then_some(())?;
                            i128::from(c.checked_div(w)?)
                        }
                        None => {
                            (t.1.checked_rem(cb)? == 0).then_some(())?;
                            t.1.checked_div(cb)?
                        }
                    };
                }
            }
        }
        Some(a)
    }

    /// `a / b` when `b` divides `a` with every quotient exponent within the bound: by
    /// [`Ring::div_by_term`] for a one-term divisor, else term by term from the top.
    fn div_exact(&self, a: P, b: &P) -> Option<P> {
        if a.is_empty() {
            return Some(a);
        }
        let (&(mb, cb), rest) = b.split_last()?;
        if rest.is_empty() {
            return self.div_by_term(a, mb, cb);
        }
        let mut r: BTreeMap<u128, i128> = a.into_iter().collect();
        let mut q: P = Vec::new();
        while let Some((mr, cr)) = r.pop_last() {
            let m = self.div_mono(mr, mb)?;
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

/// The greatest common divisor of two integers, positive (`b` nonzero, neither
/// `i128::MIN`): in 64-bit words once both fit (a division of 128-bit words is a call).
fn gcd_i128(a: i128, b: i128) -> i128 {
    let (mut a, mut b) = (a.unsigned_abs(), b.unsigned_abs());
    while b != 0 {
        if let (Ok(x), Ok(y)) = (u64::try_from(a), u64::try_from(b)) {
            let (mut x, mut y) = (x, y);
            while y != 0 {
                (x, y) = (y, x % y);
            }
            return i128::from(x);
        }
        (a, b) = (b, a % b);
    }
    // At most |b| ≤ i128::MAX.
    a as i128
}

/// `v` as a big integer, built from one word when it fits one (the general conversion
/// from `i128` builds two words and trims one).
fn big(v: i128) -> BigInt {
    match i64::try_from(v) {
        Ok(w) => BigInt::from(w),
        Err(_) => BigInt::from(v),
    }
}

/// The product, `None` on overflow or past the term limit.
#[cfg(test)]
fn mul(a: &P, b: &P) -> Option<P> {
    mul_sub(a, b, &[], &[])
}

/// `a·b − c·d`, `None` on overflow or past the term limit.
///
/// Every term product is added into an open-addressing table keyed by the packed
/// monomial (the entries in a dense list, the table holding their positions), and the
/// terms left nonzero are sorted once at the end. Bareiss's products cancel heavily
/// (on the chain of rods, some 24,000 term products leave 286 terms), so the table
/// stays small and each product costs one probe, where merging the sorted partial
/// products costs a comparison per level of the merge.
fn mul_sub(
    a: &[(u128, i128)],
    b: &[(u128, i128)],
    c: &[(u128, i128)],
    d: &[(u128, i128)],
) -> Option<P> {
    // Past this many term products the table (up to one entry each, where little
    // cancels, as in a generic matrix) leaves the cache, and merging, which streams,
    // is faster: the dense 7 × 7 system took 1.26 s by the table against 0.77 s.
    const TABLE_PRODUCTS: usize = 1 << 15;
    let products = a
        .len()
        .saturating_mul(b.len())
        .saturating_add(c.len().saturating_mul(d.len()));
    if products > TABLE_PRODUCTS {
        return mul_sub_merged(a, b, c, d);
    }
    sum_of_products(
        &[(a, b, false), (c, d, true)],
        a.len() + b.len() + c.len() + d.len(),
    )
}

/// `Σ ±x·y` over `pairs` (`true`: subtracted), in one table sized for about `hint`
/// terms (as [`mul_sub`]), `None` on overflow or past the term limit.
fn sum_of_products(pairs: &[(Terms<'_>, Terms<'_>, bool)], hint: usize) -> Option<P> {
    let mut acc = Accumulator::new(hint);
    for &(x, y, negate) in pairs {
        if x.is_empty() || y.is_empty() {
            continue;
        }
        let (small, big, fits) = ordered(x, y)?;
        for &(m, k) in small {
            let k = if negate { k.checked_neg()? } else { k };
            // The fields hold the sum of two bounded degrees: no carry, order kept.
            for &(e, f) in big {
                let v = if fits { f * k } else { f.checked_mul(k)? };
                acc.add(e + m, v)?;
            }
            if acc.entries.len() > max_terms() || check_deadline().is_err() {
                return None;
            }
        }
    }
    Some(acc.into_sorted())
}

/// Terms added by monomial: a dense list of `(monomial, coefficient)` and a table of
/// positions in it (`0` empty, `i + 1` the entry `i`), probed linearly from a
/// multiplicative hash, doubled when half full.
struct Accumulator {
    entries: Vec<(u128, i128)>,
    table: Vec<u32>,
    /// `64 − log2(table.len())`: the hash's top bits index the table.
    shift: u32,
}

impl Accumulator {
    /// An empty accumulator sized for about `hint` distinct monomials.
    fn new(hint: usize) -> Accumulator {
        let bits = (hint.max(8) * 2)
            .next_power_of_two()
            .trailing_zeros()
            .min(30);
        Accumulator {
            entries: Vec::with_capacity(hint),
            table: vec![0; 1 << bits],
            shift: 64 - bits,
        }
    }

    fn slot(&self, key: u128) -> usize {
        let h = ((key as u64) ^ ((key >> 64) as u64).rotate_left(29))
            .wrapping_mul(0x9E37_79B9_7F4A_7C15);
        (h >> self.shift) as usize
    }

    /// Adds `v` to the coefficient of `key`; `None` on overflow.
    fn add(&mut self, key: u128, v: i128) -> Option<()> {
        let mask = self.table.len() - 1;
        let mut i = self.slot(key);
        loop {
            let at = *self.table.get(i)?;
            if at == 0 {
                break;
            }
            let entry = self.entries.get_mut(at as usize - 1)?;
            if entry.0 == key {
                entry.1 = entry.1.checked_add(v)?;
                return Some(());
            }
            i = (i + 1) & mask;
        }
        self.entries.push((key, v));
        *self.table.get_mut(i)? = u32::try_from(self.entries.len()).ok()?;
        if self.entries.len() * 2 > self.table.len() {
            self.grow()?;
        }
        Some(())
    }

    /// Doubles the table and places every entry again.
    fn grow(&mut self) -> Option<()> {
        let bits = 64 - self.shift + 1;
        if bits > 31 {
            return None;
        }
        self.table = vec![0; 1 << bits];
        self.shift = 64 - bits;
        let mask = self.table.len() - 1;
        for (n, &(key, _)) in self.entries.iter().enumerate() {
            let mut i = self.slot(key);
            while *self.table.get(i)? != 0 {
                i = (i + 1) & mask;
            }
            *self.table.get_mut(i)? = u32::try_from(n + 1).ok()?;
        }
        Some(())
    }

    /// The nonzero terms, ascending.
    fn into_sorted(self) -> P {
        let mut out = self.entries;
        out.retain(|t| t.1 != 0);
        out.sort_unstable_by_key(|t| t.0);
        out
    }
}

/// A list of packed terms (monomial, coefficient).
type Terms<'t> = &'t [(u128, i128)];

/// `x` and `y`, the shorter first, and whether every product of their coefficients
/// fits in an `i128`: one bound for every product (the largest coefficients'), so that
/// none of the term products is checked again. `None` for an empty list.
fn ordered<'t>(x: Terms<'t>, y: Terms<'t>) -> Option<(Terms<'t>, Terms<'t>, bool)> {
    let (small, big) = if x.len() <= y.len() { (x, y) } else { (y, x) };
    let big_max = big.iter().map(|t| t.1.unsigned_abs()).max()?;
    let small_max = small.iter().map(|t| t.1.unsigned_abs()).max()?;
    let fits = big_max
        .checked_mul(small_max)
        .is_some_and(|p| p <= i128::MAX as u128);
    Some((small, big, fits))
}

/// [`mul_sub`] by merges, for products too many for a table to stay in cache.
///
/// Each term of a product's shorter factor times the longer one is a sorted list (the
/// second product's negated); the lists of both products are added pairwise, like the
/// runs of a bottom-up merge sort (a stack in which two sums of the same number of
/// lists merge), so the difference comes out sorted with `O(N log k)` comparisons and
/// no hashing (`N` products, `k` lists), and terms the two products cancel go in the
/// merges rather than in a subtraction of two stored products.
fn mul_sub_merged(
    a: &[(u128, i128)],
    b: &[(u128, i128)],
    c: &[(u128, i128)],
    d: &[(u128, i128)],
) -> Option<P> {
    // (number of lists summed, their sum)
    let mut stack: Vec<(usize, P)> = Vec::new();
    for (x, y, negate) in [(a, b, false), (c, d, true)] {
        if x.is_empty() || y.is_empty() {
            continue;
        }
        let (small, big, fits) = ordered(x, y)?;
        for &(m, k) in small {
            let k = if negate { k.checked_neg()? } else { k };
            // The fields hold the sum of two bounded degrees: no carry, order kept.
            let list: P = if fits {
                big.iter().map(|&(e, f)| (e + m, f * k)).collect()
            } else {
                big.iter()
                    .map(|&(e, f)| Some((e + m, f.checked_mul(k)?)))
                    .collect::<Option<P>>()?
            };
            let mut run = (1usize, list);
            while stack.last().is_some_and(|top| top.0 == run.0) {
                let top = stack.pop()?;
                run = (top.0 + run.0, add(&top.1, &run.1)?);
                if run.1.len() > max_terms() || check_deadline().is_err() {
                    return None;
                }
            }
            stack.push(run);
        }
    }
    let mut out = stack.pop().map(|t| t.1).unwrap_or_default();
    while let Some(top) = stack.pop() {
        out = add(&top.1, &out)?;
        if out.len() > max_terms() {
            return None;
        }
    }
    Some(out)
}

/// `a + b`, `None` on overflow.
fn add(mut a: &[(u128, i128)], mut b: &[(u128, i128)]) -> Option<P> {
    let mut out = Vec::with_capacity(a.len() + b.len());
    while let ([x, ra @ ..], [y, rb @ ..]) = (a, b) {
        if x.0 < y.0 {
            out.push(*x);
            a = ra;
        } else if x.0 > y.0 {
            out.push(*y);
            b = rb;
        } else {
            let c = x.1.checked_add(y.1)?;
            if c != 0 {
                out.push((x.0, c));
            }
            a = ra;
            b = rb;
        }
    }
    out.extend_from_slice(a);
    out.extend_from_slice(b);
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::normal::AtomId;
    use proptest::prelude::*;

    /// A one-row matrix whose atoms 0–5 have degree bounds 1–6: fields of several widths.
    fn ring() -> Ring {
        let row: Vec<Poly> = (0..6u32)
            .filter_map(|a| {
                let m = Mono::from_pairs(vec![(AtomId::from_index(a), a + 1)])?;
                Some(Poly::term(m, Q::one()))
            })
            .collect();
        match Ring::new(&[row]) {
            Some(r) => r,
            None => panic!("six small atoms pack"),
        }
    }

    /// Exponents that fit the fields of [`ring`]: up to twice each bound.
    fn any_mono() -> impl Strategy<Value = Vec<u32>> {
        (0u32..=2, 0u32..=4, 0u32..=6, 0u32..=8, 0u32..=10, 0u32..=12)
            .prop_map(|(a, b, c, d, e, f)| vec![a, b, c, d, e, f])
    }

    fn mono(e: &[u32]) -> Option<Mono> {
        let pairs = e
            .iter()
            .enumerate()
            .map(|(a, &k)| (AtomId::from_index(a as u32), k))
            .filter(|t| t.1 > 0)
            .collect();
        Mono::from_pairs(pairs)
    }

    proptest! {
        /// The gcd of two machine integers is the big integers' gcd (positive), in
        /// 128-bit and in 64-bit words; `big` keeps the value.
        #[test]
        fn word_gcd_is_the_gcd(a in any::<i128>(), b in any::<i128>(), shift in 0u32..127) {
            use num_integer::Integer;
            for (a, b) in [(a, b), (a >> shift, b >> shift), (a >> 70, b >> 70)] {
                if b == 0 || a == i128::MIN || b == i128::MIN {
                    continue;
                }
                let want = BigInt::from(a).gcd(&BigInt::from(b));
                prop_assert_eq!(BigInt::from(gcd_i128(a, b)), want);
                prop_assert_eq!(big(a), BigInt::from(a));
            }
        }

        /// The word-wide quotient is the field-by-field one: `Some` exactly when every
        /// exponent of `b` is at most `a`'s and the difference is within the bound.
        #[test]
        fn word_division_is_field_division(a in any_mono(), b in any_mono()) {
            let r = ring();
            let (Some(ma), Some(mb)) = (mono(&a), mono(&b)) else {
                return Err(TestCaseError::fail("monomials"));
            };
            let (Some(pa), Some(pb)) = (r.pk.pack(&ma), r.pk.pack(&mb)) else {
                return Err(TestCaseError::fail("the exponents fit"));
            };
            let want = a
                .iter()
                .zip(&b)
                .enumerate()
                .all(|(i, (&x, &y))| y <= x && x - y <= i as u32 + 1);
            let got = r.div_mono(pa, pb);
            prop_assert_eq!(got.is_some(), want);
            if let Some(q) = got {
                let diff: Vec<u32> = a.iter().zip(&b).map(|(x, y)| x - y).collect();
                prop_assert_eq!(Some(r.pk.unpack(q)), mono(&diff));
            }
        }

        /// The product by the table is the product of [`Poly`].
        #[test]
        fn products_by_table_and_by_merges_are_the_product(
            a in proptest::collection::vec((any_mono(), -50i128..50), 0..12),
            b in proptest::collection::vec((any_mono(), -50i128..50), 0..12),
        ) {
            let r = ring();
            let poly = |t: &[(Vec<u32>, i128)]| -> Poly {
                Poly::from_terms(
                    t.iter()
                        .filter_map(|(e, c)| {
                            let e: Vec<u32> = e.iter().enumerate().map(|(i, &k)| k.min(i as u32 + 1)).collect();
                            Some((mono(&e)?, Q::from_integer(BigInt::from(*c))))
                        })
                        .collect(),
                )
            };
            let (pa, pb) = (poly(&a), poly(&b));
            let (Some(ka), Some(kb)) = (r.pack(&pa), r.pack(&pb)) else {
                return Err(TestCaseError::fail("bounded monomials pack"));
            };
            let Some(prod) = mul(&ka, &kb) else {
                return Err(TestCaseError::fail("small products fit"));
            };
            prop_assert_eq!(Ok(r.unpack(&prod)), pa.mul(&pb));
            // The merging product (used past 2^15 term products) agrees, and so does
            // a difference of two products.
            prop_assert_eq!(mul_sub_merged(&ka, &kb, &[], &[]), Some(prod));
            prop_assert_eq!(mul_sub_merged(&ka, &kb, &kb, &ka), mul_sub(&ka, &kb, &kb, &ka));
            prop_assert_eq!(mul_sub_merged(&ka, &kb, &ka, &ka), mul_sub(&ka, &kb, &ka, &ka));
        }
    }
}
