//! The exact normal form: rational functions over ℚ in atoms, canonical by construction.
//!
//! Nothing here knows about source spans; [`lower`](crate::lower) turns syntax
//! into these values and reports errors with spans.

pub mod atom;
pub(crate) mod bases;
pub(crate) mod denest;
pub(crate) mod func;
pub mod gcd;
pub mod limits;
pub(crate) mod merge;
pub mod mono;
pub(crate) mod numeric;
pub mod pack;
pub(crate) mod poly;
pub(crate) mod power;
pub mod present;
pub mod print;
pub(crate) mod qops;
pub(crate) mod ranges;
pub(crate) mod rat;
pub(crate) mod reduce;
pub(crate) mod series;
pub(crate) mod sign;
pub mod subst;
pub(crate) mod trig;

pub use atom::{Atom, AtomId};
pub use poly::{Poly, Q};
pub use rat::Rat;
pub use sign::{Assumptions, Range, Sign};

use std::fmt;

/// A difference `d` (zero when a step holds) looked at again where its normal form is
/// not canonical: zero when sines and cosines of related angles, large powers kept
/// factored (`power::settle`), products of `abs` and roots (`merge::merged`) or roots
/// of one base over a common index (`bases::common_index`) show it zero; otherwise `d`,
/// with kept factors written out where that is affordable.
pub fn settle(d: &Rat, s: &Assumptions) -> Rat {
    if d.is_zero() {
        return Rat::zero();
    }
    // Symbols alone: the form is canonical, nothing to look at again (the bulk case).
    let plain = |a: AtomId| {
        matches!(
            atom::get(a),
            Atom::Sym(_) | Atom::Pi | Atom::Moment(..) | Atom::At(..)
        )
    };
    if d.atoms().into_iter().all(plain) {
        return d.clone();
    }
    let rebased = trig::rebase(d, s).ok();
    if rebased.as_ref().is_some_and(|r| r.is_zero()) {
        return Rat::zero();
    }
    let d = power::settle(d, s);
    let merged_zero = |r: &Rat| {
        merge::merged(r, s).is_some_and(|m| m.is_zero())
            || merge::merged_logs(r, s).is_some_and(|m| m.is_zero())
    };
    if d.is_zero() || merged_zero(&d) || rebased.as_ref().is_some_and(merged_zero) {
        return Rat::zero();
    }
    // Roots of one base with different indices (`2^(3/4)`, `sqrt(2) 2^(1/4)`).
    if let Some(b) = bases::common_index(&d, s) {
        if b.is_zero() || merged_zero(&b) {
            return Rat::zero();
        }
    }
    d
}

/// A resource limit that an operation would exceed. The size limits carry the limit in
/// force (this thread's [`limits::Limits`] when the operation failed), and the messages
/// say the limit, never how to change it (only the command line knows its flags).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Limit {
    /// An intermediate result would have more than this many terms.
    Terms(usize),
    /// An exponent would not fit.
    Exponent,
    /// A fractional power whose root index is above 64 (`x^(1/65)`).
    RootIndex,
    /// A number would have more than this many decimal digits.
    Digits(u64),
    /// The time budget of the current claim ran out.
    Time,
}

impl Limit {
    /// [`Limit::Terms`] with this thread's limit.
    pub fn terms() -> Limit {
        Limit::Terms(limits::max_terms())
    }
}

impl fmt::Display for Limit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Limit::Terms(n) => write!(f, "the result would have more than the limit of {n} terms"),
            Limit::Exponent => write!(f, "an exponent exceeds {}", mono::MAX_EXPONENT),
            Limit::RootIndex => {
                f.write_str("a root index above 64 (rigor takes roots up to the 64th)")
            }
            Limit::Digits(n) => write!(f, "a number would have more than the limit of {n} digits"),
            Limit::Time => f.write_str("the time budget ran out"),
        }
    }
}

/// Why an operation on normal forms failed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum NormError {
    /// Division by an expression that is exactly zero.
    DivisionByZero,
    /// `0^0`.
    ZeroToZero,
    /// A value outside a function's real domain (`sqrt(-1)`, `ln(0)`).
    Domain(String),
    /// A resource limit.
    Limit(Limit),
}

impl From<Limit> for NormError {
    fn from(l: Limit) -> NormError {
        NormError::Limit(l)
    }
}

impl fmt::Display for NormError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            NormError::DivisionByZero => {
                f.write_str("division by an expression that is exactly zero")
            }
            NormError::ZeroToZero => f.write_str("0^0 is undefined"),
            NormError::Domain(s) => f.write_str(s),
            // Running out of time is not a refusal: the step is undecided.
            NormError::Limit(Limit::Time) => write!(f, "{}", Limit::Time),
            NormError::Limit(l) => write!(f, "refused: {l}"),
        }
    }
}

impl std::error::Error for NormError {}
