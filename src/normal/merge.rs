//! A second normal form for products of absolute values and roots.
//!
//! The constructors split `abs` and roots over what they can see (squarefree parts,
//! signed symbols), but they cannot factor: `abs(x^2 - 4)` is one atom, `abs(x - 2)
//! abs(x + 2)` two. [`merged`] multiplies, in every term, the `abs` atoms into one and
//! the roots of one index into one, and rebuilds each product with its constructor, so
//! both become `abs(x^2 - 4)`. Each merge is an identity wherever both sides are defined
//! (`abs(p) abs(q) = abs(p q)` everywhere; `sqrt(p) sqrt(q) = sqrt(p q)` where
//! `p, q ≥ 0`), which is how the rules of [`reduce`](super::reduce) hold too. The checker
//! uses it only to show a difference zero.

use super::atom::{self, Atom, AtomId};
use super::func;
use super::mono::Mono;
use super::poly::Poly;
use super::rat::Rat;
use super::sign::Assumptions;
use super::NormError;
use num_traits::One;
use std::collections::BTreeMap;

/// `r` with, in each term, the `abs` atoms merged into one and the roots of each index
/// merged into one; `None` when no term has two to merge (or a product is refused).
pub fn merged(r: &Rat, s: &Assumptions) -> Option<Rat> {
    let (num, a) = merged_poly(r.num(), s).ok()?;
    let (den, b) = merged_poly(r.den(), s).ok()?;
    if !(a || b) {
        return None;
    }
    num.div(&den).ok()
}

/// How a term's atom takes part in a merge.
enum Part {
    /// `abs(p)^e`: all of a term's merge into one `abs`.
    Abs(Poly),
    /// `root_n(p)^e` with `p ≥ 0` by the declared signs (or a number): all of a term's
    /// merge into one root of the least common index.
    Nonneg(u32, Poly, u32),
    /// `root_n(p)^e`, `n` odd, `p` of unknown sign: odd roots of one index merge (they
    /// are multiplicative for every sign), but not with even roots.
    Odd(u32, Poly, u32),
}

fn part(a: AtomId, e: u32, s: &Assumptions) -> Option<Part> {
    let (p, n) = match atom::get(a) {
        Atom::Abs(p) => return Some(Part::Abs(p.pow(u64::from(e)).ok()?)),
        Atom::Sqrt(p) => (p.clone(), 2),
        Atom::Root(p, n) => (p.clone(), *n),
        _ => return None,
    };
    // Only what the signs show nonnegative: `sqrt(x) sqrt(y) = sqrt(x y)` where both
    // sides are defined, but the right side is defined for x, y < 0 too, so merging
    // roots of unknown sign would verify a step that is false there.
    let nonneg = matches!(s.poly(&p), super::Sign::Pos | super::Sign::NonNeg)
        || number_sign(&p).is_some_and(|x| !num_traits::Signed::is_negative(&x));
    if nonneg {
        Some(Part::Nonneg(n, p, e))
    } else if n % 2 == 1 {
        Some(Part::Odd(n, p, e))
    } else {
        None
    }
}

/// The sign of a number `a + b·sqrt(c)` (`c` a positive integer), as ±1 or 0: `a + b√c`
/// has the sign of `a` when `a² > b²c`, else of `b` (the radicands of `cos(π/8)`).
fn number_sign(p: &Poly) -> Option<super::Q> {
    use num_traits::{Signed, Zero};
    let (mut a, mut b, mut c) = (super::Q::zero(), super::Q::zero(), None);
    for (m, q) in p.terms() {
        match m.pairs() {
            [] => a = q.clone(),
            [(x, 1)] => match atom::get(*x) {
                Atom::Sqrt(r) if c.is_none() => {
                    c = Some(r.as_constant().filter(|v| v.is_positive())?);
                    b = q.clone();
                }
                _ => return None,
            },
            _ => return None,
        }
    }
    let c = c.unwrap_or_else(super::Q::zero);
    let signum = |q: &super::Q| q.signum();
    let (aa, bb) = (&a * &a, &b * &b * &c);
    Some(if aa > bb {
        signum(&a)
    } else if bb > aa {
        signum(&b)
    } else if signum(&a) == signum(&b) {
        signum(&a)
    } else {
        super::Q::zero()
    })
}

fn merged_poly(p: &Poly, s: &Assumptions) -> Result<(Rat, bool), NormError> {
    use num_integer::Integer;
    let mut total = Rat::zero();
    let mut any = false;
    for (m, q) in p.terms() {
        let mut abs = (Poly::one(), 0usize);
        let mut nonneg: Vec<(u32, Poly, u32)> = Vec::new();
        let mut odd: BTreeMap<u32, (Poly, usize)> = BTreeMap::new();
        let mut rest = Vec::new();
        for &(a, e) in m.pairs() {
            match part(a, e, s) {
                Some(Part::Abs(v)) => {
                    abs.0 = abs.0.mul(&v)?;
                    abs.1 += 1;
                }
                Some(Part::Nonneg(n, p, e)) => nonneg.push((n, p, e)),
                Some(Part::Odd(n, p, e)) => {
                    let g = odd.entry(n).or_insert((Poly::one(), 0));
                    g.0 = g.0.mul(&p.pow(u64::from(e))?)?;
                    g.1 += 1;
                }
                None => rest.push((a, e)),
            }
        }
        let rest = Mono::from_pairs(rest).ok_or(super::Limit::Exponent)?;
        let mut term = Rat::poly(Poly::term(rest, q.clone()))?;
        if abs.1 > 0 {
            any |= abs.1 >= 2;
            term = term.mul(&func::abs(&Rat::poly(abs.0)?, s)?)?;
        }
        let lcm = nonneg.iter().fold(1u32, |l, x| l.lcm(&x.0));
        if nonneg.len() >= 2 && lcm <= 64 {
            // ∏ root_nᵢ(pᵢ)^eᵢ = root_L(∏ pᵢ^(eᵢ L/nᵢ)), every pᵢ ≥ 0.
            any = true;
            let mut radicand = Poly::one();
            for (n, p, e) in &nonneg {
                radicand = radicand.mul(&p.pow(u64::from(*e) * u64::from(lcm / n))?)?;
            }
            term = term.mul(&func::root(&Rat::poly(radicand)?, lcm, s)?)?;
        } else {
            for (n, p, e) in nonneg {
                term = term.mul(&func::root(&Rat::poly(p)?, n, s)?.powi(i64::from(e))?)?;
            }
        }
        for (n, (v, count)) in odd {
            any |= count >= 2;
            term = term.mul(&func::root(&Rat::poly(v)?, n, s)?)?;
        }
        total = total.add(&term)?;
    }
    Ok((total, any))
}

/// `r`'s numerator with the logarithms that share a cofactor merged: `Σ qₖ ln(uₖ) · M`
/// is `ln(∏ uₖ^(D qₖ)) · M / D` (every `uₖ > 0` wherever `ln(uₖ)` is defined), rebuilt by
/// `ln`, so `ln(a + 1) + ln(a + 5c)` meets `ln(a² + 5ac + a + 5c)`. The numerator alone
/// decides whether a difference is zero. `None` when nothing merges.
pub fn merged_logs(r: &Rat, s: &Assumptions) -> Option<Rat> {
    merged_logs_with(r, s, &|us: &[&Rat]| {
        us.iter().all(|u| s.rat(u) == super::Sign::Pos)
    })
}

/// [`merged_logs`] with `may_merge` saying which logarithms (by their arguments) may be
/// merged: those the signs show positive (as there), or, for a caller that states where
/// the sides are defined, arguments positive on one and the same set (`ln(1/x) + ln(x)`
/// is `ln(1) = 0` wherever both are defined, that is for x > 0).
pub fn merged_logs_with(
    r: &Rat,
    s: &Assumptions,
    may_merge: &dyn Fn(&[&Rat]) -> bool,
) -> Option<Rat> {
    use num_integer::Integer;
    use num_traits::ToPrimitive;
    // By cofactor (the term's monomial without its logarithm): each term with its `ln`'s
    // argument.
    type Logs = Vec<(Mono, super::Q, Rat)>;
    let mut groups: BTreeMap<Vec<(AtomId, u32)>, Logs> = BTreeMap::new();
    let mut others = Vec::new();
    for (m, q) in r.num().terms() {
        let lns: Vec<(AtomId, u32, Rat)> = m
            .pairs()
            .iter()
            .filter_map(|&(a, e)| match atom::get(a) {
                Atom::Ln(u) => Some((a, e, u.clone())),
                _ => None,
            })
            .collect();
        match lns.as_slice() {
            [(a, 1, u)] => {
                let key: Vec<(AtomId, u32)> =
                    m.pairs().iter().filter(|p| p.0 != *a).copied().collect();
                groups
                    .entry(key)
                    .or_default()
                    .push((m.clone(), q.clone(), u.clone()));
            }
            _ => others.push((m.clone(), q.clone())),
        }
    }
    let mut merged = Vec::new();
    for (key, items) in groups {
        // ln(u) + ln(v) = ln(u v) only where u, v > 0: the signs must show it (as for
        // roots, the right side is defined for u, v < 0 too). Otherwise the terms stay.
        let args: Vec<&Rat> = items.iter().map(|(_, _, u)| u).collect();
        let merge = items.len() >= 2 && may_merge(&args);
        if !merge {
            others.extend(items.into_iter().map(|(m, q, _)| (m, q)));
            continue;
        }
        let den = items
            .iter()
            .fold(num_bigint::BigInt::from(1), |d, (_, q, _)| d.lcm(q.denom()));
        let mut product = Rat::one();
        for (_, q, u) in &items {
            let k = (q * super::Q::from_integer(den.clone())).to_integer();
            let k = k.to_i64().filter(|k| k.abs() <= 64)?;
            product = product.mul(&u.powi(k).ok()?).ok()?;
        }
        let cofactor = Rat::poly(Poly::term(Mono::from_pairs(key)?, super::Q::one())).ok()?;
        let scale = super::Q::new(num_bigint::BigInt::from(1), den);
        merged.push(
            func::ln(&product, s)
                .ok()?
                .mul(&cofactor)
                .ok()?
                .scale(&scale),
        );
    }
    if merged.is_empty() {
        return None;
    }
    let mut total = Rat::poly(Poly::from_terms(others)).ok()?;
    for m in &merged {
        total = total.add(m).ok()?;
    }
    Some(total)
}

/// The one quantity `p` with `u > 0` exactly where `p > 0`, when `u` is, up to factors
/// the signs show positive and a constant, one factor of unknown sign to an odd power
/// (`1/x` and `x` give `x`, `sqrt(x)` gives `x`, `-(a + 1)` gives `-a - 1`); `None` for
/// anything else (`x y`, `x^2`, `abs(x)`). Two logarithms whose arguments give the same
/// `p` are defined on the same set.
pub fn positive_where(u: &Rat, s: &Assumptions) -> Option<Poly> {
    use num_traits::Signed;
    let mut found: Option<Poly> = None;
    let mut negative = false;
    let take = |f: Poly, found: &mut Option<Poly>| -> Option<()> {
        match found {
            Some(_) => None,
            None => {
                *found = Some(f);
                Some(())
            }
        }
    };
    for p in [u.num(), u.den()] {
        if p.is_one() {
            continue;
        }
        // The content is positive: the sign stays with the terms.
        let prim = p.scale(&p.content().recip());
        let mc = prim.mono_content();
        let mut rest = prim.div_mono(&mc).unwrap_or(prim.clone());
        for &(a, e) in mc.pairs() {
            if s.atom(a) == super::Sign::Pos {
                continue;
            }
            if e % 2 == 0 {
                return None;
            }
            let f = match atom::get(a) {
                Atom::Sqrt(q) | Atom::Root(q, _) => q.clone(),
                Atom::Abs(_) => return None,
                _ => Poly::atom(a),
            };
            take(f, &mut found)?;
        }
        if rest.is_one() || s.poly(&rest) == super::Sign::Pos {
            continue;
        }
        if rest.lead().is_some_and(|t| t.1.is_negative()) {
            negative = !negative;
            rest = rest.neg();
        }
        if rest.is_one() {
            continue;
        }
        match super::gcd::squarefree(&rest).ok()?.as_slice() {
            [(f, 1)] => take(f.clone(), &mut found)?,
            _ => return None,
        }
    }
    let f = found?;
    Some(if negative { f.neg() } else { f })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sym(n: &str) -> Rat {
        Rat::atom(atom::sym(n))
    }

    #[test]
    fn products_of_abs_and_of_roots_merge_into_one() {
        let s = Assumptions::default();
        let x = sym("x");
        let two = Rat::int(2);
        let (m, p) = (x.sub(&two).unwrap(), x.add(&two).unwrap());
        let lhs = func::abs(&m.mul(&p).unwrap(), &s).unwrap();
        let rhs = func::abs(&m, &s)
            .unwrap()
            .mul(&func::abs(&p, &s).unwrap())
            .unwrap();
        assert_ne!(lhs, rhs);
        let d = lhs.sub(&rhs).unwrap();
        assert!(merged(&d, &s).unwrap().is_zero());
        // sqrt(x^2 + 1) sqrt(x^2 + 2) against sqrt((x^2 + 1)(x^2 + 2)).
        let (a, b) = (
            x.powi(2).unwrap().add(&Rat::one()).unwrap(),
            x.powi(2).unwrap().add(&two).unwrap(),
        );
        let lhs = func::sqrt(&a.mul(&b).unwrap(), &s).unwrap();
        let rhs = func::sqrt(&a, &s)
            .unwrap()
            .mul(&func::sqrt(&b, &s).unwrap())
            .unwrap();
        assert!(merged(&lhs.sub(&rhs).unwrap(), &s).unwrap().is_zero());
        // A false neighbour stays nonzero: abs(x - 2) abs(x + 3).
        let q = x.add(&Rat::int(3)).unwrap();
        let wrong = func::abs(&m, &s)
            .unwrap()
            .mul(&func::abs(&q, &s).unwrap())
            .unwrap();
        let d = func::abs(&m.mul(&p).unwrap(), &s)
            .unwrap()
            .sub(&wrong)
            .unwrap();
        assert!(!merged(&d, &s).unwrap().is_zero());
    }
}
