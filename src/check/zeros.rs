//! What the facts force to be zero over the reals, beyond linear elimination: the
//! consequences a divisor's safety and the facts' consistency are judged with.
//!
//! - A power is zero only where its base is: a fact is replaced by its squarefree part
//!   (`cos(theta)^2 = 0` gives `cos(theta) = 0`; a kept factor `(q + 1)^64 = 0` gives
//!   `q + 1 = 0`).
//! - A sum of squares with positive weights is zero only where each square's base is: a
//!   fact is split by completing the square in one atom after another (`u^2 + v^2 = 0`
//!   gives `u = 0` and `v = 0`; `(v - 1)^2 + u^2 = 0` gives `v = 1` and `u = 0`), and
//!   one that completes to a strictly positive sum can never hold (`m (v - w)^2/2 + k`
//!   with `m, k > 0`).
//! - `sin(u)^2 + cos(u)^2 = 1` for one angle is already in the normal form (`cos(u)^2` is
//!   written `1 - sin(u)^2`), so a quantity is tested together with its square: given
//!   `sin(theta) = 1`, `cos(theta)^2` is `1 - sin(theta)^2 = 0`, so `cos(theta) = 0`.
//!
//! Every consequence is an exact identity over the reals; nothing here is sampled.

use super::elimination::{zero_by_facts, Fact};
use crate::normal::atom;
use crate::normal::limits::Limits;
use crate::normal::{Assumptions, Poly, Rat, Sign};
use foldhash::{HashMap, HashMapExt};
use std::sync::Mutex;

/// Nesting of square completions tried on one fact (one per atom completed).
const DEPTH: usize = 6;

/// Facts past which the consequences are not looked for (each costs a gcd).
const MAX_FACTS: usize = 64;

/// Terms of a fact or quantity past which its squarefree part and squares are not
/// looked for.
const MAX_TERMS: usize = 200;

/// Degree in one atom past which the squarefree part of a sum is not looked for.
const MAX_DEGREE: u32 = 64;

/// A fact's numerator as a sum of weighted squares plus a rest of known sign.
struct Squares {
    /// The bases: `p = Σ wᵢ bᵢ² + rest` with every weight positive.
    bases: Vec<Poly>,
    /// The rest's sign: `Pos` (so `p > 0`), or `NonNeg`.
    rest: Sign,
    /// The rest itself, when it is not known to be positive.
    rest_value: Poly,
}

/// `p` (a polynomial the signs cannot place) shown `>= 0` by completing squares: in an
/// atom `x` of degree 2 whose leading coefficient `a` is positive,
/// `p = a x^2 + b x + c = (2 a x + b)^2/(4 a) + (4 a c - b^2)/(4 a)`, and the rest is
/// placed the same way, one atom after another.
fn squares(p: &Poly, signs: &Assumptions, depth: usize) -> Option<Squares> {
    let s = signs.poly(p);
    if s == Sign::Pos || s == Sign::NonNeg || s == Sign::Zero {
        return Some(Squares {
            bases: Vec::new(),
            rest: if s == Sign::Pos {
                Sign::Pos
            } else {
                Sign::NonNeg
            },
            rest_value: p.clone(),
        });
    }
    if depth == 0 {
        return None;
    }
    let mut atoms = p.atoms();
    atoms.sort_by(|a, b| atom::cmp_atoms(*a, *b));
    for x in atoms {
        if atom::is_pi(x) || p.degree_in(x) != 2 {
            continue;
        }
        let coeff = |k: u32| {
            p.coeffs_in(x)
                .into_iter()
                .find(|(e, _)| *e == k)
                .map_or_else(Poly::zero, |(_, c)| c)
        };
        let (a, b, c) = (coeff(2), coeff(1), coeff(0));
        if signs.poly(&a) != Sign::Pos {
            continue;
        }
        let four_a = a.scale(&crate::normal::Q::from_integer(4.into()));
        let Ok(four_ac) = four_a.mul(&c) else {
            continue;
        };
        let Ok(b2) = b.mul(&b) else {
            continue;
        };
        let Ok(base) = a
            .scale(&crate::normal::Q::from_integer(2.into()))
            .mul(&Poly::atom(x))
        else {
            continue;
        };
        let base = base.add(&b);
        if let Some(mut rest) = squares(&four_ac.sub(&b2), signs, depth - 1) {
            rest.bases.push(base);
            return Some(rest);
        }
    }
    None
}

/// Whether the squarefree part of `p` is cheap to find: a few terms of low degree (a
/// kept factor's large power is one term).
fn affordable(p: &Poly) -> bool {
    p.len() == 1
        || p.len() <= MAX_TERMS && p.atoms().into_iter().all(|a| p.degree_in(a) <= MAX_DEGREE)
}

/// The squares of `p` or of `-p`.
fn squares_either(p: &Poly, signs: &Assumptions) -> Option<Squares> {
    if p.len() > MAX_TERMS {
        return None;
    }
    squares(p, signs, DEPTH).or_else(|| squares(&p.neg(), signs, DEPTH))
}

/// Whether the fact `value = 0` can never hold: its numerator is a sum of weighted
/// squares plus a positive rest (or the negative of one).
pub fn never_zero(value: &Rat, signs: &Assumptions) -> bool {
    let n = value.num();
    !n.is_zero() && squares_either(n, signs).is_some_and(|s| s.rest == Sign::Pos)
}

/// The facts that follow from `facts` over the reals by the rules of this module (not
/// the facts themselves), each named after the fact it came from.
pub fn consequences(facts: &[Fact], signs: &Assumptions) -> Vec<Fact> {
    let mut out: Vec<Fact> = Vec::new();
    if facts.len() > MAX_FACTS {
        return out;
    }
    for f in facts {
        for value in of_fact(&f.value, signs) {
            if !value.is_zero() && !out.iter().any(|f| f.value == value) {
                out.push(Fact {
                    value,
                    name: f.name.clone(),
                });
            }
        }
    }
    out
}

/// What one fact `value = 0` forces to zero, in the order found (repeats and zeros
/// included), remembered for the process: the same facts come back with every given
/// after them and in every check of the same notes. The answer depends on the value,
/// the signs and the size limits, and on the clock only when the deadline passed while
/// it was found — then it is not kept (a deadline never un-passes, so one that has not
/// passed by the end did not cut anything short).
fn of_fact(value: &Rat, signs: &Assumptions) -> Vec<Rat> {
    type Known = HashMap<Rat, Vec<(Assumptions, Limits, Vec<Rat>)>>;
    static KNOWN: Mutex<Option<Known>> = Mutex::new(None);
    const KEEP: usize = 4096;
    let limits = crate::normal::limits::current();
    let lock = || KNOWN.lock().unwrap_or_else(|e| e.into_inner());
    let known = lock().as_ref().and_then(|k| {
        k.get(value)?
            .iter()
            .find(|(s, l, _)| s == signs && *l == limits)
            .map(|(_, _, v)| v.clone())
    });
    if let Some(v) = known {
        return v;
    }
    let found = of_fact_found(value, signs);
    if crate::normal::limits::check_deadline().is_ok() {
        let mut k = lock();
        let k = k.get_or_insert_with(HashMap::new);
        if k.len() >= KEEP {
            k.clear();
        }
        k.entry(value.clone())
            .or_default()
            .push((signs.clone(), limits, found.clone()));
    }
    found
}

/// [`of_fact`], found.
fn of_fact_found(value: &Rat, signs: &Assumptions) -> Vec<Rat> {
    let mut out = Vec::new();
    let n = value.num();
    if n.atoms().is_empty() || !affordable(n) {
        return out;
    }
    // A power is zero only where its base is. Kept factors (large powers of sums)
    // are atoms here, so the radical holds each once and writing it out is cheap.
    if let Ok(parts) = crate::normal::gcd::squarefree(n) {
        let mut radical = Poly::one();
        for (part, _) in &parts {
            match radical.mul(part) {
                Ok(r) => radical = r,
                Err(_) => break,
            }
        }
        let written = Rat::poly(radical).and_then(|r| crate::normal::power::expand(&r, signs));
        if let Ok(r) = written {
            if r != *value {
                out.push(r);
            }
        }
    }
    if crate::normal::power::has_kept(value) {
        return out;
    }
    // A sum of weighted squares is zero only where each base is.
    if let Some(sq) = squares_either(n, signs) {
        for b in sq.bases {
            if let Ok(r) = Rat::poly(b) {
                out.push(r);
            }
        }
        if sq.rest == Sign::NonNeg && !sq.rest_value.atoms().is_empty() {
            out.extend(nonnegative_terms(&sq.rest_value, signs));
        }
    }
    out
}

/// A rest of nonnegative terms is zero only where each term is: a term that is a
/// positive number times one atom's power gives that atom = 0.
fn nonnegative_terms(p: &Poly, signs: &Assumptions) -> Vec<Rat> {
    let each_nonneg = p.terms().iter().all(|(m, q)| {
        let t = Poly::term(m.clone(), q.clone());
        signs.poly(&t).is_nonneg()
    });
    if !each_nonneg || p.len() < 2 {
        return Vec::new();
    }
    p.terms()
        .iter()
        .filter_map(|(m, _)| match m.pairs() {
            [(a, _)] => Some(Rat::atom(*a)),
            _ => None,
        })
        .collect()
}

/// What [`forced_zero_in`] found under one set of facts and signs: the divisors of a
/// file's links repeat (`m R^2`, then `m R`, both bringing `m` and `R`), and each answer
/// costs an elimination. Only answers for exactly these facts (by value) and these
/// signs are reused; any other facts or signs start it afresh.
#[derive(Default)]
pub struct ZeroMemo {
    /// The facts' values and the signs the answers hold for.
    facts: Vec<Rat>,
    signs: Assumptions,
    /// The facts' consequences, once found.
    consequences: Option<Vec<Fact>>,
    /// Whether a value is zero by the facts (`false`) or by the facts and their
    /// consequences (`true`).
    zero: HashMap<(Rat, bool), bool>,
    /// A point where the facts hold, once looked for.
    witness: Option<Option<std::sync::Arc<super::witness::Point>>>,
}

impl ZeroMemo {
    /// Forgets what was found unless it was found for these facts and signs.
    fn under(&mut self, facts: &[Fact], signs: &Assumptions) {
        let same = self.facts.len() == facts.len()
            && self.facts.iter().zip(facts).all(|(a, f)| *a == f.value)
            && self.signs == *signs;
        if !same {
            *self = ZeroMemo {
                facts: facts.iter().map(|f| f.value.clone()).collect(),
                signs: signs.clone(),
                ..ZeroMemo::default()
            };
        }
    }

    /// `zero_by_facts` of `d` (a value and its negation are zero together).
    fn zero(&mut self, d: &Rat, all: &[Fact], with: bool, signs: &Assumptions) -> bool {
        let neg = d.neg();
        let known = self
            .zero
            .get(&(d.clone(), with))
            .or_else(|| self.zero.get(&(neg, with)));
        if let Some(z) = known {
            return *z;
        }
        let z = zero_by_facts(d, all, signs);
        self.zero.insert((d.clone(), with), z);
        z
    }
}

/// The fact sets (their values without repeats, in order) that [`contradiction`] found
/// no contradiction in, under the signs they were checked with: a link that uses the
/// facts a given was just checked with needs no second look. Only "no contradiction"
/// is kept; a contradiction is found again, so its message names its own facts.
///
/// [`contradiction`]: super::elimination::contradiction
#[derive(Default)]
pub struct Consistent {
    signs: Assumptions,
    sets: Vec<Vec<Rat>>,
}

impl Consistent {
    /// How many sets are kept (the facts grow through a file; older sets recur rarely).
    const KEEP: usize = 8;

    /// Whether `facts` are free of contradiction (`None`) as [`contradiction`] finds,
    /// or the contradiction.
    ///
    /// [`contradiction`]: super::elimination::contradiction
    pub fn check(&mut self, facts: &[Fact], signs: &Assumptions) -> Option<crate::diag::Text> {
        let values: Vec<Rat> = super::elimination::distinct_values(facts);
        if self.signs != *signs {
            *self = Consistent {
                signs: signs.clone(),
                sets: Vec::new(),
            };
        }
        if self.sets.contains(&values) {
            return None;
        }
        // Facts that hold together at a point (with the signs) contradict nothing.
        let found = if super::witness::remembered(facts, signs).is_some() {
            None
        } else {
            super::elimination::contradiction(facts, signs)
        };
        if found.is_none() {
            if self.sets.len() >= Self::KEEP {
                self.sets.remove(0);
            }
            self.sets.push(values);
        }
        found
    }
}

/// Whether `d` is zero wherever the facts hold: by elimination with the facts and their
/// consequences, for `d`, for its squarefree part, and for its square (which brings in
/// `sin^2 + cos^2 = 1`). What `memo` found under the same facts and signs is reused.
pub fn forced_zero_in(d: &Rat, facts: &[Fact], signs: &Assumptions, memo: &mut ZeroMemo) -> bool {
    memo.under(facts, signs);
    // A point where the facts hold and `d` does not vanish settles it at once.
    let witness = memo
        .witness
        .get_or_insert_with(|| super::witness::remembered(facts, signs));
    if witness.as_ref().is_some_and(|p| p.nonzero_at(d, signs)) {
        return false;
    }
    if memo.zero(d, facts, false, signs) {
        return true;
    }
    if d.num().atoms().is_empty() || facts.is_empty() {
        return false;
    }
    let all: Vec<Fact> = {
        let more = memo
            .consequences
            .get_or_insert_with(|| consequences(facts, signs));
        facts.iter().chain(more.iter()).cloned().collect()
    };
    let mut candidates: Vec<Rat> = vec![d.clone()];
    if affordable(d.num()) {
        if let Ok(parts) = crate::normal::gcd::squarefree(d.num()) {
            candidates.extend(parts.into_iter().filter_map(|(p, _)| {
                Rat::poly(p)
                    .and_then(|r| crate::normal::power::expand(&r, signs))
                    .ok()
            }));
        }
    }
    let squares: Vec<Rat> = candidates.iter().filter_map(|c| c.mul(c).ok()).collect();
    candidates.extend(squares);
    candidates
        .iter()
        .any(|c| !c.num().atoms().is_empty() && memo.zero(c, &all, true, signs))
}

/// The sign of `r` from the declared signs, and where they cannot place it, from its
/// numerator completed to weighted squares (`m v^2/2 - m v w + m w^2/2 + k` is positive
/// for `m, k > 0`).
pub fn definite_sign(r: &Rat, signs: &Assumptions) -> Sign {
    let s = signs.rat(r);
    if s != Sign::Unknown {
        return s;
    }
    let den = signs.poly(r.den());
    if !matches!(den, Sign::Pos | Sign::Neg) {
        return Sign::Unknown;
    }
    let n = r.num();
    if n.len() > MAX_TERMS || crate::normal::power::has_kept(r) {
        return Sign::Unknown;
    }
    let num = if let Some(sq) = squares(n, signs, DEPTH) {
        if sq.rest == Sign::Pos {
            Sign::Pos
        } else {
            Sign::NonNeg
        }
    } else if let Some(sq) = squares(&n.neg(), signs, DEPTH) {
        if sq.rest == Sign::Pos {
            Sign::Neg
        } else {
            Sign::NonPos
        }
    } else {
        Sign::Unknown
    };
    num.times(den)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sym(n: &str) -> Rat {
        Rat::atom(atom::sym(n))
    }

    /// `a x^2 - 2 a x + a`: a weighted square only where `a > 0`.
    fn weighted() -> Rat {
        let (a, x) = (sym("zq_a"), sym("zq_x"));
        let x1 = x.sub(&Rat::one()).unwrap();
        a.mul(&x1.mul(&x1).unwrap()).unwrap()
    }

    #[test]
    fn remembered_consequences_are_those_of_the_signs_asked() {
        let value = weighted();
        let mut positive = Assumptions::default();
        positive.set(atom::sym("zq_a"), Sign::Pos);
        let unsigned = Assumptions::default();
        // Each answer, asked twice and in turn under the other signs, is the one found
        // afresh: the memo never answers for other signs.
        for _ in 0..2 {
            for signs in [&positive, &unsigned] {
                assert_eq!(of_fact(&value, signs), of_fact_found(&value, signs));
            }
        }
        assert_ne!(
            of_fact_found(&value, &positive),
            of_fact_found(&value, &unsigned),
            "the signs must matter for this test to say anything"
        );
        assert!(!of_fact_found(&value, &positive).is_empty());
    }

    #[test]
    fn remembered_consequences_are_those_of_the_limits_in_force() {
        use crate::normal::limits::{install, Limits};
        let value = weighted();
        let mut positive = Assumptions::default();
        positive.set(atom::sym("zq_a"), Sign::Pos);
        let wide = of_fact(&value, &positive);
        // Under limits too small to find anything, the answer is the small one.
        let tiny = Limits {
            max_terms: 1,
            ..Limits::DEFAULT
        };
        let g = install(tiny);
        let small = of_fact_found(&value, &positive);
        assert_eq!(of_fact(&value, &positive), small);
        drop(g);
        assert_ne!(
            small, wide,
            "the limits must matter for this test to say anything"
        );
        assert_eq!(of_fact(&value, &positive), wide);
    }
}
