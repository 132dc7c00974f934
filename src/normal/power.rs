//! Large integer powers of sums, kept factored.
//!
//! Expanding `(x - a)^6000` takes time that grows with the cube of the exponent, though
//! the question asked of it is usually answered without expanding: `(x - a)^6000` against
//! itself, against `(a - x)^6000`, or the derivative `6000 (x - a)^5999`. So a power of a
//! sum at or above [`KEEP_FROM`] is written `c · m^k · F^k`, with `F` an
//! [`Atom::Factor`] holding the sum made primitive (content, sign and monomial factor
//! pulled out). Exponents then add and cancel like those of any atom.
//!
//! The form is sound but not canonical: `F · (x - a)` and `F²` are equal values with
//! different forms. A zero difference is therefore a proof, and a nonzero one is not a
//! disproof: [`expand`] writes every kept factor out in full, and the checker does so
//! before it concludes anything from a difference that is not zero.

use super::atom::{self, Atom, AtomId};
use super::poly::{pow_q_checked, Poly};
use super::rat::Rat;
use super::subst::Subst;
use super::{Assumptions, Limit, NormError};

/// Powers of sums from this exponent on are kept factored.
pub const KEEP_FROM: u64 = 64;

/// `base^k` kept factored, when `|k| ≥ KEEP_FROM` and the numerator or the denominator of
/// `base` is a sum; `None` when the power is to be expanded as usual.
pub fn keep(base: &Rat, k: i64) -> Option<Result<Rat, NormError>> {
    let e = k.unsigned_abs();
    if e < KEEP_FROM || (base.num().len() <= 1 && base.den().len() <= 1) {
        return None;
    }
    let whole = || -> Result<Rat, NormError> {
        let num = factored(base.num(), e)?;
        let den = factored(base.den(), e)?;
        if k < 0 {
            den.div(&num)
        } else {
            num.div(&den)
        }
    };
    Some(whole())
}

/// `p^e` with a sum `p` kept as one factor.
fn factored(p: &Poly, e: u64) -> Result<Rat, NormError> {
    let e32 = u32::try_from(e).map_err(|_| Limit::Exponent)?;
    if p.len() <= 1 {
        return Rat::poly(p.pow(e)?);
    }
    let mc = p.mono_content();
    let rest = p.div_mono(&mc).unwrap_or_else(|| p.clone());
    let prim = rest.primitive();
    // p = c · mc · prim, with c the (signed) ratio of the leading coefficients.
    let c = match (rest.lead(), prim.lead()) {
        (Some((_, a)), Some((_, b))) => a / b,
        _ => return Err(NormError::DivisionByZero),
    };
    let coeff = pow_q_checked(&c, e32)?;
    let mut pairs = mc.pow(e32).ok_or(Limit::Exponent)?.pairs().to_vec();
    // The parts are primitive with positive leading coefficients, so their product is
    // primitive with a positive leading coefficient (Gauss): it is `prim` itself.
    for (part, i) in super::gcd::squarefree(&prim)? {
        let exp = i.checked_mul(e32).ok_or(Limit::Exponent)?;
        if part.len() == 1 {
            // A part that is a monomial (cannot happen for a primitive sum, but costs nothing).
            let m = part.lead().map(|t| t.0.clone()).unwrap_or_default();
            pairs.extend(m.pow(exp).ok_or(Limit::Exponent)?.pairs().iter().copied());
        } else {
            pairs.push((atom::intern(Atom::Factor(part)), exp));
        }
    }
    let kept = super::mono::Mono::from_pairs(pairs).ok_or(Limit::Exponent)?;
    Rat::poly(Poly::term(kept, coeff))
}

/// `r` with the sums of its numerator and denominator kept as factors: the value of a
/// kept factor whose sum a substitution changed.
pub fn refactor(r: &Rat) -> Result<Rat, NormError> {
    factored(r.num(), 1)?.div(&factored(r.den(), 1)?)
}

/// Whether `r` holds a kept factor anywhere (inside other atoms too).
pub fn has_kept(r: &Rat) -> bool {
    r.atoms().into_iter().any(|a| {
        std::iter::once(a)
            .chain(super::subst::atoms_within(a))
            .any(|b| matches!(atom::get(b), Atom::Factor(_)))
    })
}

/// Largest cost (terms of a written-out power times its exponent, summed over the kept
/// factors) that [`settle`] spends on writing kept factors out.
const SETTLE_COST: u64 = 2_000_000;

/// `d`, a difference that is zero when the step holds, settled as far as its kept factors
/// allow: zero when it vanishes (`vanishes`); otherwise written out in full when that is
/// affordable (the canonical form, from which the checker may conclude), else as it is.
pub fn settle(d: &Rat, s: &Assumptions) -> Rat {
    if d.is_zero() || !has_kept(d) {
        return d.clone();
    }
    if vanishes(d, s) {
        return Rat::zero();
    }
    // Kept factors that share a factor (`x^2 - a^2` beside `x - a`), over a gcd-free basis.
    if let Some(r) = coprime(d, s) {
        if r.is_zero() || vanishes(&r, s) {
            return Rat::zero();
        }
    }
    if cost(d) <= SETTLE_COST {
        if let Ok(full) = expand(d, s) {
            return full;
        }
    }
    d.clone()
}

/// Whether `d` is zero, shown by writing out its numerator after setting aside the
/// powers of kept factors common to all its terms: `F^k · M` is zero when `M` is
/// (`(x - a)^200 - (x - a)^199 (x - a)` is `F^199 (F - (x - a))`), whatever `F`'s value.
fn vanishes(d: &Rat, s: &Assumptions) -> bool {
    let num = d.num();
    let common = num.mono_content();
    let kept: Vec<(AtomId, u32)> = common
        .pairs()
        .iter()
        .filter(|(a, _)| matches!(atom::get(*a), Atom::Factor(_)))
        .copied()
        .collect();
    let rest = match super::mono::Mono::from_pairs(kept) {
        Some(m) if !m.is_one() => num.div_mono(&m).unwrap_or_else(|| num.clone()),
        _ => num.clone(),
    };
    let Ok(rest) = Rat::poly(rest) else {
        return false;
    };
    cost(&rest) <= SETTLE_COST && expand(&rest, s).is_ok_and(|r| r.is_zero())
}

/// `r` with its kept factors rewritten over a gcd-free basis of their sums, when two of
/// them share a factor: `(x^2 - a^2)^k` becomes `(x - a)^k (x + a)^k`.
fn coprime(r: &Rat, s: &Assumptions) -> Option<Rat> {
    use super::gcd::{div_exact, gcd};
    let kept: Vec<(AtomId, Poly)> = r
        .atoms()
        .into_iter()
        .filter_map(|a| match atom::get(a) {
            Atom::Factor(p) => Some((a, p.clone())),
            _ => None,
        })
        .collect();
    if kept.len() < 2 {
        return None;
    }
    let mut basis: Vec<Poly> = kept.iter().map(|k| k.1.clone()).collect();
    let mut split = false;
    for _ in 0..64 {
        let mut pair = None;
        'find: for i in 0..basis.len() {
            for j in i + 1..basis.len() {
                let g = gcd(&basis[i], &basis[j]).ok()?;
                if g.as_constant().is_none() {
                    pair = Some((i, j, g));
                    break 'find;
                }
            }
        }
        let Some((i, j, g)) = pair else {
            break;
        };
        let bi = div_exact(&basis[i], &g).ok()??;
        let bj = div_exact(&basis[j], &g).ok()??;
        basis = basis
            .into_iter()
            .enumerate()
            .filter(|(k, _)| *k != i && *k != j)
            .map(|(_, x)| x)
            .chain([g, bi, bj])
            .filter(|x| x.as_constant().is_none())
            .map(|x| x.primitive())
            .collect();
        basis.dedup();
        split = true;
    }
    if !split {
        return None;
    }
    // Each kept sum as a constant times a product of basis elements.
    let mut values = Vec::new();
    for (a, p) in &kept {
        let mut rest = p.clone();
        let mut v = Rat::one();
        for b in &basis {
            while let Ok(Some(q)) = div_exact(&rest, b) {
                rest = q;
                v = v.mul(&factor_of(b)).ok()?;
            }
        }
        let c = rest.as_constant()?;
        values.push((*a, v.scale(&c)));
    }
    let map = |a: AtomId| values.iter().find(|v| v.0 == a).map(|v| v.1.clone());
    Subst::new(&map, s).rat(r).ok()
}

/// A basis sum as a kept factor (a primitive sum of two or more terms), else as itself.
fn factor_of(p: &Poly) -> Rat {
    if p.len() >= 2 {
        Rat::atom(atom::intern(Atom::Factor(p.clone())))
    } else {
        Rat::poly(p.clone()).unwrap_or_else(|_| Rat::one())
    }
}

/// What writing out the kept factors of `r` would cost: for each, the number of terms of
/// its largest power (a multinomial count) times that exponent (the growth of the
/// coefficients), summed; saturating.
fn cost(r: &Rat) -> u64 {
    let mut top: foldhash::HashMap<AtomId, u32> = foldhash::HashMap::default();
    let mut scan = |p: &Poly| {
        for (m, _) in p.terms() {
            for &(a, e) in m.pairs() {
                let t = top.entry(a).or_insert(0);
                *t = (*t).max(e);
            }
        }
    };
    scan(r.num());
    scan(r.den());
    for a in r.atoms() {
        for b in std::iter::once(a).chain(super::subst::atoms_within(a)) {
            match atom::get(b) {
                Atom::Sqrt(p) | Atom::Root(p, _) | Atom::Abs(p) | Atom::Factor(p) => scan(p),
                Atom::Sin(u) | Atom::Cos(u) | Atom::Exp(u) | Atom::Ln(u) | Atom::At(_, u) => {
                    scan(u.num());
                    scan(u.den());
                }
                Atom::Pow(x, y) => {
                    for u in [x, y] {
                        scan(u.num());
                        scan(u.den());
                    }
                }
                Atom::Sym(_) | Atom::Pi | Atom::Moment(..) => {}
            }
        }
    }
    top.into_iter()
        .filter_map(|(a, e)| match atom::get(a) {
            Atom::Factor(p) => Some(multinomial(p.len() as u64, e).saturating_mul(u64::from(e))),
            _ => None,
        })
        .fold(0u64, u64::saturating_add)
}

/// The number of monomials of degree `e` in `n` variables, `C(e + n − 1, n − 1)`, an upper
/// bound on the terms of an `n`-term sum to the `e`-th power; saturating.
fn multinomial(n: u64, e: u32) -> u64 {
    let mut c: u64 = 1;
    for i in 1..n {
        // c = C(e + i, i) from C(e + i − 1, i − 1).
        c = match c.checked_mul(u64::from(e) + i) {
            Some(x) => x / i,
            None => return u64::MAX,
        };
    }
    c
}

/// `r` with every kept factor written out in full: the canonical form.
pub fn expand(r: &Rat, s: &Assumptions) -> Result<Rat, NormError> {
    if !has_kept(r) {
        return Ok(r.clone());
    }
    // A kept factor's sum may hold kept factors of its own: expand those too.
    let map = |a: AtomId| match atom::get(a) {
        Atom::Factor(p) => Rat::poly(p.clone()).and_then(|v| expand(&v, s)).ok(),
        _ => None,
    };
    Subst::new(&map, s).rat(r)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::normal::func::int_pow;
    use crate::normal::Q;

    fn x() -> Rat {
        Rat::atom(atom::sym("x"))
    }

    fn a() -> Rat {
        Rat::atom(atom::sym("a"))
    }

    #[test]
    fn large_powers_of_a_sum_and_its_negative_agree() {
        let d = x().sub(&a()).unwrap();
        let p = int_pow(&d, 6000).unwrap();
        let q = int_pow(&d.neg(), 6000).unwrap();
        assert_eq!(p, q);
        // Odd powers differ in sign.
        let p = int_pow(&d, 6001).unwrap();
        let q = int_pow(&d.neg(), 6001).unwrap();
        assert_eq!(p, q.neg());
        assert!(!p.is_zero());
    }

    #[test]
    fn kept_powers_multiply_and_cancel() {
        let d = x().sub(&a()).unwrap();
        let p = int_pow(&d, 3000).unwrap();
        let q = int_pow(&d, 6000).unwrap();
        assert_eq!(p.mul(&p).unwrap(), q);
        assert_eq!(q.div(&p).unwrap(), p);
        // The content comes out: (2x - 2a)^100 = 2^100 (x - a)^100.
        let two = Rat::int(2);
        let r = int_pow(&d.mul(&two).unwrap(), 100).unwrap();
        let s = int_pow(&d, 100)
            .unwrap()
            .mul(&int_pow(&two, 100).unwrap())
            .unwrap();
        assert_eq!(r, s);
    }

    #[test]
    fn expanding_gives_the_canonical_form() {
        // (x + 1)^64 kept, against its expansion: different forms, equal once expanded.
        let d = x().add(&Rat::one()).unwrap();
        let kept = int_pow(&d, 64).unwrap();
        let full = d.powi(64).unwrap();
        assert_ne!(kept, full);
        let s = Assumptions::default();
        assert_eq!(expand(&kept, &s).unwrap(), full);
        assert!(has_kept(&kept) && !has_kept(&full));
        // A negative power: 1 / (x + 1)^64.
        let inv = int_pow(&d, -64).unwrap();
        assert_eq!(expand(&inv, &s).unwrap(), full.recip().unwrap());
    }

    #[test]
    fn powers_of_squares_are_powers_of_their_roots() {
        // (x^2 - 2ax + a^2)^3000 = (x - a)^6000, and (3x (x+1)^2)^64 written out is the
        // expansion.
        let d = x().sub(&a()).unwrap();
        let sq = d.powi(2).unwrap();
        assert_eq!(int_pow(&sq, 3000).unwrap(), int_pow(&d, 6000).unwrap());
        let x1 = x().add(&Rat::one()).unwrap();
        let base = x1
            .powi(2)
            .unwrap()
            .mul(&x())
            .unwrap()
            .scale(&Q::from_integer(3.into()));
        let kept = int_pow(&base, 64).unwrap();
        let s = Assumptions::default();
        assert_eq!(expand(&kept, &s).unwrap(), base.powi(64).unwrap());
        let mut parts =
            crate::normal::gcd::squarefree(x1.powi(3).unwrap().mul(&d).unwrap().num()).unwrap();
        parts.sort_by_key(|p| p.1);
        assert_eq!(parts, vec![(d.num().primitive(), 1), (x1.num().clone(), 3)]);
    }

    #[test]
    fn kept_factors_sharing_a_factor_are_compared_over_a_coprime_basis() {
        // (x^2 - a^2)^6000 = (x - a)^6000 (x + a)^6000, and not = (x - a)^6000 (x + a)^5999.
        let s = Assumptions::default();
        let (m, p) = (x().sub(&a()).unwrap(), x().add(&a()).unwrap());
        let sq = m.mul(&p).unwrap();
        let lhs = int_pow(&sq, 6000).unwrap();
        let rhs = int_pow(&m, 6000)
            .unwrap()
            .mul(&int_pow(&p, 6000).unwrap())
            .unwrap();
        assert!(settle(&lhs.sub(&rhs).unwrap(), &s).is_zero());
        let off = int_pow(&m, 6000)
            .unwrap()
            .mul(&int_pow(&p, 5999).unwrap())
            .unwrap();
        assert!(!settle(&lhs.sub(&off).unwrap(), &s).is_zero());
    }

    #[test]
    fn small_powers_and_monomials_expand_as_before() {
        let d = x().sub(&a()).unwrap();
        assert_eq!(int_pow(&d, 63).unwrap(), d.powi(63).unwrap());
        let m = x().mul(&a()).unwrap();
        assert_eq!(int_pow(&m, 1000).unwrap(), m.powi(1000).unwrap());
    }
}
