//! Signs: what the declared signs of symbols say about the sign of an expression.

use super::atom::{self, Atom, AtomId};
use super::poly::Poly;
use super::rat::Rat;
use foldhash::HashMap;
use num_traits::{Signed, Zero};

/// What is known of a value's sign.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Sign {
    /// `= 0`
    Zero,
    /// `> 0`
    Pos,
    /// `< 0`
    Neg,
    /// `>= 0`
    NonNeg,
    /// `<= 0`
    NonPos,
    /// `!= 0`
    NonZero,
    /// nothing known
    Unknown,
}

impl Sign {
    /// The sign of `-x`.
    pub fn flip(self) -> Sign {
        match self {
            Sign::Pos => Sign::Neg,
            Sign::Neg => Sign::Pos,
            Sign::NonNeg => Sign::NonPos,
            Sign::NonPos => Sign::NonNeg,
            s => s,
        }
    }

    /// The sign of a product.
    pub fn times(self, o: Sign) -> Sign {
        use Sign::*;
        match (self, o) {
            (Zero, _) | (_, Zero) => Zero,
            (Pos, s) | (s, Pos) => s,
            (Neg, s) | (s, Neg) => s.flip(),
            (NonZero, NonZero) => NonZero,
            (NonNeg, NonNeg) | (NonPos, NonPos) => NonNeg,
            (NonNeg, NonPos) | (NonPos, NonNeg) => NonPos,
            _ => Unknown,
        }
    }

    /// The sign of a sum.
    pub fn plus(self, o: Sign) -> Sign {
        use Sign::*;
        match (self, o) {
            (Zero, s) | (s, Zero) => s,
            (Pos, Pos) | (Pos, NonNeg) | (NonNeg, Pos) => Pos,
            (NonNeg, NonNeg) => NonNeg,
            (Neg, Neg) | (Neg, NonPos) | (NonPos, Neg) => Neg,
            (NonPos, NonPos) => NonPos,
            _ => Unknown,
        }
    }

    /// The sign of `x^e`.
    pub fn pow(self, e: u32) -> Sign {
        if e == 0 {
            return Sign::Pos;
        }
        if e % 2 == 1 {
            return self;
        }
        match self {
            Sign::Pos | Sign::Neg | Sign::NonZero => Sign::Pos,
            Sign::Zero => Sign::Zero,
            _ => Sign::NonNeg,
        }
    }

    /// Known to be nonzero.
    pub fn is_nonzero(self) -> bool {
        matches!(self, Sign::Pos | Sign::Neg | Sign::NonZero)
    }

    /// Known to be `>= 0`.
    pub fn is_nonneg(self) -> bool {
        matches!(self, Sign::Pos | Sign::NonNeg | Sign::Zero)
    }

    /// Known to be `<= 0`.
    pub fn is_nonpos(self) -> bool {
        matches!(self, Sign::Neg | Sign::NonPos | Sign::Zero)
    }
}

/// An interval a symbol is declared in (`symbols 0 < beta < pi/2`).
#[derive(Clone, Debug, PartialEq)]
pub struct Range {
    /// The lower bound.
    pub lo: Rat,
    /// Whether the lower bound is excluded.
    pub lo_strict: bool,
    /// The upper bound.
    pub hi: Rat,
    /// Whether the upper bound is excluded.
    pub hi_strict: bool,
}

/// The declared signs of symbols, and the intervals of those declared in one.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Assumptions {
    signs: HashMap<AtomId, Sign>,
    ranges: HashMap<AtomId, Range>,
}

impl Assumptions {
    /// No assumptions.
    pub fn new() -> Assumptions {
        Assumptions::default()
    }

    /// Declares the sign of a symbol (the later declaration wins).
    pub fn set(&mut self, a: AtomId, s: Sign) {
        self.signs.insert(a, s);
    }

    /// Declares (or, with `None`, forgets) the interval of a symbol; returns the old one.
    pub fn set_range(&mut self, a: AtomId, r: Option<Range>) -> Option<Range> {
        match r {
            Some(r) => self.ranges.insert(a, r),
            None => self.ranges.remove(&a),
        }
    }

    /// The interval declared for a symbol, if any.
    pub fn range(&self, a: AtomId) -> Option<&Range> {
        self.ranges.get(&a)
    }

    /// The declared sign of an atom that is a symbol.
    pub fn declared(&self, a: AtomId) -> Sign {
        self.signs.get(&a).copied().unwrap_or(Sign::Unknown)
    }

    /// The symbols with a declared sign.
    pub fn iter(&self) -> impl Iterator<Item = (AtomId, Sign)> + '_ {
        self.signs.iter().map(|(a, s)| (*a, *s))
    }

    /// The sign of an atom.
    pub fn atom(&self, a: AtomId) -> Sign {
        match atom::get(a) {
            Atom::Sym(_) => self.declared(a),
            Atom::Pi | Atom::Exp(_) => Sign::Pos,
            Atom::Factor(p) => self.poly(p),
            Atom::Sqrt(p) => {
                if self.poly(p) == Sign::Pos {
                    Sign::Pos
                } else {
                    Sign::NonNeg
                }
            }
            Atom::Root(p, n) => {
                let s = self.poly(p);
                if n % 2 == 1 {
                    s
                } else if s == Sign::Pos {
                    Sign::Pos
                } else {
                    Sign::NonNeg
                }
            }
            Atom::Abs(p) => {
                if self.poly(p).is_nonzero() {
                    Sign::Pos
                } else {
                    Sign::NonNeg
                }
            }
            Atom::Moment(_, exps) => {
                if exps.iter().all(|e| e.1 % 2 == 0) {
                    Sign::NonNeg
                } else {
                    Sign::Unknown
                }
            }
            Atom::Pow(b, _) => {
                if self.rat(b) == Sign::Pos {
                    Sign::Pos
                } else {
                    Sign::Unknown
                }
            }
            Atom::Ln(u) => match u.as_constant() {
                Some(q) if q > num_traits::One::one() => Sign::Pos,
                Some(q) if q.is_positive() && q < num_traits::One::one() => Sign::Neg,
                _ => Sign::Unknown,
            },
            Atom::Sin(u) => super::ranges::trig_sign(self, u, false),
            Atom::Cos(u) => super::ranges::trig_sign(self, u, true),
            Atom::At(..) => Sign::Unknown,
        }
    }

    /// The sign of a polynomial, term by term (and `±(1 − sin(u)²)`, which is `±cos(u)²`).
    pub fn poly(&self, p: &Poly) -> Sign {
        if let Some(u) = super::func::one_minus_sin_squared(p) {
            return match super::ranges::trig_sign(self, &u, true) {
                s if s.is_nonzero() => Sign::Pos,
                _ => Sign::NonNeg,
            };
        }
        if let Some(u) = super::func::one_minus_sin_squared(&p.neg()) {
            return match super::ranges::trig_sign(self, &u, true) {
                s if s.is_nonzero() => Sign::Neg,
                _ => Sign::NonPos,
            };
        }
        let mut total = Sign::Zero;
        for (m, q) in p.terms() {
            let mut s = if q.is_zero() {
                Sign::Zero
            } else if q.is_positive() {
                Sign::Pos
            } else {
                Sign::Neg
            };
            for &(a, e) in m.pairs() {
                s = s.times(self.atom(a).pow(e));
            }
            total = total.plus(s);
            if total == Sign::Unknown {
                // A constant (`sqrt(2) - 1`): by a rigorous enclosure, where it excludes 0.
                return super::numeric::sign(p).unwrap_or(Sign::Unknown);
            }
        }
        total
    }

    /// The sign of a rational function.
    pub fn rat(&self, r: &Rat) -> Sign {
        let d = self.poly(r.den());
        let d = match d {
            // A denominator is never zero where the expression is defined.
            Sign::NonNeg => Sign::Pos,
            Sign::NonPos => Sign::Neg,
            Sign::Unknown => Sign::NonZero,
            s => s,
        };
        let n = self.poly(r.num());
        match (n, d) {
            (n, Sign::NonZero) => {
                if n.is_nonzero() {
                    Sign::NonZero
                } else if n == Sign::Zero {
                    Sign::Zero
                } else {
                    Sign::Unknown
                }
            }
            (n, d) => n.times(d),
        }
    }
}
