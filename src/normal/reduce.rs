//! The atoms' rewrite rules applied to polynomials, and rationalising denominators.
//!
//! Rules: `sqrt(p)² = p`, `root(p, n)ⁿ = p`, `abs(p)² = p²`, `cos(u)² = 1 − sin(u)²`,
//! and `exp(u)·exp(v) = exp(u + v)`. Each is an identity wherever both sides are
//! defined, so reducing never changes a value.

use super::atom::{self, Atom, AtomId, Rule};
use super::mono::Mono;
use super::poly::{Poly, Q};
use super::rat::Rat;
use super::{Limit, NormError};
use num_traits::One;

/// The value `a^n` reduces to for an atom with rule `Power(n)`.
fn power_value(a: AtomId) -> Option<Poly> {
    match atom::get(a) {
        Atom::Sqrt(p) | Atom::Root(p, _) => Some(p.clone()),
        Atom::Abs(p) => p.mul(p).ok(),
        Atom::Cos(u) => {
            let s = atom::intern(Atom::Sin(u.clone()));
            Some(Poly::one().sub(&Poly::term(Mono::atom(s, 2), Q::one())))
        }
        _ => None,
    }
}

/// Applies the rules until none applies.
pub fn reduce(p: &Poly) -> Result<Poly, NormError> {
    let mut cur = p.clone();
    for _ in 0..64 {
        match reduce_once(&cur)? {
            None => return Ok(cur),
            Some(next) => cur = next,
        }
    }
    Err(NormError::Limit(Limit::terms()))
}

/// One pass; `None` when nothing applied.
fn reduce_once(p: &Poly) -> Result<Option<Poly>, NormError> {
    let ids = p.atoms();
    if ids.is_empty() {
        return Ok(None);
    }
    let rules = atom::rules(&ids);
    if rules.iter().all(|r| *r == Rule::Free) {
        return Ok(None);
    }
    let rule_of = |a: AtomId| match ids.binary_search(&a) {
        Ok(i) => rules.get(i).copied().unwrap_or(Rule::Free),
        Err(_) => Rule::Free,
    };
    let needs = |m: &Mono| {
        let mut exps = 0u32;
        for &(a, e) in m.pairs() {
            match rule_of(a) {
                Rule::Power(n) if e >= n => return true,
                Rule::Exp => {
                    exps += e;
                    if exps >= 2 {
                        return true;
                    }
                }
                _ => {}
            }
        }
        false
    };
    if !p.terms().iter().any(|(m, _)| needs(m)) {
        return Ok(None);
    }
    let mut out = Poly::zero();
    let mut keep = Vec::new();
    for (m, q) in p.terms() {
        if !needs(m) {
            keep.push((m.clone(), q.clone()));
            continue;
        }
        let mut rest = Vec::new();
        let mut factor = Poly::constant(q.clone());
        let mut exp_arg: Option<Rat> = None;
        for &(a, e) in m.pairs() {
            match rule_of(a) {
                Rule::Power(n) if e >= n => {
                    let v = power_value(a).ok_or(NormError::Limit(Limit::terms()))?;
                    factor = factor.mul(&v.pow(u64::from(e / n))?)?;
                    if e % n > 0 {
                        rest.push((a, e % n));
                    }
                }
                Rule::Exp => {
                    if let Atom::Exp(u) = atom::get(a) {
                        let term = u.scale(&Q::from_integer(e.into()));
                        exp_arg = Some(match exp_arg {
                            None => term,
                            Some(acc) => acc.add(&term)?,
                        });
                    }
                }
                _ => rest.push((a, e)),
            }
        }
        if let Some(u) = exp_arg {
            if !u.is_zero() {
                rest.push((atom::intern(Atom::Exp(u)), 1));
            }
        }
        let rest = Mono::from_pairs(rest).ok_or(Limit::Exponent)?;
        out = out.add(&factor.mul_term(&rest, &Q::one())?);
    }
    Ok(Some(out.add(&Poly::from_terms(keep))))
}

/// Removes square roots from the denominator by multiplying with conjugates
/// (deepest radical first), and moves exponential factors into the numerator.
pub fn rationalise(num: Poly, den: Poly) -> Result<(Poly, Poly), NormError> {
    let (mut num, mut den) = move_exps(num, den)?;
    for _ in 0..32 {
        let ids = den.atoms();
        let radical = ids
            .iter()
            .copied()
            .filter(|a| matches!(atom::get(*a), Atom::Sqrt(_)))
            .max_by_key(|a| (atom::depth(*a), *a));
        let Some(s) = radical else {
            break;
        };
        // den = d0 + d1·s with s of degree ≤ 1 after reduction; conj = d0 − d1·s.
        let coeffs = den.coeffs_in(s);
        let mut conj = Poly::zero();
        for (e, c) in &coeffs {
            let t = c.mul_term(&Mono::atom(s, *e), &Q::one())?;
            conj = if e % 2 == 1 {
                conj.sub(&t)
            } else {
                conj.add(&t)
            };
        }
        let new_den = reduce(&den.mul(&conj)?)?;
        if new_den.is_zero() || new_den.contains(s) {
            // A zero divisor (the radicand is a square rigor did not see): leave it.
            break;
        }
        num = reduce(&num.mul(&conj)?)?;
        den = new_den;
    }
    Ok((num, den))
}

/// Moves a common factor `exp(u)^k` of the denominator to the numerator as `exp(−k·u)`.
fn move_exps(num: Poly, den: Poly) -> Result<(Poly, Poly), NormError> {
    let mc = den.mono_content();
    let mut moved = Vec::new();
    let mut arg: Option<Rat> = None;
    for &(a, e) in mc.pairs() {
        if let Atom::Exp(u) = atom::get(a) {
            moved.push((a, e));
            let t = u.scale(&-Q::from_integer(e.into()));
            arg = Some(match arg {
                None => t,
                Some(acc) => acc.add(&t)?,
            });
        }
    }
    let Some(arg) = arg else {
        return Ok((num, den));
    };
    let m = Mono::from_pairs(moved).ok_or(Limit::Exponent)?;
    let den = den.div_mono(&m).unwrap_or(den);
    let num = if arg.is_zero() {
        num
    } else {
        let e = atom::intern(Atom::Exp(arg));
        reduce(&num.mul_term(&Mono::atom(e, 1), &Q::one())?)?
    };
    Ok((num, den))
}
