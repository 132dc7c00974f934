//! A normal form written as a person writes its radicals, for reading only.
//!
//! The normal form keeps every square root of one factor apart, so that `sqrt(g)^2`
//! reduces to `g`; a result then reads `sqrt(6) sqrt(L) sqrt(g)/(2 L)`. A person writes
//! `sqrt(3 g/(2 L))`. [`radicals`] prints:
//!
//! - the square roots of each term as one root: `sqrt(a) sqrt(b) = sqrt(a b)` holds
//!   wherever both roots are real, which is wherever the term is defined;
//! - a quotient whose numerator is one term with a root, over a denominator that is
//!   not a number alone and that the declared signs make positive, with the
//!   denominator and the numerator's fraction moved under the root:
//!   `sqrt(S)/D = sqrt(S/D^2)` for `D > 0`.
//!
//! The text means the same value wherever the normal form is defined, but it does not
//! always read back to the same normal form (with no signs declared, `sqrt(g h)` stays
//! one root while `sqrt(g) sqrt(h)` is two), so nothing that is read back — `rigor
//! simplify`'s answer, the checker's own notes — is printed this way. Worked solutions
//! print their values with it.

use super::atom::{get, intern, Atom, AtomId};
use super::mono::Mono;
use super::poly::{Poly, Q};
use super::print::plain;
use super::rat::Rat;
use super::sign::Assumptions;
use num_traits::{One, Signed};

/// `r` in rigor's plain syntax with its square roots written as a person writes them
/// (see the module's documentation); `signs` says which denominators are positive.
pub fn radicals(r: &Rat, signs: &Assumptions) -> String {
    if !has_square_root(r) {
        return plain(r);
    }
    if let Some(text) = one_root(r, signs) {
        return text;
    }
    match merged(r) {
        Some(m) => plain(&m),
        None => plain(r),
    }
}

/// Whether any term of `r` has a square root factor.
fn has_square_root(r: &Rat) -> bool {
    [r.num(), r.den()].iter().any(|p| {
        p.terms()
            .iter()
            .any(|(m, _)| m.pairs().iter().any(|(a, _)| radicand(*a).is_some()))
    })
}

/// The radicand of a square root atom.
fn radicand(a: AtomId) -> Option<Poly> {
    match get(a) {
        Atom::Sqrt(p) => Some(p.clone()),
        _ => None,
    }
}

/// One term split into the product of its square roots' radicands and the rest.
fn split_term(m: &Mono) -> Option<(Poly, Mono)> {
    let mut under = Poly::one();
    let mut rest = Vec::new();
    for &(a, e) in m.pairs() {
        match radicand(a) {
            Some(p) if e == 1 => under = under.mul(&p).ok()?,
            _ => rest.push((a, e)),
        }
    }
    Some((under, Mono::from_pairs(rest).unwrap_or_else(Mono::one)))
}

/// `r` with the roots of each term merged into one root (an atom made for printing).
fn merged(r: &Rat) -> Option<Rat> {
    let term = |p: &Poly| -> Option<Poly> {
        let mut terms = Vec::with_capacity(p.len());
        for (m, q) in p.terms() {
            let (under, rest) = split_term(m)?;
            let m = if under.is_one() {
                m.clone()
            } else {
                rest.mul(&Mono::atom(intern(Atom::Sqrt(under)), 1))?
            };
            terms.push((m, q.clone()));
        }
        Some(Poly::from_terms(terms))
    };
    Rat::new(term(r.num())?, term(r.den())?).ok()
}

/// `k sqrt(S/D^2)` for `r = k sqrt(S)/D` (one term over a positive denominator free of
/// roots), with `k` an integer times the term's other factors.
fn one_root(r: &Rat, signs: &Assumptions) -> Option<String> {
    let [(m, q)] = r.num().terms() else {
        return None;
    };
    let (under, rest) = split_term(m)?;
    let den = r.den();
    if under.is_one() || has_square_root(&Rat::poly(den.clone()).ok()?) {
        return None;
    }
    // A number alone stays outside (`sqrt(3) L/3`, not `L sqrt(1/3)`).
    if den.as_constant().is_some() || !signs.poly(den).is_nonneg() {
        return None;
    }
    // k = n/d · rest; d goes under the root with the denominator.
    let (n, d) = (Q::from_integer(q.numer().clone()), q.denom().clone());
    let outside_den = den.scale(&Q::from_integer(d));
    let square = outside_den.mul(&outside_den).ok()?;
    let inner = Rat::new(under, square).ok()?;
    let outside = Rat::poly(Poly::term(rest, n.clone())).ok()?;
    let root = format!("sqrt({})", plain(&inner));
    Some(if outside.as_constant().is_some_and(|c| c.is_one()) {
        root
    } else if outside.as_constant().is_some_and(|c| (-c).is_one()) {
        format!("-{root}")
    } else if n.is_negative() && outside.num().len() == 1 {
        format!("-{} {root}", plain(&outside.neg()))
    } else {
        format!("{} {root}", plain(&outside))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::normal::sign::Sign;

    fn sym(name: &str) -> Rat {
        Rat::atom(crate::normal::atom::sym(name))
    }

    fn root(p: Rat) -> Rat {
        Rat::atom(intern(Atom::Sqrt(
            p.as_poly().expect("a polynomial").clone(),
        )))
    }

    fn positive(names: &[&str]) -> Assumptions {
        let mut a = Assumptions::new();
        for n in names {
            a.set(crate::normal::atom::sym(n), Sign::Pos);
        }
        a
    }

    #[test]
    fn roots_of_a_quotient_over_a_positive_denominator_become_one_root() {
        // sqrt(6) sqrt(L) sqrt(g)/(2 L)
        let num = root(Rat::int(6))
            .mul(&root(sym("L")))
            .and_then(|x| x.mul(&root(sym("g"))))
            .unwrap();
        let r = num
            .div(&sym("L").scale(&Q::from_integer(2.into())))
            .unwrap();
        assert_eq!(plain(&r), "sqrt(6) sqrt(L) sqrt(g)/(2 L)");
        assert_eq!(radicals(&r, &positive(&["g", "L"])), "sqrt(3 g/(2 L))");
        // With the sign of L unknown, the denominator stays outside.
        assert_eq!(radicals(&r, &positive(&["g"])), "sqrt(6 g L)/(2 L)");
    }

    #[test]
    fn other_factors_and_signs_stay_outside() {
        // -2 pi sqrt(d) sqrt(g)/(d g) = -2 pi sqrt(1/(d g))
        let pi = Rat::atom(intern(Atom::Pi));
        let num = pi
            .scale(&Q::from_integer((-2).into()))
            .mul(&root(sym("d")))
            .and_then(|x| x.mul(&root(sym("g"))))
            .unwrap();
        let r = num.div(&sym("d").mul(&sym("g")).unwrap()).unwrap();
        assert_eq!(radicals(&r, &positive(&["d", "g"])), "-2 pi sqrt(1/(d g))");
    }

    #[test]
    fn sums_merge_term_by_term() {
        // sqrt(2) sqrt(g) sqrt(h) + v
        let r = root(Rat::int(2))
            .mul(&root(sym("g")))
            .and_then(|x| x.mul(&root(sym("h"))))
            .and_then(|x| x.add(&sym("v")))
            .unwrap();
        assert_eq!(radicals(&r, &Assumptions::new()), "v + sqrt(2 g h)");
    }

    #[test]
    fn a_number_alone_stays_under_the_fraction() {
        // sqrt(3) L/3
        let r = root(Rat::int(3))
            .mul(&sym("L"))
            .unwrap()
            .scale(&Q::new(1.into(), 3.into()));
        assert_eq!(radicals(&r, &positive(&["L"])), "sqrt(3) L/3");
    }

    #[test]
    fn no_root_prints_as_the_normal_form() {
        let r = sym("g").div(&sym("L")).unwrap();
        assert_eq!(radicals(&r, &positive(&["g", "L"])), plain(&r));
    }
}
