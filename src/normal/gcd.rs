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

/// `gcd(a, b)` when evaluation proves it a monomial: the monomial (the common part of
/// the two monomial contents). For every atom `v` in both whose exponent varies in both
/// (an atom with one exponent throughout one of them leaves it with its monomial
/// content, so `G` below cannot contain it), the other atoms are set to
/// values modulo the prime 2⁶¹ − 1 at which neither leading coefficient in `v`
/// vanishes, and the univariate images, with `v`'s power in the monomial content
/// divided out, have a gcd of degree 0. (If `G` divides both polynomials without their
/// monomial contents, its image divides both images and keeps its degree in `v`.) This
/// only ever proves; `None` means "not shown", and the exact gcd runs.
fn monomial_gcd_by_evaluation(a: &Poly, b: &Poly) -> Option<Mono> {
    let (ra, rb) = (exponent_ranges(a), exponent_ranges(b));
    // The common part of the monomial contents, and the atoms to check: those whose
    // exponent varies in both (in one where it does not, `v` leaves with its monomial
    // content, and `G` cannot contain it).
    let mut gm = Vec::new();
    let mut vars = Vec::new();
    for &(v, la, ha) in &ra {
        let Ok(i) = rb.binary_search_by_key(&v, |t| t.0) else {
            continue;
        };
        let &(_, lb, hb) = rb.get(i)?;
        if la.min(lb) > 0 {
            gm.push((v, la.min(lb)));
        }
        if u64::from(la) < ha && u64::from(lb) < hb {
            vars.push(v);
        }
    }
    let (da, db): (Vec<_>, Vec<_>) = (
        ra.iter().map(|&(v, _, h)| (v, h)).collect(),
        rb.iter().map(|&(v, _, h)| (v, h)).collect(),
    );
    let mut pending = vars;
    for attempt in 0..3u64 {
        if pending.is_empty() {
            break;
        }
        let value = |x: AtomId| hashed(x, attempt);
        let (ia, _) = images(a, &da, &pending, &value)?;
        let (ib, _) = images(b, &db, &pending, &value)?;
        let mut unsettled = Vec::new();
        for ((v, ua), ub) in pending.into_iter().zip(ia).zip(ib) {
            match (ua, ub) {
                (Some(ua), Some(ub)) => {
                    if gcd_degree_mod_p(ua, ub) != 0 {
                        return None;
                    }
                }
                // A leading coefficient vanished at this point: try another.
                _ => unsettled.push(v),
            }
        }
        pending = unsettled;
    }
    if !pending.is_empty() {
        return None;
    }
    Mono::from_pairs(gm)
}

/// Every atom of `p` (ascending) with its exponent in the monomial content (the least
/// over the terms, 0 when a term lacks it) and its degree.
fn exponent_ranges(p: &Poly) -> Vec<(AtomId, u32, u64)> {
    // (terms containing the atom, least exponent there, largest)
    let mut seen: BTreeMap<AtomId, (usize, u32, u32)> = BTreeMap::new();
    let (mut lo, mut hi) = (u32::MAX, 0);
    for (m, _) in p.terms() {
        if let (Some(first), Some(last)) = (m.pairs().first(), m.pairs().last()) {
            lo = lo.min(first.0.index());
            hi = hi.max(last.0.index());
        }
    }
    let mut table: Vec<(usize, u32, u32)> = if lo <= hi && hi - lo < 4096 {
        vec![(0, u32::MAX, 0); (hi - lo) as usize + 1]
    } else {
        Vec::new()
    };
    for (m, _) in p.terms() {
        for &(x, e) in m.pairs() {
            let slot = match table.get_mut(x.index().wrapping_sub(lo) as usize) {
                Some(slot) => slot,
                None => seen.entry(x).or_insert((0, u32::MAX, 0)),
            };
            *slot = (slot.0 + 1, slot.1.min(e), slot.2.max(e));
        }
    }
    let n = p.len();
    let row = |x: AtomId, (count, least, most): (usize, u32, u32)| {
        (x, if count == n { least } else { 0 }, u64::from(most))
    };
    if table.is_empty() {
        return seen.into_iter().map(|(x, s)| row(x, s)).collect();
    }
    (lo..=hi)
        .zip(table)
        .filter(|t| t.1 .0 > 0)
        .map(|(x, s)| row(AtomId::from_index(x), s))
        .collect()
}

/// What [`images`] finds: one image per atom (`None` where a leading coefficient
/// vanished), and the atoms' exponents in the monomial content.
type Images = (Vec<Option<Vec<u64>>>, Vec<u32>);

/// One atom's part in [`images`]: where its image is in the shared buffer, and (terms
/// containing it, the smallest exponent there, the sum of their values).
struct Slot {
    at: usize,
    len: usize,
    count: usize,
    least: u32,
    with: u64,
}

/// The images of `p` in 𝔽ₚ[t] for each `v` of `vars` (ascending): every other atom set
/// by `value`, `v` set to `value(v)·t` (a change of variable that changes neither the
/// degree of a gcd nor whether a leading coefficient vanishes, and needs no inverse),
/// and `t`'s power in the monomial content divided out; `None` for a `v` whose leading
/// coefficient vanishes there. Also the exponents of `vars` in the monomial content;
/// `None` altogether when a coefficient has no image. `degs` are `p`'s atoms with their
/// degrees. One pass over the terms serves every `v`.
fn images(
    p: &Poly,
    degs: &[(AtomId, u64)],
    vars: &[AtomId],
    value: &dyn Fn(AtomId) -> u64,
) -> Option<Images> {
    // Each atom of p: its value, where its powers start in `pows` and how many, and its
    // slot when it is one of `vars`.
    let (powers, pows) = powers(degs, value);
    let mut atoms: Vec<(u64, usize, usize, Option<usize>)> = powers
        .into_iter()
        .map(|(v, at, len)| (v, at, len, None))
        .collect();
    let mut slots = Vec::with_capacity(vars.len());
    let mut buf: Vec<u64> = Vec::new();
    for (j, &v) in vars.iter().enumerate() {
        let pos = degs.binary_search_by_key(&v, |t| t.0).ok()?;
        let deg = degs.get(pos)?.1;
        atoms.get_mut(pos)?.3 = Some(j);
        let len = if deg > 100_000 {
            0
        } else {
            usize::try_from(deg).ok()? + 1
        };
        slots.push(Slot {
            at: buf.len(),
            len,
            count: 0,
            least: u32::MAX,
            with: 0,
        });
        buf.resize(buf.len() + len, 0);
    }
    let place = Places::of(degs)?;
    let locate = |x: AtomId| place.of_atom(x);
    let mut inverses = Vec::new();
    let mut total = 0u64;
    for (m, q) in p.terms() {
        let mut w = q_mod_p(q, &mut inverses)?;
        for &(x, k) in m.pairs() {
            let &(val, at, len, _) = atoms.get(locate(x)?)?;
            let xk = match (k as usize) < len {
                true => *pows.get(at + k as usize)?,
                false => powmod(val, u64::from(k)),
            };
            w = mulmod(w, xk);
        }
        total = (total + w) % P;
        for &(x, k) in m.pairs() {
            let Some(s) = atoms.get(locate(x)?)?.3.and_then(|j| slots.get_mut(j)) else {
                continue;
            };
            s.count += 1;
            s.least = s.least.min(k);
            s.with = (s.with + w) % P;
            if (k as usize) < s.len {
                let slot = buf.get_mut(s.at + k as usize)?;
                *slot = (*slot + w) % P;
            }
        }
    }
    let mut contents = Vec::with_capacity(slots.len());
    let mut out = Vec::with_capacity(slots.len());
    for s in slots {
        let c = if s.count == p.len() { s.least } else { 0 };
        contents.push(c);
        let image = buf.get_mut(s.at..s.at + s.len)?;
        if let Some(first) = image.first_mut() {
            // The terms without v.
            *first = (*first + total + P - s.with) % P;
        }
        let image = image
            .get(c as usize..)
            .filter(|i| i.last().is_some_and(|&l| l != 0));
        out.push(image.map(<[u64]>::to_vec));
    }
    Some((out, contents))
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

/// Degree of the gcd of two dense univariate polynomials over 𝔽ₚ (coefficients ascending).
fn gcd_degree_mod_p(mut a: Vec<u64>, mut b: Vec<u64>) -> usize {
    fn trim(p: &mut Vec<u64>) {
        while p.last() == Some(&0) {
            p.pop();
        }
    }
    trim(&mut a);
    trim(&mut b);
    // Pseudo-remainders (a ← lc(b)·a − lc(a)·tˢ·b): scaling by a nonzero constant keeps
    // the gcd's degree and needs no inverse.
    while let Some(&lb) = b.last() {
        while a.len() >= b.len() {
            let Some(&la) = a.last() else {
                break;
            };
            let shift = a.len() - b.len();
            for x in a.iter_mut() {
                *x = mulmod(*x, lb);
            }
            for (i, c) in b.iter().enumerate() {
                if let Some(slot) = a.get_mut(i + shift) {
                    *slot = (*slot + P - mulmod(*c, la)) % P;
                }
            }
            a.pop();
            trim(&mut a);
        }
        std::mem::swap(&mut a, &mut b);
    }
    a.len().saturating_sub(1)
}

/// A polynomial `d` of degree 1 in an atom `v`, with a point modulo the prime 2⁶¹ − 1
/// at which it vanishes: the other atoms at hashed values where the coefficient of `v`
/// does not vanish, `v` at the root of the image. A polynomial `n` whose image there is
/// not 0 is not divisible by `d`. (If `d | n`, write `d = c·d₀` with `d₀` primitive over
/// ℤ and `n = n₀/L` with `n₀` over ℤ: by Gauss's lemma `n₀ = d₀·q` with `q` over ℤ, so
/// `n₀` vanishes modulo the prime wherever `d₀` does, and so does `n` when every
/// denominator of `n` has an image, which `q_mod_p` requires.)
pub struct LinearFactor {
    d: Poly,
    v: AtomId,
    attempt: u64,
    root: u64,
}

impl LinearFactor {
    /// `d` with its point; `None` when `d` is not of degree 1 in `v` or no point was
    /// found (three tries).
    pub fn new(d: Poly, v: AtomId) -> Option<LinearFactor> {
        let mut inverses = Vec::new();
        for attempt in 0..3u64 {
            // d's image: alpha·v + beta.
            let (mut alpha, mut beta) = (0u64, 0u64);
            for (m, q) in d.terms() {
                let mut w = q_mod_p(q, &mut inverses)?;
                let mut in_v = 0;
                for &(x, k) in m.pairs() {
                    if x == v {
                        in_v = k;
                    } else {
                        w = mulmod(w, powmod(hashed(x, attempt), u64::from(k)));
                    }
                }
                match in_v {
                    0 => beta = (beta + w) % P,
                    1 => alpha = (alpha + w) % P,
                    _ => return None,
                }
            }
            // The coefficient of v vanished at this point: try another.
            let Some(inv) = invmod(alpha) else {
                continue;
            };
            let root = mulmod((P - beta) % P, inv);
            return Some(LinearFactor {
                d,
                v,
                attempt,
                root,
            });
        }
        None
    }

    /// The polynomial `d`.
    pub fn poly(&self) -> &Poly {
        &self.d
    }

    /// Whether evaluation proves that `d` does not divide `n`. This only ever proves;
    /// `false` means "not shown", and an exact division must decide.
    pub fn shown_not_to_divide(&self, n: &Poly) -> bool {
        let at = |x: AtomId| {
            if x == self.v {
                self.root
            } else {
                hashed(x, self.attempt)
            }
        };
        evaluate(n, &at).is_some_and(|y| y != 0)
    }
}

/// The value modulo [`P`] that evaluation gives atom `x` in its `attempt`-th try: in
/// 2..P, from the id and the attempt mixed by splitmix64's finaliser. A multiplicative
/// hash alone left the values of atoms linearly related (atom 3's twice atom 1's modulo
/// `P`), so that `2·x₁ − x₃` vanished at every first point: such a point only loses a
/// proof (the exact gcd then runs), never makes a wrong one, but it lost it every time.
fn hashed(x: AtomId, attempt: u64) -> u64 {
    let mut z = (u64::from(x.index()) << 8 | attempt).wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    (z ^ (z >> 31)) % (P - 2) + 2
}

/// Each atom's value and its powers modulo [`P`], up to its degree (at most 64; a higher
/// power is found by squaring): (value, where its powers start in the second list, how
/// many), in the order of `degs`.
fn powers(degs: &[(AtomId, u64)], value: &dyn Fn(AtomId) -> u64) -> PowerTable {
    const DIRECT: u64 = 64;
    let mut atoms = Vec::with_capacity(degs.len());
    let mut pows = Vec::new();
    for &(x, d) in degs {
        let val = value(x);
        let start = pows.len();
        let mut y = 1u64;
        for _ in 0..=d.min(DIRECT) {
            pows.push(y);
            y = mulmod(y, val);
        }
        atoms.push((val, start, pows.len() - start));
    }
    (atoms, pows)
}

/// Atoms' values with where their powers are, and the powers.
type PowerTable = (Vec<(u64, usize, usize)>, Vec<u64>);

/// Where an atom is in `degs` (sorted by atom): a direct table over the ids in use when
/// they are narrow, else a binary search.
struct Places<'d> {
    degs: &'d [(AtomId, u64)],
    lo: u32,
    table: Vec<usize>,
}

impl<'d> Places<'d> {
    fn of(degs: &'d [(AtomId, u64)]) -> Option<Places<'d>> {
        let lo = degs.first().map_or(0, |t| t.0.index());
        let span = degs.last().map_or(0, |t| t.0.index() - lo) as usize;
        let mut table = Vec::new();
        if span < 4096 {
            table = vec![usize::MAX; span + 1];
            for (i, (x, _)) in degs.iter().enumerate() {
                *table.get_mut((x.index() - lo) as usize)? = i;
            }
        }
        Some(Places { degs, lo, table })
    }

    fn of_atom(&self, x: AtomId) -> Option<usize> {
        match self.table.get(x.index().checked_sub(self.lo)? as usize) {
            Some(&i) => (i != usize::MAX).then_some(i),
            None => self.degs.binary_search_by_key(&x, |t| t.0).ok(),
        }
    }
}

/// `p` at the point `at` modulo [`P`]; `None` when a coefficient has no image. Each
/// atom's value and its powers (to its degree, at most 64; beyond, by squaring) are
/// found once.
fn evaluate(p: &Poly, at: &dyn Fn(AtomId) -> u64) -> Option<u64> {
    let degs = super::pack::degrees(p);
    let (atoms, pows) = powers(&degs, at);
    let place = Places::of(&degs)?;
    let locate = |x: AtomId| place.of_atom(x);
    let mut inverses = Vec::new();
    let mut total = 0u64;
    for (m, q) in p.terms() {
        let mut w = q_mod_p(q, &mut inverses)?;
        for &(x, k) in m.pairs() {
            let &(val, start, len) = atoms.get(locate(x)?)?;
            let xk = match (k as usize) < len {
                true => *pows.get(start + k as usize)?,
                false => powmod(val, u64::from(k)),
            };
            w = mulmod(w, xk);
        }
        total = (total + w) % P;
    }
    Some(total)
}

/// The monic greatest common divisor (`gcd(0, 0) = 0`).
pub fn gcd(a: &Poly, b: &Poly) -> Result<Poly, Limit> {
    if a.is_zero() {
        return Ok(b.monic());
    }
    if b.is_zero() {
        return Ok(a.monic());
    }
    if a.is_constant() || b.is_constant() {
        return Ok(Poly::one());
    }
    if a == b {
        return Ok(a.monic());
    }
    if a.len() > 1 && b.len() > 1 {
        if let Some(gm) = monomial_gcd_by_evaluation(a, b) {
            return Ok(Poly::term(gm, Q::one()));
        }
    }
    let (ma, mb) = (a.mono_content(), b.mono_content());
    let gm = ma.gcd(&mb);
    let a1 = a.div_mono(&ma).unwrap_or_else(|| a.clone());
    let b1 = b.div_mono(&mb).unwrap_or_else(|| b.clone());
    Ok(gcd_nomono(&a1, &b1)?.mul_term(&gm, &Q::one())?.monic())
}

fn gcd_nomono(a: &Poly, b: &Poly) -> Result<Poly, Limit> {
    if a.is_constant() || b.is_constant() {
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
        if g.is_constant() {
            break;
        }
        g = gcd(&g, &p.deriv_atom(a))?;
    }
    if g.is_constant() {
        return Ok(vec![(p.primitive(), 1)]);
    }
    let mut w = exact(p, &g)?; // s₁ s₂ s₃ ⋯
    let mut y = g; // s₂ s₃² ⋯
    let mut out = Vec::new();
    let mut i = 1u32;
    while !w.is_constant() {
        let z = gcd(&w, &y)?; // s_{i+1} s_{i+2} ⋯
        let s = exact(&w, &z)?;
        if !s.is_constant() {
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
    use super::{div_exact, gcd_nomono, monomial_gcd_by_evaluation, mulmod, P};
    use crate::normal::mono::Mono;
    use crate::normal::poly::{Poly, Q};
    use num_bigint::BigInt;
    use num_traits::One;
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

    proptest! {
        /// What evaluation proves is what the remainder sequence finds: the monomial
        /// gcd when it proves one, and never a proof when the two share a factor
        /// that is not a monomial.
        #[test]
        fn evaluation_agrees_with_the_remainder_sequence(a in poly(), b in poly(), c in poly()) {
            let slow = |a: &Poly, b: &Poly| -> Result<Poly, crate::normal::Limit> {
                let (ma, mb) = (a.mono_content(), b.mono_content());
                let a1 = a.div_mono(&ma).unwrap_or_else(|| a.clone());
                let b1 = b.div_mono(&mb).unwrap_or_else(|| b.clone());
                Ok(gcd_nomono(&a1, &b1)?.mul_term(&ma.gcd(&mb), &Q::one())?.monic())
            };
            let ok = |r: Result<Poly, crate::normal::Limit>| r.unwrap_or_else(|_| Poly::zero());
            let (ac, bc) = (ok(a.mul(&c)), ok(b.mul(&c)));
            for (x, y) in [(&a, &b), (&ac, &bc)] {
                if x.len() < 2 || y.len() < 2 {
                    continue;
                }
                let want = ok(slow(x, y));
                match monomial_gcd_by_evaluation(x, y) {
                    Some(gm) => prop_assert_eq!(Poly::term(gm, Q::one()), want),
                    None => prop_assert!(want.len() > 1 || x.len() < 2, "not proved: {}", want.len()),
                }
            }
            // A common factor that is not a monomial is never proved away.
            if c.len() > 1 && ac.len() > 1 && bc.len() > 1 {
                prop_assert!(monomial_gcd_by_evaluation(&ac, &bc).is_none());
            }
        }
    }

    proptest! {
        /// A multiple of a polynomial linear in an atom is never shown not to be one,
        /// and whatever is shown not to be a multiple is not.
        #[test]
        fn non_divisibility_is_never_claimed_wrongly(a in poly(), b in poly(), q in poly(), r in poly()) {
            let x = Poly::atom(crate::normal::AtomId::from_index(7));
            let d = a.mul(&x).unwrap_or_else(|_| Poly::zero()).add(&b);
            let Some(f) = super::LinearFactor::new(d.clone(), crate::normal::AtomId::from_index(7)) else {
                return Ok(());
            };
            let n = d.mul(&q).unwrap_or_else(|_| Poly::zero());
            prop_assert!(!f.shown_not_to_divide(&n));
            if f.shown_not_to_divide(&r) {
                prop_assert_eq!(div_exact(&r, &d), Ok(None));
            }
        }
    }

    /// `k·xᵢ·x₀ − x₀²` and `x₀³ − xⱼ³` are coprime unless k = 1 and i = j (then
    /// `x₀ − xᵢ` divides both), and evaluation proves it for every pair of atoms. (With
    /// points from a multiplicative hash of the ids, atom 3's value was twice atom 1's
    /// modulo P, and the pair with k = 2, i = 1, j = 3 was never proved.)
    #[test]
    fn evaluation_proves_coprime_pairs_whatever_the_atoms_ids() {
        let x = |i: u32| Poly::atom(crate::normal::AtomId::from_index(i));
        let cube = |p: &Poly| p.pow(3).unwrap_or_else(|e| panic!("{e}"));
        let mut unproved = Vec::new();
        for k in 1..=3i64 {
            for i in 1..24 {
                for j in 1..24 {
                    let a = x(i)
                        .mul(&x(0))
                        .map(|p| p.scale(&Q::from_integer(BigInt::from(k))))
                        .and_then(|p| Ok(p.sub(&x(0).mul(&x(0))?)))
                        .unwrap_or_else(|e| panic!("{e}"));
                    let b = cube(&x(0)).sub(&cube(&x(j)));
                    let proved = monomial_gcd_by_evaluation(&a, &b);
                    if i == j && k == 1 {
                        // x₀ − xᵢ divides both: never proved away.
                        assert_eq!(proved, None);
                    } else if proved != Some(Mono::one()) {
                        unproved.push((k, i, j));
                    }
                }
            }
        }
        assert!(unproved.is_empty(), "not proved coprime: {unproved:?}");
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
