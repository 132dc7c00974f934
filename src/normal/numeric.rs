//! Signs of constants (no symbols: numbers, `pi`, nested roots, functions of them) by
//! rigorous interval arithmetic, where the signs of the terms alone do not decide
//! (`sqrt(2) - 1`, `1 + sqrt(1 + sqrt(3)) - sqrt(5)`).
//!
//! A sign is given only when an enclosure excludes zero, at 96 bits and then at 320: a
//! constant that is exactly zero (one the rules did not reduce) never gets one. This is
//! how `sqrt((1 + sqrt(1 + sqrt(3)))^2)` comes out as `1 + sqrt(1 + sqrt(3))`, and how the
//! radicands of nested roots are known to be positive.

use super::atom::{self, Atom, AtomId};
use super::poly::Poly;
use super::rat::Rat;
use super::sign::Sign;
use crate::interval::{Interval, Prec};
use foldhash::{HashMap, HashMapExt};
use num_traits::ToPrimitive;

/// Atoms deeper than this are not evaluated (every level of nesting costs a root).
const MAX_DEPTH: u32 = 8;

/// Terms beyond which a constant is not evaluated.
const MAX_TERMS: usize = 64;

/// The sign of `p` when it is a constant whose enclosure excludes zero.
pub fn sign(p: &Poly) -> Option<Sign> {
    // Symbols are the common case: leave at the first one, without collecting atoms.
    let constant = p
        .terms()
        .iter()
        .all(|(m, _)| m.pairs().iter().all(|&(a, _)| constant_atom(a)));
    if p.len() > MAX_TERMS || !constant {
        return None;
    }
    for bits in [96, 320] {
        let mut e = Enclosure {
            prec: Prec { bits },
            memo: HashMap::new(),
        };
        let v = e.poly(p)?;
        if v.is_positive() {
            return Some(Sign::Pos);
        }
        if v.is_negative() {
            return Some(Sign::Neg);
        }
    }
    None
}

/// Whether `a` holds no symbol, at a depth rigor evaluates.
fn constant_atom(a: AtomId) -> bool {
    if atom::depth(a) > MAX_DEPTH {
        return false;
    }
    let rat = |r: &Rat| {
        r.num().atoms().into_iter().all(constant_atom)
            && r.den().atoms().into_iter().all(constant_atom)
    };
    match atom::get(a) {
        Atom::Pi => true,
        Atom::Sqrt(p) | Atom::Root(p, _) | Atom::Abs(p) => p.atoms().into_iter().all(constant_atom),
        Atom::Sin(u) | Atom::Cos(u) | Atom::Exp(u) | Atom::Ln(u) => rat(u),
        _ => false,
    }
}

struct Enclosure {
    prec: Prec,
    memo: HashMap<AtomId, Option<Interval>>,
}

impl Enclosure {
    fn poly(&mut self, p: &Poly) -> Option<Interval> {
        let mut total = Interval::point(num_traits::Zero::zero());
        for (m, q) in p.terms() {
            let mut t = Interval::point(q.clone());
            for &(a, e) in m.pairs() {
                let v = self.atom(a)?;
                t = t.mul(&v.powi(i64::from(e), self.prec)?, self.prec)?;
            }
            total = total.add(&t, self.prec)?;
        }
        Some(total)
    }

    fn rat(&mut self, r: &Rat) -> Option<Interval> {
        let n = self.poly(r.num())?;
        if r.den().is_one() {
            return Some(n);
        }
        n.div(&self.poly(r.den())?, self.prec)
    }

    fn atom(&mut self, a: AtomId) -> Option<Interval> {
        if let Some(v) = self.memo.get(&a) {
            return v.clone();
        }
        let p = self.prec;
        let v = match atom::get(a) {
            Atom::Pi => Interval::pi(p),
            Atom::Sqrt(x) => self.poly(x)?.sqrt(p),
            Atom::Root(x, n) => self.poly(x)?.real_root(*n, p),
            Atom::Abs(x) => self.poly(x)?.abs(),
            Atom::Sin(u) => self.rat(u)?.sin(p),
            Atom::Cos(u) => self.rat(u)?.cos(p),
            Atom::Exp(u) => self.rat(u)?.exp(p),
            Atom::Ln(u) => self.rat(u)?.ln(p),
            _ => None,
        };
        let v = v.filter(|v| v.width().to_f64().is_some_and(f64::is_finite));
        self.memo.insert(a, v.clone());
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::normal::func;
    use crate::normal::sign::Assumptions;

    #[test]
    fn constants_get_the_sign_of_an_enclosure_that_excludes_zero() {
        let s = Assumptions::default();
        let sqrt = |r: &Rat| func::sqrt(r, &s).unwrap();
        let r2 = sqrt(&Rat::int(2));
        let d = r2.sub(&Rat::one()).unwrap();
        assert_eq!(sign(d.num()), Some(Sign::Pos));
        assert_eq!(sign(d.neg().num()), Some(Sign::Neg));
        // A nested root against its value: 1 + sqrt(1 + sqrt(3)) > sqrt(5).
        let inner = sqrt(&Rat::one().add(&sqrt(&Rat::int(3))).unwrap());
        let d = Rat::one()
            .add(&inner)
            .unwrap()
            .sub(&sqrt(&Rat::int(5)))
            .unwrap();
        assert_eq!(sign(d.num()), Some(Sign::Pos));
        // A symbol: no sign from here.
        let x = Rat::atom(atom::sym("x"));
        assert_eq!(sign(x.add(&r2).unwrap().num()), None);
    }
}
