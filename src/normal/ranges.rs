//! Signs that a declared interval fixes: `sin`, `cos` (and so `tan`) of `c·β + d` for a
//! symbol `β` declared in an interval whose bounds are numbers or rational multiples of
//! `π` (`symbols 0 < beta < pi/2` makes `sin(beta)`, `cos(beta)`, `sin(2 beta)` positive
//! and `cos(pi - beta)` negative), or symbols declared in intervals of their own
//! (`0 < del < gam` with `0 < gam < pi/2` makes `sin(del)` positive).

use super::atom::{self, Atom, AtomId};
use super::poly::Q;
use super::rat::Rat;
use super::sign::{Assumptions, Sign};
use crate::interval::{Interval, Prec};
use num_bigint::BigInt;
use num_traits::{One, Signed, Zero};

/// `r` as `p + q·π` with rational `p`, `q`, if it is one.
fn pi_form(r: &Rat) -> Option<(Q, Q)> {
    if !r.den().is_one() {
        return None;
    }
    let (mut p, mut q) = (Q::zero(), Q::zero());
    for (m, c) in r.num().terms() {
        match m.pairs() {
            [] => p = c.clone(),
            [(a, 1)] if matches!(atom::get(*a), Atom::Pi) => q = c.clone(),
            _ => return None,
        }
    }
    Some((p, q))
}

/// `u` as `c·β + (p + q·π)` for one symbol `β`, if it is one.
fn linear(u: &Rat) -> Option<(AtomId, Q, Q, Q)> {
    if !u.den().is_one() {
        return None;
    }
    let (mut sym, mut c) = (None, Q::zero());
    let (mut p, mut q) = (Q::zero(), Q::zero());
    for (m, k) in u.num().terms() {
        match m.pairs() {
            [] => p = k.clone(),
            [(a, 1)] if matches!(atom::get(*a), Atom::Pi) => q = k.clone(),
            [(a, 1)] if atom::sym_name(*a).is_some() && sym.is_none() => {
                sym = Some(*a);
                c = k.clone();
            }
            _ => return None,
        }
    }
    Some((sym?, c, p, q))
}

/// How many symbols deep a bound is followed (`0 < del < gam`, `0 < gam < pi/2`).
const BOUND_DEPTH: u32 = 4;

/// A bound of a declared interval as `p + q·π`: itself when it is one, else, for a
/// bound that is a symbol declared in an interval of its own, that interval's upper
/// (for `upper`) or lower end, followed up to `depth` symbols. With whether the end is
/// reached only strictly through a symbol (`del < gam < pi/2` gives `del < pi/2`).
fn bound(s: &Assumptions, r: &Rat, upper: bool, depth: u32) -> Option<((Q, Q), bool)> {
    if let Some(pq) = pi_form(r) {
        return Some((pq, false));
    }
    let a = r.as_atom().filter(|a| atom::sym_name(*a).is_some())?;
    if depth == 0 {
        return None;
    }
    let range = s.range(a)?;
    let (next, strict) = if upper {
        (&range.hi, range.hi_strict)
    } else {
        (&range.lo, range.lo_strict)
    };
    let (pq, wider) = bound(s, next, upper, depth - 1)?;
    Some((pq, strict || wider))
}

/// `(p + q·π)/π` as an enclosure, exact when `p = 0`.
fn in_pi_units(p: &Q, q: &Q) -> Option<Interval> {
    if p.is_zero() {
        return Some(Interval::point(q.clone()));
    }
    let prec = Prec::new(96);
    Interval::point(p.clone())
        .div(&Interval::pi(prec)?, prec)?
        .add(&Interval::point(q.clone()), prec)
}

/// The sign of `sin(u)` (or, with `cos`, of `cos(u)`) that the declared intervals fix.
pub(super) fn trig_sign(s: &Assumptions, u: &Rat, cos: bool) -> Sign {
    trig_sign_opt(s, u, cos).unwrap_or(Sign::Unknown)
}

fn trig_sign_opt(s: &Assumptions, u: &Rat, cos: bool) -> Option<Sign> {
    // The argument's interval, in units of π: [lo, hi], each end with whether it is
    // excluded.
    let ((lo, lo_open), (hi, hi_open)) = match pi_form(u) {
        Some((p, q)) => {
            let x = in_pi_units(&p, &q)?;
            ((x.clone(), false), (x, false))
        }
        None => {
            let (b, c, p, q) = linear(u)?;
            let r = s.range(b)?;
            let ((lp, lq), lo_wider) = bound(s, &r.lo, false, BOUND_DEPTH)?;
            let ((hp, hq), hi_wider) = bound(s, &r.hi, true, BOUND_DEPTH)?;
            let end = |bp: &Q, bq: &Q| in_pi_units(&(&c * bp + &p), &(&c * bq + &q));
            let (a, z) = (
                (end(&lp, &lq)?, r.lo_strict || lo_wider),
                (end(&hp, &hq)?, r.hi_strict || hi_wider),
            );
            if c.is_negative() {
                (z, a)
            } else {
                (a, z)
            }
        }
    };
    // cos(x) = sin(x + π/2).
    let half = Interval::point(Q::new(BigInt::one(), BigInt::from(2)));
    let shift = |x: Interval| {
        if cos {
            x.add(&half, Prec::new(96))
        } else {
            Some(x)
        }
    };
    let (lo, hi) = (shift(lo)?, shift(hi)?);
    // sin has one sign on (kπ, (k+1)π).
    let k = lo.lo().floor();
    if hi.hi() > &(&k + Q::one()) {
        return None;
    }
    let exact = |x: &Interval, at: &Q| x.lo() == at && x.hi() == at;
    let zero_at_lo = exact(&lo, &k) && !lo_open;
    let zero_at_hi = exact(&hi, &(&k + Q::one())) && !hi_open;
    // An empty or one-point interval at a zero of sin.
    if exact(&lo, &k) && exact(&hi, &k) {
        return Some(if lo_open || hi_open {
            Sign::Unknown
        } else {
            Sign::Zero
        });
    }
    let even = (k.to_integer() % BigInt::from(2)).is_zero();
    Some(match (even, zero_at_lo || zero_at_hi) {
        (true, false) => Sign::Pos,
        (true, true) => Sign::NonNeg,
        (false, false) => Sign::Neg,
        (false, true) => Sign::NonPos,
    })
}

/// A value to try for a symbol, as its declaration allows.
#[derive(Clone, Debug, PartialEq)]
pub enum Sample {
    /// No interval is declared: any value of the declared sign.
    Free,
    /// A value strictly inside the declared interval.
    At(Q),
    /// An interval is declared whose bounds are not numbers or multiples of π (they are
    /// symbols): no value can be chosen without knowing them.
    Unusable,
}

/// The value the fraction `t` (in (0, 1)) of the way through the declared interval of `a`.
pub fn sample(s: &Assumptions, a: AtomId, t: &Q) -> Sample {
    let Some(r) = s.range(a) else {
        return Sample::Free;
    };
    let prec = Prec::new(96);
    let enclose = |b: &Rat| -> Option<Interval> {
        let (p, q) = pi_form(b)?;
        if q.is_zero() {
            return Some(Interval::point(p));
        }
        Interval::point(q)
            .mul(&Interval::pi(prec)?, prec)?
            .add(&Interval::point(p), prec)
    };
    let (Some(lo), Some(hi)) = (enclose(&r.lo), enclose(&r.hi)) else {
        return Sample::Unusable;
    };
    let (lo, hi) = (lo.hi().clone(), hi.lo().clone());
    if lo >= hi {
        return Sample::Unusable;
    }
    Sample::At(&lo + t * (&hi - &lo))
}

/// Whether the region the declarations allow for the symbols `syms` (and, through their
/// bounds, the symbols those mention) is known to have interior: each declared interval
/// has bounds whose difference the declared signs show positive (`0 < x < L` with
/// `L > 0`), or numeric bounds that enclosures show apart. Only then is a nonzero
/// rational function nonzero somewhere in it: on a one-point interval (`1 <= x <= 1`),
/// or between bounds nobody can compare, `x - 1` may vanish on all of it.
pub fn have_interior(s: &Assumptions, syms: &[AtomId]) -> bool {
    let mut todo: Vec<AtomId> = syms.to_vec();
    let mut seen: Vec<AtomId> = Vec::new();
    let half = Q::new(BigInt::one(), BigInt::from(2));
    while let Some(a) = todo.pop() {
        if seen.contains(&a) {
            continue;
        }
        seen.push(a);
        let Some(r) = s.range(a) else {
            continue;
        };
        let apart = r.hi.sub(&r.lo).is_ok_and(|d| s.rat(&d) == Sign::Pos)
            || matches!(sample(s, a, &half), Sample::At(_));
        if !apart {
            return false;
        }
        crate::decide::symbols_in(&r.lo, &mut todo);
        crate::decide::symbols_in(&r.hi, &mut todo);
    }
    true
}
