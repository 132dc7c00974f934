//! Rigorous interval arithmetic over exact rationals with outward dyadic rounding.
//!
//! This module is used only to *prove* that two values differ (disjoint
//! enclosures) or to prove signs (an enclosure entirely above or below zero).
//! It can never establish equality. Every operation returns an enclosure that
//! is guaranteed to contain the exact mathematical result; endpoints are
//! rounded outward (lower endpoint down, upper endpoint up) to dyadic
//! rationals with a bounded number of significant bits, so sizes stay small.
//! Operations return `None` when the result is undefined (e.g. division by an
//! interval containing zero) or cannot be bounded within the size limits.
//! No floating point is used anywhere.

use foldhash::{HashMap, HashMapExt};
use num_bigint::{BigInt, BigUint};
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};
use std::cmp::Ordering;
use std::sync::Mutex;

/// Largest binary exponent (in absolute value) an endpoint may have;
/// operations whose result would exceed it return `None`.
pub const MAX_EXP: i64 = 1 << 20;
/// Largest exponent magnitude accepted by [`Interval::powi`].
pub const MAX_POWI: i64 = 1_000_000;
/// Largest argument magnitude accepted by `sin`, `cos` and `tan`.
pub const MAX_TRIG_ARG: i64 = 1 << 20;
/// Largest argument magnitude accepted by `exp`.
pub const MAX_EXP_ARG: i64 = 1 << 19;
/// Safety cap on the number of series terms.
const MAX_TERMS: u32 = 200_000;

/// Working precision: endpoints keep `bits` significant bits after every
/// operation (clamped internally to `8..=65536`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Prec {
    /// Number of significant bits kept in each endpoint.
    pub bits: u32,
}

impl Default for Prec {
    fn default() -> Self {
        Prec { bits: 96 }
    }
}

impl Prec {
    /// A precision of `bits` significant bits.
    pub const fn new(bits: u32) -> Prec {
        Prec { bits }
    }
    fn eff(self) -> u32 {
        self.bits.clamp(8, 1 << 16)
    }
    fn plus(self, extra: u32) -> Prec {
        Prec {
            bits: self.eff().saturating_add(extra),
        }
    }
}

/// A closed interval `[lo, hi]` of rationals with `lo <= hi`.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Interval {
    lo: BigRational,
    hi: BigRational,
}

fn rat(n: i64) -> BigRational {
    BigRational::from_integer(BigInt::from(n))
}

/// `2^e` exactly.
fn two_pow(e: i64) -> BigRational {
    let p = BigInt::one() << (e.unsigned_abs() as usize);
    if e >= 0 {
        BigRational::from_integer(p)
    } else {
        BigRational::new_raw(BigInt::one(), p)
    }
}

/// Approximate binary magnitude: for `q != 0`, `2^(m-1) < |q| < 2^(m+1)`.
fn mag(q: &BigRational) -> i64 {
    q.numer().bits() as i64 - q.denom().bits() as i64
}

/// Round `q` to a dyadic with about `bits` significant bits, down or up.
fn round(q: &BigRational, bits: u32, up: bool) -> Option<BigRational> {
    round_frac(q.numer(), q.denom(), bits, up)
}

/// Round the (possibly unreduced) fraction `n / d` like [`round`]; `d != 0`.
fn round_frac(n: &BigInt, d: &BigInt, bits: u32, up: bool) -> Option<BigRational> {
    if d.is_zero() {
        return None;
    }
    if n.is_zero() {
        return Some(BigRational::zero());
    }
    let e = n.bits() as i64 - d.bits() as i64;
    if e.abs() > MAX_EXP {
        return None;
    }
    let s = bits as i64 + 1 - e;
    // A power-of-two denominator (dyadic endpoints, and their products and sums): the
    // rounding is a shift.
    if let Some(k) = two_exponent(d) {
        return Some(dyadic(shift_round(n, s - k as i64, up), -s));
    }
    Some(dyadic(scaled_round(n, d, s, up), -s))
}

/// `k` where `d = 2^k` (`d > 0`), else `None`.
pub(crate) fn two_exponent(d: &BigInt) -> Option<u64> {
    d.trailing_zeros()
        .filter(|&k| d.is_positive() && d.bits() == k + 1)
}

/// `n * 2^s / d` rounded to an integer, down or up, by a division; `d > 0`.
fn scaled_round(n: &BigInt, d: &BigInt, s: i64, up: bool) -> BigInt {
    let (n, d) = scaled(n, d, s);
    if up {
        -((-n).div_floor(&d))
    } else {
        n.div_floor(&d)
    }
}

/// `n * 2^s` rounded to an integer, down (toward minus infinity) or up.
fn shift_round(n: &BigInt, s: i64, up: bool) -> BigInt {
    if s >= 0 {
        return n << (s as usize);
    }
    let r = s.unsigned_abs();
    let floor = n >> (r as usize);
    // `>>` rounds toward minus infinity; it is exact when no bit below 2^r is set.
    let exact = n.trailing_zeros().is_none_or(|z| z >= r);
    if up && !exact {
        floor + 1
    } else {
        floor
    }
}

/// The fraction `(n * 2^s) / d`, unreduced.
fn scaled(n: &BigInt, d: &BigInt, s: i64) -> Frac {
    let sh = s.unsigned_abs() as usize;
    if s >= 0 {
        (n << sh, d.clone())
    } else {
        (n.clone(), d << sh)
    }
}

/// An unreduced fraction `(n, d)` with `d > 0`.
type Frac = (BigInt, BigInt);

/// Fraction with the sign moved to the numerator.
fn fr(n: BigInt, d: BigInt) -> Frac {
    if d.is_negative() {
        (-n, -d)
    } else {
        (n, d)
    }
}

fn frac(q: &BigRational) -> Frac {
    fr(q.numer().clone(), q.denom().clone())
}

/// Compare fractions by cross-multiplication (cheaper than `Ratio`'s `Ord`).
fn fcmp(a: &Frac, b: &Frac) -> Ordering {
    (&a.0 * &b.1).cmp(&(&b.0 * &a.1))
}

/// `a + sign * b` as an unreduced fraction.
fn fsum(a: &BigRational, b: &BigRational, sign: i32) -> Frac {
    let bn = b.numer() * BigInt::from(sign);
    if a.denom() == b.denom() {
        return fr(a.numer() + bn, a.denom().clone());
    }
    fr(
        a.numer() * b.denom() + bn * a.denom(),
        a.denom() * b.denom(),
    )
}

fn qlt(a: &BigRational, b: &BigRational) -> bool {
    fcmp(&frac(a), &frac(b)) == Ordering::Less
}

/// `m * 2^e` as a reduced rational, built without a gcd.
fn dyadic(m: BigInt, e: i64) -> BigRational {
    if e >= 0 || m.is_zero() {
        return BigRational::from_integer(m << (e.max(0) as usize));
    }
    let tz = m.trailing_zeros().unwrap_or(0).min(e.unsigned_abs());
    let den = BigInt::one() << ((e.unsigned_abs() - tz) as usize);
    BigRational::new_raw(m >> (tz as usize), den)
}

/// Rigorous bound on `sqrt(q)` for `q >= 0` (lower if `!up`, upper if `up`).
fn sqrt_bound(q: &BigRational, bits: u32, up: bool) -> Option<BigRational> {
    if q.is_zero() {
        return Some(q.clone());
    }
    let e = mag(q);
    if e.abs() > MAX_EXP || q.is_negative() {
        return None;
    }
    let s = bits as i64 + 2 - e / 2;
    let (n, d) = scaled(q.numer(), q.denom(), 2 * s);
    let (n, d): (BigUint, BigUint) = (n.to_biguint()?, d.to_biguint()?);
    let (t, rem) = n.div_rem(&d);
    let r = if up {
        let t = if rem.is_zero() { t } else { t + 1u32 };
        let r = t.sqrt();
        if &r * &r < t {
            r + 1u32
        } else {
            r
        }
    } else {
        t.sqrt()
    };
    Some(BigRational::from_integer(BigInt::from(r)) * two_pow(-s))
}

/// Rigorous bound on `a^n` for `a >= 0`, `n >= 1` via rounded binary powering.
fn pow_bound(a: &BigRational, n: u64, bits: u32, up: bool) -> Option<BigRational> {
    // A short fraction (the guard's points are) has a short exact power: rounded once,
    // it is the tightest bound, and cheaper than rounding every square.
    let size = a.numer().bits().max(a.denom().bits());
    if size.saturating_mul(n) <= 2 * u64::from(bits) {
        let n = u32::try_from(n).ok()?;
        return round_frac(&a.numer().pow(n), &a.denom().pow(n), bits, up);
    }
    let mut result = BigRational::one();
    let mut base = round(a, bits, up)?;
    let mut k = n;
    loop {
        if k & 1 == 1 {
            result = round(&(&result * &base), bits, up)?;
        }
        k >>= 1;
        if k == 0 {
            return Some(result);
        }
        base = round(&(&base * &base), bits, up)?;
    }
}

impl Interval {
    /// The degenerate interval `[q, q]` (exact, not rounded).
    pub fn point(q: BigRational) -> Interval {
        Interval {
            lo: q.clone(),
            hi: q,
        }
    }

    /// The interval `[lo, hi]`, or `None` if `lo > hi`. Endpoints are kept exactly.
    pub fn new(lo: BigRational, hi: BigRational) -> Option<Interval> {
        if lo <= hi {
            Some(Interval { lo, hi })
        } else {
            None
        }
    }

    fn int(n: i64) -> Interval {
        Interval::point(rat(n))
    }

    /// Build `[lo, hi]` with endpoints rounded outward to precision `p`.
    fn mk(lo: BigRational, hi: BigRational, p: Prec) -> Option<Interval> {
        Interval::mk_frac(frac(&lo), frac(&hi), p)
    }

    fn mk_frac(lo: Frac, hi: Frac, p: Prec) -> Option<Interval> {
        let lo = round_frac(&lo.0, &lo.1, p.eff(), false)?;
        let hi = round_frac(&hi.0, &hi.1, p.eff(), true)?;
        (!qlt(&hi, &lo)).then_some(Interval { lo, hi })
    }

    /// `self + t` or `self - t`.
    fn add_signed(&self, t: &Interval, minus: bool, p: Prec) -> Option<Interval> {
        if minus {
            self.sub(t, p)
        } else {
            self.add(t, p)
        }
    }

    fn widen(self, err: &BigRational) -> Interval {
        Interval {
            lo: self.lo - err,
            hi: self.hi + err,
        }
    }

    /// Largest absolute value of a member, `max(|lo|, |hi|)`.
    fn mag_bound(&self) -> BigRational {
        let (a, b) = (self.lo.abs(), self.hi.abs());
        if qlt(&a, &b) {
            b
        } else {
            a
        }
    }

    /// Lower endpoint.
    pub fn lo(&self) -> &BigRational {
        &self.lo
    }

    /// Upper endpoint.
    pub fn hi(&self) -> &BigRational {
        &self.hi
    }

    /// True if the two enclosures share no point, which proves the enclosed values differ.
    pub fn disjoint(&self, other: &Interval) -> bool {
        self.hi < other.lo || other.hi < self.lo
    }

    /// True if every member is strictly positive (`lo > 0`).
    pub fn is_positive(&self) -> bool {
        self.lo.is_positive()
    }

    /// True if every member is strictly negative (`hi < 0`).
    pub fn is_negative(&self) -> bool {
        self.hi.is_negative()
    }

    /// True if `lo <= 0 <= hi`.
    pub fn contains_zero(&self) -> bool {
        !self.is_positive() && !self.is_negative()
    }

    /// True if `lo <= q <= hi`.
    pub fn contains(&self, q: &BigRational) -> bool {
        &self.lo <= q && q <= &self.hi
    }

    /// `hi - lo`.
    pub fn width(&self) -> BigRational {
        &self.hi - &self.lo
    }

    /// `(lo + hi) / 2`.
    pub fn midpoint(&self) -> BigRational {
        let (a, b) = (self.lo.numer(), self.lo.denom());
        let (c, d) = (self.hi.numer(), self.hi.denom());
        if let (Some(k), Some(l)) = (two_exponent(b), two_exponent(d)) {
            // Dyadic endpoints (every rounded one): over the larger power of two, then
            // halved; lowest terms by a shift, with no gcd.
            let e = k.max(l);
            let sum = (a << ((e - k) as usize)) + (c << ((e - l) as usize));
            return dyadic(sum, -(e as i64) - 1);
        }
        // One gcd, where adding and then halving `Ratio`s takes several.
        BigRational::new(a * d + c * b, b * d * 2)
    }

    /// Smallest interval containing both `self` and `other`.
    pub fn hull(&self, other: &Interval) -> Interval {
        Interval {
            lo: std::cmp::min(&self.lo, &other.lo).clone(),
            hi: std::cmp::max(&self.hi, &other.hi).clone(),
        }
    }

    /// Enclosure of `x + y`.
    pub fn add(&self, other: &Interval, p: Prec) -> Option<Interval> {
        Interval::mk_frac(
            fsum(&self.lo, &other.lo, 1),
            fsum(&self.hi, &other.hi, 1),
            p,
        )
    }

    /// Enclosure of `x - y`.
    pub fn sub(&self, other: &Interval, p: Prec) -> Option<Interval> {
        Interval::mk_frac(
            fsum(&self.lo, &other.hi, -1),
            fsum(&self.hi, &other.lo, -1),
            p,
        )
    }

    /// Exact negation `[-hi, -lo]` (never `None`; `Option` for uniformity).
    pub fn neg(&self) -> Option<Interval> {
        Some(Interval {
            lo: -&self.hi,
            hi: -&self.lo,
        })
    }

    /// Enclosure of `|x|`.
    pub fn abs(&self) -> Option<Interval> {
        if !self.lo.is_negative() {
            Some(self.clone())
        } else if !self.hi.is_positive() {
            self.neg()
        } else {
            Some(Interval {
                lo: BigRational::zero(),
                hi: self.mag_bound(),
            })
        }
    }

    fn hull_of<const N: usize>(v: [Frac; N], p: Prec) -> Option<Interval> {
        let lo = v.iter().min_by(|a, b| fcmp(a, b))?.clone();
        let hi = v.iter().max_by(|a, b| fcmp(a, b))?.clone();
        Interval::mk_frac(lo, hi, p)
    }

    /// Enclosure of `x * y`.
    pub fn mul(&self, other: &Interval, p: Prec) -> Option<Interval> {
        let (a, b, c, d) = (&self.lo, &self.hi, &other.lo, &other.hi);
        let m = |x: &BigRational, y: &BigRational| fr(x.numer() * y.numer(), x.denom() * y.denom());
        // Structural equality: `Ratio`'s own comparison divides.
        let same =
            |x: &BigRational, y: &BigRational| x.numer() == y.numer() && x.denom() == y.denom();
        match (same(a, b), same(c, d)) {
            // Points (the guard's values, a term's coefficient): fewer products.
            (true, true) => {
                let x = m(a, c);
                Interval::mk_frac(x.clone(), x, p)
            }
            (true, false) => Interval::hull_of([m(a, c), m(a, d)], p),
            (false, true) => Interval::hull_of([m(a, c), m(b, c)], p),
            (false, false) => Interval::hull_of([m(a, c), m(a, d), m(b, c), m(b, d)], p),
        }
    }

    /// Enclosure of `1 / x`; `None` if `x` contains zero.
    pub fn recip(&self, p: Prec) -> Option<Interval> {
        if self.contains_zero() {
            return None;
        }
        Interval::mk(self.hi.recip(), self.lo.recip(), p)
    }

    /// Enclosure of `x / y`; `None` if `y` contains zero.
    pub fn div(&self, other: &Interval, p: Prec) -> Option<Interval> {
        if other.contains_zero() {
            return None;
        }
        let (a, b, c, d) = (&self.lo, &self.hi, &other.lo, &other.hi);
        let q = |x: &BigRational, y: &BigRational| fr(x.numer() * y.denom(), x.denom() * y.numer());
        Interval::hull_of([q(a, c), q(a, d), q(b, c), q(b, d)], p)
    }

    /// Enclosure of `x^n`. `x^0 = 1`; negative `n` uses `recip` (so `None` if
    /// `x` contains zero). `None` if `|n| > MAX_POWI` or the result is too large.
    pub fn powi(&self, n: i64, p: Prec) -> Option<Interval> {
        if n.unsigned_abs() > MAX_POWI as u64 {
            return None;
        }
        if n < 0 {
            return self.powi(-n, p)?.recip(p);
        }
        if n == 0 {
            return Some(Interval::int(1));
        }
        if n == 1 {
            return Some(self.clone());
        }
        let big = self.mag_bound();
        if !big.is_zero() && mag(&big).saturating_mul(n).unsigned_abs() > (MAX_EXP + 64) as u64 {
            return None;
        }
        let wp = p.plus(32).eff() + 32;
        let un = n as u64;
        // A lower bound on a^n for a >= 0; 0 is a safe fallback on underflow.
        let down = |a: &BigRational| pow_bound(a, un, wp, false).unwrap_or_else(BigRational::zero);
        let up = |a: &BigRational| pow_bound(a, un, wp, true);
        let (lo, hi) = if n % 2 == 1 {
            let lo = if self.lo.is_negative() {
                -up(&-&self.lo)?
            } else {
                down(&self.lo)
            };
            let hi = if self.hi.is_negative() {
                -down(&-&self.hi)
            } else {
                up(&self.hi)?
            };
            (lo, hi)
        } else if !self.lo.is_negative() {
            (down(&self.lo), up(&self.hi)?)
        } else if !self.hi.is_positive() {
            (down(&-&self.hi), up(&-&self.lo)?)
        } else {
            (BigRational::zero(), up(&big)?)
        };
        Interval::mk(lo, hi, p)
    }

    /// The real principal `n`-th root (`n ≥ 1`): of a positive interval, or, for odd `n`,
    /// the negated root of a negative one; `None` for an interval that holds 0 or, with
    /// `n` even, negative values.
    pub fn real_root(&self, n: u32, p: Prec) -> Option<Interval> {
        let inv = Interval::point(BigRational::new(BigInt::one(), BigInt::from(n)));
        let root = |v: &Interval| v.ln(p)?.mul(&inv, p)?.exp(p);
        if self.is_positive() {
            root(self)
        } else if self.is_negative() && n % 2 == 1 {
            root(&self.neg()?)?.neg()
        } else {
            None
        }
    }

    /// Enclosure of `sqrt(x)`; `None` unless `lo >= 0`.
    pub fn sqrt(&self, p: Prec) -> Option<Interval> {
        if self.lo.is_negative() {
            return None;
        }
        let b = p.eff() + 4;
        Interval::mk(
            sqrt_bound(&self.lo, b, false)?,
            sqrt_bound(&self.hi, b, true)?,
            p,
        )
    }

    /// Enclosure of `pi` (Machin's formula with alternating-series remainders).
    pub fn pi(p: Prec) -> Option<Interval> {
        // Kept for the process (the checks of one run run on several threads): the
        // enclosure depends on nothing but the precision.
        static PI: Mutex<Vec<(u32, Interval)>> = Mutex::new(Vec::new());
        let lock = || PI.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(v) = lock().iter().find(|e| e.0 == p.bits).map(|e| e.1.clone()) {
            return Some(v);
        }
        let v = Interval::pi_uncached(p)?;
        let mut c = lock();
        if c.len() < 16 && !c.iter().any(|e| e.0 == p.bits) {
            c.push((p.bits, v.clone()));
        }
        Some(v)
    }

    fn pi_uncached(p: Prec) -> Option<Interval> {
        let wp = p.plus(16);
        let a = atan_inv(5, wp)?.mul(&Interval::int(16), wp)?;
        let b = atan_inv(239, wp)?.mul(&Interval::int(4), wp)?;
        let r = a.sub(&b, wp)?;
        Interval::mk(r.lo, r.hi, p)
    }

    /// Enclosure of `exp(x)`; `None` if `|x| > MAX_EXP_ARG`.
    pub fn exp(&self, p: Prec) -> Option<Interval> {
        self.increasing(p, exp_point)
    }

    /// Apply an increasing function given by point enclosures to both endpoints.
    fn increasing(
        &self,
        p: Prec,
        f: fn(&BigRational, Prec) -> Option<Interval>,
    ) -> Option<Interval> {
        let lo = f(&self.lo, p)?;
        let hi = if self.lo == self.hi {
            lo.clone()
        } else {
            f(&self.hi, p)?
        };
        Interval::mk(lo.lo, hi.hi, p)
    }

    /// Enclosure of the natural logarithm; `None` unless `lo > 0`.
    pub fn ln(&self, p: Prec) -> Option<Interval> {
        if !self.lo.is_positive() {
            return None;
        }
        self.increasing(p, ln_point)
    }

    /// Enclosure of `sin(x)`; `None` if `|x| > MAX_TRIG_ARG`.
    pub fn sin(&self, p: Prec) -> Option<Interval> {
        self.trig(p, false)
    }

    /// Enclosure of `cos(x)`; `None` if `|x| > MAX_TRIG_ARG`.
    pub fn cos(&self, p: Prec) -> Option<Interval> {
        self.trig(p, true)
    }

    /// Enclosure of `tan(x) = sin(x) / cos(x)`; `None` if the cosine
    /// enclosure contains zero or `|x| > MAX_TRIG_ARG`.
    pub fn tan(&self, p: Prec) -> Option<Interval> {
        self.sin(p)?.div(&self.cos(p)?, p)
    }

    fn trig(&self, p: Prec, cos: bool) -> Option<Interval> {
        if self.mag_bound() > rat(MAX_TRIG_ARG) {
            return None;
        }
        if self.width() > rat(7) {
            return Interval::new(rat(-1), rat(1));
        }
        let pick = |q: &BigRational| -> Option<Interval> {
            let (s, c) = sincos_point(q, p)?;
            Some(if cos { c } else { s })
        };
        let half_width = self.width() / rat(2);
        let mut res;
        if self.lo != self.hi && qlt(&half_width, &two_pow(-32)) {
            // A narrow enclosure (a value computed at the guard's precision): sine and
            // cosine move by at most the distance moved, so the value at the midpoint
            // widened by half the width holds every member. One evaluation, not two.
            res = pick(&self.midpoint())?.widen(&half_width);
        } else {
            res = pick(&self.lo)?;
        }
        if self.lo != self.hi && !qlt(&half_width, &two_pow(-32)) {
            res = res.hull(&pick(&self.hi)?);
            // Include the extreme values if a critical point may lie inside.
            let wp = p.plus(8);
            let pi = Interval::pi(wp)?;
            let two_pi = pi.mul(&Interval::int(2), wp)?;
            let half_pi = pi.div(&Interval::int(2), wp)?;
            let (max_at, min_at) = if cos {
                (Interval::int(0), pi)
            } else {
                (half_pi.clone(), half_pi.neg()?)
            };
            let hits = |off: &Interval| -> Option<bool> {
                let t = self.sub(off, wp)?.div(&two_pi, wp)?;
                Some(t.lo.ceil() <= t.hi.floor())
            };
            if hits(&max_at)? {
                res.hi = std::cmp::max(res.hi, rat(1));
            }
            if hits(&min_at)? {
                res.lo = std::cmp::min(res.lo, rat(-1));
            }
        }
        let lo = std::cmp::max(res.lo, rat(-1));
        let hi = std::cmp::min(res.hi, rat(1));
        Interval::mk(lo, hi, p)
    }

    /// Short decimal approximation of the midpoint with about `digits`
    /// significant digits, e.g. `0.70710678` (diagnostics only).
    pub fn to_decimal_string(&self, digits: usize) -> String {
        decimal(&self.midpoint(), digits.clamp(1, 1000))
    }
}

impl std::fmt::Display for Interval {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "[{}, {}]", decimal(&self.lo, 12), decimal(&self.hi, 12))
    }
}

/// `atan(1/n)` for integer `n >= 2` by the alternating Taylor series.
fn atan_inv(n: i64, wp: Prec) -> Option<Interval> {
    let x = Interval::point(BigRational::new(BigInt::one(), BigInt::from(n)));
    let x2 = x.mul(&x, wp)?;
    let tiny = two_pow(-(wp.bits as i64) - 4);
    let mut pow = x.clone();
    let mut sum = Interval::int(0);
    for k in 0..MAX_TERMS {
        if qlt(&pow.hi, &tiny) {
            // Alternating series with decreasing terms: tail <= first omitted term.
            return Some(sum.widen(&pow.hi));
        }
        let term = pow.div(&Interval::int(2 * k as i64 + 1), wp)?;
        sum = sum.add_signed(&term, k % 2 == 1, wp)?;
        pow = pow.mul(&x2, wp)?;
    }
    None
}

/// `2 atanh(z) = ln((1+z)/(1-z))` for rational `|z| <= 1/3`.
fn atanh2(z: &BigRational, wp: Prec) -> Option<Interval> {
    if z.abs() > BigRational::new(BigInt::one(), BigInt::from(3)) {
        return None;
    }
    let z = Interval::point(z.clone());
    let z2 = z.mul(&z, wp)?;
    let tiny = two_pow(-(wp.bits as i64) - 4);
    let mut pow = z;
    let mut sum = Interval::int(0);
    for j in 0..MAX_TERMS {
        let m = pow.mag_bound();
        if qlt(&m, &tiny) {
            // Tail <= |z|^(2j+1) / (1 - z^2) <= (9/8) |z|^(2j+1) <= 2 m.
            return sum.widen(&(m * rat(2))).mul(&Interval::int(2), wp);
        }
        sum = sum.add(&pow.div(&Interval::int(2 * j as i64 + 1), wp)?, wp)?;
        pow = pow.mul(&z2, wp)?;
    }
    None
}

fn ln_point(q: &BigRational, p: Prec) -> Option<Interval> {
    let e = mag(q);
    if e.abs() > MAX_EXP || !q.is_positive() {
        return None;
    }
    let wp = p.plus(24 + 64 - e.unsigned_abs().leading_zeros());
    let m = q * two_pow(-e); // in (1/2, 2)
    let one = BigRational::one();
    let res = atanh2(&((&m - &one) / (&m + &one)), wp)?;
    if e == 0 {
        return Some(res);
    }
    let ln2 = atanh2(&BigRational::new(BigInt::one(), BigInt::from(3)), wp)?;
    res.add(&ln2.mul(&Interval::int(e), wp)?, wp)
}

fn exp_point(q: &BigRational, p: Prec) -> Option<Interval> {
    if q.abs() > rat(MAX_EXP_ARG) {
        return None;
    }
    if q.is_zero() {
        return Some(Interval::int(1));
    }
    let k = (mag(q) + 9).max(0); // |q / 2^k| < 2^-8
    let wp = p.plus(k as u32 + 16);
    let r = Interval::point(q * two_pow(-k));
    let tiny = two_pow(-(wp.bits as i64) - 4);
    let mut sum = Interval::int(1);
    let mut term = Interval::int(1);
    for j in 1..MAX_TERMS {
        term = term.mul(&r, wp)?.div(&Interval::int(j as i64), wp)?;
        let m = term.mag_bound();
        if qlt(&m, &tiny) {
            // Tail from term j on: ratio of successive terms <= |r|/(j+1) <= 1/2.
            let mut s = sum.widen(&(m * rat(2)));
            for _ in 0..k {
                s = s.mul(&s, wp)?;
            }
            return Some(s);
        }
        sum = sum.add(&term, wp)?;
    }
    None
}

/// Enclosures of `(sin q, cos q)` using reduction modulo `pi/2`.
fn sincos_point(q: &BigRational, p: Prec) -> Option<(Interval, Interval)> {
    type Known = HashMap<(BigRational, Prec), Option<(Interval, Interval)>>;
    // The guard evaluates the same angles over and over (its points are short binary
    // fractions): each enclosure is found once per process. The answer depends on
    // nothing but the arguments, so a remembered one is the one it would compute.
    static KNOWN: Mutex<Option<Known>> = Mutex::new(None);
    const KEEP: usize = 4096;
    let key = (q.clone(), p);
    let lock = || KNOWN.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(known) = lock().as_ref().and_then(|k| k.get(&key).cloned()) {
        return known;
    }
    let found = sincos_enclosure(q, p);
    let mut k = lock();
    let k = k.get_or_insert_with(HashMap::new);
    if k.len() >= KEEP {
        k.clear();
    }
    k.insert(key, found.clone());
    found
}

/// `(sin x, cos x)` for `x = ax/2^w` (`0 <= ax <= 2^w`) by the Taylor series in fixed
/// point, scaled by `2^w`, with a bound on their error in units of `2^-w`. Each term is
/// the one before times `x/k`, floored: term `k` is off from `x^k/k!` by at most `k`
/// units (an error of `e` units becomes at most `e x/k + 1 <= e + 1`), and the first
/// term left out bounds the remainder (Lagrange: every derivative is bounded by 1) up
/// to its own error. The terms summed and the one left out are off by less than
/// `k^2 + 1` units in all.
fn taylor_fixed(ax: &BigInt, w: usize) -> Option<(BigInt, BigInt, BigInt)> {
    let one = BigInt::one() << w;
    if ax.is_negative() || *ax > one {
        return None;
    }
    let (mut s, mut c) = (BigInt::zero(), one.clone());
    let mut term = one;
    let mut k: u32 = 1;
    loop {
        term = ((term * ax) >> w) / BigInt::from(k);
        if term.is_zero() {
            break;
        }
        if k >= MAX_TERMS {
            return None;
        }
        let acc = if k % 2 == 1 { &mut s } else { &mut c };
        if (k / 2) % 2 == 1 {
            *acc -= &term;
        } else {
            *acc += &term;
        }
        k += 1;
    }
    Some((s, c, BigInt::from(u64::from(k) * u64::from(k) + 1)))
}

/// [`sincos_point`], computed by reduction modulo `pi/2` in fixed point: with `w` bits
/// after the point, `q 2^w` lies in `[Q, Q + 1]` and `(pi/2) 2^w` in `[H, H']` (from an
/// enclosure of `pi`), so `r = q - j pi/2` lies in `[A, B]` units; the series is summed
/// at a point of it, and widened by the distance to the farther end (sine and cosine
/// move by at most the distance moved) and by its own error.
fn sincos_enclosure(q: &BigRational, p: Prec) -> Option<(Interval, Interval)> {
    if q.abs() > rat(MAX_TRIG_ARG) {
        return None;
    }
    let wp = p.plus(40);
    let w = wp.eff() as usize + 16;
    let pi = Interval::pi(Prec::new(w as u32 + 8))?;
    let (h_lo, h_hi) = (
        (pi.lo.numer() << (w - 1)).div_floor(pi.lo.denom()),
        -((-(pi.hi.numer() << (w - 1))).div_floor(pi.hi.denom())),
    );
    let qw = (q.numer() << w).div_floor(q.denom());
    let j = BigRational::new(qw.clone(), h_lo.clone())
        .round()
        .to_integer();
    let (jh1, jh2) = (&j * &h_lo, &j * &h_hi);
    let (jmin, jmax) = if jh1 <= jh2 { (jh1, jh2) } else { (jh2, jh1) };
    let (a, b) = (&qw - jmax, &qw + BigInt::one() - jmin);
    let x: BigInt = (&a + &b).div_floor(&BigInt::from(2));
    let reach = std::cmp::max(&b - &x, &x - &a);
    let (s, c, units) = taylor_fixed(&x.abs(), w)?;
    let s = if x.is_negative() { -s } else { s };
    let err = units + reach;
    let around = |v: &BigInt| {
        Interval::mk(
            dyadic(v - &err, -(w as i64)),
            dyadic(v + &err, -(w as i64)),
            wp,
        )
    };
    let (s, c) = (around(&s)?, around(&c)?);
    let res = match j.mod_floor(&BigInt::from(4)).to_u32()? {
        0 => (s, c),
        1 => (c, s.neg()?),
        2 => (s.neg()?, c.neg()?),
        _ => (c.neg()?, s),
    };
    Some(res)
}

/// Decimal rendering of `q` with about `digits` significant digits.
fn decimal(q: &BigRational, digits: usize) -> String {
    if q.is_zero() {
        return "0".to_string();
    }
    let e2 = mag(q);
    if e2.abs() > 3000 {
        // Huge or tiny: print a mantissa times a power of two (cheap).
        let (n, d) = scaled(q.numer(), q.denom(), -e2);
        let m = round_frac(&n, &d, 4 * digits as u32 + 16, false);
        return m.map_or_else(String::new, |m| format!("{}*2^{e2}", decimal(&m, digits)));
    }
    let sign = if q.is_negative() { "-" } else { "" };
    let a = q.abs();
    let ten = rat(10);
    let pow10 = |e: i64| -> BigRational {
        let p =
            BigRational::from_integer(num_traits::pow(BigInt::from(10), e.unsigned_abs() as usize));
        if e >= 0 {
            p
        } else {
            p.recip()
        }
    };
    // Find e10 with 10^e10 <= a < 10^(e10+1).
    let mut e10 = mag(&a) * 30103 / 100000;
    let mut p = pow10(e10);
    while p > a {
        p /= &ten;
        e10 -= 1;
    }
    while &p * &ten <= a {
        p *= &ten;
        e10 += 1;
    }
    let d = digits as i64;
    if (-5..d).contains(&e10) {
        let decimals = (d - 1 - e10) as usize;
        let n = (&a * pow10(decimals as i64))
            .round()
            .to_integer()
            .to_string();
        if decimals == 0 {
            return format!("{sign}{n}");
        }
        let n = format!("{:0>width$}", n, width = decimals + 1);
        let (i, f) = n.split_at(n.len() - decimals);
        format!("{sign}{i}.{f}")
    } else {
        let mut n = (&a / pow10(e10 - d + 1)).round().to_integer().to_string();
        if n.len() > digits {
            n.pop(); // rounding carried into a new digit
            e10 += 1;
        }
        let (i, f) = n.split_at(1);
        let f = if f.is_empty() {
            String::new()
        } else {
            format!(".{f}")
        };
        format!("{sign}{i}{f}e{e10}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn q(n: i64, d: i64) -> BigRational {
        BigRational::new(BigInt::from(n), BigInt::from(d))
    }
    fn pt(n: i64, d: i64) -> Interval {
        Interval::point(q(n, d))
    }
    /// Parse a decimal literal exactly.
    fn dec(s: &str) -> BigRational {
        let (neg, s) = s.strip_prefix('-').map_or((false, s), |t| (true, t));
        let (i, f) = s.split_once('.').unwrap_or((s, ""));
        let n: BigInt = format!("{i}{f}").parse().unwrap();
        let r = BigRational::new(n, num_traits::pow(BigInt::from(10), f.len()));
        if neg {
            -r
        } else {
            r
        }
    }
    /// The enclosure contains a point within `tol` of `v` and is narrow.
    fn near(iv: &Interval, v: &str, tol: &str) {
        let (v, tol) = (dec(v), dec(tol));
        assert!(
            iv.lo() <= &(&v + &tol) && &(&v - &tol) <= iv.hi(),
            "{iv} vs {v}"
        );
        assert!(iv.width() < two_pow(-80), "too wide: {iv}");
    }
    const P: Prec = Prec { bits: 96 };

    proptest! {
        /// The midpoint is `(lo + hi) / 2` in lowest terms, whether the endpoints are
        /// dyadic (the shift) or not (one gcd).
        #[test]
        fn midpoint_is_the_mean_in_lowest_terms(
            a in -10_000i64..10_000, b in 1i64..5_000, c in -10_000i64..10_000,
            d in 1i64..5_000, k in 0u32..70, l in 0u32..70, dyadic_ends in any::<bool>(),
        ) {
            let (lo, hi) = if dyadic_ends {
                (q(a, 1) / two_pow(k.into()), q(c, 1) / two_pow(l.into()))
            } else {
                (q(a, b), q(c, d))
            };
            let (lo, hi) = if hi < lo { (hi, lo) } else { (lo, hi) };
            let m = Interval::new(lo.clone(), hi.clone()).unwrap().midpoint();
            let want = (&lo + &hi) / rat(2);
            prop_assert_eq!((m.numer(), m.denom()), (want.numer(), want.denom()));
        }
    }

    #[test]
    fn known_values() {
        let s2 = pt(2, 1).sqrt(P).unwrap();
        assert!(s2.lo() * s2.lo() <= rat(2) && rat(2) <= s2.hi() * s2.hi());
        near(&s2, "1.41421356237", "0.00000000001");
        near(
            &pt(1, 1).sin(P).unwrap(),
            "0.8414709848078965",
            "0.000000000000001",
        );
        let pi = Interval::pi(P).unwrap();
        near(&pi, "3.14159265358979323846", "0.00000000000000000001");
        let c = pi.div(&pt(3, 1), P).unwrap().cos(P).unwrap();
        assert!(c.contains(&q(1, 2)) && c.width() < two_pow(-80));
        near(
            &pt(1, 1).exp(P).unwrap(),
            "2.71828182845904523536",
            "0.00000000000000000001",
        );
        near(
            &pt(2, 1).ln(P).unwrap(),
            "0.69314718055994530942",
            "0.00000000000000000001",
        );
        near(
            &pt(1000, 1).cos(P).unwrap(),
            "0.562379076290702991078",
            "0.000000000000000000001",
        );
        near(
            &pt(-3, 1).exp(P).unwrap(),
            "0.0497870683678639429793",
            "0.0000000000000000000001",
        );
        near(
            &pt(1, 1000).ln(P).unwrap(),
            "-6.90775527898213705205",
            "0.00000000000000000001",
        );
        near(
            &pt(1, 1).tan(P).unwrap(),
            "1.5574077246549022305",
            "0.0000000000000000001",
        );
        let p10 = pt(3, 2).powi(10, P).unwrap();
        assert!(p10.contains(&q(59049, 1024)));
        assert!(pt(-3, 2).powi(-3, P).unwrap().contains(&q(-8, 27)));
        assert_eq!(pt(1, 1).sin(P).unwrap().to_decimal_string(8), "0.84147098");
        assert_eq!(pt(-1, 8).to_decimal_string(3), "-0.125");
        assert_eq!(pt(12345, 1).to_decimal_string(3), "1.23e4");
        assert_eq!(pt(1, 1000000).to_decimal_string(2), "1.0e-6");
        assert_eq!(pt(99999, 10_000_000_000).to_decimal_string(2), "1.0e-5");
        let big = pt(3, 1).powi(100_000, P).unwrap().to_decimal_string(4);
        assert!(big.ends_with("*2^158496"), "{big}");
    }

    #[test]
    fn domains_and_limits() {
        assert!(pt(-1, 1).sqrt(P).is_none());
        assert!(pt(0, 1).ln(P).is_none());
        assert!(Interval::new(rat(-1), rat(1)).unwrap().recip(P).is_none());
        assert!(pt(1, 1).div(&pt(0, 1), P).is_none());
        assert!(pt(2, 1).powi(MAX_POWI + 1, P).is_none());
        assert!(pt(3, 1).powi(i64::MIN, P).is_none());
        assert!(pt(3, 1).powi(MAX_POWI, P).is_none()); // too large
        assert!(pt(2, 1).powi(MAX_POWI, P).is_some());
        assert!(pt(10_000_000, 1).sin(P).is_none());
        assert!(pt(1_000_000, 1).exp(P).is_none());
        assert!(pt(500_000, 1).exp(P).unwrap().is_positive());
        let pi = Interval::pi(P).unwrap();
        let half = pi.div(&pt(2, 1), P).unwrap();
        assert!(half.tan(P).is_none());
        let wide = Interval::new(rat(0), rat(3)).unwrap();
        let s = wide.sin(P).unwrap();
        assert!(s.contains(&rat(1)) && s.contains(&rat(0)) && s.lo() >= &rat(-1));
        let c = wide.cos(P).unwrap();
        assert!(c.contains(&rat(1)) && !c.contains(&rat(-1)));
        assert_eq!(
            Interval::new(rat(-5), rat(5)).unwrap().cos(P).unwrap().lo(),
            &rat(-1)
        );
        assert!(pt(0, 1).exp(P).unwrap() == pt(1, 1));
        assert!(pt(1, 1).ln(P).unwrap() == pt(0, 1));
        // a wrong 16-digit value is refuted; sign proofs
        assert!(pt(1, 1)
            .sin(P)
            .unwrap()
            .disjoint(&Interval::point(dec("0.8414709848078966"))));
        assert!(pi.sub(&pt(355, 113), P).unwrap().is_negative());
        assert!(pt(2, 1)
            .sqrt(P)
            .unwrap()
            .sub(&pt(1414, 1000), P)
            .unwrap()
            .is_positive());
    }

    fn r() -> impl Strategy<Value = BigRational> {
        (-1_000_000i64..1_000_000, 1i64..1_000_000).prop_map(|(n, d)| q(n, d))
    }
    fn rpos() -> impl Strategy<Value = BigRational> {
        (1i64..1_000_000_000, 1i64..1_000_000).prop_map(|(n, d)| q(n, d))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        #[test]
        fn arith_contains(a in r(), b in r(), bits in 8u32..200) {
            let p = Prec::new(bits);
            let (x, y) = (Interval::point(a.clone()), Interval::point(b.clone()));
            prop_assert!(x.add(&y, p).unwrap().contains(&(&a + &b)));
            prop_assert!(x.sub(&y, p).unwrap().contains(&(&a - &b)));
            prop_assert!(x.mul(&y, p).unwrap().contains(&(&a * &b)));
            if !b.is_zero() {
                prop_assert!(x.div(&y, p).unwrap().contains(&(&a / &b)));
            }
            let n = (bits % 7) as i32 - 3;
            if !(a.is_zero() && n < 0) {
                prop_assert!(x.powi(n as i64, p).unwrap().contains(&num_traits::pow::Pow::pow(&a, n)));
            }
            let w = Interval::new(std::cmp::min(&a, &b).clone(), std::cmp::max(&a, &b).clone()).unwrap();
            let sq = w.powi(2, p).unwrap();
            prop_assert!(sq.contains(&(&a * &a)) && sq.contains(&(&b * &b)));
        }

        #[test]
        fn shift_rounding_is_division(n in any::<i64>(), k in 0u32..90, s in -100i64..100, up in any::<bool>()) {
            // The shift taken for a power-of-two denominator rounds as the division does.
            let (n, d) = (BigInt::from(n) << 7usize, BigInt::one() << (k as usize));
            prop_assert_eq!(shift_round(&n, s - i64::from(k), up), scaled_round(&n, &d, s, up));
        }

        #[test]
        fn mul_with_points_is_the_hull(a in r(), b in r(), c in r(), bits in 8u32..200) {
            // The shortcuts for points give the hull of all four products.
            let p = Prec::new(bits);
            let w = Interval::new(std::cmp::min(&b, &c).clone(), std::cmp::max(&b, &c).clone()).unwrap();
            let x = Interval::point(a.clone());
            let m = |x: &BigRational, y: &BigRational| fr(x.numer() * y.numer(), x.denom() * y.denom());
            let all = |u: &Interval, v: &Interval| Interval::hull_of(
                [m(&u.lo, &v.lo), m(&u.lo, &v.hi), m(&u.hi, &v.lo), m(&u.hi, &v.hi)], p);
            prop_assert_eq!(x.mul(&w, p), all(&x, &w));
            prop_assert_eq!(w.mul(&x, p), all(&w, &x));
            prop_assert_eq!(x.mul(&x, p), all(&x, &x));
            prop_assert_eq!(w.powi(1, p), Some(w.clone()));
        }

        #[test]
        fn sqrt_sq(a in rpos()) {
            let s = Interval::point(a.clone()).sqrt(P).unwrap();
            prop_assert!(s.mul(&s, P).unwrap().contains(&a));
            prop_assert!(s.lo() * s.lo() <= a && a <= s.hi() * s.hi());
        }

        #[test]
        fn trig_against_f64(n in -1_000_000i64..1_000_000, d in 1i64..1000) {
            // An independent sine and cosine (the platform's, within a few ulps).
            let (x, xf) = (q(n, d), n as f64 / d as f64);
            let pt = Interval::point(x);
            let slack = |v: f64| q((v * 2f64.powi(40)).round() as i64, 1 << 40);
            let (s, c) = (pt.sin(P).unwrap(), pt.cos(P).unwrap());
            let tol = q(1, 1 << 30);
            prop_assert!(s.lo() <= &(slack(xf.sin()) + &tol) && &(slack(xf.sin()) - &tol) <= s.hi());
            prop_assert!(c.lo() <= &(slack(xf.cos()) + &tol) && &(slack(xf.cos()) - &tol) <= c.hi());
            prop_assert!(s.width() < two_pow(-80) && c.width() < two_pow(-80));
        }

        #[test]
        fn fixed_point_error_bound(ax in 0u64..(1 << 40), extra in 0usize..80) {
            // The series at 64 more bits (its own error bounded the same way) must lie
            // within the error claimed at the lower precision.
            let w = 40 + extra;
            let ax = BigInt::from(ax) << extra;
            let (s1, c1, u1) = taylor_fixed(&ax, w).unwrap();
            let (s2, c2, u2) = taylor_fixed(&(&ax << 64), w + 64).unwrap();
            let room: BigInt = (&u1 << 64) + &u2;
            let (d_s, d_c): (BigInt, BigInt) = ((&s1 << 64) - &s2, (&c1 << 64) - &c2);
            prop_assert!(d_s.abs() <= room);
            prop_assert!(d_c.abs() <= room);
        }

        #[test]
        fn trig_identities(a in r()) {
            let x = Interval::point(a.clone());
            let (s, c) = (x.sin(P).unwrap(), x.cos(P).unwrap());
            let one = s.powi(2, P).unwrap().add(&c.powi(2, P).unwrap(), P).unwrap();
            prop_assert!(one.contains(&rat(1)));
            // sin(2x) two ways
            let s2 = Interval::point(&a * rat(2)).sin(P).unwrap();
            let s2b = s.mul(&c, P).unwrap().mul(&Interval::int(2), P).unwrap();
            prop_assert!(!s2.disjoint(&s2b));
            // wide interval enclosure contains the endpoint values and midpoint
            let w = Interval::new(a.clone(), &a + q(3, 2)).unwrap();
            let sw = w.sin(P).unwrap();
            let m = Interval::point(&a + q(3, 4)).sin(P).unwrap();
            prop_assert!(!sw.disjoint(&m) && !sw.disjoint(&s));
        }

        #[test]
        fn exp_ln(a in rpos(), b in r()) {
            let x = Interval::point(a.clone());
            let e = x.ln(P).unwrap().exp(P).unwrap();
            prop_assert!(e.contains(&a));
            // exp(a+b) = exp(a) exp(b), with a scaled down
            let (u, v) = (Interval::point(&a / rat(100_000)), Interval::point(b.clone() / rat(1000)));
            let lhs = u.add(&v, P).unwrap().exp(P).unwrap();
            let rhs = u.exp(P).unwrap().mul(&v.exp(P).unwrap(), P).unwrap();
            prop_assert!(!lhs.disjoint(&rhs));
            // ln(a*a) = 2 ln a
            let l2 = Interval::point(&a * &a).ln(P).unwrap();
            prop_assert!(!l2.disjoint(&x.ln(P).unwrap().mul(&Interval::int(2), P).unwrap()));
        }

        #[test]
        fn precisions_agree(a in r(), bits in 8u32..160) {
            // Enclosures at a low and a high precision must overlap and nest around the value.
            let (x, lo, hi) = (Interval::point(a.clone()), Prec::new(bits), Prec::new(300));
            let fs: [fn(&Interval, Prec) -> Option<Interval>; 6] = [
                Interval::sin, Interval::cos, Interval::exp, Interval::ln, Interval::sqrt, Interval::tan,
            ];
            for f in fs {
                if let (Some(u), Some(v)) = (f(&x, lo), f(&x, hi)) {
                    prop_assert!(!u.disjoint(&v), "{u} vs {v}");
                    prop_assert!(v.width() < two_pow(-250) * (v.mag_bound() + rat(1)));
                }
            }
            let w = Interval::new(a.clone() / rat(1000), a.clone() / rat(1000) + q(1, 7)).unwrap();
            for f in fs {
                if let (Some(u), Some(v)) = (f(&w, lo), f(&Interval::point(w.midpoint()), hi)) {
                    prop_assert!(!u.disjoint(&v), "{u} vs {v}");
                }
            }
        }

        #[test]
        fn distributive_never_disjoint(a in r(), b in r(), c in r()) {
            let (x, y, z) = (Interval::point(a), Interval::point(b), Interval::point(c));
            let lhs = x.add(&y, P).unwrap().mul(&z, P).unwrap();
            let rhs = x.mul(&z, P).unwrap().add(&y.mul(&z, P).unwrap(), P).unwrap();
            prop_assert!(!lhs.disjoint(&rhs));
        }
    }
}
