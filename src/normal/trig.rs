//! Sines and cosines: sums and integer multiples expanded, exact values at multiples of
//! π/12, π/8, π/60 and π/24.
//!
//! An argument `Σ qᵢ·mᵢ` is split into terms; a term `(a/b)·m` is the integer
//! multiple `a` of the base angle `m/b`, so `sin(2θ)` becomes `2 sin θ cos θ` while
//! `sin(θ/2)` stays an atom. The `π` term is reduced modulo 2π and, at multiples of
//! π/12, π/8, π/60 (π/5, π/10) and π/24, replaced by its exact value; other multiples
//! of π are reduced to an angle in (0, π/4) by the symmetries of the circle.

use super::atom::{self, Atom};
use super::mono::Mono;
use super::poly::{Poly, Q};
use super::rat::Rat;
use super::NormError;
use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Signed, ToPrimitive, Zero};

/// Multiples larger than this stay unexpanded atoms (`sin(1000 x)`).
const MAX_MULTIPLE: i64 = 32;

/// The largest multiple `rebase` writes out when it compares sines and cosines of one
/// angle (only to decide whether a difference is zero, never in a normal form).
const MAX_REBASE: i64 = 128;

/// An argument whose expansion could have more terms than this (the product of
/// `|k| + 1` over its terms `k·θ`) stays one atom (`cos(a + b + … + z)`).
const MAX_EXPANSION: u64 = 1 << 16;

/// `(cos u, sin u)`.
type Pair = (Rat, Rat);

fn rotate(a: &Pair, b: &Pair) -> Result<Pair, NormError> {
    let c = a.0.mul(&b.0)?.sub(&a.1.mul(&b.1)?)?;
    let s = a.1.mul(&b.0)?.add(&a.0.mul(&b.1)?)?;
    Ok((c, s))
}

fn atoms_of(base: Rat) -> Pair {
    (
        Rat::atom(atom::intern(Atom::Cos(base.clone()))),
        Rat::atom(atom::intern(Atom::Sin(base))),
    )
}

/// The pair of `k·base` for an atom pair of `base`.
fn multiple(p: &Pair, k: i64) -> Result<Pair, NormError> {
    let mut result: Pair = (Rat::one(), Rat::zero());
    let mut b = p.clone();
    let mut e = k.unsigned_abs();
    while e > 0 {
        if e & 1 == 1 {
            result = rotate(&result, &b)?;
        }
        e >>= 1;
        if e > 0 {
            b = rotate(&b, &b)?;
        }
    }
    if k < 0 {
        result.1 = result.1.neg();
    }
    Ok(result)
}

fn sqrt_prime(p: i64) -> Rat {
    Rat::atom(atom::intern(Atom::Sqrt(Poly::int(p))))
}

/// `(cos(jπ/12), sin(jπ/12))` exactly.
fn exact_pi_twelfths(j: i64) -> Result<Pair, NormError> {
    let j = j.rem_euclid(24);
    let quarter = Q::new(BigInt::from(1), BigInt::from(4));
    let s6 = sqrt_prime(2).mul(&sqrt_prime(3))?;
    let c15 = s6.add(&sqrt_prime(2))?.scale(&quarter);
    let s15 = s6.sub(&sqrt_prime(2))?.scale(&quarter);
    multiple(&(c15, s15), j)
}

/// `(cos(jπ/8), sin(jπ/8))` exactly for odd `j` (even `j` are twelfths): from
/// `cos(π/8) = sqrt(2 + sqrt(2))/2` and `sin(π/8) = sqrt(2 - sqrt(2))/2`, by the
/// symmetries of the circle. The constructor writes `sqrt(2 - sqrt(2))` through its
/// conjugate as `(√2 − 1) sqrt(2 + sqrt(2))`, so the values are canonical in
/// ℚ(√2, sqrt(2 + √2)).
fn exact_pi_odd_eighths(j: i64) -> Result<Pair, NormError> {
    let half = Q::new(BigInt::from(1), BigInt::from(2));
    let r2 = sqrt_prime(2);
    let c = sqrt_of(&Rat::int(2).add(&r2)?)?.scale(&half);
    let s = sqrt_of(&Rat::int(2).sub(&r2)?)?.scale(&half);
    Ok(match j.rem_euclid(16) {
        1 => (c, s),
        3 => (s, c),
        5 => (s.neg(), c),
        7 => (c.neg(), s),
        9 => (c.neg(), s.neg()),
        11 => (s.neg(), c.neg()),
        13 => (s, c.neg()),
        _ => (c, s.neg()),
    })
}

/// The pair of the argument `u`.
fn pair(u: &Rat) -> Result<Pair, NormError> {
    if u.is_zero() {
        return Ok((Rat::one(), Rat::zero()));
    }
    let Some(p) = u.as_poly() else {
        let neg = u.num().lead().is_some_and(|t| t.1.is_negative());
        return Ok(if neg {
            let (c, s) = atoms_of(u.neg());
            (c, s.neg())
        } else {
            atoms_of(u.clone())
        });
    };
    let pi = atom::intern(Atom::Pi);
    // Each term `k·θ` expands on its own (|k| ≤ MAX_MULTIPLE), exactly as the product
    // of the separate expansions would, so `cos(A + B)` and `cos A cos B − sin A sin B`
    // normalise alike. Only when the product of the terms' sizes would exceed
    // MAX_EXPANSION does the whole argument stay one atom (never wrong, at worst
    // undecided).
    let size = p
        .terms()
        .iter()
        .filter(|(m, _)| m.pairs() != [(pi, 1)])
        .map(|(m, q)| {
            if m.is_one() {
                2
            } else {
                q.numer()
                    .to_i64()
                    .filter(|k| k.abs() <= MAX_MULTIPLE)
                    .map_or(2, |k| k.unsigned_abs() + 1)
            }
        })
        .try_fold(1u64, |a, b| {
            a.checked_mul(b).filter(|n| *n <= MAX_EXPANSION)
        });
    if size.is_none() && p.len() > 1 {
        let neg = p.lead().is_some_and(|t| t.1.is_negative());
        return Ok(if neg {
            let (c, s) = atoms_of(u.neg());
            (c, s.neg())
        } else {
            atoms_of(u.clone())
        });
    }
    let mut total: Pair = (Rat::one(), Rat::zero());
    for (m, q) in p.terms() {
        let part = if m.pairs() == [(pi, 1)] {
            pi_pair(q)?
        } else if m.is_one() {
            let p = atoms_of(Rat::constant(q.abs()));
            multiple(&p, if q.is_negative() { -1 } else { 1 })?
        } else {
            let k = q.numer().to_i64().filter(|k| k.abs() <= MAX_MULTIPLE);
            match k {
                Some(k) => {
                    let b = Q::new(BigInt::one(), q.denom().clone());
                    multiple(&atoms_of(Rat::poly(Poly::term(m.clone(), b))?), k)?
                }
                None => {
                    let base = Rat::poly(Poly::term(m.clone(), q.abs()))?;
                    multiple(&atoms_of(base), if q.is_negative() { -1 } else { 1 })?
                }
            }
        };
        total = rotate(&total, &part)?;
    }
    Ok(total)
}

/// The pair of `q·π`: exact where `q` is a multiple of 1/12, 1/8, 1/60 or 1/24 (the
/// angles whose sines are square roots of square roots rigor writes canonically), else
/// atoms of an angle in (0, π/4) by the symmetries of the circle, so that `sin(6π/7)` and
/// `sin(π/7)`, `cos(8π/5)` and `cos(2π/5)`, `sin(3π/7)` and `cos(π/14)` meet.
fn pi_pair(q: &Q) -> Result<Pair, NormError> {
    let two = Q::from_integer(BigInt::from(2));
    // q mod 2, in [0, 2).
    let r = q - (q / &two).floor() * &two;
    let times = |k: i64| {
        let x = &r * Q::from_integer(BigInt::from(k));
        x.is_integer().then(|| x.to_integer().to_i64().unwrap_or(0))
    };
    if let Some(j) = times(12) {
        return exact_pi_twelfths(j);
    }
    if let Some(j) = times(8) {
        return exact_pi_odd_eighths(j);
    }
    if let Some(j) = times(60) {
        return exact_pi_sixtieths(j);
    }
    if let Some(j) = times(24) {
        return exact_pi_odd_twentyfourths(j);
    }
    let half = Q::new(BigInt::one(), BigInt::from(2));
    let quarter = Q::new(BigInt::one(), BigInt::from(4));
    // sin(x + π) = −sin x, cos(x + π) = −cos x.
    let (r, turn) = if r > Q::one() {
        (r - Q::one(), true)
    } else {
        (r, false)
    };
    // sin(π − x) = sin x, cos(π − x) = −cos x.
    let (r, mirror) = if r > half {
        (Q::one() - r, true)
    } else {
        (r, false)
    };
    // sin(π/2 − x) = cos x.
    let (r, swap) = if r > quarter {
        (half - r, true)
    } else {
        (r, false)
    };
    let pi = atom::intern(Atom::Pi);
    let (mut c, mut s) = atoms_of(Rat::poly(Poly::term(Mono::atom(pi, 1), r))?);
    if swap {
        std::mem::swap(&mut c, &mut s);
    }
    if mirror {
        c = c.neg();
    }
    Ok(if turn { (c.neg(), s.neg()) } else { (c, s) })
}

/// `sqrt(n)` of a rational, through the constructor (numbers carry no signs).
fn sqrt_of(n: &Rat) -> Result<Rat, NormError> {
    super::func::sqrt(n, &super::sign::Assumptions::default())
}

/// `(cos(jπ/60), sin(jπ/60))` exactly: `π/60 = 5·π/12 − 2·π/5`, with the twelfths and
/// `cos(π/5) = (1 + √5)/4`, `sin(π/5) = sqrt(10 − 2√5)/4 = √2 (√5 − 1) sqrt(5 + √5)/8`
/// (one nested radical, `sqrt(5 + √5)`, whose square the rules reduce: the values are
/// canonical in ℚ(√2, √3, √5, sqrt(5 + √5))).
fn exact_pi_sixtieths(j: i64) -> Result<Pair, NormError> {
    let q = |a: i64, b: i64| Q::new(BigInt::from(a), BigInt::from(b));
    let r5 = sqrt_prime(5);
    let w = sqrt_of(&Rat::int(5).add(&r5)?)?;
    let c5 = r5.add(&Rat::one())?.scale(&q(1, 4));
    let s5 = sqrt_prime(2)
        .mul(&r5.sub(&Rat::one())?)?
        .mul(&w)?
        .scale(&q(1, 8));
    // j/60 = (−2j)/5 + 5j/12.
    let fifths = multiple(&(c5, s5), (-2 * j).rem_euclid(10))?;
    rotate(&fifths, &exact_pi_twelfths((5 * j).rem_euclid(24))?)
}

/// `(cos(jπ/24), sin(jπ/24))` exactly for `j` prime to 6 (the other multiples are
/// twelfths or eighths): `cos(π/24) = √2 X/4`, `sin(π/24) = √2 (√6 − √2)/(4X)` with
/// `X = sqrt(4 + √6 + √2)` (half angles of π/12; `sqrt(4 − √6 − √2) = (√6 − √2)/X`).
fn exact_pi_odd_twentyfourths(j: i64) -> Result<Pair, NormError> {
    let q = |a: i64, b: i64| Q::new(BigInt::from(a), BigInt::from(b));
    let (r2, r6) = (sqrt_prime(2), sqrt_prime(2).mul(&sqrt_prime(3))?);
    let x = sqrt_of(&Rat::int(4).add(&r6)?.add(&r2)?)?;
    let c = r2.mul(&x)?.scale(&q(1, 4));
    let s = r2.mul(&r6.sub(&r2)?)?.div(&x)?.scale(&q(1, 4));
    multiple(&(c, s), j.rem_euclid(48))
}

/// `sin(u)`.
pub fn sin(u: &Rat) -> Result<Rat, NormError> {
    Ok(pair(u)?.1)
}

/// `cos(u)`.
pub fn cos(u: &Rat) -> Result<Rat, NormError> {
    Ok(pair(u)?.0)
}

/// `tan(u) = sin(u)/cos(u)`; an error where the cosine is exactly zero.
pub fn tan(u: &Rat) -> Result<Rat, NormError> {
    let (c, s) = pair(u)?;
    if c.is_zero() {
        return Err(NormError::DivisionByZero);
    }
    s.div(&c)
}

/// Rewrites sines and cosines of different multiples of the same angle in terms of
/// their common base angle (`sin(θ)` and `sin(θ/2)` both in terms of `θ/2`), so that
/// identities such as `sin θ = 2 sin(θ/2) cos(θ/2)` normalise to zero. Multiples above
/// `MAX_REBASE` are left alone.
pub fn rebase(r: &Rat, s: &super::sign::Assumptions) -> Result<Rat, NormError> {
    use foldhash::{HashMap, HashMapExt};
    let mut groups: HashMap<Mono, Vec<(super::atom::AtomId, bool, Q)>> = HashMap::new();
    for a in r.atoms() {
        let at = atom::get(a);
        let (is_sin, u) = match at {
            Atom::Sin(u) => (true, u),
            Atom::Cos(u) => (false, u),
            _ => continue,
        };
        let Some(p) = u.as_poly() else { continue };
        if let [(m, c)] = p.terms() {
            groups
                .entry(m.clone())
                .or_default()
                .push((a, is_sin, c.clone()));
        }
    }
    let mut map: HashMap<super::atom::AtomId, Rat> = HashMap::new();
    for (m, items) in groups {
        let mut cs: Vec<&Q> = items.iter().map(|i| &i.2).collect();
        cs.sort();
        cs.dedup();
        if cs.len() < 2 {
            continue;
        }
        // gcd of rationals: gcd of numerators over lcm of denominators.
        let mut num = BigInt::zero();
        let mut den = BigInt::one();
        for c in &cs {
            num = num.gcd(c.numer());
            den = den.lcm(c.denom());
        }
        let g = Q::new(num, den);
        let ks: Option<Vec<i64>> = items
            .iter()
            .map(|i| {
                (&i.2 / &g)
                    .to_integer()
                    .to_i64()
                    .filter(|k| k.abs() <= MAX_REBASE)
            })
            .collect();
        let Some(ks) = ks else { continue };
        let base = atoms_of(Rat::poly(Poly::term(m.clone(), g.clone()))?);
        for (item, k) in items.iter().zip(ks) {
            let (c, sn) = multiple(&base, k)?;
            map.insert(item.0, if item.1 { sn } else { c });
        }
    }
    if map.is_empty() {
        return Ok(r.clone());
    }
    let f = |a: super::atom::AtomId| map.get(&a).cloned();
    super::subst::Subst::new(&f, s).rat(r)
}
