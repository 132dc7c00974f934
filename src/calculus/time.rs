//! Calculus over the time variable `t`: `time` symbols are functions of `t`, never
//! constants. A time symbol at an instant (`subs(x', t, T)`) is the atom `x'(T)`.

use super::integrate::{antiderivative, IntError};
use crate::normal::atom::{self, Atom, AtomId};
use crate::normal::mono::Mono;
use crate::normal::print::plain;
use crate::normal::subst::{atom_depends_on, Subst};
use crate::normal::{Assumptions, NormError, Poly, Rat, Q};
use num_bigint::BigInt;

/// An atom and its exponent in a monomial.
type Factor = (AtomId, u32);

/// Whether atom `a` is a `time` symbol (or a derivative of one) or contains one.
fn time_dependent(a: AtomId, is_time: &dyn Fn(&str) -> bool) -> bool {
    match atom::get(a) {
        Atom::Sym(n) => is_time(n.trim_end_matches('\'')),
        _ => {
            let mut found = false;
            for b in crate::normal::subst::atoms_within(a) {
                if let Atom::Sym(n) = atom::get(b) {
                    found |= is_time(n.trim_end_matches('\''));
                }
            }
            found
        }
    }
}

/// `r` at the instant `v`: the time variable `t` becomes `v` and every `time` symbol
/// `x'` becomes `x'(v)`.
pub fn at_instant(
    r: &Rat,
    t: AtomId,
    v: &Rat,
    is_time: &dyn Fn(&str) -> bool,
    s: &Assumptions,
) -> Result<Rat, NormError> {
    let map = |a: AtomId| -> Option<Rat> {
        if a == t {
            return Some(v.clone());
        }
        match atom::get(a) {
            Atom::Sym(n) if is_time(n.trim_end_matches('\'')) => Some(Rat::atom(atom::at(n, v))),
            _ => None,
        }
    };
    Subst::new(&map, s).rat(r)
}

/// `∫ f dt` with constant of integration 0, where `time` symbols depend on `t`: terms
/// free of them are integrated as usual; `c·x^(k+1)` gives `c·x^(k)` and
/// `c·(x^(k))^n·x^(k+1)` gives `c·(x^(k))^(n+1)/(n+1)` for `c` free of `t`; anything
/// else is refused (never integrated as if it were constant).
pub fn time_antiderivative(
    f: &Rat,
    t: AtomId,
    is_time: &dyn Fn(&str) -> bool,
    s: &Assumptions,
) -> Result<Rat, IntError> {
    let dep = |a: AtomId| time_dependent(a, is_time);
    if !f.atoms().iter().any(|a| dep(*a)) {
        return antiderivative(f, t, s);
    }
    if f.den()
        .atoms()
        .iter()
        .any(|a| dep(*a) || atom_depends_on(*a, t))
    {
        return Err(IntError::Time(format!(
            "rigor has no antiderivative over t for {}: its denominator depends on time",
            plain(f)
        )));
    }
    let den = Rat::poly(f.den().clone())?;
    let mut total = Rat::zero();
    for (m, q) in f.num().terms() {
        let term = Rat::poly(Poly::term(m.clone(), q.clone()))?;
        let (timed, rest): (Vec<Factor>, Vec<Factor>) =
            m.pairs().iter().partition(|(a, _)| dep(*a));
        if timed.is_empty() {
            total = total.add(&antiderivative(&term, t, s)?)?;
            continue;
        }
        let refuse = || {
            IntError::Time(format!(
                "rigor has no antiderivative over t for the term {}",
                plain(&term)
            ))
        };
        if rest.iter().any(|(a, _)| atom_depends_on(*a, t)) {
            return Err(refuse());
        }
        let prim = primitive_of(&timed).ok_or_else(refuse)?;
        let coeff = Rat::poly(Poly::term(
            Mono::from_pairs(rest).ok_or(crate::normal::Limit::Exponent)?,
            q.clone(),
        ))?;
        total = total.add(&coeff.mul(&prim)?)?;
    }
    Ok(total.div(&den)?)
}

/// The antiderivative of a product of time symbols of the form `x^(k+1)` or
/// `(x^(k))^n · x^(k+1)` (one symbol, consecutive derivatives).
fn primitive_of(timed: &[(AtomId, u32)]) -> Option<Rat> {
    let name = |a: AtomId| match atom::get(a) {
        Atom::Sym(n) => Some(n.clone()),
        _ => None,
    };
    let lower = |n: &str| n.strip_suffix('\'').map(str::to_string);
    match timed {
        [(a, 1)] => Some(Rat::atom(atom::sym(&lower(&name(*a)?)?))),
        [(a, ea), (b, eb)] => {
            let (na, nb) = (name(*a)?, name(*b)?);
            let (low, n) = if *eb == 1 && lower(&nb).as_deref() == Some(na.as_str()) {
                (a, *ea)
            } else if *ea == 1 && lower(&na).as_deref() == Some(nb.as_str()) {
                (b, *eb)
            } else {
                return None;
            };
            let p = Rat::atom(*low).powi(i64::from(n) + 1).ok()?;
            Some(p.scale(&Q::new(BigInt::from(1), BigInt::from(u64::from(n) + 1))))
        }
        _ => None,
    }
}
