//! Constructors of the functions of §1 on normal forms: `sqrt`, roots, `abs`,
//! `exp`, `ln` and powers, each applying the rules the declared signs allow.

use super::atom::{self, Atom};
use super::mono::Mono;
use super::poly::{Poly, Q};
use super::rat::Rat;
use super::sign::{Assumptions, Sign};
use super::{Limit, NormError};
use num_bigint::{BigInt, BigUint};
use num_integer::Integer;
use num_traits::{One, Signed, ToPrimitive, Zero};

/// Primes by trial division up to this bound; a larger cofactor is kept whole.
const TRIAL_LIMIT: u32 = 10_000;

/// `n = k^root · ∏ rest`: the largest perfect `root`-th power found, and the remaining
/// factors (primes, each with exponent below `root`, plus possibly one unfactored cofactor).
fn split_power(n: &BigUint, root: u32) -> (BigUint, Vec<(BigUint, u32)>) {
    let mut n = n.clone();
    let mut k = BigUint::one();
    let mut rest = Vec::new();
    let mut p = 2u32;
    while p <= TRIAL_LIMIT {
        let bp = BigUint::from(p);
        if &bp * &bp > n {
            break;
        }
        let mut e = 0u32;
        while (&n % &bp).is_zero() {
            n /= &bp;
            e += 1;
        }
        if e > 0 {
            k *= num_traits::pow(bp.clone(), (e / root) as usize);
            if e % root > 0 {
                rest.push((bp, e % root));
            }
        }
        p += if p == 2 { 1 } else { 2 };
    }
    if n > BigUint::one() {
        let r = n.nth_root(root);
        if num_traits::pow(r.clone(), root as usize) == n {
            k *= r;
        } else {
            rest.push((n, 1));
        }
    }
    (k, rest)
}

fn q_of(n: BigUint) -> Q {
    Q::from_integer(BigInt::from(n))
}

/// The principal square root.
pub fn sqrt(u: &Rat, s: &Assumptions) -> Result<Rat, NormError> {
    if let Some(r) = super::denest::denest(u, s)? {
        return Ok(r);
    }
    root(u, 2, s)
}

/// The principal `n`-th root (`n ≥ 2`); negative radicands only for odd `n`.
pub fn root(u: &Rat, n: u32, s: &Assumptions) -> Result<Rat, NormError> {
    if u.is_zero() {
        return Ok(Rat::zero());
    }
    if n == 1 {
        return Ok(u.clone());
    }
    if u.den().is_one() {
        return root_poly(u.num(), n, s);
    }
    // root(p/q) = root(p·q^(n−1)) / |q| for even n; an odd root is an odd function,
    // so there root(p/q) = root(p·q^(n−1)) / q.
    let q = u.den();
    let p = u.num().mul(&q.pow(u64::from(n - 1))?)?;
    let top = root_poly(&p, n, s)?;
    let q = Rat::poly(q.clone())?;
    let bottom = if n % 2 == 0 { abs(&q, s)? } else { q };
    top.div(&bottom)
}

fn root_poly(p: &Poly, n: u32, s: &Assumptions) -> Result<Rat, NormError> {
    let sign = s.poly(p);
    let even = n % 2 == 0;
    if even && sign == Sign::Neg {
        return Err(NormError::Domain(format!(
            "the square root{} of a negative quantity is not real",
            if n == 2 { "" } else { " (even root)" }
        )));
    }
    // Constant factor: c = a/b, root(c) = root(a·b^(n−1))/b.
    let c = p.content();
    let neg = p.lead().is_some_and(|t| t.1.is_negative());
    let rest = p
        .scale(&c.recip())
        .scale(&if neg { -Q::one() } else { Q::one() });
    let (a, b) = (c.numer().magnitude().clone(), c.denom().magnitude().clone());
    let radicand = &a * num_traits::pow(b.clone(), (n - 1) as usize);
    let (k, factors) = split_power(&radicand, n);
    let mut out = Rat::constant(Q::new(BigInt::from(k), BigInt::from(b)));
    for (f, e) in factors {
        // A positive number: root_n(f^e) = root_(n/g)(f^(e/g)), g = gcd(e, n) (9^(1/4) = sqrt(3)).
        let g = e.gcd(&n);
        let base = Poly::constant(q_of(num_traits::pow(f, (e / g) as usize)));
        out = out.mul(&Rat::atom(root_atom(base, n / g)))?;
    }
    // Monomial factors: a^e = a^(n·(e/n)) · a^(e mod n).
    let mc = rest.mono_content();
    let rest = rest.div_mono(&mc).unwrap_or(rest);
    let mut inside = Vec::new();
    for &(a, e) in mc.pairs() {
        let outside = e / n;
        if outside > 0 {
            let ar = Rat::atom(a);
            let f = if even {
                abs(&ar, s)?.powi(i64::from(outside))?
            } else {
                ar.powi(i64::from(outside))?
            };
            out = out.mul(&f)?;
        }
        if e % n > 0 {
            match split_root(a, e % n, n, s)? {
                Some(f) => out = out.mul(&f)?,
                None => inside.push((a, e % n)),
            }
        }
    }
    let inside = Mono::from_pairs(inside).ok_or(Limit::Exponent)?;
    // The sum: over its squarefree parts, each power taken out or kept in the same way.
    let rest = if rest.len() > 1 && !rest.is_one() {
        let (outside, kept) = root_of_parts(&rest, n, s)?;
        out = out.mul(&outside)?;
        kept
    } else {
        rest
    };
    let mut radicand = rest.mul_term(&inside, &Q::one())?;
    if neg {
        if even {
            radicand = radicand.neg();
        } else {
            out = out.neg();
        }
    }
    if radicand.is_one() {
        return Ok(out);
    }
    // A whole polynomial that is a perfect square.
    if n == 2 && radicand.len() > 1 {
        if let Some(r) = poly_sqrt(&radicand)? {
            return out.mul(&abs(&Rat::poly(r)?, s)?);
        }
        // 1 − sin(u)² is cos(u)², which the rules keep as 1 − sin(u)².
        if let Some(u) = one_minus_sin_squared(&radicand) {
            return out.mul(&abs(&super::trig::cos(&u)?, s)?);
        }
    }
    out.mul(&Rat::atom(root_atom(radicand, n)))
}

/// The `n`-th root of a primitive sum `p = ∏ sᵢ^i` (its squarefree parts): the factors
/// that come out, and the part that stays under the root. `sᵢ^i = sᵢ^(n·q) · sᵢ^r`: the
/// first comes out as `|sᵢ|^q` (`sᵢ^q` for odd `n` or `sᵢ ≥ 0`); the second is a root of
/// its own where [`part_root`] allows, else it stays inside.
fn root_of_parts(p: &Poly, n: u32, s: &Assumptions) -> Result<(Rat, Poly), NormError> {
    let parts = super::gcd::squarefree(p)?;
    if parts.len() == 1 && parts[0].1 == 1 {
        return Ok((Rat::one(), p.clone()));
    }
    let mut out = Rat::one();
    let mut kept = Poly::one();
    for (part, i) in parts {
        let sign = s.poly(&part);
        let (q, r) = (i / n, i % n);
        if q > 0 {
            let base = Rat::poly(part.clone())?;
            let f = if n % 2 == 0 && !matches!(sign, Sign::Pos | Sign::NonNeg) {
                abs(&base, s)?
            } else {
                base
            };
            out = out.mul(&f.powi(i64::from(q))?)?;
        }
        if r > 0 {
            match part_root(&part, sign, r, n, s)? {
                Some(f) => out = out.mul(&f)?,
                None => kept = kept.mul(&part.pow(u64::from(r))?)?,
            }
        }
    }
    Ok((out, kept))
}

/// `root_n(b^r)` (`0 < r < n`) as a factor of its own, reduced by `g = gcd(r, n)` to
/// `root_(n/g)(b^(r/g))`, where that is an identity wherever both sides are defined: odd
/// roots are multiplicative; for even `n`, `b ≥ 0` may split off, and so may an even
/// power, as `|b|^r`. `None`: nothing to gain (or not allowed); it stays inside.
fn part_root(
    b: &Poly,
    sign: Sign,
    r: u32,
    n: u32,
    s: &Assumptions,
) -> Result<Option<Rat>, NormError> {
    let g = r.gcd(&n);
    let nonneg = matches!(sign, Sign::Pos | Sign::NonNeg);
    if g == 1 {
        // Already in lowest terms: a root of its own only where it may split off.
        if !nonneg {
            return Ok(None);
        }
        // root_n(b^r) = root_n(b)^r for b ≥ 0: one form for `b^(r/n)` however written.
        return Ok(Some(Rat::atom(root_atom(b.clone(), n)).powi(i64::from(r))?));
    }
    // g > 1: the index and the exponent both shrink, so the recursion ends.
    let b = Rat::poly(b.clone())?;
    if n % 2 == 1 || nonneg {
        return root(&b.powi(i64::from(r / g))?, n / g, s).map(Some);
    }
    if r % 2 == 0 {
        return root(&abs(&b, s)?.powi(i64::from(r / g))?, n / g, s).map(Some);
    }
    Ok(None)
}

/// The `n`-th root of `a^e` (`0 < e < n`) as a factor of its own, where that is an
/// identity wherever both sides are defined: a root of a root is one root
/// (`sqrt(sqrt(x)) = x^(1/4)`), an odd root is multiplicative, and an even root of a
/// product splits off the factors the signs show nonnegative (`sqrt(a b) = sqrt(a)
/// sqrt(b)` for `a, b >= 0`). `None`: it stays inside the radicand.
fn split_root(a: atom::AtomId, e: u32, n: u32, s: &Assumptions) -> Result<Option<Rat>, NormError> {
    let inner = match atom::get(a) {
        Atom::Sqrt(p) => Some((p.clone(), 2)),
        Atom::Root(p, m) => Some((p.clone(), *m)),
        // exp(u)^(e/n) = exp(e u/n): exp is positive.
        Atom::Exp(u) => {
            return exp(&u.scale(&Q::new(BigInt::from(e), BigInt::from(n)))).map(Some);
        }
        _ => None,
    };
    if let Some((p, m)) = inner {
        // root_n(root_m(p)^e) = root_nm(p^e): both need p >= 0 when either index is
        // even (and root_m(p)^e >= 0), and agree there; for odd indices, everywhere.
        // Taken out of an even root as a factor of its own, root_m(p)^e must be ≥ 0 on
        // its own: so for an odd inner index, an even power or a p the signs show ≥ 0
        // (sqrt(y cbrt(y)) is defined for y < 0, sqrt(y) root_6(y) is not).
        let own_sign = m % 2 == 0
            || n % 2 == 1
            || e % 2 == 0
            || matches!(s.poly(&p), Sign::Pos | Sign::NonNeg);
        if n * m <= 64 && own_sign {
            let radicand = Rat::poly(p)?.powi(i64::from(e))?;
            return root(&radicand, n * m, s).map(Some);
        }
    }
    let g = e.gcd(&n);
    let nonneg = matches!(s.atom(a), Sign::Pos | Sign::NonNeg);
    if g > 1 && (n % 2 == 1 || nonneg || e % 2 == 0) {
        // root_n(a^e) = root_(n/g)(a^(e/g)), through |a| for an even power under an even
        // root (`(x^2)^(1/4) = sqrt(abs(x))`).
        return part_root(&Poly::atom(a), s.atom(a), e, n, s);
    }
    if n % 2 == 1 || nonneg {
        // root_n(a^e) = root_n(a)^e (odd roots for every sign, even ones for a ≥ 0): one
        // form for `a^(e/n)` however written.
        return Ok(Some(
            Rat::atom(root_atom(Poly::atom(a), n)).powi(i64::from(e))?,
        ));
    }
    Ok(None)
}

/// `u` when `p` is `1 − sin(u)²`.
pub(super) fn one_minus_sin_squared(p: &Poly) -> Option<Rat> {
    let [(m1, c1), (m2, c2)] = p.terms() else {
        return None;
    };
    let sq = match (m1.pairs(), m2.pairs()) {
        ([(a, 2)], []) if c1 == &-Q::one() && c2.is_one() => *a,
        ([], [(a, 2)]) if c2 == &-Q::one() && c1.is_one() => *a,
        _ => return None,
    };
    match atom::get(sq) {
        Atom::Sin(u) => Some(u.clone()),
        _ => None,
    }
}

fn root_atom(p: Poly, n: u32) -> atom::AtomId {
    if n == 2 {
        atom::intern(Atom::Sqrt(p))
    } else {
        atom::intern(Atom::Root(p, n))
    }
}

/// `r` with `r² = p`, if `p` is the square of a polynomial.
pub fn poly_sqrt(p: &Poly) -> Result<Option<Poly>, Limit> {
    let Some((lm, lc)) = p.lead().cloned() else {
        return Ok(Some(Poly::zero()));
    };
    let Some(rc) = rational_sqrt(&lc) else {
        return Ok(None);
    };
    let pairs: Option<Vec<_>> = lm
        .pairs()
        .iter()
        .map(|&(a, e)| (e % 2 == 0).then_some((a, e / 2)))
        .collect();
    let Some(pairs) = pairs else {
        return Ok(None);
    };
    let Some(rm) = Mono::from_pairs(pairs) else {
        return Ok(None);
    };
    let lead_r = (rm, rc);
    let mut r = Poly::term(lead_r.0.clone(), lead_r.1.clone());
    let two_lead = Poly::term(lead_r.0.clone(), &lead_r.1 * Q::from_integer(2.into()));
    for _ in 0..=p.len() {
        let rem = p.sub(&r.mul(&r)?);
        let Some((m, c)) = rem.lead().cloned() else {
            return Ok(Some(r));
        };
        let Some((tm, tc)) = two_lead.lead().cloned() else {
            return Ok(None);
        };
        let Some(qm) = m.div(&tm) else {
            return Ok(None);
        };
        if qm >= lead_r.0 {
            return Ok(None);
        }
        r = r.add(&Poly::term(qm, c / tc));
    }
    Ok(None)
}

fn rational_sqrt(q: &Q) -> Option<Q> {
    if q.is_negative() {
        return None;
    }
    let (n, d) = (q.numer().magnitude(), q.denom().magnitude());
    let (rn, rd) = (n.sqrt(), d.sqrt());
    (&rn * &rn == *n && &rd * &rd == *d).then(|| Q::new(BigInt::from(rn), BigInt::from(rd)))
}

/// `abs(u)`, resolved where the signs decide it.
pub fn abs(u: &Rat, s: &Assumptions) -> Result<Rat, NormError> {
    match s.rat(u) {
        Sign::Pos | Sign::NonNeg | Sign::Zero => return Ok(u.clone()),
        Sign::Neg | Sign::NonPos => return Ok(u.neg()),
        _ => {}
    }
    let n = abs_poly(u.num(), s)?;
    if u.den().is_one() {
        return Ok(n);
    }
    n.div(&abs_poly(u.den(), s)?)
}

fn abs_poly(p: &Poly, s: &Assumptions) -> Result<Rat, NormError> {
    match s.poly(p) {
        Sign::Pos | Sign::NonNeg | Sign::Zero => return Rat::poly(p.clone()),
        Sign::Neg | Sign::NonPos => return Rat::poly(p.neg()),
        _ => {}
    }
    let c = p.content();
    let prim = p.primitive();
    let mc = prim.mono_content();
    let rest = prim.div_mono(&mc).unwrap_or(prim);
    let mut out = Rat::constant(c);
    for &(a, e) in mc.pairs() {
        let ar = Rat::atom(a);
        let f = match s.atom(a) {
            Sign::Pos | Sign::NonNeg => ar.powi(i64::from(e))?,
            Sign::Neg | Sign::NonPos => ar.neg().powi(i64::from(e))?,
            _ if e % 2 == 0 => ar.powi(i64::from(e))?,
            _ => ar
                .powi(i64::from(e - 1))?
                .mul(&Rat::atom(atom::intern(Atom::Abs(Poly::atom(a)))))?,
        };
        out = out.mul(&f)?;
    }
    if rest.is_one() {
        return Ok(out);
    }
    match s.poly(&rest) {
        Sign::Pos | Sign::NonNeg => return out.mul(&Rat::poly(rest)?),
        Sign::Neg | Sign::NonPos => return out.mul(&Rat::poly(rest.neg())?),
        _ => {}
    }
    // |∏ sᵢ^i| over the squarefree parts: even powers and parts of known sign come out;
    // the parts of odd power and unknown sign stay in one abs.
    let mut inside = Poly::one();
    for (part, i) in super::gcd::squarefree(&rest)? {
        let sign = s.poly(&part);
        let odd =
            i % 2 == 1 && !matches!(sign, Sign::Pos | Sign::NonNeg | Sign::Neg | Sign::NonPos);
        let e = if odd { i - 1 } else { i };
        let mut f = part.pow(u64::from(e))?;
        if matches!(sign, Sign::Neg | Sign::NonPos) && e % 2 == 1 {
            f = f.neg();
        }
        out = out.mul(&Rat::poly(f)?)?;
        if odd {
            inside = inside.mul(&part)?;
        }
    }
    if inside.is_one() {
        return Ok(out);
    }
    out.mul(&Rat::atom(atom::intern(Atom::Abs(inside))))
}

/// `exp(u)`: `exp(0) = 1`, `exp(k·ln(v)) = v^k`, otherwise one exponential atom.
pub fn exp(u: &Rat) -> Result<Rat, NormError> {
    if u.is_zero() {
        return Ok(Rat::one());
    }
    let mut out = Rat::one();
    let mut arg = u.clone();
    if u.den().is_one() {
        let mut rest = Vec::new();
        for (m, q) in u.num().terms() {
            let ln_of = match m.pairs() {
                [(a, 1)] => match atom::get(*a) {
                    Atom::Ln(v) => Some(v.clone()),
                    _ => None,
                },
                _ => None,
            };
            match (ln_of, q.is_integer()) {
                (Some(v), true) => {
                    let k = q.to_integer().to_i64().ok_or(Limit::Exponent)?;
                    out = out.mul(&v.powi(k)?)?;
                }
                // exp((p/n) ln v) = (v^(1/n))^p: v > 0 wherever ln v is defined, so the
                // principal root is the value.
                (Some(v), false) if q.denom().to_u32().is_some_and(|n| n <= 64) => {
                    let n = q.denom().to_u32().unwrap_or(2);
                    let k = q.numer().to_i64().ok_or(Limit::Exponent)?;
                    let r = root(&v, n, &Assumptions::default())?;
                    out = out.mul(&int_pow(&r, k)?)?;
                }
                _ => rest.push((m.clone(), q.clone())),
            }
        }
        arg = Rat::poly(Poly::from_terms(rest))?;
    }
    if arg.is_zero() {
        return Ok(out);
    }
    out.mul(&Rat::atom(atom::intern(Atom::Exp(arg))))
}

/// `ln(u)`: `ln(exp(v)) = v`; products split only where the signs make every factor positive.
pub fn ln(u: &Rat, s: &Assumptions) -> Result<Rat, NormError> {
    match s.rat(u) {
        Sign::Neg | Sign::NonPos | Sign::Zero => {
            return Err(NormError::Domain(
                "ln of a quantity that is not positive".into(),
            ))
        }
        _ => {}
    }
    if let Some(q) = u.as_constant() {
        return ln_rational(&q);
    }
    // ln(P·L) = ln(P) + ln(L) where P·L > 0 and P > 0. P collects what is positive
    // (the constant's size, atoms and factors the signs show positive) and even powers,
    // as |a|^(2k) = a^(2k) (`ln(x^2) = 2 ln(abs(x))`); the rest, L, stays one logarithm.
    // Nothing is replaced by its absolute value where the two differ, so exp(ln(x)) is
    // still x.
    let mut out = Rat::zero();
    let mut leftover = [Poly::one(), Poly::one()];
    for (k, (p, sgn)) in [(u.num(), 1i64), (u.den(), -1i64)].into_iter().enumerate() {
        if p.is_one() {
            continue;
        }
        let scale = |r: Rat, m: i64| r.scale(&Q::from_integer(BigInt::from(sgn * m)));
        let c = p.content();
        out = out.add(&scale(ln_rational(&c.abs())?, 1))?;
        let mut left = Poly::constant(if c.is_negative() { -Q::one() } else { Q::one() });
        let prim = p
            .scale(&c.recip())
            .scale(&if c.is_negative() { -Q::one() } else { Q::one() });
        let mc = prim.mono_content();
        let rest = prim.div_mono(&mc).unwrap_or(prim.clone());
        for &(a, e) in mc.pairs() {
            let ar = Rat::atom(a);
            if s.atom(a) == Sign::Pos {
                out = out.add(&scale(ln_abs(&ar, s)?, i64::from(e)))?;
                continue;
            }
            if e >= 2 {
                out = out.add(&scale(ln_abs(&ar, s)?, i64::from(e - e % 2)))?;
            }
            if e % 2 == 1 {
                left = left.mul(&Poly::atom(a))?;
            }
        }
        // The sum, over its squarefree parts, like the atoms above:
        // ln((a + 1)^2) = 2 ln(a + 1) for a > 0, ln((x + 1)^2) = 2 ln(abs(x + 1)).
        // The parts have positive leading coefficients: their product is ±rest.
        // ±(1 − sin(u)²) is ±cos(u)², which the rules keep as 1 − sin(u)²: an even power.
        let cos_sq = match (
            one_minus_sin_squared(&rest),
            one_minus_sin_squared(&rest.neg()),
        ) {
            (Some(u), _) => Some((u, false)),
            (None, Some(u)) => Some((u, true)),
            _ => None,
        };
        if let Some((u, negated)) = cos_sq {
            if negated {
                left = left.neg();
            }
            out = out.add(&scale(ln_abs(&super::trig::cos(&u)?, s)?, 2))?;
            leftover[k] = left;
            continue;
        }
        if rest.lead().is_some_and(|t| t.1.is_negative()) {
            left = left.neg();
        }
        let parts = if rest.len() > 1 {
            super::gcd::squarefree(&rest)?
        } else {
            Vec::new()
        };
        for (part, i) in parts {
            let pr = Rat::poly(part.clone())?;
            if s.poly(&part) == Sign::Pos {
                out = out.add(&scale(ln_abs(&pr, s)?, i64::from(i)))?;
                continue;
            }
            if i >= 2 {
                out = out.add(&scale(ln_abs(&pr, s)?, i64::from(i - i % 2)))?;
            }
            if i % 2 == 1 {
                left = left.mul(&part)?;
            }
        }
        leftover[k] = left;
    }
    let [num, den] = leftover;
    let v = Rat::new(num, den)?;
    if v != Rat::one() {
        let l = match v.as_atom().map(atom::get) {
            Some(Atom::Exp(w)) => w.clone(),
            _ => Rat::atom(atom::intern(Atom::Ln(v))),
        };
        out = out.add(&l)?;
    }
    Ok(out)
}

/// `ln(abs(v))` for an atom or a primitive polynomial `v`, one atom: `ln(v)` where the
/// signs show `v > 0`, `ln(-v)` where `v < 0`, otherwise `ln(abs(v))`; `ln(exp(w)) = w`.
fn ln_abs(v: &Rat, s: &Assumptions) -> Result<Rat, NormError> {
    if let Some(a) = v.as_atom() {
        match atom::get(a) {
            Atom::Exp(w) => return Ok(w.clone()),
            // |p^(1/n)| = |p|^(1/n) for the principal root (real: p ≥ 0 for even n), so
            // ln|p^(1/n)| = ln|p|/n wherever the root is not zero.
            Atom::Sqrt(p) | Atom::Root(p, _) => {
                let n = match atom::get(a) {
                    Atom::Root(_, n) => i64::from(*n),
                    _ => 2,
                };
                let p = Rat::poly(p.clone())?;
                let l = ln(&abs(&p, s)?, s)?;
                return Ok(l.scale(&Q::new(BigInt::one(), BigInt::from(n))));
            }
            _ => {}
        }
    }
    let arg = abs(v, s)?;
    Ok(Rat::atom(atom::intern(Atom::Ln(arg))))
}

/// `ln(q)` for a positive rational: a sum over its prime factors.
fn ln_rational(q: &Q) -> Result<Rat, NormError> {
    if !q.is_positive() {
        return Err(NormError::Domain(
            "ln of a number that is not positive".into(),
        ));
    }
    let mut out = Rat::zero();
    for (n, sgn) in [(q.numer(), 1i64), (q.denom(), -1i64)] {
        let mag = n.magnitude();
        if mag.is_one() {
            continue;
        }
        // split_power with a huge root gives the plain factorisation.
        let (_, factors) = split_power(mag, u32::MAX);
        for (p, e) in factors {
            let l = Rat::atom(atom::intern(Atom::Ln(Rat::constant(q_of(p)))));
            out = out.add(&l.scale(&Q::from_integer((sgn * i64::from(e)).into())))?;
        }
    }
    Ok(out)
}

/// `base^exponent` for any exponent: integers exactly, rationals as roots,
/// symbolic exponents as `exp(e·ln(b))` when `b > 0`, else an opaque power.
pub fn pow(base: &Rat, exponent: &Rat, s: &Assumptions) -> Result<Rat, NormError> {
    if let Some(e) = exponent.as_constant() {
        // 0, 1 and −1 to any power are exact whatever its size.
        if let Some(b) = base.as_constant() {
            if e.is_integer() && (b.is_zero() || b.abs().is_one()) {
                if b.is_zero() {
                    return if e.is_positive() {
                        Ok(Rat::zero())
                    } else {
                        Err(NormError::DivisionByZero)
                    };
                }
                let odd = e.to_integer().is_odd();
                return Ok(if b.is_negative() && odd {
                    Rat::int(-1)
                } else {
                    Rat::one()
                });
            }
        }
        if e.is_integer() {
            let k = e.to_integer().to_i64().ok_or(Limit::Exponent)?;
            return int_pow(base, k);
        }
        let (p, q) = (e.numer().clone(), e.denom().clone());
        let q = q.to_u32().filter(|q| *q <= 64).ok_or(Limit::RootIndex)?;
        let p = p.to_i64().ok_or(Limit::Exponent)?;
        let r = root(base, q, s)?;
        return int_pow(&r, p);
    }
    if base.is_zero() {
        return Err(NormError::Domain("0 to a symbolic power".into()));
    }
    if s.rat(base) == Sign::Pos {
        let l = ln(base, s)?;
        return exp(&l.mul(exponent)?);
    }
    Ok(Rat::atom(atom::intern(Atom::Pow(
        base.clone(),
        exponent.clone(),
    ))))
}

/// An integer power; a large power of a sum is kept factored ([`super::power`]), and a
/// sum too large to expand becomes an opaque power atom.
pub fn int_pow(base: &Rat, k: i64) -> Result<Rat, NormError> {
    if let Some(kept) = super::power::keep(base, k) {
        return kept;
    }
    match base.powi(k) {
        Err(NormError::Limit(Limit::Terms(_))) if k > 0 => Ok(Rat::atom(atom::intern(Atom::Pow(
            base.clone(),
            Rat::int(k),
        )))),
        r => r,
    }
}
