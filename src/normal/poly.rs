//! Sparse multivariate polynomials over ℚ in atoms: sorted terms, no zero coefficients.

use super::atom::AtomId;
use super::mono::Mono;
use super::Limit;
use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use std::collections::HashMap;

/// An exact rational number.
pub type Q = BigRational;

pub use super::limits::{check_deadline, max_bits, max_terms};

/// A polynomial: terms sorted ascending by monomial order, each coefficient nonzero.
/// The fields are private so that every value is canonical and `==` is equality.
#[derive(Clone, Debug, PartialEq, Eq, Hash, Default)]
pub struct Poly {
    terms: Vec<(Mono, Q)>,
}

impl Poly {
    /// 0.
    pub fn zero() -> Poly {
        Poly { terms: Vec::new() }
    }

    /// 1.
    pub fn one() -> Poly {
        Poly::constant(Q::one())
    }

    /// A constant.
    pub fn constant(q: Q) -> Poly {
        if q.is_zero() {
            Poly::zero()
        } else {
            Poly {
                terms: vec![(Mono::one(), q)],
            }
        }
    }

    /// An integer constant.
    pub fn int(n: i64) -> Poly {
        Poly::constant(Q::from_integer(BigInt::from(n)))
    }

    /// The atom `a`.
    pub fn atom(a: AtomId) -> Poly {
        Poly::term(Mono::atom(a, 1), Q::one())
    }

    /// A single term.
    pub fn term(m: Mono, q: Q) -> Poly {
        if q.is_zero() {
            Poly::zero()
        } else {
            Poly {
                terms: vec![(m, q)],
            }
        }
    }

    /// Builds a polynomial from terms in any order, merging equal monomials.
    pub fn from_terms(mut terms: Vec<(Mono, Q)>) -> Poly {
        terms.sort_by(|a, b| a.0.cmp(&b.0));
        let mut out: Vec<(Mono, Q)> = Vec::with_capacity(terms.len());
        for (m, q) in terms {
            match out.last_mut() {
                Some(last) if last.0 == m => last.1 = super::qops::add(&last.1, &q),
                _ => {
                    if let Some(last) = out.last() {
                        if last.1.is_zero() {
                            out.pop();
                        }
                    }
                    out.push((m, q))
                }
            }
        }
        out.retain(|t| !t.1.is_zero());
        Poly { terms: out }
    }

    /// A polynomial from terms already strictly ascending with nonzero coefficients.
    pub(crate) fn from_sorted_terms(terms: Vec<(Mono, Q)>) -> Poly {
        debug_assert!(terms.windows(2).all(|w| w[0].0 < w[1].0));
        debug_assert!(terms.iter().all(|t| !t.1.is_zero()));
        Poly { terms }
    }

    /// Atom `x` renamed to `a` in place, reusing the terms. `false`, with `self`
    /// unchanged, when `a` already occurs (the renaming would merge two atoms).
    pub(crate) fn rename(&mut self, x: AtomId, a: AtomId) -> bool {
        if !self.contains(x) {
            return true;
        }
        if self.contains(a) {
            return false;
        }
        for (m, _) in &mut self.terms {
            m.rename(x, a);
        }
        // Distinct monomials stay distinct (a is new): sorting restores the order.
        if !self.terms.is_sorted_by(|s, t| s.0 < t.0) {
            self.terms.sort_unstable_by(|s, t| s.0.cmp(&t.0));
        }
        true
    }

    /// The terms, ascending, given up.
    pub(crate) fn into_terms(self) -> Vec<(Mono, Q)> {
        self.terms
    }

    /// The terms, ascending.
    pub fn terms(&self) -> &[(Mono, Q)] {
        &self.terms
    }

    /// Number of terms.
    pub fn len(&self) -> usize {
        self.terms.len()
    }

    /// Whether this is 0.
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }

    /// Whether this has no terms (is 0).
    pub fn is_empty(&self) -> bool {
        self.terms.is_empty()
    }

    /// Whether this is 1.
    pub fn is_one(&self) -> bool {
        matches!(self.terms.as_slice(), [(m, q)] if m.is_one() && q.is_one())
    }

    /// Whether this is a constant (zero included): [`Poly::as_constant`] without the copy.
    pub fn is_constant(&self) -> bool {
        match self.terms.as_slice() {
            [] => true,
            [(m, _)] => m.is_one(),
            _ => false,
        }
    }

    /// The value, if constant.
    pub fn as_constant(&self) -> Option<Q> {
        match self.terms.as_slice() {
            [] => Some(Q::zero()),
            [(m, q)] if m.is_one() => Some(q.clone()),
            _ => None,
        }
    }

    /// The single atom this is, if it is exactly one atom with coefficient 1.
    pub fn as_atom(&self) -> Option<AtomId> {
        match self.terms.as_slice() {
            [(m, q)] if q.is_one() => match m.pairs() {
                [(a, 1)] => Some(*a),
                _ => None,
            },
            _ => None,
        }
    }

    /// The leading (greatest) term.
    pub fn lead(&self) -> Option<&(Mono, Q)> {
        self.terms.last()
    }

    /// The sum.
    pub fn add(&self, other: &Poly) -> Poly {
        let (a, b) = (&self.terms, &other.terms);
        let mut out = Vec::with_capacity(a.len() + b.len());
        let (mut i, mut j) = (0, 0);
        while i < a.len() && j < b.len() {
            match a[i].0.cmp(&b[j].0) {
                std::cmp::Ordering::Less => {
                    out.push(a[i].clone());
                    i += 1;
                }
                std::cmp::Ordering::Greater => {
                    out.push(b[j].clone());
                    j += 1;
                }
                std::cmp::Ordering::Equal => {
                    let q = super::qops::add(&a[i].1, &b[j].1);
                    if !q.is_zero() {
                        out.push((a[i].0.clone(), q));
                    }
                    i += 1;
                    j += 1;
                }
            }
        }
        out.extend_from_slice(&a[i..]);
        out.extend_from_slice(&b[j..]);
        Poly { terms: out }
    }

    /// The sum, consuming both sides (no monomial is copied).
    pub fn add_owned(self, other: Poly) -> Poly {
        let mut out = Vec::with_capacity(self.terms.len() + other.terms.len());
        let mut a = self.terms.into_iter().peekable();
        let mut b = other.terms.into_iter().peekable();
        loop {
            let ord = match (a.peek(), b.peek()) {
                (Some(x), Some(y)) => x.0.cmp(&y.0),
                (Some(_), None) => std::cmp::Ordering::Less,
                (None, Some(_)) => std::cmp::Ordering::Greater,
                (None, None) => break,
            };
            match ord {
                std::cmp::Ordering::Less => out.extend(a.next()),
                std::cmp::Ordering::Greater => out.extend(b.next()),
                std::cmp::Ordering::Equal => {
                    if let (Some((m, x)), Some((_, y))) = (a.next(), b.next()) {
                        let q = super::qops::add(&x, &y);
                        if !q.is_zero() {
                            out.push((m, q));
                        }
                    }
                }
            }
        }
        Poly { terms: out }
    }

    /// The negation.
    pub fn neg(&self) -> Poly {
        Poly {
            terms: self.terms.iter().map(|(m, q)| (m.clone(), -q)).collect(),
        }
    }

    /// The difference.
    pub fn sub(&self, other: &Poly) -> Poly {
        self.clone().sub_owned(other.clone())
    }

    /// The difference, consuming both sides.
    pub fn sub_owned(self, mut other: Poly) -> Poly {
        for t in &mut other.terms {
            t.1 = -std::mem::take(&mut t.1);
        }
        self.add_owned(other)
    }

    /// `q · self`.
    pub fn scale(&self, q: &Q) -> Poly {
        if q.is_zero() {
            return Poly::zero();
        }
        Poly {
            terms: self
                .terms
                .iter()
                .map(|(m, c)| (m.clone(), super::qops::mul(c, q)))
                .collect(),
        }
    }

    /// `q · self`, reusing `self`'s terms (their monomials are not copied).
    pub(crate) fn into_scaled(mut self, q: &Q) -> Poly {
        if q.is_zero() {
            return Poly::zero();
        }
        if !q.is_one() {
            for t in &mut self.terms {
                t.1 = super::qops::mul(&t.1, q);
            }
        }
        self
    }

    /// `q · m · self`.
    pub fn mul_term(&self, m: &Mono, q: &Q) -> Result<Poly, Limit> {
        if q.is_zero() {
            return Ok(Poly::zero());
        }
        // By a monomial alone (the common case), the coefficients are copied, not
        // multiplied and reduced.
        let one = q.is_one();
        let mut terms = Vec::with_capacity(self.terms.len());
        for (n, c) in &self.terms {
            let c = if one {
                c.clone()
            } else {
                super::qops::mul(c, q)
            };
            terms.push((n.mul(m).ok_or(Limit::Exponent)?, c));
        }
        // Multiplying by a monomial preserves a monomial order.
        Ok(Poly { terms })
    }

    /// The product, refused when it would exceed the term limit.
    pub fn mul(&self, other: &Poly) -> Result<Poly, Limit> {
        if self.is_zero() || other.is_zero() {
            return Ok(Poly::zero());
        }
        let (small, big) = if self.len() <= other.len() {
            (self, other)
        } else {
            (other, self)
        };
        if small.len() == 1 {
            let (m, q) = &small.terms[0];
            return big.mul_term(m, q);
        }
        // Multiply over ℤ: scale both sides to integer coefficients, multiply, scale back
        // once per result term. Small products accumulate in i128, the rest in BigInt.
        let (sa, ia) = integer_form(small);
        let (sb, ib) = integer_form(big);
        let scale = sa * sb;
        let bits = |v: &[(&Mono, BigInt)]| v.iter().map(|t| t.1.bits()).max().unwrap_or(0);
        let fits =
            bits(&ia) + bits(&ib) + (usize::BITS - small.len().leading_zeros()) as u64 + 2 < 126;
        if fits {
            if let Some(out) = mul_packed(&ia, &ib, &scale, small, big)? {
                return Ok(out);
            }
        }
        if small.len() <= 8 {
            // A short factor: each of its terms shifts `big` in order, and a merge
            // tree of the sorted shifts needs no hashing.
            let mut parts = small
                .terms
                .iter()
                .map(|(m, q)| big.mul_term(m, q))
                .collect::<Result<Vec<Poly>, Limit>>()?;
            while parts.len() > 1 {
                let mut next = Vec::with_capacity(parts.len().div_ceil(2));
                let mut it = parts.into_iter();
                while let Some(a) = it.next() {
                    next.push(match it.next() {
                        Some(b) => a.add_owned(b),
                        None => a,
                    });
                }
                parts = next;
                check_deadline()?;
            }
            let out = parts.pop().unwrap_or_else(Poly::zero);
            if out.len() > max_terms() {
                return Err(Limit::terms());
            }
            return Ok(out);
        }
        let mut terms: Vec<(Mono, Q)> = if fits {
            let ib: Vec<(&Mono, i128)> = ib.iter().map(|t| (t.0, i128_of(&t.1))).collect();
            let mut acc: HashMap<Mono, i128, FxBuild> = HashMap::with_capacity_and_hasher(
                small.len().saturating_mul(big.len()).min(1 << 16),
                FxBuild,
            );
            for (m1, c1) in &ia {
                let c1 = i128_of(c1);
                for (m2, c2) in &ib {
                    let m = m1.mul(m2).ok_or(Limit::Exponent)?;
                    *acc.entry(m).or_insert(0) += c1 * c2;
                }
                if acc.len() > max_terms() {
                    return Err(Limit::terms());
                }
                check_deadline()?;
            }
            acc.into_iter()
                .filter(|t| t.1 != 0)
                .map(|(m, c)| (m, scale_int(c, &scale)))
                .collect()
        } else {
            let mut acc: HashMap<Mono, BigInt, FxBuild> = HashMap::with_capacity_and_hasher(
                small.len().saturating_mul(big.len()).min(1 << 16),
                FxBuild,
            );
            for (m1, c1) in &ia {
                for (m2, c2) in &ib {
                    let m = m1.mul(m2).ok_or(Limit::Exponent)?;
                    let c = c1 * c2;
                    match acc.get_mut(&m) {
                        Some(v) => *v += c,
                        None => {
                            acc.insert(m, c);
                        }
                    }
                }
                if acc.len() > max_terms() {
                    return Err(Limit::terms());
                }
                check_deadline()?;
            }
            acc.into_iter()
                .filter(|t| !t.1.is_zero())
                .map(|(m, c)| (m, super::qops::mul(&Q::from_integer(c), &scale)))
                .collect()
        };
        terms.sort_unstable_by(|a, b| a.0.cmp(&b.0));
        Ok(Poly { terms })
    }

    /// `self^k` by repeated squaring, refused when too big.
    pub fn pow(&self, k: u64) -> Result<Poly, Limit> {
        if k == 0 {
            return Ok(Poly::one());
        }
        if self.len() == 1 {
            let (m, q) = &self.terms[0];
            let k32 = u32::try_from(k).map_err(|_| Limit::Exponent)?;
            let m = m.pow(k32).ok_or(Limit::Exponent)?;
            return Ok(Poly::term(m, pow_q_checked(q, k32)?));
        }
        if self.is_zero() {
            return Ok(Poly::zero());
        }
        if !pow_fits(self.len(), k) {
            return Err(Limit::terms());
        }
        if let Some(out) = super::pack::pow_multinomial(self, k)? {
            // Terms without a common atom, `(1 + x + y + z)^k`: each term made once.
            return Ok(out);
        }
        if iterate_is_cheaper(self.len(), k) {
            // A short sum: multiplying by it k − 1 times touches far fewer terms than
            // squaring (the last squaring alone costs |self^(k/2)|²).
            // (A square is one product: the packed path of `mul` already serves it.)
            if let Some(out) = (k > 2).then(|| pow_packed(self, k)).transpose()?.flatten() {
                return Ok(out);
            }
            let mut result = self.clone();
            for _ in 1..k {
                result = result.mul(self)?;
            }
            return Ok(result);
        }
        let mut result = Poly::one();
        let mut base = self.clone();
        let mut e = k;
        while e > 0 {
            if e & 1 == 1 {
                result = result.mul(&base)?;
            }
            e >>= 1;
            if e > 0 {
                base = base.mul(&base)?;
            }
        }
        Ok(result)
    }

    /// The atoms occurring, sorted.
    pub fn atoms(&self) -> Vec<AtomId> {
        if self.terms.len() > 32 {
            // A long polynomial: the degree table visits each pair once, where sorting
            // every occurrence costs a logarithm more.
            return super::pack::degrees(self)
                .into_iter()
                .map(|t| t.0)
                .collect();
        }
        let mut v: Vec<AtomId> = self
            .terms
            .iter()
            .flat_map(|(m, _)| m.pairs().iter().map(|p| p.0))
            .collect();
        v.sort_unstable();
        v.dedup();
        v
    }

    /// Whether atom `a` occurs.
    pub fn contains(&self, a: AtomId) -> bool {
        self.terms.iter().any(|(m, _)| m.exp(a) > 0)
    }

    /// Degree in atom `a`.
    pub fn degree_in(&self, a: AtomId) -> u32 {
        self.terms.iter().map(|(m, _)| m.exp(a)).max().unwrap_or(0)
    }

    /// The coefficients of `self` as a polynomial in `a`: `(exponent, coefficient)`, ascending.
    pub fn coeffs_in(&self, a: AtomId) -> Vec<(u32, Poly)> {
        let mut map: std::collections::BTreeMap<u32, Vec<(Mono, Q)>> = Default::default();
        for (m, q) in &self.terms {
            let (rest, e) = m.split(a);
            map.entry(e).or_default().push((rest, q.clone()));
        }
        map.into_iter()
            .map(|(e, t)| (e, Poly::from_terms(t)))
            .collect()
    }

    /// Σ cᵢ aⁱ from coefficients.
    pub fn from_coeffs(a: AtomId, coeffs: &[(u32, Poly)]) -> Result<Poly, Limit> {
        let mut out = Poly::zero();
        for (e, c) in coeffs {
            out = out.add(&c.mul_term(&Mono::atom(a, *e), &Q::one())?);
        }
        Ok(out)
    }

    /// `self` with atom `a` replaced by polynomial `v`.
    pub fn subst(&self, a: AtomId, v: &Poly) -> Result<Poly, Limit> {
        if !self.contains(a) {
            return Ok(self.clone());
        }
        let coeffs = self.coeffs_in(a);
        // Horner's scheme from the top degree down.
        let mut out = Poly::zero();
        let mut prev: Option<u32> = None;
        for (e, c) in coeffs.iter().rev() {
            if let Some(p) = prev {
                out = out.mul(&v.pow(u64::from(p - e))?)?;
            }
            out = out.add(c);
            prev = Some(*e);
        }
        if let Some(p) = prev {
            out = out.mul(&v.pow(u64::from(p))?)?;
        }
        Ok(out)
    }

    /// The partial derivative with respect to atom `a`, treating every other atom as constant.
    pub fn deriv_atom(&self, a: AtomId) -> Poly {
        let mut terms = Vec::new();
        for (m, q) in &self.terms {
            let (rest, e) = m.split(a);
            if e == 0 {
                continue;
            }
            let m2 = rest
                .mul(&Mono::atom(a, e - 1))
                .unwrap_or_else(|| rest.clone());
            terms.push((m2, q * Q::from_integer(BigInt::from(e))));
        }
        Poly::from_terms(terms)
    }

    /// The gcd of the numerators over the lcm of the denominators of the coefficients (positive).
    pub fn content(&self) -> Q {
        let mut num = BigInt::zero();
        let mut den = BigInt::one();
        for (_, q) in &self.terms {
            num = num.gcd(q.numer());
            den = den.lcm(q.denom());
        }
        if num.is_zero() {
            return Q::one();
        }
        Q::new(num, den)
    }

    /// `self` divided by its content, with a positive leading coefficient.
    pub fn primitive(&self) -> Poly {
        if self.is_zero() {
            return Poly::zero();
        }
        let mut c = self.content();
        if self.lead().is_some_and(|t| t.1.is_negative()) {
            c = -c;
        }
        self.scale(&c.recip())
    }

    /// `self` scaled so that its leading coefficient is 1.
    pub fn monic(&self) -> Poly {
        match self.lead() {
            Some((_, q)) if !q.is_one() => self.scale(&q.recip()),
            _ => self.clone(),
        }
    }

    /// The greatest monomial dividing every term.
    pub fn mono_content(&self) -> Mono {
        let mut it = self.terms.iter();
        let Some((first, _)) = it.next() else {
            return Mono::one();
        };
        let mut g = first.clone();
        for (m, _) in it {
            if g.is_one() {
                break;
            }
            g = g.gcd(m);
        }
        g
    }

    /// `self / m` for a monomial dividing every term.
    pub fn div_mono(&self, m: &Mono) -> Option<Poly> {
        let mut terms = Vec::with_capacity(self.terms.len());
        for (n, q) in &self.terms {
            terms.push((n.div(m)?, q.clone()));
        }
        Some(Poly { terms })
    }

    /// Maps every coefficient (the result is re-normalised).
    pub fn map_coeffs(&self, f: impl Fn(&Q) -> Q) -> Poly {
        Poly::from_terms(self.terms.iter().map(|(m, q)| (m.clone(), f(q))).collect())
    }
}

/// `p = scale · Σ cᵢ mᵢ` with integer `cᵢ`.
fn integer_form(p: &Poly) -> (Q, Vec<(&Mono, BigInt)>) {
    let mut l = BigInt::one();
    for (_, q) in &p.terms {
        if !q.denom().is_one() {
            l = l.lcm(q.denom());
        }
    }
    let ints = p
        .terms
        .iter()
        .map(|(m, q)| (m, q.numer() * (&l / q.denom())))
        .collect();
    (Q::new(BigInt::one(), l), ints)
}

/// The product of two integer forms (coefficients that fit in `i128` with room for
/// the sums) on packed monomials; `None` when the monomials do not pack.
fn mul_packed(
    ia: &[(&Mono, BigInt)],
    ib: &[(&Mono, BigInt)],
    scale: &Q,
    a: &Poly,
    b: &Poly,
) -> Result<Option<Poly>, Limit> {
    let Some(pk) = super::pack::Packing::for_product(a, b) else {
        return Ok(None);
    };
    let packed = |v: &[(&Mono, BigInt)]| -> Option<Vec<(u128, i128)>> {
        v.iter()
            .map(|(m, c)| Some((pk.pack(m)?, i128_of(c))))
            .collect()
    };
    let (Some(pa), Some(pb)) = (packed(ia), packed(ib)) else {
        return Ok(None);
    };
    if pa.len() <= 8 {
        // A short factor (`ia` is the shorter): each of its terms shifts the other in
        // order (the fields hold the product's degrees: no carry), and a merge tree of the
        // sorted shifts needs no hash table.
        let parts = pa
            .iter()
            .map(|&(m, c)| {
                pb.iter()
                    .map(|&(x, d)| Some((x + m, d.checked_mul(c)?)))
                    .collect()
            })
            .collect::<Option<Vec<Vec<_>>>>();
        let Some(v) = parts.and_then(merge_tree) else {
            return Ok(None);
        };
        if v.len() > max_terms() {
            return Err(Limit::terms());
        }
        return Ok(Some(unpacked(&pk, v, scale)));
    }
    let mut acc: HashMap<u128, i128, FxBuild> =
        HashMap::with_capacity_and_hasher(pa.len().saturating_mul(pb.len()).min(1 << 16), FxBuild);
    for (x, c1) in &pa {
        for (y, c2) in &pb {
            // The fields are wide enough for the sum of the degrees: no carry.
            *acc.entry(x + y).or_insert(0) += c1 * c2;
        }
        if acc.len() > max_terms() {
            return Err(Limit::terms());
        }
        check_deadline()?;
    }
    let mut v: Vec<(u128, i128)> = acc.into_iter().filter(|t| t.1 != 0).collect();
    // The integer order of packed monomials is the monomial order.
    v.sort_unstable_by_key(|t| t.0);
    Ok(Some(unpacked(&pk, v, scale)))
}

/// A polynomial in the atoms `ids` from `(exponents, numerator, denominator)` terms, one
/// exponent per atom (tests draw polynomials this way).
#[cfg(test)]
pub(crate) fn from_exponents(ids: &[AtomId], terms: &[(Vec<u32>, i64, i64)]) -> Poly {
    Poly::from_terms(
        terms
            .iter()
            .filter_map(|(es, n, d)| {
                let pairs = ids.iter().copied().zip(es.iter().copied()).collect();
                Some((
                    Mono::from_pairs(pairs)?,
                    Q::new(BigInt::from(*n), BigInt::from(*d)),
                ))
            })
            .collect(),
    )
}

/// The polynomial `scale · Σ c·m` of ascending packed terms with nonzero coefficients.
fn unpacked(pk: &super::pack::Packing, v: Vec<(u128, i128)>, scale: &Q) -> Poly {
    Poly {
        terms: v
            .into_iter()
            .map(|(k, c)| (pk.unpack(k), scale_int(c, scale)))
            .collect(),
    }
}

/// `p^k` by k − 1 multiplications by `p`, all on packed monomials with `i128`
/// coefficients (one packing for the final degrees, no conversion between the steps);
/// `None` when the monomials do not pack or a coefficient would overflow (the caller
/// then multiplies on [`Poly`]s).
fn pow_packed(p: &Poly, k: u64) -> Result<Option<Poly>, Limit> {
    let fields: Vec<(AtomId, u64)> = super::pack::degrees(p)
        .into_iter()
        .map(|(a, d)| (a, d.saturating_mul(k)))
        .collect();
    let Some(pk) = super::pack::Packing::new(&fields) else {
        return Ok(None);
    };
    let (scale, ints) = integer_form(p);
    let Some(base) = ints
        .iter()
        .map(|(m, c)| Some((pk.pack(m)?, num_traits::ToPrimitive::to_i128(c)?)))
        .collect::<Option<Vec<(u128, i128)>>>()
    else {
        return Ok(None);
    };
    let mut acc = base.clone();
    for _ in 1..k {
        // Each term of the base shifts `acc` in order (the fields hold the final
        // degrees: no carry); the shifted copies are merged pairwise.
        let mut parts: Vec<Vec<(u128, i128)>> = Vec::with_capacity(base.len());
        for &(m, c) in &base {
            let Some(part) = acc
                .iter()
                .map(|&(x, d)| Some((x + m, d.checked_mul(c)?)))
                .collect::<Option<Vec<_>>>()
            else {
                return Ok(None);
            };
            parts.push(part);
        }
        let Some(sum) = merge_tree(parts) else {
            return Ok(None);
        };
        acc = sum;
        if acc.len() > max_terms() {
            return Err(Limit::terms());
        }
        check_deadline()?;
    }
    let Ok(k32) = u32::try_from(k) else {
        return Ok(None);
    };
    let scale = pow_q_checked(&scale, k32)?;
    Ok(Some(Poly {
        terms: acc
            .into_iter()
            .map(|(x, c)| (pk.unpack(x), scale_int(c, &scale)))
            .collect(),
    }))
}

/// The sum of ascending packed polynomials, merged pairwise; `None` on overflow.
fn merge_tree(mut parts: Vec<Vec<(u128, i128)>>) -> Option<Vec<(u128, i128)>> {
    while parts.len() > 1 {
        let mut next = Vec::with_capacity(parts.len().div_ceil(2));
        let mut it = parts.into_iter();
        while let Some(a) = it.next() {
            next.push(match it.next() {
                Some(b) => merge_packed(&a, &b)?,
                None => a,
            });
        }
        parts = next;
    }
    Some(parts.pop().unwrap_or_default())
}

/// The sum of two ascending packed polynomials, `None` on overflow.
fn merge_packed(a: &[(u128, i128)], b: &[(u128, i128)]) -> Option<Vec<(u128, i128)>> {
    let mut out = Vec::with_capacity(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    while let (Some(&x), Some(&y)) = (a.get(i), b.get(j)) {
        match x.0.cmp(&y.0) {
            std::cmp::Ordering::Less => {
                out.push(x);
                i += 1;
            }
            std::cmp::Ordering::Greater => {
                out.push(y);
                j += 1;
            }
            std::cmp::Ordering::Equal => {
                let c = x.1.checked_add(y.1)?;
                if c != 0 {
                    out.push((x.0, c));
                }
                i += 1;
                j += 1;
            }
        }
    }
    out.extend_from_slice(a.get(i..).unwrap_or(&[]));
    out.extend_from_slice(b.get(j..).unwrap_or(&[]));
    Some(out)
}

/// `c · scale` for an integer `c`.
fn scale_int(c: i128, scale: &Q) -> Q {
    if scale.is_one() {
        return Q::from_integer(BigInt::from(c));
    }
    super::qops::mul(&Q::from_integer(BigInt::from(c)), scale)
}

fn i128_of(n: &BigInt) -> i128 {
    num_traits::ToPrimitive::to_i128(n).unwrap_or(0)
}

/// A fast hasher for monomials (FxHash's multiply-rotate), not exposed to input-chosen
/// denial of service beyond what the term limit already bounds.
#[derive(Clone, Copy, Default)]
pub struct FxBuild;

/// The hasher of [`FxBuild`].
#[derive(Default)]
pub struct Fx(u64);

impl std::hash::BuildHasher for FxBuild {
    type Hasher = Fx;
    fn build_hasher(&self) -> Fx {
        Fx(0)
    }
}

impl std::hash::Hasher for Fx {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for b in bytes {
            self.write_u64(u64::from(*b));
        }
    }
    fn write_u32(&mut self, n: u32) {
        self.write_u64(u64::from(n));
    }
    fn write_usize(&mut self, n: usize) {
        self.write_u64(n as u64);
    }
    fn write_u128(&mut self, n: u128) {
        self.write_u64(n as u64);
        self.write_u64((n >> 64) as u64);
    }
    fn write_u64(&mut self, n: u64) {
        self.0 = (self.0.rotate_left(5) ^ n).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
}

/// `q^k` exactly (callers check the size first with [`pow_q_checked`]).
pub fn pow_q(q: &Q, k: u32) -> Q {
    num_traits::pow::Pow::pow(q, k)
}

/// `q^k`, refused when the result would exceed [`max_bits`].
pub fn pow_q_checked(q: &Q, k: u32) -> Result<Q, Limit> {
    if q.is_one() {
        return Ok(Q::one());
    }
    let bits = q.numer().bits().max(q.denom().bits());
    if bits > 1 && bits.saturating_sub(1).saturating_mul(u64::from(k)) > max_bits() {
        return Err(Limit::Digits(super::limits::current().max_digits));
    }
    Ok(pow_q(q, k))
}

/// Whether expanding an `n`-term sum to the `k`-th power fits the limits: the result
/// (up to C(n+k−1, k) terms) and the work of the last squaring.
pub fn pow_fits(n: usize, k: u64) -> bool {
    let half = estimate_pow_terms(n, k / 2);
    estimate_pow_terms(n, k) <= max_terms() as u128 && half.saturating_mul(half) <= 50_000_000
}

/// Whether `p^k` for an `n`-term `p` costs less as k − 1 multiplications by `p`
/// (about Σⱼ n·|p^j| term products) than by repeated squaring (at least |p^(k/2)|²).
fn iterate_is_cheaper(n: usize, k: u64) -> bool {
    if k > 4096 {
        return false;
    }
    let half = estimate_pow_terms(n, k / 2);
    let squaring = half.saturating_mul(half);
    let mut iterating: u128 = 0;
    for j in 1..k {
        iterating = iterating.saturating_add(estimate_pow_terms(n, j).saturating_mul(n as u128));
        if iterating >= squaring {
            return false;
        }
    }
    true
}

/// C(n+k-1, k), the term count of a dense power of an n-term sum, saturating.
fn estimate_pow_terms(n: usize, k: u64) -> u128 {
    let mut r: u128 = 1;
    for i in 1..n as u128 {
        // r = C(k+i, i) stays an exact integer at every step.
        r = r.saturating_mul(u128::from(k) + i) / i;
        if r > 1 << 64 {
            return u128::MAX;
        }
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn any_poly() -> impl Strategy<Value = Poly> {
        poly_of_up_to(5)
    }

    /// Polynomials of 2 to `n − 1` terms drawn (fewer when monomials repeat).
    fn poly_of_up_to(n: usize) -> impl Strategy<Value = Poly> {
        let term = (
            proptest::collection::vec((0u32..4, 1u32..3), 0..3),
            -3i64..=3,
            1i64..=3,
        );
        proptest::collection::vec(term, 2..n).prop_map(|ts| {
            Poly::from_terms(
                ts.into_iter()
                    .filter_map(|(m, n, d)| {
                        let m = m.into_iter().map(|(a, e)| (AtomId::from_index(a), e));
                        Some((
                            Mono::from_pairs(m.collect())?,
                            Q::new(BigInt::from(n), BigInt::from(d)),
                        ))
                    })
                    .collect(),
            )
        })
    }

    #[test]
    fn constant_tests_agree_with_the_constant() {
        let cases = [
            Poly::zero(),
            Poly::one(),
            Poly::constant(Q::new(BigInt::from(2), BigInt::from(3))),
            Poly::atom(AtomId::from_index(0)),
            Poly::atom(AtomId::from_index(0)).add(&Poly::one()),
        ];
        let agree = |p: &Poly| {
            assert_eq!(p.is_constant(), p.as_constant().is_some(), "{p:?}");
            assert_eq!(p.is_one(), p.as_constant() == Some(Q::one()), "{p:?}");
        };
        cases.iter().for_each(agree);
        assert!(cases[1].is_one() && cases[2].is_constant() && !cases[3].is_constant());
    }

    proptest! {
        #[test]
        fn constant_tests_agree_on_any_poly(p in any_poly()) {
            prop_assert_eq!(p.is_constant(), p.as_constant().is_some());
            prop_assert_eq!(p.is_one(), p.as_constant() == Some(Q::one()));
        }

        /// The product, by whichever path its sizes take (a short factor's merge tree, a
        /// hash table of packed monomials), is the sum of one factor times each term of the
        /// other.
        #[test]
        fn product_is_the_sum_of_the_term_products(p in poly_of_up_to(14), q in poly_of_up_to(14)) {
            let mut want = Poly::zero();
            for (m, c) in p.terms() {
                let part = q.mul_term(m, c).unwrap_or_else(|e| panic!("{e:?}"));
                want = want.add(&part);
            }
            prop_assert_eq!(p.mul(&q), Ok(want));
        }

        /// The packed power is the product of k copies, term for term.
        #[test]
        fn packed_power_is_repeated_product(p in any_poly(), k in 1u64..7) {
            let mut want = p.clone();
            for _ in 1..k {
                want = want.mul(&p).unwrap_or_else(|_| Poly::zero());
            }
            match pow_packed(&p, k) {
                Ok(Some(got)) => prop_assert_eq!(got, want),
                other => return Err(TestCaseError::fail(format!("small powers pack: {other:?}"))),
            }
        }
    }

    /// A coefficient past `i128` leaves the packed power (the general path answers).
    #[test]
    fn packed_power_overflow_falls_back() {
        let x = Poly::atom(AtomId::from_index(0));
        let p = x.add(&Poly::int(1 << 40));
        assert_eq!(pow_packed(&p, 4), Ok(None));
        let p4 = p.pow(4).unwrap_or_else(|e| panic!("{e:?}"));
        assert_eq!(p4.len(), 5);
        assert_eq!(p4.as_constant(), None);
    }
}
