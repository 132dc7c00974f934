//! The guard at work: before a link is reported verified, both sides as written are
//! evaluated by the independent evaluator of `crate::guard` at a few points that respect
//! the declared signs and satisfy the facts the link used (unknowns take the values the
//! elimination gives). A clear disagreement makes the link "undecided: internal check
//! disagrees", with both values; it can never make a link verified or failed.

use super::elimination::{Fact, Step};
use super::report::Status;
use super::step::{LinkInput, Reduced};
use super::walk::{unknown_atom, Checker};
use crate::decide::Evaluator;
use crate::diag::Code;
use crate::diag::Diagnostic;
use crate::guard::{self, Ball};
use crate::interval::Prec;
use crate::normal::atom::{self, AtomId};
use crate::normal::ranges::Sample;
use crate::normal::{Sign, Q};
use crate::syntax::ast::RelOp;
use foldhash::{HashMap, HashMapExt};
use num_traits::{FromPrimitive, ToPrimitive};

/// Points tried per link.
const POINTS: u64 = 3;

/// A small deterministic generator (splitmix64): the same file is checked the same way
/// in every run.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        guard::splitmix64(&mut self.0)
    }

    /// A value of the declared sign, a short binary fraction in [0.25, 4): (4 + k)/16.
    fn value(&mut self, sign: Sign) -> Q {
        let k = (self.next() % 60) as i64;
        let negative = match sign {
            Sign::Pos | Sign::NonNeg => false,
            Sign::Neg | Sign::NonPos => true,
            _ => self.next() % 2 == 0,
        };
        let n = if negative { -(4 + k) } else { 4 + k };
        Q::new(n.into(), 16.into())
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
        // A link verified from facts under a side condition must hold somewhere: at a
        // point that satisfies the facts with every condition it assumes nonzero.
        let assumes = matches!(&status, Status::Verified { side_conditions, .. } if !side_conditions.is_empty());
        let via = red.is_some_and(|r| !r.via.is_empty());
        let signs = &self.env.signs;
        let nonzero: Vec<crate::normal::Rat> = if assumes && via {
            self.conditions
                .iter()
                .filter(|(d, need)| {
                    *need == crate::lower::Need::NonZero && !signs.rat(d).is_nonzero()
                })
                .map(|(d, _)| d.clone())
                .collect()
        } else {
            Vec::new()
        };
        let base = Situation::of(red);
        let is_unknown = |a: AtomId| unknown_atom(&self.scope, a);
        // A parameter the elimination set to zero by dividing (`g = 0` from
        // `g m L (3 I_A - m L^2) = 0`, assuming `3 I_A - m L^2 != 0`) is not taken from
        // it: the facts leave the condition room only where that parameter vanishes,
        // and a point must show room with the parameters as given.
        let steps: Vec<Step> = if nonzero.is_empty() {
            base.steps.to_vec()
        } else {
            base.steps
                .iter()
                .filter(|s| is_unknown(s.unknown) || s.divisor.is_none() || !s.value.is_zero())
                .cloned()
                .collect()
        };
        let params: Vec<Step> = if nonzero.is_empty() {
            Vec::new()
        } else {
            let left: Vec<Fact> = base
                .facts
                .iter()
                .filter_map(|f| {
                    let v = super::elimination::apply_steps(&f.value, &steps, signs).ok()?;
                    (!v.is_zero()).then(|| Fact {
                        value: v,
                        name: f.name.clone(),
                    })
                })
                .collect();
            super::elimination::solve_for_point(&left, &is_unknown, signs).0
        };
        let sit = Situation {
            nonzero: &nonzero,
            params: &params,
            steps: &steps,
            ..base
        };
        // Whether every point tried was ruled out by the facts or the conditions (not
        // by a quantity the guard could not give a value).
        let mut ruled_out = true;
        let names = self.point_names(input, &sit);
        for _ in 0..POINTS {
            let mut excluded = false;
            let Some(point) = self.point(
                (input, &names),
                &sit,
                &HashMap::new(),
                &mut rng,
                &mut excluded,
            ) else {
                ruled_out &= excluded;
                continue;
            };
            ruled_out = false;
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
        if assumes && via && ruled_out {
            if let Status::Verified {
                side_conditions, ..
            } = &status
            {
                self.report.diagnostics.push(
                    Diagnostic::error(
                        Code::NotVerified,
                        format!(
                            "not verified: this step assumes {}, and rigor found no values that satisfy the facts with that: the facts may rule it out",
                            side_conditions.join(" and ")
                        ),
                        input.span,
                        "not verified",
                    )
                    .note("where the facts force a divisor to zero, the step says nothing; declare the signs that rule that out (`symbols g > 0`), or check the facts"),
                );
            }
            return Status::Undecided;
        }
        status
    }

    /// The symbols a point for `input` gives values: those of both sides as written and
    /// of the facts.
    fn point_names(&self, input: &LinkInput<'_>, sit: &Situation<'_>) -> Vec<String> {
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
        names
    }

    /// A point for the guard: `fixed` values, random values of the declared signs for
    /// the other symbols, `where` values, and the unknowns' values from the elimination;
    /// `None` when it cannot be made to satisfy the facts.
    fn point(
        &self,
        (input, names): (&LinkInput<'_>, &[String]),
        sit: &Situation<'_>,
        fixed: &HashMap<String, Q>,
        rng: &mut Rng,
        excluded: &mut bool,
    ) -> Option<HashMap<String, f64>> {
        let env = &self.guard_env;
        let mut exact: HashMap<AtomId, Q> = HashMap::new();
        let mut point: HashMap<String, f64> = HashMap::new();
        for n in names {
            let a = atom::sym(n);
            let q = match fixed.get(n) {
                Some(q) => q.clone(),
                None => {
                    let t = Q::new(((rng.next() % 15) + 1).into(), 16.into());
                    match crate::normal::ranges::sample(&self.env.signs, a, &t) {
                        Sample::At(q) => q,
                        Sample::Unusable => return None,
                        Sample::Free => rng.value(self.env.signs.declared(a)),
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
        // The parameters the facts tie, once the unknowns are eliminated, come first.
        let mut memo = HashMap::new();
        for s in sit.params.iter().rev().chain(sit.steps.iter().rev()) {
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
        // `q` against ±10^-20, as `q · 10^20` against ±1 (denominators are positive).
        let ten20 = num_bigint::BigInt::from(10).pow(20);
        let scaled = |q: &Q| q.numer() * &ten20;
        let above = |q: &Q, sign: i32| scaled(q) > q.denom() * sign;
        let below = |q: &Q, sign: i32| scaled(q) < q.denom() * sign;
        let mut ev = Evaluator::with_values(&exact, Prec::new(128), memo);
        let holds = sit.facts.iter().all(|f| match ev.rat(&f.value) {
            Some(v) => !below(v.lo(), -1) && !above(v.hi(), 1),
            None => !sit.strict,
        }) && sit.nonzero.iter().all(|d| match ev.rat(d) {
            Some(v) => above(v.lo(), 1) || below(v.hi(), -1),
            None => false,
        });
        let unknown_left = names.iter().any(|n| {
            let a = atom::sym(n);
            unknown_atom(&self.scope, a) && !exact.contains_key(&a)
        });
        if unknown_left && sit.via {
            return None;
        }
        *excluded = !holds;
        holds.then_some(point)
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
        let names = self.point_names(input, sit);
        let Some(point) = self.point((input, &names), sit, &fixed, &mut rng, &mut false) else {
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
    /// Quantities that must be clearly nonzero at the point (the conditions a verified
    /// link assumes).
    pub nonzero: &'r [crate::normal::Rat],
    /// Values of parameters that the facts tie once the unknowns are eliminated (from
    /// [`super::elimination::solve_for_point`]), evaluated before the steps.
    pub params: &'r [Step],
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
            nonzero: &[],
            params: &[],
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
        Code::GuardDisagrees,
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
