//! Roots of one base over a common index: a second look at a difference in which
//! `2^(3/4)` and `sqrt(2) 2^(1/4)`, or `sqrt(y) y^(1/4)` and `y^(3/4)` (y ≥ 0), have
//! different forms.
//!
//! The constructors keep each root as written in lowest terms (`Sqrt(2)`, `Root(2, 4)`,
//! `Root(8, 4)`), so roots of one base with different indices are different atoms.
//! [`common_index`] writes every root `root_n(b^k)` of a base `b` that occurs under two
//! or more roots as `root_L(b)^(k L/n)`, `L` the least common index, after which the
//! rules (`root_L(b)^L = b`) and the products of [`merge`](super::merge) meet. Each
//! rewrite is an identity: for `b > 0` (a positive number, or a base the declared signs
//! show nonnegative) principal roots are powers of one another, and odd roots of any
//! real base are too; even roots of a base of unknown sign are left alone (`cbrt(y)` is
//! defined for y < 0, `root_6(y)^2` is not). Used only to show a difference zero.

use super::atom::{self, Atom, AtomId};
use super::func;
use super::poly::{Poly, Q};
use super::rat::Rat;
use super::sign::{Assumptions, Sign};
use num_integer::Integer;
use num_traits::{One, Signed};

/// A root atom `root_n(b^k)`, read as a power of its base.
struct Power {
    atom: AtomId,
    base: Poly,
    k: u32,
    n: u32,
}

/// `(b, k)` with `p = b^k`, `k` as large as rigor sees: a positive integer as a perfect
/// power, a monomial by the gcd of its exponents, a sum by its squarefree parts.
fn as_power(p: &Poly) -> Option<(Poly, u32)> {
    if let Some(q) = p.as_constant() {
        if !q.is_integer() || !q.is_positive() {
            return None;
        }
        let n = q.to_integer();
        let bits = n.bits();
        for k in (2..=u32::try_from(bits).ok()?.min(64)).rev() {
            let r = n.nth_root(k);
            if num_traits::pow(r.clone(), k as usize) == n {
                return Some((Poly::constant(Q::from_integer(r)), k));
            }
        }
        return Some((p.clone(), 1));
    }
    if let [(m, c)] = p.terms() {
        if !c.is_one() {
            return None;
        }
        let k = m.pairs().iter().fold(0u32, |g, &(_, e)| g.gcd(&e));
        let pairs = m.pairs().iter().map(|&(a, e)| (a, e / k)).collect();
        let base = super::mono::Mono::from_pairs(pairs)?;
        return Some((Poly::term(base, Q::one()), k));
    }
    // A large sum is kept whole rather than decomposed on every second look.
    if p.len() > 32 {
        return Some((p.clone(), 1));
    }
    match super::gcd::squarefree(p).ok()?.as_slice() {
        [(b, k)] if b.pow(u64::from(*k)).ok().as_ref() == Some(p) => Some((b.clone(), *k)),
        _ => Some((p.clone(), 1)),
    }
}

/// The root atoms of `r` (numerator and denominator, not inside other atoms).
fn powers(r: &Rat) -> Vec<Power> {
    r.atoms()
        .into_iter()
        .filter_map(|a| {
            let (p, n) = match atom::get(a) {
                Atom::Sqrt(p) => (p.clone(), 2),
                Atom::Root(p, n) => (p.clone(), *n),
                _ => return None,
            };
            let (base, k) = as_power(&p)?;
            Some(Power {
                atom: a,
                base,
                k,
                n,
            })
        })
        .collect()
}

/// `r` with the roots of every base that occurs under two or more roots written over
/// their least common index; `None` when there is no such base (or the index would be
/// above 64).
pub fn common_index(r: &Rat, s: &Assumptions) -> Option<Rat> {
    let all = powers(r);
    if all.len() < 2 {
        return None;
    }
    let mut values: Vec<(AtomId, Rat)> = Vec::new();
    for (i, first) in all.iter().enumerate() {
        // Each base once, at its first root.
        if all[..i].iter().any(|x| x.base == first.base) {
            continue;
        }
        let group: Vec<&Power> = all[i..].iter().filter(|x| x.base == first.base).collect();
        if group.len() < 2 {
            continue;
        }
        let base = &group[0].base;
        let nonneg = match base.as_constant() {
            Some(q) => !q.is_negative(),
            None => matches!(s.poly(base), Sign::Pos | Sign::NonNeg),
        };
        let lcm = group.iter().fold(1u32, |l, x| l.lcm(&x.n));
        if lcm > 64 || !(nonneg || lcm % 2 == 1) {
            continue;
        }
        let unit = func::root(&Rat::poly(base.clone()).ok()?, lcm, s).ok()?;
        for x in group {
            let e = i64::from(x.k) * i64::from(lcm / x.n);
            values.push((x.atom, unit.powi(e).ok()?));
        }
    }
    if values.is_empty() {
        return None;
    }
    let map = |a: AtomId| values.iter().find(|v| v.0 == a).map(|v| v.1.clone());
    super::subst::Subst::new(&map, s).rat(r).ok()
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_bigint::BigInt;

    fn pow(b: &Rat, p: i64, q: i64, s: &Assumptions) -> Rat {
        let e = Rat::constant(Q::new(BigInt::from(p), BigInt::from(q)));
        func::pow(b, &e, s).unwrap()
    }

    #[test]
    fn roots_of_one_number_meet_over_their_common_index() {
        let s = Assumptions::default();
        let two = Rat::int(2);
        // 2^(3/4) against sqrt(2) 2^(1/4), and 8^(1/4) against 2^(3/4).
        let lhs = pow(&two, 3, 4, &s);
        let rhs = func::sqrt(&two, &s)
            .unwrap()
            .mul(&pow(&two, 1, 4, &s))
            .unwrap();
        let d = lhs.sub(&rhs).unwrap();
        assert!(!d.is_zero());
        assert!(common_index(&d, &s).unwrap().is_zero());
        let d = pow(&Rat::int(8), 1, 4, &s).sub(&rhs).unwrap();
        assert!(crate::normal::settle(&d, &s).is_zero());
        // A false neighbour: 2^(3/4) against sqrt(2) 2^(1/3) stays nonzero.
        let wrong = func::sqrt(&two, &s)
            .unwrap()
            .mul(&pow(&two, 1, 3, &s))
            .unwrap();
        assert!(!common_index(&lhs.sub(&wrong).unwrap(), &s)
            .unwrap()
            .is_zero());
    }

    #[test]
    fn even_roots_of_a_base_of_unknown_sign_are_left_alone() {
        let y = Rat::atom(atom::sym("y"));
        let free = Assumptions::default();
        // cbrt(y) against root_6(y)^2: equal for y ≥ 0 only.
        let d = pow(&y, 1, 3, &free).sub(&pow(&y, 2, 6, &free)).unwrap();
        assert!(common_index(&d, &free).is_none_or(|r| !r.is_zero()));
        // sqrt(y) y^(1/4) = y^(3/4) where the signs show y ≥ 0.
        let mut nonneg = Assumptions::default();
        nonneg.set(atom::sym("y"), Sign::NonNeg);
        let lhs = func::sqrt(&y, &nonneg)
            .unwrap()
            .mul(&pow(&y, 1, 4, &nonneg))
            .unwrap();
        let d = lhs.sub(&pow(&y, 3, 4, &nonneg)).unwrap();
        assert!(crate::normal::settle(&d, &nonneg).is_zero());
        // Odd roots of any sign: cbrt(y) root_9(y) = root_9(y)^4.
        let lhs = pow(&y, 1, 3, &free).mul(&pow(&y, 1, 9, &free)).unwrap();
        let d = lhs.sub(&pow(&y, 4, 9, &free)).unwrap();
        assert!(crate::normal::settle(&d, &free).is_zero());
    }
}
