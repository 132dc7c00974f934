//! The guard at work: before a link is reported verified, both sides as written are
//! evaluated by the independent evaluator of `crate::guard` at a few points that respect
//! the declared signs and satisfy the facts the link used (unknowns take the values the
//! elimination gives). A clear disagreement makes the link "undecided: internal check
//! disagrees", with both values; it can never make a link verified or failed.

use super::report::Status;
use super::solve::{Fact, Step};
use super::step::{LinkInput, Reduced};
use super::walk::{unknown_atom, Checker};
use crate::decide::Evaluator;
use crate::diag::Diagnostic;
use crate::guard::{self, Ball};
use crate::interval::Prec;
use crate::normal::atom::{self, AtomId};
use crate::normal::ranges::Sample;
use crate::normal::{Sign, Q};
use crate::syntax::ast::RelOp;
use num_traits::{FromPrimitive, ToPrimitive};
use std::collections::HashMap;

/// Points tried per link.
const POINTS: u64 = 3;

/// A small deterministic generator (splitmix64): the same file is checked the same way
/// in every run.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A value of the declared sign, a short binary fraction in [0.25, 4).
    fn value(&mut self, sign: Sign) -> f64 {
        let k = (self.next() % 60) as f64;
        let x = 0.25 + k / 16.0;
        let negative = match sign {
            Sign::Pos | Sign::NonNeg => false,
            Sign::Neg | Sign::NonPos => true,
            _ => self.next() % 2 == 0,
        };
        if negative {
            -x
        } else {
            x
        }
    }
}

impl Checker<'_, '_> {
    /// `status` as the guard lets it stand: a verified `=` or inequality whose sides,
    /// as written, clearly disagree at a point becomes undecided.
    pub(super) fn confirm(
        &mut self,
        input: &LinkInput<'_>,
        red: Option<&Reduced>,
        status: Status,
    ) -> Status {
        if !status.is_verified() || input.link.op == RelOp::Approx || input.link.op == RelOp::Ne {
            return status;
        }
        let (lhs, rhs) = (input.lhs_expr, &input.link.rhs);
        let mut rng =
            Rng(0x5EED ^ ((input.span.start as u64) << 20) ^ self.report.source.len() as u64);
        let mut agreed = false;
        for _ in 0..POINTS {
            let Some(point) = self.point(input, &Situation::of(red), &HashMap::new(), &mut rng)
            else {
                continue;
            };
            let env = &self.guard_env;
            let (Ok(a), Ok(b)) = guard::eval_both(lhs, rhs, env, &point) else {
                continue;
            };
            if disagrees(input.link.op, &a, &b) {
                self.report
                    .diagnostics
                    .push(disagreement(input, &point, a, b));
                return Status::Undecided;
            }
            agreed = true;
        }
        self.report.guarded += usize::from(agreed);
        status
    }

    /// A point for the guard: `fixed` values, random values of the declared signs for
    /// the other symbols, `where` values, and the unknowns' values from the elimination;
    /// `None` when it cannot be made to satisfy the facts.
    fn point(
        &self,
        input: &LinkInput<'_>,
        sit: &Situation<'_>,
        fixed: &HashMap<String, Q>,
        rng: &mut Rng,
    ) -> Option<HashMap<String, f64>> {
        let env = &self.guard_env;
        let mut names: Vec<String> = guard::free_symbols(input.lhs_expr, env)
            .into_iter()
            .chain(guard::free_symbols(&input.link.rhs, env))
            .collect();
        for f in sit.facts {
            let mut syms = Vec::new();
            crate::decide::symbols_in(&f.value, &mut syms);
            names.extend(syms.into_iter().filter_map(atom::sym_name));
        }
        names.sort();
        names.dedup();
        let mut exact: HashMap<AtomId, Q> = HashMap::new();
        let mut point: HashMap<String, f64> = HashMap::new();
        for n in &names {
            let a = atom::sym(n);
            let q = match fixed.get(n) {
                Some(q) => q.clone(),
                None => {
                    let t = Q::new(((rng.next() % 15) + 1).into(), 16.into());
                    match crate::normal::ranges::sample(&self.env.signs, a, &t) {
                        Sample::At(q) => q,
                        Sample::Unusable => return None,
                        Sample::Free => Q::from_f64(rng.value(self.env.signs.declared(a)))?,
                    }
                }
            };
            point.insert(n.clone(), q.to_f64()?);
            exact.insert(a, q);
        }
        for (a, e) in input.subs.iter().zip(input.where_) {
            let v = guard::eval(&e.value, env, &point).ok()?;
            point.insert(e.name.name.clone(), v.mid);
            exact.insert(a.0, Q::from_f64(v.mid)?);
        }
        // Atoms' values carry over from one evaluation to the next: the point only grows.
        let mut memo = HashMap::new();
        for s in sit.steps.iter().rev() {
            let mut ev = Evaluator::with_values(&exact, Prec::new(128), memo);
            let v = ev.rat(&s.value)?.midpoint();
            memo = ev.values();
            if let Some(n) = atom::sym_name(s.unknown) {
                point.insert(n, v.to_f64()?);
            }
            exact.insert(s.unknown, v);
        }
        // The facts must hold there (else the point says nothing); with `strict`, a fact
        // that cannot be evaluated there fails the point too.
        let tiny = Q::new(1.into(), num_bigint::BigInt::from(10).pow(20));
        let mut ev = Evaluator::with_values(&exact, Prec::new(128), memo);
        let holds = sit.facts.iter().all(|f| match ev.rat(&f.value) {
            Some(v) => v.lo() >= &-tiny.clone() && v.hi() <= &tiny,
            None => !sit.strict,
        });
        let unknown_left = names.iter().any(|n| {
            let a = atom::sym(n);
            unknown_atom(&self.scope, a) && !exact.contains_key(&a)
        });
        (holds && !(unknown_left && sit.via)).then_some(point)
    }

    /// Whether the guard lets a refutation stand: at the counterexample (and the
    /// unknowns' values there), the sides as written must not come out equal.
    pub(super) fn counterexample_stands(
        &self,
        input: &LinkInput<'_>,
        sit: &Situation<'_>,
        values: &[(String, Q)],
    ) -> Result<(), Diagnostic> {
        let fixed: HashMap<String, Q> = values.iter().cloned().collect();
        let mut rng = Rng(0xC0FFEE);
        let Some(point) = self.point(input, sit, &fixed, &mut rng) else {
            return Ok(());
        };
        let env = &self.guard_env;
        let (Ok(a), Ok(b)) = guard::eval_both(input.lhs_expr, &input.link.rhs, env, &point) else {
            return Ok(());
        };
        // Equal there only when the guard's enclosures overlap and are tight relative to
        // the values themselves (tiny values, `exp(-30 y)`, are not equal to each other
        // for being small).
        let scale = a.mid.abs().max(b.mid.abs());
        let equal_there = (a.mid - b.mid).abs() <= a.rad + b.rad && a.rad + b.rad <= 1e-10 * scale;
        if equal_there {
            let mut d = disagreement(input, &point, a, b);
            d.notes[1] = "rigor's exact argument says the sides differ here; please report this derivation as a bug in rigor".into();
            return Err(d);
        }
        Ok(())
    }
}

/// The facts and the elimination a point must agree with.
pub(super) struct Situation<'r> {
    /// Facts that must hold at the point.
    pub facts: &'r [Fact],
    /// The elimination's steps: the unknowns' values.
    pub steps: &'r [Step],
    /// Whether the link used facts (then every unknown needs a value from them).
    pub via: bool,
    /// Whether a fact that cannot be evaluated at the point rules the point out.
    pub strict: bool,
}

impl<'r> Situation<'r> {
    /// What a verified link used.
    pub fn of(red: Option<&'r Reduced>) -> Situation<'r> {
        Situation {
            facts: red.map_or(&[][..], |r| &r.used[..]),
            steps: red
                .and_then(|r| r.elim.as_ref())
                .map_or(&[][..], |e| &e.steps[..]),
            via: red.is_some_and(|r| !r.via.is_empty()),
            strict: true,
        }
    }
}

fn disagrees(op: RelOp, a: &Ball, b: &Ball) -> bool {
    let margin = |x: &Ball, y: &Ball| x.clearly_differs(y);
    match op {
        RelOp::Eq => margin(a, b),
        RelOp::Lt | RelOp::Le => a.mid > b.mid && margin(a, b),
        RelOp::Gt | RelOp::Ge => a.mid < b.mid && margin(a, b),
        _ => false,
    }
}

fn disagreement(
    input: &LinkInput<'_>,
    point: &HashMap<String, f64>,
    a: Ball,
    b: Ball,
) -> Diagnostic {
    let mut at: Vec<String> = point.iter().map(|(n, v)| format!("{n} = {v}")).collect();
    at.sort();
    Diagnostic::error(
        "E0903",
        "undecided: rigor's internal check disagrees with the exact verdict",
        input.span,
        "undecided",
    )
    .note(format!(
        "evaluated as written at {}: the left side is ≈ {:.9}, the right side ≈ {:.9}",
        at.join(", "),
        a.mid,
        b.mid
    ))
    .note(
        "the exact engine found this step to hold; please report this derivation as a bug in rigor",
    )
}
