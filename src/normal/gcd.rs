//! Greatest common divisors and exact division of multivariate polynomials over ℚ.
//!
//! The gcd is the recursive primitive polynomial remainder sequence: view both
//! polynomials in their highest common atom, split off contents, and run the
//! pseudo-remainder sequence on primitive parts. Atoms are treated as
//! independent variables; a common factor found that way is a common factor
//! in any quotient ring too, so cancelling it is always valid.

use super::atom::AtomId;
use super::mono::Mono;
use super::poly::{Poly, Q};
use super::Limit;
use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, ToPrimitive, Zero};
use std::collections::btree_map::Entry;
use std::collections::BTreeMap;

/// `a / b` when `b` divides `a` exactly, else `None`.
pub fn div_exact(a: &Poly, b: &Poly) -> Result<Option<Poly>, Limit> {
    if b.is_zero() {
        return Ok(None);
    }
    if a.is_zero() {
        return Ok(Some(Poly::zero()));
    }
    if let Some(c) = b.as_constant() {
        return Ok(Some(a.scale(&c.recip())));
    }
    if b.len() == 1 {
        let (m, c) = &b.terms()[0];
        return Ok(a
            .div_mono(m)
            .map(|q| if c.is_one() { q } else { q.scale(&c.recip()) }));
    }
    let Some((mb, cb)) = b.lead().cloned() else {
        return Ok(None);
    };
    if let Some(pk) = super::pack::Packing::for_quotient(a, b) {
        if let Some(r) = div_exact_packed(a, b, &pk, &cb)? {
            return Ok(r);
        }
    }
    let rest = &b.terms()[..b.len() - 1];
    let q = divide(
        a.terms().iter().cloned(),
        rest,
        &cb,
        |mr| mr.div(&mb),
        |mt, m| mt.mul(m).ok_or(Limit::Exponent),
    )?;
    Ok(q.map(|q| Poly::from_sorted_terms(q.into_iter().rev().collect())))
}

/// The division loop of [`div_exact`] on any monomial key ordered like the monomials:
/// the remainder is an ordered map, so each quotient term costs |b| updates, not |a|.
/// `div` divides a remainder monomial by the leading monomial `cb` belongs to (`None`:
/// `b ∤ a`), `mul` multiplies one of `rest` (b's other terms) by a quotient monomial.
/// The quotient comes out in strictly descending order; `None` when `b ∤ a`.
fn divide<K: Ord>(
    a: impl Iterator<Item = (K, Q)>,
    rest: &[(K, Q)],
    cb: &Q,
    div: impl Fn(&K) -> Option<K>,
    mul: impl Fn(&K, &K) -> Result<K, Limit>,
) -> Result<Option<Vec<(K, Q)>>, Limit> {
    let mut r: BTreeMap<K, Q> = a.collect();
    let mut q_terms: Vec<(K, Q)> = Vec::new();
    while let Some((mr, cr)) = r.pop_last() {
        let Some(m) = div(&mr) else {
            return Ok(None);
        };
        let c = super::qops::div(&cr, cb);
        for (mt, ct) in rest {
            let v = super::qops::mul(ct, &c);
            match r.entry(mul(mt, &m)?) {
                Entry::Occupied(mut e) => {
                    *e.get_mut() = super::qops::sub(e.get(), &v);
                    if e.get().is_zero() {
                        e.remove();
                    }
                }
                Entry::Vacant(e) => {
                    e.insert(-v);
                }
            }
        }
        q_terms.push((m, c));
        if q_terms.len() > super::poly::max_terms() {
            return Err(Limit::terms());
        }
        if q_terms.len() % 256 == 0 {
            super::poly::check_deadline()?;
        }
    }
    Ok(Some(q_terms))
}

/// [`div_exact`] on packed monomials; `Ok(None)` when some monomial does not pack
/// (the caller then takes the general path), `Ok(Some(None))` when `b ∤ a`.
fn div_exact_packed(
    a: &Poly,
    b: &Poly,
    pk: &super::pack::Packing,
    cb: &Q,
) -> Result<Option<Option<Poly>>, Limit> {
    // An exact quotient has degree deg_v(a) − deg_v(b) in every atom v: a larger
    // quotient exponent proves b ∤ a, and keeps every packed sum within its field.
    let (da, db) = (super::pack::degrees(a), super::pack::degrees(b));
    let mut limit = Vec::new();
    let mut j = 0;
    for &(v, ea) in &da {
        let eb = match db.get(j) {
            Some(&(w, _)) if w < v => return Ok(Some(None)),
            Some(&(w, e)) if w == v => {
                j += 1;
                e
            }
            _ => 0,
        };
        if eb > ea {
            return Ok(Some(None));
        }
        if ea > eb {
            limit.push((v, u32::try_from(ea - eb).unwrap_or(u32::MAX)));
        }
    }
    if j < db.len() {
        // b has an atom that a lacks.
        return Ok(Some(None));
    }
    let Some(limit) = Mono::from_pairs(limit).and_then(|m| pk.pack(&m)) else {
        return Ok(None);
    };
    let packed = |p: &Poly| -> Option<Vec<(u128, Q)>> {
        p.terms()
            .iter()
            .map(|(m, q)| Some((pk.pack(m)?, q.clone())))
            .collect()
    };
    let (Some(pa), Some(mut pb)) = (packed(a), packed(b)) else {
        return Ok(None);
    };
    let Some((mb, _)) = pb.pop() else {
        return Ok(Some(None));
    };
    // The fields hold deg_v(a) ≥ exponent of mt + m: the sum never carries.
    let Some(q) = divide(
        pa.into_iter(),
        &pb,
        cb,
        |&mr| pk.div(mr, mb, limit),
        |mt, m| Ok(mt + m),
    )?
    else {
        return Ok(Some(None));
    };
    let terms = q
        .into_iter()
        .rev()
        .map(|(m, c)| (pk.unpack(m), c))
        .collect();
    Ok(Some(Some(Poly::from_sorted_terms(terms))))
}

/// Proves `gcd(a, b)` constant by evaluation, when it is: for every atom `v` in both,
/// the other atoms are set to values modulo the prime 2⁶¹ − 1 at which neither leading
/// coefficient in `v` vanishes, and the gcd of the univariate images has degree 0. (If
/// `G` divides both, its image divides both images and keeps its degree in `v`.) This
/// only ever proves coprimality; `false` means "not shown", and the exact gcd runs.
fn coprime_by_evaluation(a: &Poly, b: &Poly) -> bool {
    let aa = a.atoms();
    let mut pending: Vec<AtomId> = b
        .atoms()
        .into_iter()
        .filter(|v| aa.binary_search(v).is_ok())
        .collect();
    for attempt in 0..3u64 {
        if pending.is_empty() {
            return true;
        }
        let value = |x: AtomId| -> u64 {
            let h = (u64::from(x.index()) + 1).wrapping_mul(0x9E37_79B9_7F4A_7C15)
                ^ attempt.wrapping_mul(0xD6E8_FEB8_6659_FD93);
            h % (P - 2) + 2
        };
        // Every atom gets its value once; the image in v divides v's own factor back out.
        let (Some(wa), Some(wb)) = (weights(a, &value), weights(b, &value)) else {
            continue;
        };
        let mut unsettled = Vec::new();
        for v in pending {
            let Some(inv) = invmod(value(v)) else {
                unsettled.push(v);
                continue;
            };
            match (image_mod_p(a, &wa, v, inv), image_mod_p(b, &wb, v, inv)) {
                (Some(ua), Some(ub)) => {
                    if gcd_degree_mod_p(ua, ub) != 0 {
                        return false;
                    }
                }
                // A leading coefficient vanished at this point: try another.
                _ => unsettled.push(v),
            }
        }
        pending = unsettled;
    }
    pending.is_empty()
}

/// The Mersenne prime 2⁶¹ − 1.
const P: u64 = (1 << 61) - 1;

/// `a·b mod P` for `a, b < P`, by the Mersenne identity 2⁶¹ ≡ 1 (no 128-bit division).
fn mulmod(a: u64, b: u64) -> u64 {
    let x = u128::from(a) * u128::from(b);
    let r = ((x as u64) & P) + ((x >> 61) as u64);
    let r = (r & P) + (r >> 61);
    if r >= P {
        r - P
    } else {
        r
    }
}

fn powmod(mut b: u64, mut e: u64) -> u64 {
    let mut r = 1u64;
    while e > 0 {
        if e & 1 == 1 {
            r = mulmod(r, b);
        }
        b = mulmod(b, b);
        e >>= 1;
    }
    r
}

fn invmod(a: u64) -> Option<u64> {
    (a != 0).then(|| powmod(a, P - 2))
}

/// `q mod P`; `inverses` remembers the inverses of small denominators already seen
/// (a polynomial's coefficients share few denominators).
fn q_mod_p(q: &Q, inverses: &mut Vec<(u64, u64)>) -> Option<u64> {
    if let (Some(n), Some(d)) = (q.numer().to_i64(), q.denom().to_u64()) {
        // Small numbers: one machine-word remainder, no big-integer allocation.
        let r = n.unsigned_abs() % P;
        let n = if n < 0 && r != 0 { P - r } else { r };
        if d == 1 {
            return Some(n);
        }
        let inv = match inverses.iter().find(|c| c.0 == d) {
            Some(c) => c.1,
            None => {
                let inv = invmod(d % P)?;
                if inverses.len() < 16 {
                    inverses.push((d, inv));
                }
                inv
            }
        };
        return Some(mulmod(n, inv));
    }
    let pb = BigInt::from(P);
    let n = u64::try_from(q.numer().mod_floor(&pb)).ok()?;
    let d = u64::try_from(q.denom().mod_floor(&pb)).ok()?;
    Some(mulmod(n, invmod(d)?))
}

/// The image of `p` in 𝔽ₚ[v] with every other atom set by `value`, if its degree in `v`
/// is kept.
/// The value of every term of `p` modulo P with every atom set by `value`.
fn weights(p: &Poly, value: &dyn Fn(AtomId) -> u64) -> Option<Vec<u64>> {
    let mut cache: Vec<(AtomId, u64)> = Vec::new();
    let mut inverses = Vec::new();
    let mut out = Vec::with_capacity(p.len());
    for (m, q) in p.terms() {
        let mut t = q_mod_p(q, &mut inverses)?;
        for &(x, k) in m.pairs() {
            let base = match cache.iter().find(|c| c.0 == x) {
                Some(c) => c.1,
                None => {
                    let val = value(x);
                    cache.push((x, val));
                    val
                }
            };
            t = mulmod(t, powmod(base, u64::from(k)));
        }
        out.push(t);
    }
    Some(out)
}

/// The image of `p` in 𝔽ₚ[v] from its term values `w` (`inv` is the inverse of the
/// value of `v`, whose powers are divided back out), if its degree in `v` is kept.
fn image_mod_p(p: &Poly, w: &[u64], v: AtomId, inv: u64) -> Option<Vec<u64>> {
    let deg = p.degree_in(v) as usize;
    if deg > 100_000 {
        return None;
    }
    let mut inv_pow = Vec::with_capacity(deg + 1);
    let mut x = 1u64;
    for _ in 0..=deg {
        inv_pow.push(x);
        x = mulmod(x, inv);
    }
    let mut out = vec![0u64; deg + 1];
    for ((m, _), t) in p.terms().iter().zip(w) {
        let e = m.exp(v) as usize;
        let slot = out.get_mut(e)?;
        *slot = (*slot + mulmod(*t, *inv_pow.get(e)?)) % P;
    }
    (*out.last()? != 0).then_some(out)
}

/// Degree of the gcd of two dense univariate polynomials over 𝔽ₚ (coefficients ascending).
fn gcd_degree_mod_p(mut a: Vec<u64>, mut b: Vec<u64>) -> usize {
    fn trim(p: &mut Vec<u64>) {
        while p.last() == Some(&0) {
            p.pop();
        }
    }
    trim(&mut a);
    trim(&mut b);
    while !b.is_empty() {
        let Some(inv) = b.last().copied().and_then(invmod) else {
            break;
        };
        while a.len() >= b.len() && !a.is_empty() {
            let Some(&la) = a.last() else {
                break;
            };
            let f = mulmod(la, inv);
            let shift = a.len() - b.len();
            for (i, c) in b.iter().enumerate() {
                if let Some(slot) = a.get_mut(i + shift) {
                    *slot = (*slot + P - mulmod(*c, f)) % P;
                }
            }
            a.pop();
            trim(&mut a);
        }
        std::mem::swap(&mut a, &mut b);
    }
    a.len().saturating_sub(1)
}

/// The monic greatest common divisor (`gcd(0, 0) = 0`).
pub fn gcd(a: &Poly, b: &Poly) -> Result<Poly, Limit> {
    if a.is_zero() {
        return Ok(b.monic());
    }
    if b.is_zero() {
        return Ok(a.monic());
    }
    if a.as_constant().is_some() || b.as_constant().is_some() {
        return Ok(Poly::one());
    }
    if a == b {
        return Ok(a.monic());
    }
    let (ma, mb) = (a.mono_content(), b.mono_content());
    let gm = ma.gcd(&mb);
    let a1 = a.div_mono(&ma).unwrap_or_else(|| a.clone());
    let b1 = b.div_mono(&mb).unwrap_or_else(|| b.clone());
    let g = if a1.len() > 1 && b1.len() > 1 && coprime_by_evaluation(&a1, &b1) {
        Poly::one()
    } else {
        gcd_nomono(&a1, &b1)?
    };
    Ok(g.mul_term(&gm, &Q::one())?.monic())
}

fn gcd_nomono(a: &Poly, b: &Poly) -> Result<Poly, Limit> {
    if a.as_constant().is_some() || b.as_constant().is_some() {
        return Ok(Poly::one());
    }
    if a.len() == 1 || b.len() == 1 {
        // One side is a monomial with no monomial factor in common: only constants remain.
        return Ok(Poly::one());
    }
    let aa = a.atoms();
    let ba = b.atoms();
    // An atom in only one of them: the gcd divides that one's content in it.
    if let Some(v) = aa.iter().rev().find(|v| ba.binary_search(v).is_err()) {
        let c = content_in(a, *v)?;
        return gcd(&c, b);
    }
    if let Some(v) = ba.iter().rev().find(|v| aa.binary_search(v).is_err()) {
        let c = content_in(b, *v)?;
        return gcd(a, &c);
    }
    // The main variable: the one of lowest degree keeps the remainder sequence short.
    let Some(&v) = aa.iter().min_by_key(|v| {
        (
            a.degree_in(**v).max(b.degree_in(**v)),
            a.len().min(b.len()),
            **v,
        )
    }) else {
        return Ok(Poly::one());
    };
    let ca = content_in(a, v)?;
    let cb = content_in(b, v)?;
    let gc = gcd(&ca, &cb)?;
    let mut p = div_exact(a, &ca)?.unwrap_or_else(|| a.clone());
    let mut q = div_exact(b, &cb)?.unwrap_or_else(|| b.clone());
    if p.degree_in(v) < q.degree_in(v) {
        std::mem::swap(&mut p, &mut q);
    }
    loop {
        let r = prem(&p, &q, v)?;
        if r.is_zero() {
            break;
        }
        if r.degree_in(v) == 0 {
            q = Poly::one();
            break;
        }
        p = q;
        q = primitive_in(&r, v)?;
    }
    let g = primitive_in(&q, v)?;
    gc.mul(&g)
}

/// The gcd of the coefficients of `p` viewed as a polynomial in `v`.
pub fn content_in(p: &Poly, v: AtomId) -> Result<Poly, Limit> {
    let coeffs = p.coeffs_in(v);
    let mut g = Poly::zero();
    for (_, c) in &coeffs {
        g = gcd(&g, c)?;
        if g.is_one() {
            break;
        }
    }
    Ok(g)
}

/// `p` divided by its content in `v`.
pub fn primitive_in(p: &Poly, v: AtomId) -> Result<Poly, Limit> {
    let c = content_in(p, v)?;
    Ok(div_exact(p, &c)?.unwrap_or_else(|| p.clone()).primitive())
}

/// The pseudo-remainder of `a` by `b` in `v`, scaled to integer content 1.
fn prem(a: &Poly, b: &Poly, v: AtomId) -> Result<Poly, Limit> {
    let db = b.degree_in(v);
    let bc = b.coeffs_in(v);
    let lc_b = bc.last().map(|c| c.1.clone()).unwrap_or_else(Poly::one);
    let mut r = a.clone();
    let mut guard = 0u32;
    while !r.is_zero() {
        let dr = r.degree_in(v);
        if dr < db {
            break;
        }
        let rc = r.coeffs_in(v);
        let lc_r = rc.last().map(|c| c.1.clone()).unwrap_or_else(Poly::zero);
        let shift = Poly::term(Mono::atom(v, dr - db), Q::one());
        r = lc_b.mul(&r)?.sub(&lc_r.mul(&shift)?.mul(b)?);
        r = r.primitive();
        super::poly::check_deadline()?;
        guard += 1;
        if guard > dr.saturating_add(2) * 4 + 64 {
            return Err(Limit::terms());
        }
    }
    Ok(r)
}

/// The squarefree decomposition of `p` as a polynomial in its atoms (taken as free
/// variables, so the product is `p` whatever relations the atoms satisfy): parts `sᵢ`,
/// pairwise coprime and squarefree, each primitive with a positive leading coefficient,
/// with `p = c · ∏ sᵢ^i` for a constant `c`.
/// In characteristic zero, `g = gcd(p, ∂p/∂x₁, …, ∂p/∂xₙ) = ∏ sᵢ^(i−1)`; then Yun's
/// step peels the parts off one multiplicity at a time.
pub fn squarefree(p: &Poly) -> Result<Vec<(Poly, u32)>, Limit> {
    let exact =
        |a: &Poly, b: &Poly| -> Result<Poly, Limit> { div_exact(a, b)?.ok_or(Limit::terms()) };
    let mut g = p.clone();
    for a in p.atoms() {
        if g.as_constant().is_some() {
            break;
        }
        g = gcd(&g, &p.deriv_atom(a))?;
    }
    if g.as_constant().is_some() {
        return Ok(vec![(p.primitive(), 1)]);
    }
    let mut w = exact(p, &g)?; // s₁ s₂ s₃ ⋯
    let mut y = g; // s₂ s₃² ⋯
    let mut out = Vec::new();
    let mut i = 1u32;
    while w.as_constant().is_none() {
        let z = gcd(&w, &y)?; // s_{i+1} s_{i+2} ⋯
        let s = exact(&w, &z)?;
        if s.as_constant().is_none() {
            out.push((s.primitive(), i));
        }
        y = exact(&y, &z)?;
        w = z;
        i = i.checked_add(1).ok_or(Limit::Exponent)?;
        super::poly::check_deadline()?;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::{div_exact, mulmod, P};
    use crate::normal::mono::Mono;
    use crate::normal::poly::{Poly, Q};
    use num_bigint::BigInt;
    use proptest::prelude::*;

    fn poly() -> impl Strategy<Value = Poly> {
        let term = (
            proptest::collection::vec((0u32..4, 1u32..4), 0..3),
            -3i64..=3,
        );
        proptest::collection::vec(term, 1..5).prop_map(|ts| {
            Poly::from_terms(
                ts.into_iter()
                    .filter_map(|(m, c)| {
                        let m = m
                            .into_iter()
                            .map(|(a, e)| (crate::normal::AtomId::from_index(a), e));
                        Some((
                            Mono::from_pairs(m.collect())?,
                            Q::from_integer(BigInt::from(c)),
                        ))
                    })
                    .collect(),
            )
        })
    }

    proptest! {
        #[test]
        fn exact_division_recovers_the_factor(a in poly(), b in poly(), r in poly()) {
            if b.is_zero() {
                return Ok(());
            }
            let ab = a.mul(&b).unwrap_or_else(|_| Poly::zero());
            prop_assert_eq!(div_exact(&ab, &b), Ok(Some(a.clone())));
            // With a remainder the division is not exact, unless b divides it.
            let abr = ab.add(&r);
            if let Ok(Some(q)) = div_exact(&abr, &b) {
                prop_assert_eq!(q.mul(&b).unwrap_or_else(|_| Poly::zero()), abr);
            }
        }
    }

    #[test]
    fn mersenne_reduction_matches_division() {
        let samples = [
            0,
            1,
            2,
            3,
            P / 2,
            P - 2,
            P - 1,
            0x1234_5678_9abc_def0 % P,
            (1 << 60) + 7,
        ];
        for &a in &samples {
            for &b in &samples {
                let want = ((u128::from(a) * u128::from(b)) % u128::from(P)) as u64;
                assert_eq!(mulmod(a, b), want, "{a} * {b}");
            }
        }
    }
}
