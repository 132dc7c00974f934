//! Exact integration: polynomials in the variable (coefficients any normal form), and
//! polynomials times a sine, cosine or exponential of an argument linear in the variable.

use crate::normal::atom::{self, Atom, AtomId};
use crate::normal::mono::Mono;
use crate::normal::subst::{atom_depends_on, depends_on, subst_atom, subst_atom_owned};
use crate::normal::{func, trig, Assumptions, NormError, Poly, Rat, Q};
use num_bigint::BigInt;
use num_traits::One;
use std::fmt;

/// Why an integral could not be computed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum IntError {
    /// The integrand is outside what rigor integrates; the text says what it is.
    Unsupported(String),
    /// An integral over time of a quantity that depends on time in a way rigor has no
    /// antiderivative for; the text names the term.
    Time(String),
    /// An error of the normal form.
    Norm(NormError),
}

impl From<NormError> for IntError {
    fn from(e: NormError) -> IntError {
        IntError::Norm(e)
    }
}

impl From<crate::normal::Limit> for IntError {
    fn from(e: crate::normal::Limit) -> IntError {
        IntError::Norm(e.into())
    }
}

impl fmt::Display for IntError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            IntError::Unsupported(s) => write!(
                f,
                "{s}; rigor integrates polynomials in the variable, times at most a sin, cos or exp of an argument linear in it"
            ),
            IntError::Time(s) => write!(
                f,
                "{s}; over t, rigor integrates c·x' to c·x and c·x^n·x' to c·x^(n+1)/(n+1) for a `time` symbol x and its derivatives, and never treats a `time` symbol as a constant"
            ),
            IntError::Norm(e) => write!(f, "{e}"),
        }
    }
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Kind {
    Cos,
    Sin,
    Exp,
}

/// `∫ f dx` with constant of integration 0.
pub fn antiderivative(f: &Rat, x: AtomId, s: &Assumptions) -> Result<Rat, IntError> {
    let name = atom::sym_name(x).unwrap_or_default();
    // Large powers of sums kept factored are integrated written out.
    let expanded;
    let f = if crate::normal::power::has_kept(f) {
        expanded = crate::normal::power::expand(f, s)?;
        &expanded
    } else {
        f
    };
    if depends_on(&Rat::poly(f.den().clone())?, x) {
        return Err(IntError::Unsupported(format!(
            "the integrand is not a polynomial in {name} (its denominator depends on {name})"
        )));
    }
    if let Some(p) = polynomial_antiderivative(f, x) {
        let p = Rat::poly(p)?;
        if f.den().is_one() {
            return Ok(p);
        }
        return Ok(p.div(&Rat::poly(f.den().clone())?)?);
    }
    let den = Rat::poly(f.den().clone())?;
    let mut total = Rat::zero();
    // Group the numerator's terms by their factor that depends on x other than x itself.
    for (m, q) in f.num().terms() {
        let mut k = 0u32;
        let mut rest = Vec::new();
        let mut dep = Vec::new();
        for &(a, e) in m.pairs() {
            if a == x {
                k = e;
            } else if atom_depends_on(a, x) {
                dep.push((a, e));
            } else {
                rest.push((a, e));
            }
        }
        let rest = Mono::from_pairs(rest).ok_or(crate::normal::Limit::Exponent)?;
        let coeff = Rat::poly(Poly::term(rest, q.clone()))?;
        let part = if dep.is_empty() {
            let p = Rat::atom(x).powi(i64::from(k) + 1)?;
            p.scale(&Q::new(BigInt::one(), BigInt::from(u64::from(k) + 1)))
        } else {
            integrate_special(k, &dep, x, &name, s)?
        };
        total = total.add(&coeff.mul(&part)?)?;
    }
    Ok(total.div(&den)?)
}

/// [`antiderivative`] of an integrand the caller gives up: a polynomial in which `x`
/// occurs only as itself is integrated where it is, each term's monomial and coefficient
/// replaced in place (the fast path of the borrowed one, with no copy).
pub fn antiderivative_owned(f: Rat, x: AtomId, s: &Assumptions) -> Result<Rat, IntError> {
    let in_place = f.den().is_one()
        && !crate::normal::power::has_kept(&f)
        && only_itself(f.num(), x)
        && f.num().degree_in(x) < u32::MAX;
    if !in_place {
        return antiderivative(&f, x, s);
    }
    let mut terms = f.into_parts().0.into_terms();
    let mut inverses: Vec<Q> = Vec::new();
    for (m, q) in &mut terms {
        // Every exponent of `x` is below u32::MAX: the product cannot overflow.
        let k = m.mul_by_atom(x).ok_or(crate::normal::Limit::Exponent)?;
        *q = over_k_plus_one(q, k, &mut inverses);
    }
    // Every term was multiplied by `x` (and a constant): the order is kept.
    Ok(Rat::poly(Poly::from_sorted_terms(terms))?)
}

/// Whether nothing but `x` itself depends on `x` in `p`.
fn only_itself(p: &Poly, x: AtomId) -> bool {
    !p.atoms().iter().any(|&a| a != x && atom_depends_on(a, x))
}

/// `q/(k + 1)`, with `1/(k + 1)` remembered in `inverses` (by `k`) for small `k`.
fn over_k_plus_one(q: &Q, k: u32, inverses: &mut Vec<Q>) -> Q {
    let i = k as usize;
    while inverses.len() <= i.min(4096) {
        let n = inverses.len() as u64 + 1;
        inverses.push(Q::new(BigInt::one(), BigInt::from(n)));
    }
    match inverses.get(i) {
        Some(inv) => crate::normal::qops::mul(q, inv),
        None => crate::normal::qops::div(q, &Q::from_integer(BigInt::from(u64::from(k) + 1))),
    }
}

/// The fast path: when nothing but `x` itself depends on `x`, integrate term by term
/// (`x^k → x^(k+1)/(k+1)`) without leaving the polynomial ring.
///
/// Every term is multiplied by `x` (and a constant), which keeps the terms' monomial
/// order, so the result needs no sort.
fn polynomial_antiderivative(f: &Rat, x: AtomId) -> Option<Poly> {
    if !only_itself(f.num(), x) {
        return None;
    }
    let mut terms = Vec::with_capacity(f.num().len());
    // 1/(k + 1) by exponent k, computed once each.
    let mut inverses: Vec<Q> = Vec::new();
    for (m, q) in f.num().terms() {
        let (m2, k) = m.times_atom(x)?;
        terms.push((m2, over_k_plus_one(q, k, &mut inverses)));
    }
    Some(Poly::from_sorted_terms(terms))
}

/// `∫ x^k · Π dep dx` for sine, cosine and exponential factors of linear arguments.
fn integrate_special(
    k: u32,
    dep: &[(AtomId, u32)],
    x: AtomId,
    name: &str,
    s: &Assumptions,
) -> Result<Rat, IntError> {
    // Product to sum: a list of (coefficient, kind, argument).
    let mut items: Vec<(Rat, Kind, Rat)> = vec![(Rat::one(), Kind::Cos, Rat::zero())];
    let mut exp_arg: Option<Rat> = None;
    let half = Q::new(BigInt::one(), BigInt::from(2));
    for &(a, e) in dep {
        let at = atom::get(a);
        let (kind, u) = match at {
            Atom::Sin(u) => (Kind::Sin, u.clone()),
            Atom::Cos(u) => (Kind::Cos, u.clone()),
            Atom::Exp(u) => (Kind::Exp, u.clone()),
            _ => {
                return Err(IntError::Unsupported(format!(
                    "the integrand contains {} of {name}",
                    crate::normal::print::atom_plain(at)
                )))
            }
        };
        linear_slope(&u, x, name)?;
        if kind == Kind::Exp {
            if exp_arg.is_some() || e > 1 {
                return Err(IntError::Unsupported(format!(
                    "the integrand has a product of exponentials of {name}"
                )));
            }
            exp_arg = Some(u);
            continue;
        }
        for _ in 0..e {
            let mut next = Vec::new();
            for (c, kk, arg) in &items {
                let plus = arg.add(&u)?;
                let minus = arg.sub(&u)?;
                let c = c.scale(&half);
                match (kk, kind) {
                    (Kind::Cos, Kind::Cos) => {
                        next.push((c.clone(), Kind::Cos, minus));
                        next.push((c, Kind::Cos, plus));
                    }
                    (Kind::Sin, Kind::Cos) => {
                        next.push((c.clone(), Kind::Sin, plus));
                        next.push((c, Kind::Sin, minus));
                    }
                    (Kind::Cos, Kind::Sin) => {
                        next.push((c.clone(), Kind::Sin, plus));
                        next.push((c.neg(), Kind::Sin, minus));
                    }
                    (Kind::Sin, Kind::Sin) => {
                        next.push((c.clone(), Kind::Cos, minus));
                        next.push((c.neg(), Kind::Cos, plus));
                    }
                    _ => {}
                }
            }
            items = next;
            if items.len() > 4096 {
                return Err(IntError::Norm(crate::normal::Limit::terms().into()));
            }
        }
    }
    if let Some(u) = exp_arg {
        if items.len() != 1 || items.first().is_some_and(|i| !i.2.is_zero()) {
            return Err(IntError::Unsupported(format!(
                "the integrand has an exponential times a sine or cosine of {name}"
            )));
        }
        return tabular(k, Kind::Exp, &u, x, s);
    }
    let mut total = Rat::zero();
    for (c, kind, arg) in items {
        total = total.add(&c.mul(&tabular(k, kind, &arg, x, s)?)?)?;
    }
    Ok(total)
}

/// The slope ω of an argument `ω·x + φ`; an error if not linear in x.
fn linear_slope(u: &Rat, x: AtomId, name: &str) -> Result<Rat, IntError> {
    let not_linear = || {
        IntError::Unsupported(format!(
            "the argument {} is not linear in {name}",
            crate::normal::print::plain(u)
        ))
    };
    if depends_on(&Rat::poly(u.den().clone())?, x) || u.num().degree_in(x) > 1 {
        return Err(not_linear());
    }
    let mut slope = Poly::zero();
    for (e, c) in u.num().coeffs_in(x) {
        if c.atoms().iter().any(|a| atom_depends_on(*a, x)) {
            return Err(not_linear());
        }
        if e == 1 {
            slope = c;
        }
    }
    Ok(Rat::new(slope, u.den().clone())?)
}

/// `∫ x^k g(u) dx`, `u = ωx + φ`, by repeated integration by parts.
fn tabular(k: u32, kind: Kind, u: &Rat, x: AtomId, s: &Assumptions) -> Result<Rat, IntError> {
    let omega = linear_slope(u, x, "")?;
    let g = |shift: i64| -> Result<Rat, NormError> {
        match kind {
            Kind::Exp => func::exp(u),
            Kind::Sin | Kind::Cos => {
                // G_n = sin(u − nπ/2)/ωⁿ (cos alike).
                let pi = Rat::atom(atom::intern(Atom::Pi));
                let arg = u.sub(&pi.scale(&Q::new(BigInt::from(shift), BigInt::from(2))))?;
                if kind == Kind::Sin {
                    trig::sin(&arg)
                } else {
                    trig::cos(&arg)
                }
            }
        }
    };
    if omega.is_zero() {
        let p = Rat::atom(x).powi(i64::from(k) + 1)?;
        let p = p.scale(&Q::new(BigInt::one(), BigInt::from(u64::from(k) + 1)));
        return Ok(p.mul(&g(0)?)?);
    }
    let _ = s;
    let mut total = Rat::zero();
    let mut fall = Q::one(); // k!/(k−j)!
    for j in 0..=k {
        let n = i64::from(j) + 1;
        let gj = g(n)?.div(&omega.powi(n)?)?;
        let xpow = Rat::atom(x).powi(i64::from(k - j))?;
        let sign = if j % 2 == 0 { Q::one() } else { -Q::one() };
        total = total.add(&xpow.mul(&gj)?.scale(&(sign * &fall)))?;
        fall *= Q::from_integer(BigInt::from(k - j));
    }
    Ok(total)
}

/// `∫_a^b f dx`.
pub fn definite(f: &Rat, x: AtomId, a: &Rat, b: &Rat, s: &Assumptions) -> Result<Rat, IntError> {
    Ok(between_bounds(antiderivative(f, x, s)?, x, a, b, s)?)
}

/// `F(b) − F(a)` for an antiderivative `F` in `x` the caller gives up: `F` is not
/// needed after its upper value, so a bound that is a symbol is renamed into it in
/// place, and a zero lower value costs nothing. The upper value's error, if any, is
/// reported first.
pub fn between_bounds(
    big_f: Rat,
    x: AtomId,
    a: &Rat,
    b: &Rat,
    s: &Assumptions,
) -> Result<Rat, NormError> {
    let lo = subst_atom(&big_f, x, a, s);
    let hi = subst_atom_owned(big_f, x, b, s)?;
    let lo = lo?;
    if lo.is_zero() {
        return Ok(hi);
    }
    hi.sub(&lo)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::calculus::diff::{diff, Wrt};
    use crate::normal::atom::sym;
    use proptest::prelude::*;

    use crate::normal::poly::from_exponents as poly_of;

    fn terms() -> impl Strategy<Value = Vec<(Vec<u32>, i64, i64)>> {
        proptest::collection::vec(
            (proptest::collection::vec(0u32..4, 3), -6i64..7, 1i64..4),
            0..8,
        )
    }

    proptest! {
        /// Integrating an integrand given up (in place) gives what integrating a borrowed
        /// one gives, and its derivative is the integrand: for polynomials whose terms
        /// hold `x` or not, between atoms of lower and higher id, and for the cases that
        /// leave the in-place path (a denominator, `x` inside another atom).
        #[test]
        fn integrating_in_place_is_integrating(
            num in terms(),
            den in terms(),
            kind in 0usize..3,
        ) {
            // Interned in this order, so their ids are in this order too.
            let [p, x, q] = ["p", "x", "q"].map(|n| sym(&format!("integrate_test_{n}")));
            prop_assert!(p < x && x < q);
            let s = Assumptions::new();
            let num = Rat::poly(poly_of(&[p, x, q], &num)).map_err(|e| TestCaseError::fail(e.to_string()))?;
            let f = match kind {
                0 => num,
                1 => {
                    let den = poly_of(&[p, q], &den);
                    let den = if den.is_zero() { Poly::one() } else { den };
                    let Ok(f) = Rat::new(num.num().clone(), den) else { return Ok(()) };
                    f
                }
                _ => {
                    let root = crate::normal::func::sqrt(&Rat::atom(x).add(&Rat::atom(q)).unwrap_or_else(|_| Rat::zero()), &s);
                    let Ok(root) = root else { return Ok(()) };
                    num.add(&root).unwrap_or(num)
                }
            };
            let borrowed = antiderivative(&f, x, &s);
            let owned = antiderivative_owned(f.clone(), x, &s);
            prop_assert_eq!(&owned, &borrowed);
            if kind != 2 {
                let Ok(big_f) = owned else {
                    return Err(TestCaseError::fail("a polynomial over a free denominator integrates"));
                };
                let back = diff(&big_f, &Wrt { var: x, time: None }, &s);
                prop_assert_eq!(back, Ok(f));
            }
        }
    }
}
