//! Denesting square roots: `sqrt(a + b sqrt(c))` and its generalisations, each answer
//! checked exactly before it is used.
//!
//! Three rules, after Borodin, Fagin, Hopcroft and Tompa ("Decreasing the nesting depth
//! of expressions involving square roots", 1985). Write the radicand as `A + B S` with
//! `S = sqrt(C)` one of its deepest square roots and `A, B, C` free of `S`:
//!
//! - `D = A² − B²C` whose root `d` is no deeper than the radicand's other parts: then
//!   `sqrt(A + B S) = sqrt((A + d)/2) + sign(B) sqrt((A − d)/2)` for `A ≥ 0` (square
//!   both sides); the two halves are denested in turn (`sqrt(33 − 4√14 − 2√6 + 4√21)
//!   = −√2 + √3 + 2√7`, `sqrt(2 + √3 + 2 sqrt(1 + √3)) = 1 + sqrt(1 + √3)`);
//! - for a rational `C > 0`, `sqrt(A + B S) = C^(1/4) sqrt(B + (A/C) S)`, the second root
//!   denested by the first rule (`sqrt(4 + 3√2) = 2^(3/4) + 2^(1/4)`);
//! - for `a − b√c` with `a² − b²c` a positive rational that is not a square, the
//!   conjugate: `sqrt(a − b√c) = sqrt(N) (a − b√c)/N · sqrt(a + b√c)`, so a pair of
//!   conjugate nested roots is one atom.
//!
//! A denested `r` is used only when `r² − u` is exactly zero in normal form (after
//! [`settle`](super::settle)), the signs show `r ≥ 0`, and `r` is no deeper than `u`: then
//! `r = sqrt(u)`, whatever the rules' own derivation. Anything else keeps the root an atom.

use super::atom::{self, Atom, AtomId};
use super::func::{root, sqrt};
use super::mono::Mono;
use super::poly::{Poly, Q};
use super::rat::Rat;
use super::sign::{Assumptions, Sign};
use super::NormError;
use num_bigint::BigInt;
use num_traits::{One, Signed};

/// The number of nested denestings one square root may try (each tries two halves).
const BUDGET: u32 = 24;

/// The deepest square roots of a radicand tried as `S`.
const CANDIDATES: usize = 4;

/// `sqrt(u)` denested, when one of the rules applies and its answer checks.
pub fn denest(u: &Rat, s: &Assumptions) -> Result<Option<Rat>, NormError> {
    if let Some(r) = two_terms(u, s)? {
        return Ok(Some(r));
    }
    let mut budget = BUDGET;
    Ok(nested(u, s, &mut budget))
}

/// `sqrt(u)` within the budget: denested where that checks, else the constructor's root.
fn sqrt_in(u: &Rat, s: &Assumptions, budget: &mut u32) -> Option<Rat> {
    if let Ok(Some(r)) = two_terms(u, s) {
        return Some(r);
    }
    match nested(u, s, budget) {
        Some(r) => Some(r),
        None => root(u, 2, s).ok(),
    }
}

/// The deepest nesting among the atoms of `r` (0 for a number).
fn depth_of(r: &Rat) -> u32 {
    r.atoms().into_iter().map(atom::depth).max().unwrap_or(0)
}

/// The general rules on a radicand holding a square root; `None` when none applies.
fn nested(u: &Rat, s: &Assumptions, budget: &mut u32) -> Option<Rat> {
    if *budget == 0 || !u.den().is_one() || u.num().len() < 2 {
        return None;
    }
    *budget -= 1;
    let p = u.num();
    let atoms = p.atoms();
    let top = atoms.iter().map(|a| atom::depth(*a)).max()?;
    let roots: Vec<AtomId> = atoms
        .iter()
        .copied()
        .filter(|a| atom::depth(*a) == top && matches!(atom::get(*a), Atom::Sqrt(_)))
        .take(CANDIDATES)
        .collect();
    for x in roots {
        let Atom::Sqrt(c) = atom::get(x) else {
            continue;
        };
        let coeffs = p.coeffs_in(x);
        let part = |k: u32| {
            coeffs
                .iter()
                .find(|t| t.0 == k)
                .map_or(Ok(Rat::zero()), |t| Rat::poly(t.1.clone()))
        };
        if coeffs.iter().any(|t| t.0 > 1) {
            continue;
        }
        let (Ok(a), Ok(b), Ok(c)) = (part(0), part(1), Rat::poly(c.clone())) else {
            continue;
        };
        if let Some(r) = by_halves(&a, &b, &c, atom::depth(x), s, budget) {
            if checks(&r, u, top, s) {
                return Some(r);
            }
        }
        if let Some(r) = by_fourth_root(&a, &b, &c, x, s, budget) {
            if checks(&r, u, top, s) {
                return Some(r);
            }
        }
    }
    None
}

/// `sqrt((A + d)/2) + sign(B) sqrt((A − d)/2)` with `d = sqrt(A² − B²C)`, when `A ≥ 0`,
/// `B` has a sign and `d` is no deeper than `depth` allows (atoms below it, or of `A`,
/// `B`, `C`).
fn by_halves(
    a: &Rat,
    b: &Rat,
    c: &Rat,
    depth: u32,
    s: &Assumptions,
    budget: &mut u32,
) -> Option<Rat> {
    if !matches!(s.rat(a), Sign::Pos | Sign::NonNeg) {
        return None;
    }
    let positive = match s.rat(b) {
        Sign::Pos => true,
        Sign::Neg => false,
        _ => return None,
    };
    let d2 = a.mul(a).ok()?.sub(&b.mul(b).ok()?.mul(c).ok()?).ok()?;
    if !matches!(s.rat(&d2), Sign::Pos | Sign::NonNeg | Sign::Zero) {
        return None;
    }
    let d = sqrt_in(&d2, s, budget)?;
    let known: Vec<AtomId> = [a, b, c].iter().flat_map(|r| r.atoms()).collect();
    if !d
        .atoms()
        .into_iter()
        .all(|y| atom::depth(y) < depth || known.contains(&y))
    {
        return None;
    }
    let half = Q::new(BigInt::one(), BigInt::from(2));
    let hi = sqrt_in(&a.add(&d).ok()?.scale(&half), s, budget)?;
    let lo = sqrt_in(&a.sub(&d).ok()?.scale(&half), s, budget)?;
    if positive {
        hi.add(&lo).ok()
    } else {
        hi.sub(&lo).ok()
    }
}

/// `C^(1/4) sqrt(B + (A/C) S)` for a rational `C > 0`, the second root by halves.
fn by_fourth_root(
    a: &Rat,
    b: &Rat,
    c: &Rat,
    x: AtomId,
    s: &Assumptions,
    budget: &mut u32,
) -> Option<Rat> {
    let q = c.as_constant().filter(|q| q.is_positive())?;
    let a_over_c = a.scale(&q.recip());
    let inner = by_halves(b, &a_over_c, c, atom::depth(x), s, budget)?;
    root(c, 4, s).ok()?.mul(&inner).ok()
}

/// Whether `r` is `sqrt(u)`: `r² = u` exactly, `r ≥ 0` by the signs, and `r` no deeper
/// than `u`.
fn checks(r: &Rat, u: &Rat, top: u32, s: &Assumptions) -> bool {
    depth_of(r) <= top
        && matches!(s.rat(r), Sign::Pos | Sign::NonNeg | Sign::Zero)
        && r.mul(r)
            .and_then(|r2| r2.sub(u))
            .is_ok_and(|d| super::settle(&d, s).is_zero())
}

/// `sqrt(a + b·√c)` for rationals `a > 0`, `b ≠ 0` and a square-free integer `c`, when
/// `a² − b²c` is the square of a rational `d`: then it is exactly
/// `sqrt((a + d)/2) + sign(b)·sqrt((a − d)/2)` (square both sides), so that
/// `sqrt(3 + 2 sqrt(2))` and `1 + sqrt(2)` have one normal form.
fn two_terms(u: &Rat, s: &Assumptions) -> Result<Option<Rat>, NormError> {
    if !u.den().is_one() {
        return Ok(None);
    }
    let [(m0, a), (m1, b)] = u.num().terms() else {
        return Ok(None);
    };
    if !m0.is_one() || !a.is_positive() {
        return Ok(None);
    }
    // √c as a product of square roots of distinct integers, each to the first power.
    let mut c = BigInt::one();
    for &(x, e) in m1.pairs() {
        let at = atom::get(x);
        let Atom::Sqrt(p) = at else {
            return Ok(None);
        };
        match p.as_constant() {
            Some(q) if e == 1 && q.is_integer() && q.is_positive() => c *= q.numer(),
            _ => return Ok(None),
        }
    }
    let d2 = a * a - b * b * Q::from_integer(c);
    if d2.is_negative() {
        return Ok(None);
    }
    let (rn, rd) = (d2.numer().sqrt(), d2.denom().sqrt());
    if &rn * &rn != *d2.numer() || &rd * &rd != *d2.denom() {
        return conjugate(u, &d2, s);
    }
    let d = Q::new(rn, rd);
    let two = Q::from_integer(BigInt::from(2));
    let hi = root(&Rat::constant((a + &d) / &two), 2, s)?;
    let lo = root(&Rat::constant((a - &d) / &two), 2, s)?;
    Ok(Some(if b.is_positive() {
        hi.add(&lo)?
    } else {
        hi.sub(&lo)?
    }))
}

/// `sqrt(a − b√c)` (`a, b > 0`, `N = a² − b²c > 0` not a square) through its conjugate:
/// `sqrt(N) (a − b√c)/N · sqrt(a + b√c)`, since `(a − b√c)(a + b√c) = N` and both are
/// positive. One atom, `sqrt(a + b√c)`, for the pair (`sin(π/5) = sqrt(10 − 2√5)/4` and
/// `√2 (√5 − 1) sqrt(5 + √5)/8` meet). `None` for `b > 0` or `N = 0`.
fn conjugate(u: &Rat, n: &Q, s: &Assumptions) -> Result<Option<Rat>, NormError> {
    let [(_, a), (m1, b)] = u.num().terms() else {
        return Ok(None);
    };
    if !b.is_negative() || !n.is_positive() {
        return Ok(None);
    }
    let v = Rat::poly(Poly::term(Mono::one(), a.clone()).add(&Poly::term(m1.clone(), -b)))?;
    let n = Rat::constant(n.clone());
    let factor = root(&n, 2, s)?.mul(u)?.div(&n)?;
    Ok(Some(factor.mul(&sqrt(&v, s)?)?))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn root_of(n: i64) -> Rat {
        sqrt(&Rat::int(n), &Assumptions::default()).unwrap()
    }

    fn sum(terms: &[(i64, Rat)]) -> Rat {
        terms.iter().fold(Rat::zero(), |acc, (k, r)| {
            acc.add(&r.scale(&Q::from_integer(BigInt::from(*k))))
                .unwrap()
        })
    }

    #[test]
    fn several_surds_denest_into_their_value() {
        let s = Assumptions::default();
        // sqrt(33 - 4√14 - 2√6 + 4√21) = -√2 + √3 + 2√7.
        let u = sum(&[
            (33, Rat::one()),
            (-4, root_of(14)),
            (-2, root_of(6)),
            (4, root_of(21)),
        ]);
        let r = sum(&[(-1, root_of(2)), (1, root_of(3)), (2, root_of(7))]);
        assert_eq!(sqrt(&u, &s).unwrap(), r);
        // A nested root squared: sqrt((1 + sqrt(1 + √3))^2) = 1 + sqrt(1 + √3).
        let inner = sqrt(&Rat::one().add(&root_of(3)).unwrap(), &s).unwrap();
        let v = Rat::one().add(&inner).unwrap();
        assert_eq!(sqrt(&v.mul(&v).unwrap(), &s).unwrap(), v);
    }

    #[test]
    fn only_an_answer_that_squares_back_is_used() {
        let s = Assumptions::default();
        // sqrt(1 + √3) does not denest: it stays one atom.
        let r = sqrt(&Rat::one().add(&root_of(3)).unwrap(), &s).unwrap();
        assert!(r.as_atom().is_some());
        // 1 + √2 squares to 3 + 2√2, not 4 + 2√2: not its root.
        let u = sum(&[(4, Rat::one()), (2, root_of(2))]);
        let wrong = Rat::one().add(&root_of(2)).unwrap();
        assert!(!checks(&wrong, &u, 1, &s));
        let right = sum(&[(3, Rat::one()), (2, root_of(2))]);
        assert!(checks(&wrong, &right, 1, &s));
        // A negative candidate never is: -(1 + √2) squares to 3 + 2√2 too.
        assert!(!checks(&wrong.neg(), &right, 1, &s));
    }
}
