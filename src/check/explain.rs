//! Explaining a link that does not verify: a refutation (only where it holds in every
//! situation the facts in scope allow, with a checked counterexample), the unknowns no
//! fact determines, or why rigor can decide neither way.

use super::confirm::Situation;

use super::elimination::Step;
use super::elimination::{apply_steps, unknown_name, Fact};
use super::step::{LinkInput, Reduced};
use crate::diag::Code;

/// The two sides reduced by every fact in scope, and the steps that did it.
pub(super) type Sides = (Rat, Rat, Vec<Step>);
use super::walk::{unknown_atom, Checker};
use crate::clock::Deadline;
use crate::decide::Verdict;
use crate::diag::{Cited, Diagnostic, Mistake, Note, Text};
use crate::lower::Condition;
use crate::normal::atom::{self, AtomId};
use crate::normal::print::plain;
use crate::normal::Rat;
use crate::syntax::ast::Span;

impl Checker<'_, '_> {
    /// A failing `=` step may be called false only if it fails in some situation the
    /// signs and all the facts in scope allow. When the facts could make it hold, or
    /// still tie the quantities its difference is made of, the answer is "not verified"
    /// and this says why; otherwise the two sides reduced by every fact in scope, for
    /// the refutation to work on.
    pub(super) fn unrefuted(
        &self,
        red: &Reduced,
        restricted: bool,
        span: Span,
        deadline: Option<Deadline>,
    ) -> Result<Option<Sides>, Diagnostic> {
        let signs = &self.env.signs;
        let is_unknown = |x: AtomId| unknown_atom(&self.scope, x);
        let elim = |facts: &[Fact], params: bool| {
            super::elimination::eliminate_all(
                &red.diff,
                facts,
                &is_unknown,
                signs,
                deadline,
                params,
            )
            .ok()
        };
        let not_verified = |headline: Text, notes: Vec<Note>| {
            let mut d = Diagnostic::error(Code::NotVerified, headline, span, "not verified");
            d.notes = notes;
            d
        };
        let Some(full) = elim(&red.scope, true) else {
            return Ok(None);
        };
        let differs = || elim(&red.used, true).map(|r| r.0) != Some(full.0.clone());
        if restricted && (full.0.is_zero() || differs()) {
            let why = if full.0.is_zero() {
                "it follows from the facts in scope, but not from those cited"
            } else {
                "it does not follow from the facts cited, and the other facts in scope bear on it"
            };
            return Err(not_verified(
                format!("not verified from the facts cited: {why}").into(),
                vec!["cite every fact the step needs in `by [..]`, or drop `by [..]`".into()],
            ));
        }
        // The step is a fact divided by a factor the signs do not show nonzero.
        if let Some((fact, d)) = red.elim.as_ref().and_then(|e| e.multiple_where.as_ref()) {
            let d = super::signs::essential_factor(d, signs).unwrap_or_else(|| d.clone());
            let d = plain(&d);
            return Err(not_verified(
                Text::from("not verified: this step is ")
                    .cited(std::slice::from_ref(fact))
                    .and(&format!(
                        " divided by {d}, so it follows only where {d} != 0, which the declared signs do not show"
                    )),
                vec![format!(
                    "declare signs that make {d} nonzero (`symbols … != 0` or `> 0`), or state what the step needs"
                )
                .into()],
            ));
        }
        if full.0.is_zero() {
            return Err(not_verified(
                "not verified: rigor could not settle this step with the facts in scope".into(),
                Vec::new(),
            ));
        }
        // Unknowns only first (the sides read as written); parameters fixed by the facts
        // only when the facts still tie the difference's quantities.
        let mut tied = Vec::new();
        // The elimination with the parameters, kept for the explanation below.
        let with_params = full.clone();
        for (target, steps, left) in [elim(&red.scope, false), Some(full)].into_iter().flatten() {
            tied = tied_atoms(&target, &left, &is_unknown, signs);
            if tied.is_empty() {
                let reduce = |r: &Rat| apply_steps(r, &steps, signs);
                return Ok(match (reduce(&red.a), reduce(&red.b)) {
                    (Ok(x), Ok(y)) => {
                        Some(fixed_by_facts((x, y, steps), &left, &is_unknown, signs))
                    }
                    _ => None,
                });
            }
        }
        if let Some(d) = self.determined_symbol(red, &tied, span, deadline) {
            return Err(d);
        }
        let (target, _, left) = with_params;
        // Moments of an abstract body are solved for whenever that shows a step (they
        // cannot be declared): it did not show this one.
        let moment = |a: &AtomId| matches!(atom::get(*a), crate::normal::Atom::Moment(..));
        if tied.iter().all(moment) {
            return Err(not_verified(
                tied_headline(&tied, &left),
                vec![
                    Note::Remainder {
                        eliminated: false,
                        value: short(&plain(&target)),
                    },
                    Note::from(
                        "solving the facts for the body's moments does not give this step either",
                    ),
                ],
            ));
        }
        Err(not_verified(
            tied_headline(&tied, &left),
            vec![
                Note::Remainder {
                    eliminated: false,
                    value: short(&plain(&target)),
                },
                Note::Declare {
                    names: tied.iter().filter_map(|a| atom::sym_name(*a)).collect(),
                    words: format!(
                        "if the facts determine {}, declare {} with `unknowns` so that rigor solves for {}",
                        atom_names(&tied),
                        them(&tied),
                        them(&tied)
                    )
                    .into(),
                },
            ],
        ))
    }

    /// A symbol declared with `symbols` (a parameter) that the facts determine, and with
    /// which as an unknown the step follows: "the facts determine F (F = … from [Fx],
    /// [MG]); declare it with `unknowns F`". The first such symbol, if any.
    fn determined_symbol(
        &self,
        red: &Reduced,
        tied: &[AtomId],
        span: Span,
        deadline: Option<Deadline>,
    ) -> Option<Diagnostic> {
        let signs = &self.env.signs;
        // Quantities declared without a sign (forces, reactions) before those with one
        // (masses, lengths), which the facts determine only in a formal sense.
        let mut order: Vec<AtomId> = tied.to_vec();
        order.sort_by_key(|&a| {
            (
                signs.declared(a) != crate::normal::Sign::Unknown,
                atom::sym_name(a).unwrap_or_default(),
            )
        });
        for x in order {
            let Some(name) = atom::sym_name(x) else {
                continue;
            };
            let is_unknown = |a: AtomId| a == x || unknown_atom(&self.scope, a);
            let elim = |target: &Rat| {
                super::elimination::eliminate_all(
                    target,
                    &red.scope,
                    &is_unknown,
                    signs,
                    deadline,
                    false,
                )
                .ok()
            };
            let Some((rest, steps, _)) = elim(&red.diff) else {
                continue;
            };
            // Not when solving divided by a quantity the facts make zero: that proves
            // nothing (the facts may not determine it at all).
            if !rest.is_zero() || self.zero_divisor(&steps, &red.scope).is_some() {
                continue;
            }
            // Its value from the facts, if they give it in terms of the parameters.
            let value = elim(&Rat::atom(x)).and_then(|(v, steps, _)| {
                let free = !v.atoms().iter().any(|a| is_unknown(*a))
                    && self.zero_divisor(&steps, &red.scope).is_none();
                let mut from: Vec<Cited> = steps.iter().map(|s| s.fact.clone()).collect();
                from.dedup();
                free.then(|| {
                    Text::from(format!(" ({name} = {} from ", short(&plain(&v))))
                        .cited(&from)
                        .and(")")
                })
            });
            let mut d = Diagnostic::error(
                Code::NotVerified,
                Text::from(format!("not verified: the facts determine {name}"))
                    .then(&value.unwrap_or_default())
                    .and(&format!(
                        ", but `{name}` is declared with `symbols`, as a given quantity"
                    )),
                span,
                format!("with `unknowns {name}` this step follows"),
            )
            .with_mistake(Some(Mistake::DeclaredGiven(name.clone())));
            d.add_note(Note::Declare {
                names: vec![name.clone()],
                words: format!(
                    "declare it with `unknowns {name}` (keeping `symbols {name}` for its sign, if it has one) so that rigor solves for it"
                )
                .into(),
            });
            return Some(d);
        }
        None
    }

    /// A `time` symbol (or its derivative) that no fact determines is the state of the
    /// motion at an instant, which can be anything: when every quantity left undetermined
    /// is such a state and no remaining fact mentions it, the sides reduced by the facts,
    /// for the step to be refuted like one about constants rather than left "not
    /// verified".
    fn state_sides(&self, input: &LinkInput<'_>, red: &Reduced) -> Option<Sides> {
        // Not after the budget ran out (the elimination here has none of its own).
        if red.timed_out() {
            return None;
        }
        // Not when a fact the link may use failed to check: it might have fixed them.
        let facts_complete = match input.link.by.as_ref().map(|b| &b.0) {
            Some(crate::syntax::ast::By::Labels(ls)) => {
                !ls.iter().any(|l| self.failed_labels.contains_key(&l.name))
            }
            // Those that failed count only where their equations reach the link's
            // quantities (a failed `~=` never does).
            _ => {
                let mut about = Vec::new();
                super::claims::quantities(&red.a, &mut about);
                super::claims::quantities(&red.b, &mut about);
                self.failed_needed(&about).is_empty()
            }
        };
        red.elim
            .as_ref()
            .filter(|e| {
                !e.stuck.is_empty()
                    && e.stuck
                        .iter()
                        .all(|a| time_state(&self.scope, *a, &red.scope))
            })
            .filter(|_| facts_complete)
            .and_then(|_| self.free_state_sides(red))
    }

    /// The sides reduced by every fact in scope, when no fact left after the
    /// elimination mentions any quantity of their difference (so the `time` symbols
    /// left in it are free at an instant).
    fn free_state_sides(&self, red: &Reduced) -> Option<Sides> {
        let signs = &self.env.signs;
        let is_unknown = |x: AtomId| unknown_atom(&self.scope, x);
        let all = |diff: &Rat, facts: &[super::elimination::Fact]| {
            super::elimination::eliminate_all(diff, facts, &is_unknown, signs, None, false).ok()
        };
        let (mut target, mut steps, mut left) = all(&red.diff, &red.scope)?;
        // Sides found by dividing by a quantity the facts make zero say nothing: solve
        // after the parameters the facts fix, or give no sides.
        if let Some(zero) = self.zero_divisor(&steps, &red.scope) {
            let (mut first, diff, facts) = super::parameters::parameters_substituted(
                &red.diff,
                &red.scope,
                (&is_unknown, &zero),
                signs,
            )
            .ok()?;
            (target, steps, left) = all(&diff, &facts)?;
            first.append(&mut steps);
            steps = first;
            if self.zero_divisor(&steps, &red.scope).is_some() {
                return None;
            }
        }
        // Facts left over constrain nothing that an unknown absent from the difference
        // can absorb (`M = -m g d sin(theta)` only says what M is); any other quantity
        // they constrain must be absent from the difference.
        let depends = |r: &Rat, a: AtomId| crate::normal::subst::depends_on(r, a);
        let absorbs = |u: AtomId| is_unknown(u) && !depends(&target, u);
        let constrained = super::elimination::constrained_atoms(&left, &absorbs, signs);
        if constrained.iter().any(|c| depends(&target, *c)) {
            return None;
        }
        let a = apply_steps(&red.a, &steps, signs).ok()?;
        let b = apply_steps(&red.b, &steps, signs).ok()?;
        Some((a, b, steps))
    }

    /// What a refuted link got wrong. A whole side off by a constant factor (or a
    /// sign) says it best when the sides are compared as written; once facts were
    /// used (`steps`), the factor is between sides the writer never saw, so one term
    /// that explains the difference as written comes first (the headline and the notes
    /// already say that the facts were used).
    fn refuted_why(
        &self,
        input: &LinkInput<'_>,
        target: &Rat,
        steps: &[super::elimination::Step],
        diagnosis: Option<crate::decide::Diagnosis>,
    ) -> Option<crate::decide::Diagnosis> {
        let whole = diagnosis.as_ref().is_some_and(|d| d.whole);
        if whole && steps.is_empty() {
            return diagnosis;
        }
        self.term_diagnosis(input, target, steps).or(diagnosis)
    }

    /// The diagnostic of an `=` link that does not verify. `sides`: the sides reduced
    /// by every fact in scope, when a refutation may be tried on them.
    pub(super) fn not_equal(
        &self,
        input: &LinkInput<'_>,
        red: &Reduced,
        sides: Option<Sides>,
        defined: &[Condition],
    ) -> Diagnostic {
        let span = input.span;
        let state = self.state_sides(input, red);
        let free_state = state.is_some();
        let (ra, rb, steps) = state.or(sides).unwrap_or_else(|| {
            let steps = red.elim.as_ref().map_or_else(Vec::new, |e| e.steps.clone());
            (red.ra.clone(), red.rb.clone(), steps)
        });
        // `head (after using [a], line 3)tail`, or `headtail` when no fact was used.
        let using = |head: &str, tail: &str| {
            let t = Text::from(head);
            let t = if red.via.is_empty() {
                t
            } else {
                t.and(" (after using ").facts(&red.via).and(")")
            };
            t.and(tail)
        };
        let notes = side_notes(red, (&ra, &rb), &steps);
        let with_notes = |mut d: Diagnostic, extra: Vec<Note>| {
            d.notes = notes.iter().cloned().chain(extra).collect();
            d
        };
        if red.timed_out() {
            let d = Diagnostic::error(
                Code::TimeBudget,
                "not verified: the claim ran out of its time budget",
                span,
                "undecided",
            )
            .reached(crate::diag::Reached::ClaimTime);
            return with_notes(d, Vec::new());
        }
        if let Some(e) = red
            .elim
            .as_ref()
            .filter(|e| !e.stuck.is_empty() && !free_state)
        {
            // One term that, changed, makes the step follow is the likelier mistake than
            // a missing fact.
            let term = self.term_diagnosis(input, &e.target, &e.steps);
            let (mut d, extra) =
                self.undetermined(&e.stuck, &e.target, (&ra, &rb), span, term.is_some());
            if let Some(why) = term {
                d.message = format!("not verified: {}", why.text).into();
                d.mistake = Some(why.mistake);
                if let Some(p) = d.primary.as_mut() {
                    p.1 = "changed this way, the step follows from the facts".into();
                }
            }
            return with_notes(d, extra);
        }
        // The guard re-checks that a counterexample satisfies every declaration as
        // written before it is printed (then, below, that the sides differ there).
        let defined = self.defined_with_parameters(defined, &steps);
        let verdict = crate::decide::guarded(
            crate::decide::decide_where(&ra, &rb, &self.env.signs, &defined),
            |point| crate::guard::respects(&self.guard_env, point),
        );
        match verdict {
            Verdict::NotEqual {
                diagnosis,
                counterexample,
                ..
            } => {
                // The guard re-evaluates the sides as written at the counterexample.
                if let Some(c) = counterexample.as_ref().filter(|c| !c.values.is_empty()) {
                    let sit = Situation {
                        facts: &red.scope,
                        steps: &steps,
                        via: false,
                        strict: false,
                        nonzero: &[],
                        params: &[],
                    };
                    if let Err(d) = self.counterexample_stands(input, &sit, &c.values) {
                        return with_notes(d, Vec::new());
                    }
                }
                let target = ra.sub(&rb).unwrap_or_else(|_| Rat::zero());
                let why = self.refuted_why(input, &target, &steps, diagnosis);
                let d = Diagnostic::error(
                    Code::Refuted,
                    using("this step does not hold", ""),
                    span,
                    why.as_ref()
                        .map_or("the two sides differ", |w| w.text.as_str()),
                )
                .with_mistake(why.map(|w| w.mistake));
                let extra = counterexample.map(|c| c.note());
                with_notes(d, extra.into_iter().collect())
            }
            Verdict::Undecided { why } => {
                let d = Diagnostic::error(
                    Code::NotVerified,
                    using(
                        "not verified",
                        ": rigor can neither prove nor refute this step",
                    ),
                    span,
                    "undecided",
                );
                with_notes(d, vec![why.into()])
            }
            Verdict::Equal => with_notes(
                Diagnostic::error(Code::NotVerified, "not verified", span, ""),
                Vec::new(),
            ),
        }
    }

    /// Where a fact fixes a parameter (`I_G = m R^2/2`, a step of `steps` for a symbol
    /// that is not an unknown), the sides are defined where their conditions are with
    /// that value: the counterexample gives the parameter no other.
    fn defined_with_parameters(&self, defined: &[Condition], steps: &[Step]) -> Vec<Condition> {
        let params: Vec<Step> = steps
            .iter()
            .filter(|s| !unknown_atom(&self.scope, s.unknown))
            .cloned()
            .collect();
        defined
            .iter()
            .map(|(r, need)| {
                let r2 = apply_steps(r, &params, &self.env.signs);
                (r2.unwrap_or_else(|_| r.clone()), *need)
            })
            .collect()
    }

    /// Unknowns that no fact in scope determines: which, and (when a fact gives one only
    /// through a power) how to declare it so that rigor takes the root. `explained`: one
    /// term explains the step (then no note says a fact is missing).
    fn undetermined(
        &self,
        stuck: &[AtomId],
        target: &Rat,
        (ra, rb): (&Rat, &Rat),
        span: Span,
        explained: bool,
    ) -> (Diagnostic, Vec<Note>) {
        let facts: Vec<Fact> = self.facts.iter().map(|k| k.fact.clone()).collect();
        let mut headline = format!("not verified: nothing in scope determines {}", names(stuck));
        let mut powers = Vec::new();
        // (Only for quantities declared with `unknowns`: a derivative of a `time` symbol
        // cannot be declared positive, and the state of the motion is not solved for.)
        let declared_unknown =
            |u: AtomId| atom::sym_name(u).is_some_and(|n| self.scope.unknowns.contains(&n));
        for u in stuck.iter().filter(|u| declared_unknown(**u)) {
            if let Some((fact, n)) = super::elimination::power_only(&facts, *u, &self.env.signs) {
                let name = unknown_name(*u);
                headline = format!("not verified: {fact} gives {name} only through {name}^{n}");
                powers.push(format!(
                    "rigor takes the principal root only of an unknown declared positive: `symbols {name} > 0` before `unknowns {name}`"
                ));
            }
        }
        let root_missing = !powers.is_empty();
        let d = Diagnostic::error(
            Code::NotVerified,
            headline,
            span,
            if root_missing {
                "which root is meant?"
            } else {
                "a fact may be missing"
            },
        )
        .with_mistake((!root_missing).then_some(Mistake::MissingFact));
        let mut notes = vec![Note::Remainder {
            eliminated: true,
            value: plain(target),
        }];
        if root_missing {
            notes.extend(powers.into_iter().map(Note::from));
        } else if !explained {
            notes.push(
                format!(
                    "a fact about {} was needed but never given (or `by [..]` left it out)",
                    names(stuck)
                )
                .into(),
            );
        }
        if let Some(hint) = crate::decide::diagnose(ra, rb, target)
            .filter(|h| !root_missing && !explained && h.mistake != Mistake::Difference)
        {
            notes.push(format!("if {} can take any value, {}", names(stuck), hint.text).into());
        }
        (d, notes)
    }
}

/// Both sides as written, and (when facts were used) as the facts reduce them.
fn side_notes(red: &Reduced, (ra, rb): (&Rat, &Rat), steps: &[Step]) -> Vec<Note> {
    let mut notes = vec![
        Note::Side {
            left: true,
            value: short(&plain(&red.a)),
        },
        Note::Side {
            left: false,
            value: short(&plain(&red.b)),
        },
    ];
    // The facts the sides shown were reduced with: the link's, and any more a
    // refutation used (a parameter a fact fixes).
    let mut using = red.via.clone();
    for s in steps {
        if !using.contains(&s.fact.fact) {
            using.push(s.fact.fact.clone());
        }
    }
    if !using.is_empty() {
        notes.push(Note::Reduced {
            using,
            left: plain(ra),
            right: plain(rb),
        });
    }
    notes
}

/// A `time` symbol or one of its derivatives (not declared with `unknowns`) that is part
/// of the state of the motion at an instant, free unless a fact ties it: a position or
/// a velocity, or any derivative below one that a fact mentions (the equations of
/// motion determine the highest derivatives, not the state). An acceleration that no
/// fact goes beyond is what an equation of motion should give: a missing fact.
fn time_state(scope: &super::scope::Scope, a: AtomId, facts: &[Fact]) -> bool {
    let Some(name) = atom::sym_name(a) else {
        return false;
    };
    let base = name.trim_end_matches('\'');
    let order = name.len() - base.len();
    let is_time = scope.names.get(base) == Some(&super::scope::Decl::Time)
        && !scope.unknowns.contains(base)
        && !scope.unknowns.contains(&name);
    if !is_time {
        return false;
    }
    let higher_in_facts = || {
        let mut syms = Vec::new();
        for f in facts {
            crate::decide::symbols_in(&f.value, &mut syms);
        }
        syms.iter().filter_map(|s| atom::sym_name(*s)).any(|n| {
            let b = n.trim_end_matches('\'');
            b == base && n.len() - b.len() > order
        })
    };
    order <= 1 || higher_in_facts()
}

/// "not verified: the facts in scope ([IG]) relate a, b, …".
fn tied_headline(tied: &[AtomId], left: &[Fact]) -> Text {
    let mut which: Vec<Cited> = left
        .iter()
        .filter(|f| {
            tied.iter()
                .any(|a| crate::normal::subst::depends_on(&f.value, *a))
        })
        .map(|f| f.name.clone())
        .collect();
    which.dedup();
    Text::from("not verified: the facts in scope (")
        .cited(&which)
        .and(&format!(
            ") relate {}, so rigor cannot show that this step fails",
            atom_names(tied)
        ))
}

fn atom_names(atoms: &[AtomId]) -> String {
    listed(
        atoms
            .iter()
            .map(|a| crate::normal::print::atom_plain(atom::get(*a)))
            .collect(),
    )
}

/// Names in one order whatever the order atoms were made in (checks run in parallel
/// make them in any order): alphabetical, ignoring case first.
fn listed(mut names: Vec<String>) -> String {
    names.sort_by(|a, b| a.to_lowercase().cmp(&b.to_lowercase()).then(a.cmp(b)));
    names.join(", ")
}

fn them(atoms: &[AtomId]) -> &'static str {
    if atoms.len() == 1 {
        "it"
    } else {
        "them"
    }
}

/// The quantities of `target` (symbols, moments) that the facts left over still tie.
/// The sides `x`, `y` of a refutation with the parameters that facts left over fix
/// substituted (their steps added), when a side holds one: a counterexample is a point
/// where the facts hold, so `I_G` is not given a value of its own where a fact says
/// `I_G = m R^2/2`, even when the difference of the sides does not hold `I_G`.
fn fixed_by_facts(
    (x, y, mut steps): Sides,
    left: &[Fact],
    is_unknown: &dyn Fn(AtomId) -> bool,
    signs: &crate::normal::Assumptions,
) -> Sides {
    let fixed = |r: &Rat| !tied_atoms(r, left, is_unknown, signs).is_empty();
    if !fixed(&x) && !fixed(&y) {
        return (x, y, steps);
    }
    let Ok((more, _, _)) =
        super::parameters::parameters_substituted(&x, left, (is_unknown, &x), signs)
    else {
        return (x, y, steps);
    };
    match (apply_steps(&x, &more, signs), apply_steps(&y, &more, signs)) {
        (Ok(x2), Ok(y2)) if !more.is_empty() => {
            steps.extend(more);
            (x2, y2, steps)
        }
        _ => (x, y, steps),
    }
}

fn tied_atoms(
    target: &Rat,
    left: &[Fact],
    is_unknown: &dyn Fn(AtomId) -> bool,
    signs: &crate::normal::Assumptions,
) -> Vec<AtomId> {
    let constrained = super::elimination::constrained_atoms(left, is_unknown, signs);
    let mut mine = Vec::new();
    crate::decide::symbols_in(target, &mut mine);
    mine.extend(
        target
            .atoms()
            .into_iter()
            .filter(|a| matches!(atom::get(*a), crate::normal::Atom::Moment(..))),
    );
    mine.into_iter()
        .filter(|a| constrained.contains(a) && !is_unknown(*a))
        .collect()
}

/// A normal form for a diagnostic: very long ones are cut, with their length said.
pub(super) fn short(s: &str) -> String {
    const MAX: usize = 2000;
    if s.len() <= MAX {
        return s.to_string();
    }
    let mut cut = MAX;
    while !s.is_char_boundary(cut) {
        cut -= 1;
    }
    format!("{} … ({} characters in all)", &s[..cut], s.len())
}

/// Unknowns by name, comma-separated.
pub(super) fn names(ids: &[AtomId]) -> String {
    listed(ids.iter().map(|a| unknown_name(*a)).collect())
}
