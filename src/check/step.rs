//! Deciding one link `lhs op rhs` (FORMAT.md §3): `where` substitutions, identity,
//! elimination of unknowns with the facts in scope, side conditions, and the verdict
//! for each relation. Explaining a failure lives in `explain.rs`, inequalities and
//! `~=` in `relations.rs`.

use super::elimination::{apply_steps, distinct, eliminate, Elimination, Fact};
use super::report::{Justification, Status};
use super::walk::{unknown_atom, Checker, Known};
use crate::clock::Deadline;
use crate::diag::Diagnostic;
use crate::diag::{Cited, Code, FactRef, Text};
use crate::lower::{Condition, Need};
use crate::normal::atom::AtomId;
use crate::normal::Rat;
use crate::syntax::ast::{Assign, By, Expr, Link, RelOp, Span};
use foldhash::{HashSet, HashSetExt};

/// One link to decide, with what its claim gives it.
pub(super) struct LinkInput<'a> {
    /// The left side, as lowered (the previous expression of the chain).
    pub lhs: &'a Rat,
    /// The right side, as lowered.
    pub rhs: &'a Rat,
    /// The left side as written (the guard evaluates it independently).
    pub lhs_expr: &'a Expr,
    /// The claim's `where` as written.
    pub where_: &'a [Assign],
    /// Whether this is the first link of its claim (both sides newly written).
    pub first_link: bool,
    /// The link as written (relation, right side, `by`).
    pub link: &'a Link,
    /// Where to report.
    pub span: Span,
    /// The claim's `where` substitutions.
    pub subs: &'a [(AtomId, Rat)],
    /// Conditions met while lowering both sides.
    pub divisors: &'a [(Rat, Need)],
    /// When the claim's time budget runs out.
    pub deadline: Option<Deadline>,
}

impl LinkInput<'_> {
    /// The `by [..]` of the link, if any.
    pub fn by(&self) -> Option<&By> {
        self.link.by.as_ref().map(|b| &b.0)
    }

    /// Whether `by [..]` names the facts the link may use.
    pub fn restricted(&self) -> bool {
        matches!(self.by(), Some(By::Labels(_)))
    }
}

/// A link after the `where` substitutions and the facts have done their work.
pub(super) struct Reduced {
    /// The sides after `where`.
    pub a: Rat,
    /// The right side after `where`.
    pub b: Rat,
    /// `a − b`.
    pub diff: Rat,
    /// The facts the link may use, as kept.
    pub allowed: Vec<Known>,
    /// The same, after `where`.
    pub used: Vec<Fact>,
    /// Every fact in scope, after `where`.
    pub scope: Vec<Fact>,
    /// The elimination (none for an identity).
    pub elim: Option<Elimination>,
    /// The sides after the elimination's steps.
    pub ra: Rat,
    /// The right side after the elimination's steps.
    pub rb: Rat,
    /// The facts the elimination used, in order, each once.
    pub via: Vec<FactRef>,
    /// The facts the elimination used, as cited in `Fact::name`.
    pub used_names: Vec<Cited>,
}

impl Reduced {
    /// How an equality that holds was justified.
    pub fn how(&self) -> Justification {
        if self.via.is_empty() {
            Justification::Identity
        } else {
            Justification::Facts(self.via.clone())
        }
    }

    /// The difference after the elimination (zero when it holds).
    pub fn target(&self) -> Rat {
        self.elim
            .as_ref()
            .map_or_else(Rat::zero, |e| e.target.clone())
    }

    /// Whether the time budget ran out during the elimination.
    pub fn timed_out(&self) -> bool {
        self.elim.as_ref().is_some_and(|e| e.timed_out)
    }
}

fn e0101(span: Span) -> impl Fn(crate::normal::NormError) -> Diagnostic {
    move |e| Diagnostic::error(Code::NoValue, e.to_string(), span, "")
}

impl Checker<'_, '_> {
    /// `r` with the claim's `where` substitutions applied, all at once.
    pub(super) fn apply_where(&self, subs: &[(AtomId, Rat)], r: &Rat) -> Result<Rat, String> {
        if subs.is_empty() {
            return Ok(r.clone());
        }
        let map = |a: AtomId| subs.iter().find(|s| s.0 == a).map(|s| s.1.clone());
        crate::normal::subst::Subst::new(&map, &self.env.signs)
            .rat(r)
            .map_err(|e| e.to_string())
    }

    /// Decides one link; a failure comes with its diagnostic.
    pub(super) fn check_link(&mut self, input: &LinkInput<'_>) -> Result<Status, Diagnostic> {
        self.conditions.clear();
        let span = input.span;
        let (a, b) = match (
            self.apply_where(input.subs, input.lhs),
            self.apply_where(input.subs, input.rhs),
        ) {
            (Ok(a), Ok(b)) => (a, b),
            (Err(e), _) | (_, Err(e)) => {
                return Err(Diagnostic::error(
                    Code::NoValue,
                    format!("the `where` substitution fails: {e}"),
                    span,
                    "",
                ))
            }
        };
        // Related angles, large powers kept factored, products of abs and roots.
        let diff = crate::normal::settle(&a.sub(&b).map_err(e0101(span))?, &self.env.signs);
        // Logarithms merged where the sides are defined (`ln(1/x) = -ln(x)` for x > 0):
        // zero under the side conditions, which the verdict then states.
        let diff = if crate::decide::zero_where_defined(&diff, &self.env.signs, input.divisors) {
            Rat::zero()
        } else {
            diff
        };
        // `by [..]` must name facts before this line, even where none is needed.
        if input.restricted() {
            match self.facts_for(input.by(), input.subs, span) {
                Ok(_) => {}
                Err(true) => return Ok(Status::NotChecked),
                Err(false) => return Ok(Status::Error),
            }
        }
        if let Some(of) = input.link.compare.as_ref() {
            return self.compare_coefficients(input, of, (&a, &b));
        }
        if diff.is_zero() && input.divisors.is_empty() && input.link.op == RelOp::Eq {
            // An identity with nothing to assume: no facts needed.
            let status = Status::Verified {
                how: Justification::Identity,
                side_conditions: Vec::new(),
            };
            return Ok(self.confirm(input, None, status));
        }
        let Some(red) = self.reduce(input, a, b, diff)? else {
            return Ok(Status::Error);
        };
        self.refuse_contradictions(&red, span)?;
        let (conditions, all_divs) = self.side_conditions(input, &red)?;
        if let Some(c) = red.elim.as_ref().and_then(|e| e.contradiction.as_ref()) {
            return Err(Diagnostic::error(
                Code::FalseFacts,
                Text::from(
                    "the facts in scope contradict each other: after eliminating unknowns, ",
                )
                .cited(std::slice::from_ref(c))
                .and(" says a nonzero quantity is zero"),
                span,
                "checked against contradictory facts",
            )
            .note("nothing can be verified from contradictory facts; check the givens"));
        }
        let status = match input.link.op {
            RelOp::Eq => self.decide_eq(input, &red, conditions, all_divs),
            RelOp::Ne => self.decide_ne(&red, span, conditions),
            RelOp::Lt | RelOp::Le | RelOp::Gt | RelOp::Ge => {
                self.decide_order(input.link.op, &red, span, conditions)
            }
            RelOp::Approx => self.decide_approx(input, &red, conditions),
        }?;
        let status = self.confirm(input, Some(&red), status);
        if status.is_verified() {
            self.report
                .workings
                .extend(working(span, &red, &self.env.signs));
        }
        Ok(status)
    }

    /// The facts the link may use, the elimination of unknowns, and what it used.
    /// `None`: `by [..]` names no fact (already reported).
    fn reduce(
        &self,
        input: &LinkInput<'_>,
        a: Rat,
        b: Rat,
        diff: Rat,
    ) -> Result<Option<Reduced>, Diagnostic> {
        let span = input.span;
        let Ok(allowed) = self.facts_in(input.by(), input.subs) else {
            return Ok(None);
        };
        let after_where = |ks: &[Known]| -> Vec<Fact> {
            ks.iter()
                .filter_map(|k| {
                    self.apply_where(input.subs, &k.fact.value)
                        .ok()
                        .map(|v| Fact {
                            value: v,
                            name: k.fact.name.clone(),
                        })
                })
                .collect()
        };
        let used = distinct(after_where(&allowed));
        let scope = distinct(after_where(&self.facts));
        let signs = &self.env.signs;
        let is_unknown = |x: AtomId| unknown_atom(&self.scope, x);
        let elim = if diff.is_zero() {
            None
        } else {
            let e = eliminate(&diff, &used, &is_unknown, signs, input.deadline);
            let e = e.map(|e| moments_solved(e, &diff, &used, &is_unknown, signs, input.deadline));
            let e = e.map(|e| {
                self.parameters_first(e, &diff, (&used, &scope), &is_unknown, input.deadline)
            });
            Some(e.map_err(|e| match e {
                crate::normal::NormError::DivisionByZero => Diagnostic::error(
                    Code::DivisionByZero,
                    "under the facts, this step divides by zero",
                    span,
                    "a denominator here is zero once the facts are used",
                ),
                e => {
                    let mut d = Diagnostic::error(Code::SizeLimit, e.to_string(), span, "");
                    if let crate::normal::NormError::Limit(l) = e {
                        d.reached = super::walk::reached(l);
                    }
                    d
                }
            })?)
        };
        let steps = elim.as_ref().map_or(&[][..], |e| &e.steps[..]);
        let used_names: Vec<Cited> = steps
            .iter()
            .map(|s| s.fact.clone())
            .chain(elim.as_ref().and_then(|e| e.multiple_of.clone()))
            .collect();
        let (ra, rb) = match (apply_steps(&a, steps, signs), apply_steps(&b, steps, signs)) {
            (Ok(x), Ok(y)) => (x, y),
            _ => (a.clone(), b.clone()),
        };
        let mut seen = HashSet::new();
        let via = used_names
            .iter()
            .map(|f| f.fact.clone())
            .filter(|x| seen.insert(x.clone()))
            .collect();
        Ok(Some(Reduced {
            a,
            b,
            diff,
            allowed,
            used,
            scope,
            elim,
            ra,
            rb,
            via,
            used_names,
        }))
    }

    /// The divisor of a step of an elimination (`steps`) that the facts in `scope` make
    /// zero, if one is.
    pub(super) fn zero_divisor(
        &self,
        steps: &[super::elimination::Step],
        scope: &[Fact],
    ) -> Option<Rat> {
        let signs = &self.env.signs;
        steps.iter().find_map(|s| {
            let d = s.divisor.as_ref()?;
            let reduced = apply_steps(d, steps, signs).unwrap_or_else(|_| d.clone());
            self.zero_by(&reduced, scope).then(|| d.clone())
        })
    }

    /// Whether `d` (the elimination's steps applied) is zero, or the facts in `scope`
    /// force it to zero.
    pub(super) fn zero_by(&self, d: &Rat, scope: &[Fact]) -> bool {
        d.is_zero()
            || super::zeros::forced_zero_in(
                d,
                scope,
                &self.env.signs,
                &mut self.zero_memo.borrow_mut(),
            )
    }

    /// The elimination `e`, or, when one of its steps divides by a quantity the facts
    /// make zero, the elimination with the parameters the facts fix substituted first
    /// ([`super::parameters::parameters_substituted`]) if none of its steps does: a
    /// law solved for `x''` may divide by `I_G - m R^2/2`, which a given `I_G = m R^2/2`
    /// makes zero, where solving after that given does not divide by it.
    fn parameters_first(
        &self,
        e: Elimination,
        diff: &Rat,
        (used, scope): (&[Fact], &[Fact]),
        is_unknown: &dyn Fn(AtomId) -> bool,
        deadline: Option<Deadline>,
    ) -> Elimination {
        let signs = &self.env.signs;
        if e.timed_out || e.contradiction.is_some() {
            return e;
        }
        let Some(zero) = self.zero_divisor(&e.steps, scope) else {
            return e;
        };
        let again =
            super::parameters::parameters_substituted(diff, used, (is_unknown, &zero), signs)
                .and_then(|(mut steps, target, facts)| {
                    let mut p = eliminate(&target, &facts, is_unknown, signs, deadline)?;
                    steps.append(&mut p.steps);
                    p.steps = steps;
                    Ok(p)
                });
        match again {
            Ok(p)
                if !p.timed_out
                    && p.contradiction.is_none()
                    && self.zero_divisor(&p.steps, scope).is_none() =>
            {
                p
            }
            _ => e,
        }
    }

    /// Facts that contradict each other prove anything: refuse to use them.
    fn refuse_contradictions(&self, red: &Reduced, span: Span) -> Result<(), Diagnostic> {
        if red.via.is_empty() {
            return Ok(());
        }
        let found = self
            .consistent
            .borrow_mut()
            .check(&red.used, &self.env.signs);
        match found {
            None => Ok(()),
            Some(c) => Err(Diagnostic::error(
                Code::FalseFacts,
                Text::from("the facts in scope contradict each other: ").then(&c),
                span,
                "checked against contradictory facts",
            )
            .note("nothing can be verified from contradictory facts; check the givens")),
        }
    }

    /// `=`: verified when the difference vanishes once the facts are used; otherwise
    /// refuted (where the facts in scope allow it) or explained.
    fn decide_eq(
        &mut self,
        input: &LinkInput<'_>,
        red: &Reduced,
        conditions: Vec<String>,
        all_divs: Vec<Condition>,
    ) -> Result<Status, Diagnostic> {
        if red.target().is_zero() {
            self.conditions = all_divs;
            return Ok(Status::Verified {
                how: red.how(),
                side_conditions: conditions,
            });
        }
        if self.loader.opts.verdicts_only {
            return Err(Diagnostic::error(
                Code::NotVerified,
                "not verified",
                input.span,
                "not verified",
            ));
        }
        // Undetermined unknowns are explained by `not_equal`; nothing is refuted then.
        let stuck = red.elim.as_ref().is_some_and(|e| !e.stuck.is_empty());
        let sides = if stuck || red.timed_out() {
            None
        } else {
            self.unrefuted(red, input.restricted(), input.span, input.deadline)?
        };
        Err(self.not_equal(input, red, sides, &all_divs))
    }
}

/// The work behind a link verified with the facts: the unknowns solved and the sides
/// after the substitutions (`None` when no fact was used).
fn working(
    span: Span,
    red: &Reduced,
    signs: &crate::normal::Assumptions,
) -> Option<super::report::Working> {
    use super::report::{Multiple, Solved, Working};
    use crate::normal::print::plain;
    let elim = red.elim.as_ref()?;
    if elim.steps.is_empty() && elim.multiple_of.is_none() {
        return None;
    }
    let solved = elim
        .steps
        .iter()
        .map(|s| Solved {
            unknown: super::elimination::unknown_name(s.unknown),
            value: plain(&s.value),
            fact: s.fact.clone(),
            divisor: s.divisor.as_ref().map(plain),
        })
        .collect();
    let multiple = elim.multiple_of.as_ref().and_then(|name| {
        let difference = apply_steps(&red.diff, &elim.steps, signs).ok()?;
        // The links of one claim share its name: the fact is the one the difference
        // is a multiple of (the simplest factor).
        let (value, factor) = red
            .used
            .iter()
            .filter(|f| &f.name == name)
            .filter_map(|f| {
                let value = apply_steps(&f.value, &elim.steps, signs).ok()?;
                let factor = difference.div(&value).ok()?;
                Some((value, factor))
            })
            .min_by_key(|(_, factor)| factor.atoms().len())?;
        Some(Multiple {
            fact: name.clone(),
            value: plain(&value),
            factor: plain(&factor),
            difference: plain(&difference),
        })
    });
    Some(Working {
        span,
        solved,
        multiple,
        lhs: plain(&red.ra),
        rhs: plain(&red.rb),
    })
}

/// The elimination `e` of `diff`, or, when it leaves a nonzero target and moments of an
/// abstract body are about, one that also solves for those moments, if that one shows
/// the step (the moments are what the facts say they are: `int(x^2, B) = int(y^2, B)`
/// and their sum give each). Only a verification is taken from it; a failure keeps
/// the first elimination, with the moments free.
fn moments_solved(
    e: super::elimination::Elimination,
    diff: &Rat,
    facts: &[Fact],
    is_unknown: &dyn Fn(AtomId) -> bool,
    signs: &crate::normal::Assumptions,
    deadline: Option<crate::clock::Deadline>,
) -> super::elimination::Elimination {
    let moment = |a: AtomId| matches!(crate::normal::atom::get(a), crate::normal::Atom::Moment(..));
    if e.target.is_zero()
        || e.timed_out
        || !facts
            .iter()
            .any(|f| f.value.atoms().into_iter().any(moment))
    {
        return e;
    }
    let or_moment = |a: AtomId| is_unknown(a) || moment(a);
    match eliminate(diff, facts, &or_moment, signs, deadline) {
        Ok(m) if m.target.is_zero() && m.contradiction.is_none() => m,
        _ => e,
    }
}
