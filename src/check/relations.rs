//! Links other than `=`: `!=`, `<`, `<=`, `>`, `>=` (verified when the sign of the
//! difference follows from the declared signs, after the facts are used) and `~=`
//! (FORMAT.md §3: the ratio rounds to 1 at the precision of the one number written).

use super::report::{Justification, Status};
use super::signs::{describe, sign_of};
use super::step::{LinkInput, Reduced};
use super::walk::{unknown_atom, Checker};
use crate::decide::{decide, find_counterexample, Verdict};
use crate::diag::Code;
use crate::diag::Diagnostic;
use crate::interval::Prec;
use crate::normal::atom::{self, AtomId};
use crate::normal::print::plain;
use crate::normal::{Rat, Sign, Q};
use crate::syntax::ast::{BinOp, Expr, ExprKind, RelOp, Span};
use foldhash::{HashMap, HashMapExt};
use num_bigint::BigInt;
use num_traits::{One, Signed};

impl Checker<'_, '_> {
    /// `!=`: verified when the signs show `lhs − rhs` nonzero.
    pub(super) fn decide_ne(
        &self,
        red: &Reduced,
        span: Span,
        conditions: Vec<String>,
    ) -> Result<Status, Diagnostic> {
        if red.target().is_zero() {
            return Err(Diagnostic::error(
                Code::Inequality,
                "the two sides are equal, so `!=` is false",
                span,
                "",
            ));
        }
        let signs = &self.env.signs;
        let d = red
            .ra
            .sub(&red.rb)
            .map_err(|e| Diagnostic::error(Code::NoValue, e.to_string(), span, ""))?;
        if sign_of(&d, signs).is_nonzero() {
            return Ok(Status::Verified {
                how: Justification::Signs(red.via.clone()),
                side_conditions: conditions,
            });
        }
        let mut diag = Diagnostic::error(
            Code::Inequality,
            "not verified: the declared signs do not show that the sides differ",
            span,
            "",
        )
        .note(format!(
            "left − right = {}, which may be zero for some allowed values",
            plain(&d)
        ));
        if let Verdict::NotEqual { .. } = decide(&red.ra, &red.rb, signs) {
            diag.add_note(
                "the sides are not identical, but `!=` claims they differ for every allowed value",
            );
        }
        Err(diag)
    }

    /// `<`, `<=`, `>`, `>=`: verified when the sign of `lhs − rhs` follows from the signs.
    pub(super) fn decide_order(
        &self,
        op: RelOp,
        red: &Reduced,
        span: Span,
        conditions: Vec<String>,
    ) -> Result<Status, Diagnostic> {
        let signs = &self.env.signs;
        let d = red
            .ra
            .sub(&red.rb)
            .map_err(|e| Diagnostic::error(Code::NoValue, e.to_string(), span, ""))?;
        let sign = sign_of(&d, signs);
        let ok = match op {
            RelOp::Lt => sign == Sign::Neg,
            RelOp::Le => sign.is_nonpos(),
            RelOp::Gt => sign == Sign::Pos,
            _ => sign.is_nonneg(),
        };
        if ok {
            return Ok(Status::Verified {
                how: Justification::Signs(red.via.clone()),
                side_conditions: conditions,
            });
        }
        let mut diag = Diagnostic::error(
            Code::Inequality,
            format!("not verified: `{op}` does not follow from the declared signs"),
            span,
            "",
        )
        .note(format!("left − right = {}", plain(&d)));
        if let Some(e) = red.elim.as_ref().filter(|e| !e.stuck.is_empty()) {
            diag.add_note(format!(
                "the facts do not determine {}",
                super::explain::names(&e.stuck)
            ));
        }
        // "False for some values" only where no fact in scope ties those values.
        let violated = if self.facts_tie(&d, red) {
            None
        } else {
            violation(&red.ra, &red.rb, op, signs)
        };
        match violated {
            Some(c) => {
                diag.message =
                    format!("`{op}` is false for some values allowed by the declared signs").into();
                diag.add_note(c);
            }
            None => diag.add_note(format!("its sign is {}", describe(sign))),
        }
        Err(diag)
    }

    /// Whether facts in scope, left over once the unknowns are eliminated, still relate
    /// the quantities of `d` (so a point chosen from the signs alone may break them).
    fn facts_tie(&self, d: &Rat, red: &Reduced) -> bool {
        let signs = &self.env.signs;
        let is_unknown = |x: AtomId| unknown_atom(&self.scope, x);
        let steps = red.elim.as_ref().map_or(&[][..], |e| &e.steps[..]);
        let left: Vec<super::elimination::Fact> = red
            .scope
            .iter()
            .filter_map(|f| {
                super::elimination::apply_steps(&f.value, steps, signs)
                    .ok()
                    .filter(|v| !v.is_zero())
                    .map(|value| super::elimination::Fact {
                        value,
                        name: f.name.clone(),
                    })
            })
            .collect();
        let constrained = super::elimination::constrained_atoms(&left, &is_unknown, signs);
        let mut mine = Vec::new();
        crate::decide::symbols_in(d, &mut mine);
        mine.iter().any(|a| constrained.contains(a))
    }

    /// `~=`: each side's value (unknowns and fixed parameters replaced by the facts),
    /// then their ratio against the precision written.
    pub(super) fn decide_approx(
        &self,
        input: &LinkInput<'_>,
        red: &Reduced,
        conditions: Vec<String>,
    ) -> Result<Status, Diagnostic> {
        if let Some(order) = self.small_order(red) {
            return self.decide_small(input, red, order, conditions);
        }
        let signs = &self.env.signs;
        let is_unknown = |x: AtomId| unknown_atom(&self.scope, x);
        let value = |r: &Rat| {
            super::elimination::reduce_fully(r, &red.used, &is_unknown, signs, input.deadline)
                .unwrap_or_else(|_| r.clone())
        };
        let (va, vb) = (value(&red.a), value(&red.b));
        self.approx(&va, &vb, &input.link.rhs, input.span, conditions)
    }

    /// The order to keep when a side mentions a small quantity (the highest declared
    /// among those mentioned), else `None`.
    fn small_order(&self, red: &Reduced) -> Option<u32> {
        let mut syms = Vec::new();
        crate::decide::symbols_in(&red.a, &mut syms);
        crate::decide::symbols_in(&red.b, &mut syms);
        syms.iter()
            .filter_map(|a| self.small_of(*a))
            .map(|(_, o)| o)
            .max()
    }

    /// The small quantity (and order) atom `a` is, or is a time derivative of.
    fn small_of(&self, a: AtomId) -> Option<(String, u32)> {
        let n = atom::sym_name(a)?;
        let base = n.trim_end_matches('\'');
        self.small
            .iter()
            .find(|(s, _)| s.trim_end_matches('\'') == base)
            .map(|(s, o)| (s.clone(), *o))
    }

    /// `~=` with small quantities: after the facts (as for `=`), the difference has no
    /// term of order up to `order` in the small quantities and their derivatives.
    fn decide_small(
        &self,
        input: &LinkInput<'_>,
        red: &Reduced,
        order: u32,
        conditions: Vec<String>,
    ) -> Result<Status, Diagnostic> {
        let span = input.span;
        let target = red.target();
        let mut of: Vec<String> = Vec::new();
        let mut syms = Vec::new();
        crate::decide::symbols_in(&red.a, &mut syms);
        crate::decide::symbols_in(&red.b, &mut syms);
        for a in syms {
            if let Some((s, _)) = self.small_of(a) {
                if !of.contains(&s) {
                    of.push(s);
                }
            }
        }
        let verified = Status::Verified {
            how: Justification::Small {
                order,
                of: of.clone(),
            },
            side_conditions: conditions,
        };
        if target.is_zero() {
            return Ok(verified);
        }
        let eps = atom::sym("\u{1}eps");
        let scaled = |a: AtomId| {
            self.small_of(a).map(|_| {
                Rat::atom(a)
                    .mul(&Rat::atom(eps))
                    .unwrap_or_else(|_| Rat::atom(a))
            })
        };
        let d = crate::normal::subst::Subst::new(&scaled, &self.env.signs)
            .rat(&target)
            .map_err(|e| Diagnostic::error(Code::NoValue, e.to_string(), span, ""))?;
        let coeffs = crate::normal::series::series(&d, eps, order as usize, &self.env.signs)
            .map_err(|e| {
                let why = match e {
                    crate::normal::series::SeriesError::NotAnalytic(w) => w,
                    crate::normal::series::SeriesError::Norm(n) => n.to_string(),
                };
                Diagnostic::error(
                    Code::NotVerified,
                    format!("`~=` is not verified: rigor cannot expand {why} in powers of the small quantities"),
                    span,
                    "undecided",
                )
            })?;
        let Some((k, c)) = coeffs.iter().enumerate().find(|(_, c)| !c.is_zero()) else {
            return Ok(verified);
        };
        let what = if k == 0 {
            "even with the small quantities set to zero".to_string()
        } else {
            format!("at order {k} in {}", of.join(", "))
        };
        Err(Diagnostic::error(
            Code::Approximation,
            format!("`~=` does not hold to the order kept: the sides differ {what}"),
            span,
            "not equal to this order",
        )
        .note(format!(
            "left − right = {} + …, which should have no term of order up to {order}",
            plain(c)
        ))
        .note(format!("left side:  {}", plain(&red.a)))
        .note(format!("right side: {}", plain(&red.b))))
    }

    fn approx(
        &self,
        a: &Rat,
        b: &Rat,
        rhs: &Expr,
        span: Span,
        conditions: Vec<String>,
    ) -> Result<Status, Diagnostic> {
        let (c, ulp) = literal_precision(rhs, &self.report.source)
            .map_err(|why| Diagnostic::error(Code::Approximation, why, span, ""))?;
        let Ok(ratio) = a.div(b) else {
            return Err(Diagnostic::error(
                Code::Approximation,
                "the right side of `~=` is zero",
                span,
                "",
            ));
        };
        // A/B must be a number; then A ≈ B when c·A/B rounds to c at the precision
        // written (ties away from zero: with `~= 3`, 2.5 rounds to 3; with `~= 2`, not).
        let mut sy = Vec::new();
        crate::decide::symbols_in(&ratio, &mut sy);
        if !sy.is_empty() {
            return Err(Diagnostic::error(
                Code::Approximation,
                format!(
                    "`~=` is not verified: the ratio of the sides, {}, is not a number",
                    plain(&ratio)
                ),
                span,
                "",
            ));
        }
        let point = HashMap::new();
        let mut ev = crate::decide::Evaluator::new(&point);
        ev.prec = Prec::new(128);
        let half = &ulp / Q::from_integer(BigInt::from(2));
        let ci = crate::interval::Interval::point(c.clone());
        let ratio_value = ev.rat(&ratio);
        // An exact ratio is decided exactly, at any precision written.
        let scaled = match ratio.as_constant() {
            Some(r) => Some(crate::interval::Interval::point(&r * &c)),
            None => ratio_value.as_ref().and_then(|r| r.mul(&ci, ev.prec)),
        };
        let verdict = scaled
            .as_ref()
            .and_then(|v| rounds_to(v.lo(), v.hi(), &c, &half));
        match verdict {
            Some(true) => Ok(Status::Verified {
                how: Justification::Approx,
                side_conditions: conditions,
            }),
            Some(false) => {
                Err(Diagnostic::error(
                    Code::Approximation,
                    format!(
                        "`~=` does not hold at the precision written: the exact ratio is {}",
                        plain(&ratio)
                    ),
                    span,
                    "not this close",
                )
                .note(format!(
                    "left / right ≈ {}; so where the right side says {}, the left side is ≈ {}, which does not round to {} at the precision written",
                    ratio_value.map_or_else(|| "?".into(), |r| r.to_decimal_string(6)),
                    show(&c),
                    scaled.as_ref().map_or_else(|| "?".into(), |r| r.to_decimal_string(6)),
                    show(&c)
                ))
                .note_if(
                    scaled.is_some_and(|v| v.lo() == v.hi() && (v.lo() - &c).abs() == half),
                    "it lies exactly halfway; rigor rounds a tie away from zero",
                ))
            }
            _ => Err(Diagnostic::error(
                Code::NotVerified,
                "`~=` is not verified: rigor could not bound the ratio precisely enough",
                span,
                "undecided",
            )),
        }
    }
}

/// Whether every value in `[lo, hi]` rounds to `c` (`Some(true)`), none does
/// (`Some(false)`), or the interval straddles a boundary (`None`), where `v` rounds to
/// `c` at half-width `h` when `c − h <= v < c + h` for `c > 0` (ties away from zero;
/// mirrored for `c < 0`).
fn rounds_to(lo: &Q, hi: &Q, c: &Q, h: &Q) -> Option<bool> {
    let (below, above) = (c - h, c + h);
    let positive = c > &Q::from_integer(BigInt::from(0));
    // `inside(v)`: v lies in the rounding interval of c.
    let inside = |v: &Q| {
        if positive {
            v >= &below && v < &above
        } else {
            v > &below && v <= &above
        }
    };
    if inside(lo) && inside(hi) {
        return Some(true);
    }
    // Wholly outside: entirely below the interval, or entirely above it.
    let wholly_below = if positive { hi < &below } else { hi <= &below };
    let wholly_above = if positive { lo >= &above } else { lo > &above };
    (wholly_below || wholly_above).then_some(false)
}

/// A checked point where `a op b` is false, described.
fn violation(a: &Rat, b: &Rat, op: RelOp, signs: &crate::normal::Assumptions) -> Option<String> {
    // Reuse the counterexample search on `a` against `b`, then test the relation there.
    let c = find_counterexample(a, b, signs)?;
    let point: HashMap<AtomId, Q> = c
        .values
        .iter()
        .map(|(n, q)| (atom::sym(n), q.clone()))
        .collect();
    let mut ev = crate::decide::Evaluator::new(&point);
    let d = ev.rat(&a.sub(b).ok()?)?;
    let zero = Q::from_integer(0.into());
    let false_there = match op {
        RelOp::Lt => !d.is_negative() && (d.is_positive() || d.lo() >= &zero),
        RelOp::Le => d.is_positive(),
        RelOp::Gt => d.is_negative() || d.hi() <= &zero,
        _ => d.is_negative(),
    };
    false_there.then(|| {
        format!(
            "at {} the left side is {} and the right side {}",
            c.assignment(),
            c.lhs,
            c.rhs
        )
    })
}

fn show(q: &Q) -> String {
    if q.denom().is_one() {
        return q.numer().to_string();
    }
    // Decimal form of a terminating fraction, else p/q.
    let mut d = q.denom().clone();
    let mut k = 0usize;
    let two = BigInt::from(2);
    let five = BigInt::from(5);
    let zero = BigInt::from(0);
    while (&d % &two) == zero || (&d % &five) == zero {
        if (&d % &two) == zero {
            d /= &two;
        } else {
            d /= &five;
        }
        k += 1;
        if k > 60 {
            break;
        }
    }
    if !d.is_one() {
        return format!("{}/{}", q.numer(), q.denom());
    }
    let scaled = q * Q::from_integer(BigInt::from(10).pow(k as u32));
    let n = scaled.to_integer();
    let s = n.abs().to_string();
    let s = format!("{:0>width$}", s, width = k + 1);
    let (i, f) = s.split_at(s.len() - k);
    let f = f.trim_end_matches('0');
    let sign = if q.is_negative() { "-" } else { "" };
    if f.is_empty() {
        format!("{sign}{i}")
    } else {
        format!("{sign}{i}.{f}")
    }
}

/// The one number written on the right side of `~=` and the unit of its last written
/// digit: the side must be that number times symbols (`0.71 R`, `-9.8`, `0.6 m L^2`);
/// anything else is refused rather than guessed at (`2 * 0.30 R`, `1/0.3`).
fn literal_precision(e: &Expr, src: &str) -> Result<(Q, Q), String> {
    let mut found = Vec::new();
    let shape = number_times_symbols(e, src, false, false, &mut found);
    match (shape, found.as_slice()) {
        (true, [(q, ulp, false)]) => Ok((q.clone(), ulp.clone())),
        _ => Err(
            "the right side of `~=` must be one written number times symbols (`0.71 R`), whose precision says how close; write the number out (`0.60 R`, not `2 * 0.30 R`)"
                .into(),
        ),
    }
}

/// Whether `e` is a product or quotient of symbols and numbers; collects each number
/// with its precision and whether it divides.
fn number_times_symbols(
    e: &Expr,
    src: &str,
    neg: bool,
    divides: bool,
    found: &mut Vec<(Q, Q, bool)>,
) -> bool {
    match &e.kind {
        ExprKind::Num(q) => {
            let Some(ulp) = src.get(e.span.start..e.span.end).and_then(ulp_of) else {
                return false;
            };
            found.push((if neg { -q.clone() } else { q.clone() }, ulp, divides));
            true
        }
        ExprKind::Sym(_) | ExprKind::Pi => true,
        ExprKind::Neg(a) => number_times_symbols(a, src, !neg, divides, found),
        ExprKind::Bin(BinOp::Mul, a, b) => {
            number_times_symbols(a, src, neg, divides, found)
                && number_times_symbols(b, src, false, divides, found)
        }
        ExprKind::Bin(BinOp::Div, a, b) => {
            number_times_symbols(a, src, neg, divides, found)
                && number_times_symbols(b, src, false, !divides, found)
        }
        // A power or a function of symbols only (`R^2`, `sqrt(g/L)`).
        ExprKind::Bin(BinOp::Pow, base, _) => !has_number(base),
        ExprKind::Call(_, args) => !args.iter().any(has_number),
        ExprKind::Bin(..) => false,
    }
}

fn has_number(e: &Expr) -> bool {
    e.any(&|n| matches!(n.kind, ExprKind::Num(_)))
}

/// `0.71` → 1/100, `1.5e-3` → 1/10000, `3` → 1.
fn ulp_of(text: &str) -> Option<Q> {
    let t = text.trim();
    let (mant, exp) = match t.find(['e', 'E']) {
        Some(i) => (&t[..i], t[i + 1..].parse::<i32>().ok()?),
        None => (t, 0),
    };
    let decimals = mant.split_once('.').map_or(0, |(_, f)| f.len()) as i32;
    let k = decimals - exp;
    let ten = BigInt::from(10);
    Some(if k >= 0 {
        Q::new(BigInt::one(), ten.pow(k as u32))
    } else {
        Q::from_integer(ten.pow((-k) as u32))
    })
}
