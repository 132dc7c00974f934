//! Claims: the `where` substitutions, each link of the chain in turn (decided in
//! `step.rs`), and what a verified claim adds to the facts (with the conditions it was
//! derived under) and to the file's exports.

use super::elimination::Fact;
use super::report::{ClaimReport, LinkReport, Status};
use super::scope::{Decl, Scope};
use super::signs::respects_sign;
use super::step::LinkInput;
use super::walk::{Checker, Known};
use crate::clock::Deadline;
use crate::diag::{Code, FailureKind, Text};
use crate::lower::Condition;
use crate::normal::atom::{self, AtomId};
use crate::normal::print::plain;
use crate::normal::Rat;
use crate::syntax::ast::{Assign, By, Chain, Expr, ExprKind, RelOp, Span};
use crate::units::check::DimV;
use foldhash::HashSet;

/// An equation a verified link adds to the facts, with its conditions.
type NewFact = (Rat, Vec<Condition>);

impl Checker<'_, '_> {
    /// Checks a claim within its time budget.
    pub(super) fn claim(
        &mut self,
        label: Option<String>,
        chain: &Chain,
        where_: &[Assign],
        span: Span,
    ) {
        let line = self.line(span);
        let claim = ClaimReport {
            label: label.clone(),
            span,
            line,
            links: Vec::new(),
        };
        let mut budget = self.loader.opts.timeout;
        if let Some((file, reported)) = self.file_deadline.as_mut() {
            if file.passed() {
                // The file's budget is spent: this claim and the rest are undecided,
                // said once.
                if !*reported {
                    *reported = true;
                    self.report.diagnostics.push(
                        crate::diag::Diagnostic::error(
                            Code::TimeBudget,
                            "not checked: the time budget for this file ran out here",
                            span,
                            "not checked",
                        )
                        .note("this step and the ones after it are undecided")
                        .reached(crate::diag::Reached::FileBudget),
                    );
                }
                self.push_undecided_links(claim, chain, Status::Undecided);
                return;
            }
            budget = budget.min(file.remaining());
        }
        let deadline = Deadline::after(budget, self.loader.opts.clock);
        let _deadline = crate::normal::limits::until(deadline);
        self.timed_out = false;
        self.claim_inner(label, chain, where_, claim, deadline);
    }

    fn claim_inner(
        &mut self,
        label: Option<String>,
        chain: &Chain,
        where_: &[Assign],
        mut claim: ClaimReport,
        deadline: Option<Deadline>,
    ) {
        let span = claim.span;
        if let Some(failed_use) = self.uses_failed_name(chain) {
            return self.push_not_checked_use(claim, chain, failed_use);
        }
        let Some(subs) = self.where_subs(where_) else {
            return self.push_error_claim(claim, chain);
        };
        // Units first: a link whose sides disagree in units fails before any algebra.
        let dims = self.chain_dims(chain, span);
        let mut divs = Vec::new();
        let Some(first) = self.lower(&chain.first, &mut divs) else {
            return self.push_error_claim(claim, chain);
        };
        let (mut prev, mut prev_divs) = (first, divs);
        let mut new_facts: Vec<NewFact> = Vec::new();
        // What the claim's equations would bring into the facts (none with `where`).
        let mut reach = Some(Vec::new());
        // The last link, if it failed: its index, left side, diagnostic and span.
        let mut odd: Option<(usize, Rat, usize, Span)> = None;
        // The member before a run of `~=` links, with its conditions and index: each
        // link of the run compares it with its own right side, at its own precision.
        let mut approx_from: Option<(Rat, Vec<Condition>, usize)> = None;
        for (i, link) in chain.links.iter().enumerate() {
            let from = approx_from.as_ref().filter(|_| link.op == RelOp::Approx);
            let (lhs, lhs_divs, k) = from.map_or((&prev, &prev_divs, i), |(v, d, k)| (v, d, *k));
            let span = link_span(chain, i);
            let mut divs = Vec::new();
            let Some(rhs) = self.lower(&link.rhs, &mut divs) else {
                reach = None;
                claim.links.push(self.unread_link(span, link.op));
                break;
            };
            let mut all_divs = lhs_divs.clone();
            all_divs.extend(divs.iter().cloned());
            let lhs_expr = member(chain, k);
            // A fault for the guard's own tests: every right side "normalises" to the left.
            let rhs = if self.loader.opts.corrupt_for_tests {
                prev.clone()
            } else {
                rhs
            };
            let input = LinkInput {
                lhs,
                rhs: &rhs,
                lhs_expr,
                where_,
                first_link: i == 0,
                link,
                span,
                subs: &subs,
                divisors: &all_divs,
                deadline,
            };
            let units = dims
                .as_ref()
                .and_then(|d| Self::link_units(d.get(i)?, d.get(i + 1)?, span));
            let before = self.report.diagnostics.len();
            let status = match units {
                Some(d) => Err(d),
                None => self.check_link(&input),
            }
            .unwrap_or_else(|d| {
                let mut about = Vec::new();
                quantities(lhs, &mut about);
                quantities(&rhs, &mut about);
                self.failed_link(d, link.by.as_ref().map(|b| &b.0), span, &about)
            });
            if k != i {
                self.note_approx_run(before, lhs_expr);
            }
            let status = self.odd_link(&mut odd, (i, link, lhs, &rhs), before, status);
            if let Some(r) = reach
                .as_mut()
                .filter(|_| link.op == RelOp::Eq && subs.is_empty())
            {
                quantities(&prev, r);
                quantities(&rhs, r);
            }
            // With `where`, a claim is a special case and adds nothing general (its
            // equations are kept apart, for claims with the same `where`).
            if status.is_verified() && link.op == RelOp::Eq {
                if let Ok(v) = prev.sub(&rhs) {
                    new_facts.push((v, self.fact_conditions(all_divs)));
                }
            }
            let units = dims.as_ref().and_then(|d| match (d.get(i), d.get(i + 1)) {
                (Some(Ok(DimV::D(a))), Some(Ok(b))) if DimV::D(a.clone()).agrees(b) => {
                    Some(a.si().to_string())
                }
                _ => None,
            });
            let report = self.link_report((span, link.op), (lhs, &rhs), status, before);
            claim.links.push(LinkReport { units, ..report });
            if link.op != RelOp::Approx {
                approx_from = None;
            } else if approx_from.is_none() {
                approx_from = Some((prev.clone(), prev_divs.clone(), i));
            }
            prev = rhs;
            prev_divs = divs;
        }
        let verified = claim.verified();
        self.report.claims.push(claim);
        if subs.is_empty() {
            self.add_claim_facts(&label, span, (new_facts, reach), verified);
        } else {
            self.add_special_case(&label, span, (new_facts, subs), verified);
        }
    }

    /// The note on a failed link of a run of `~=` (its diagnostics from `before` on):
    /// its right side was compared with `from`, the member before the run.
    fn note_approx_run(&mut self, before: usize, from: &Expr) {
        let written = self
            .report
            .source
            .get(from.span.start..from.span.end)
            .unwrap_or("?")
            .to_string();
        if let Some(d) = self
            .report
            .diagnostics
            .get_mut(before..)
            .and_then(|ds| ds.first_mut())
        {
            d.notes.push(
                format!("in a run of `~=`, each right side is compared with `{written}`, the member before the run, at the precision it is written to")
                    .into(),
            );
        }
    }

    /// The report of a link whose right side could not be read (its error is
    /// reported): an error, or undecided when the time ran out.
    fn unread_link(&self, span: Span, op: RelOp) -> LinkReport {
        let status = if self.timed_out {
            Status::Undecided
        } else {
            Status::Error
        };
        LinkReport {
            span,
            op,
            lhs: None,
            rhs: None,
            status,
            units: None,
            mistake: None,
        }
    }

    /// The report of a checked link (its units left out); what it got wrong comes from
    /// the one error it reported, among the diagnostics from `before` on.
    fn link_report(
        &self,
        (span, op): (Span, RelOp),
        (lhs, rhs): (&Rat, &Rat),
        status: Status,
        before: usize,
    ) -> LinkReport {
        let mistake = match status {
            Status::Failed | Status::Undecided => self
                .report
                .diagnostics
                .get(before..)
                .and_then(|ds| ds.iter().find_map(|d| d.mistake.clone())),
            _ => None,
        };
        LinkReport {
            span,
            op,
            lhs: Some(plain(lhs)),
            rhs: Some(plain(rhs)),
            status,
            units: None,
            mistake,
        }
    }

    /// A link that did not hold: its diagnostic, unless it cites (`by [..]`) a step
    /// that did not hold either — then the mistake was reported there, and this link
    /// is not checked (a note says what it depends on).
    ///
    /// `about` holds the quantities of the link (`quantities`): a step undecided on all
    /// the facts in scope is put down to a failed step only if that step's equations
    /// could reach them through the facts.
    fn failed_link(
        &mut self,
        d: crate::diag::Diagnostic,
        by: Option<&By>,
        span: Span,
        about: &[String],
    ) -> Status {
        // A given that contradicted the others was set aside: a step on all the facts
        // in scope that fails now may hold with it (from contradictory facts anything
        // follows), so the contradiction is the one mistake.
        if let (None, Some(given)) = (by, self.contradicted.clone()) {
            if d.failure() != Some(FailureKind::Units) {
                self.not_checked_note(
                    Text::from("not checked: it needs the facts in scope, but ")
                        .then(&given)
                        .and(" contradicts the others"),
                    span,
                );
                return Status::NotChecked;
            }
        }
        let cited: Vec<Text> = match by {
            Some(By::Labels(ls)) => ls
                .iter()
                .filter_map(|l| {
                    let line = self.failed_labels.get(&l.name)?;
                    Some(Text::label_at(&l.name, *line))
                })
                .collect(),
            // Undecided on all the facts in scope, some of which failed earlier: the
            // missing fact is most likely one of those.
            None if matches!(d.code, Code::NotVerified) => {
                let needed = self.failed_needed(about);
                let first = needed.iter().min_by_key(|(l, line)| (*line, l.clone()));
                let others = needed.len().saturating_sub(1);
                first
                    .map(|(l, line)| match others {
                        0 => Text::label_at(l, *line),
                        n => Text::label_at(l, *line).and(&format!(
                            " and {n} later step{}",
                            if n == 1 { "" } else { "s" }
                        )),
                    })
                    .into_iter()
                    .collect()
            }
            _ => Vec::new(),
        };
        if cited.is_empty() || d.failure() == Some(FailureKind::Units) {
            // "Not verified" is neither shown true nor shown false.
            let status = match d.code {
                Code::NotVerified => Status::Undecided,
                _ => Status::Failed,
            };
            self.report.diagnostics.push(d);
            return status;
        }
        let cited = Text::join(&cited, ", ");
        let msg = if by.is_some() {
            Text::from("not checked: it cites ")
                .then(&cited)
                .and(", which did not check")
        } else {
            Text::from("not checked: it needs the facts in scope, but ")
                .then(&cited)
                .and(" did not check")
        };
        self.not_checked_note(msg, span);
        Status::NotChecked
    }

    /// Tracks the last failed link of a chain (`odd`): when this link (`i`) failed too
    /// and the line before the last equals the line after this one, the last is the
    /// odd one out and this link is not checked. `before` is the number of diagnostics
    /// before this link was checked.
    fn odd_link(
        &mut self,
        odd: &mut Option<(usize, Rat, usize, Span)>,
        (i, link, prev, rhs): (usize, &crate::syntax::ast::Link, &Rat, &Rat),
        before: usize,
        status: Status,
    ) -> Status {
        if !matches!(status, Status::Failed | Status::Undecided)
            || self.report.diagnostics.len() != before + 1
        {
            *odd = None;
            return status;
        }
        // Equal as written, or once the facts in scope are used (this only places the
        // error; both links stay unverified).
        let equal = |(k, lhs, _, _): &(usize, Rat, usize, Span)| {
            *k + 1 == i
                && link.op == RelOp::Eq
                && lhs
                    .sub(rhs)
                    .is_ok_and(|d| d.is_zero() || self.zero_by_facts(&d))
        };
        if let Some((_, _, di, at)) = odd.take_if(|o| equal(o)) {
            self.report.diagnostics.truncate(before);
            Self::odd_one_out(&mut self.report.diagnostics[di], at);
            return Status::NotChecked;
        }
        *odd = (link.op == RelOp::Eq).then(|| (i, prev.clone(), before, link.span));
        status
    }

    /// Whether `d` is zero once the unknowns are eliminated with every fact in scope.
    fn zero_by_facts(&self, d: &Rat) -> bool {
        let facts: Vec<super::elimination::Fact> =
            self.facts.iter().map(|k| k.fact.clone()).collect();
        let is_unknown = |a| super::walk::unknown_atom(&self.scope, a);
        super::elimination::eliminate_all(d, &facts, &is_unknown, &self.env.signs, None, false)
            .is_ok_and(|(t, _, _)| t.is_zero())
    }

    /// Links k and k + 1 of a chain both failed, but the line before k equals the line
    /// after k + 1: line k is the odd one out, and its error says so (the next link's
    /// error is dropped — one mistake, one error).
    fn odd_one_out(d: &mut crate::diag::Diagnostic, line: Span) {
        if let Some((span, _)) = &mut d.primary {
            *span = line;
        }
        d.message = "this line does not follow from the one before, and the next line does \
                     not follow from it; the chain holds without it"
            .into();
        d.notes.insert(
            0,
            "the lines before and after it are equal: correct this line, or remove it".into(),
        );
    }

    /// The note (`msg`) of a link not checked because what it cites did not hold.
    fn not_checked_note(&mut self, msg: impl Into<Text>, span: Span) {
        let mut d = crate::diag::Diagnostic::error(Code::NotChecked, msg, span, "not checked");
        d.severity = crate::diag::Severity::Note;
        self.report
            .diagnostics
            .push(d.note("fix the step it cites first; this one is checked again then"));
    }

    /// A note N0205 for something not checked because of a mistake reported earlier.
    pub(super) fn note_not_checked(&mut self, msg: impl Into<Text>, span: Span) {
        let mut d = crate::diag::Diagnostic::error(Code::NotChecked, msg, span, "not checked");
        d.severity = crate::diag::Severity::Note;
        self.report
            .diagnostics
            .push(d.note("fix that first; this is checked again then"));
    }

    /// The conditions a verified step's fact carries: its own, the elimination's
    /// divisors and those of the facts it used.
    fn fact_conditions(&mut self, own: Vec<Condition>) -> Vec<Condition> {
        let mut conds = own;
        for c in std::mem::take(&mut self.conditions) {
            if !conds.iter().any(|d| d.0 == c.0 && d.1 == c.1) {
                conds.push(c);
            }
        }
        conds
    }

    /// A verified claim's equalities become facts, and (labelled and wholly verified)
    /// exports.
    fn add_claim_facts(
        &mut self,
        label: &Option<String>,
        span: Span,
        (new_facts, reach): (Vec<NewFact>, Option<Vec<String>>),
        verified: bool,
    ) {
        let name = self.fact_name(label, span);
        for (v, divs) in &new_facts {
            self.facts.push(Known {
                label: label.clone(),
                fact: Fact {
                    value: v.clone(),
                    name: name.clone(),
                },
                divisors: divs.clone(),
            });
        }
        if let Some(l) = label {
            if verified && !new_facts.is_empty() {
                self.exports.claims.insert(l.clone(), new_facts);
            } else if !verified {
                let line = self.line(span);
                self.failed_labels.insert(l.clone(), line);
                if let Some(r) = reach {
                    self.failed_reach.insert(l.clone(), r);
                }
            }
        }
    }

    /// A claim with `where` (`subs`): its verified equations are a special case, kept
    /// apart from the facts (and never exported); a claim with the same `where` may
    /// cite them. It adds nothing to the facts when it fails either.
    fn add_special_case(
        &mut self,
        label: &Option<String>,
        span: Span,
        (new_facts, subs): (Vec<NewFact>, Vec<(AtomId, Rat)>),
        verified: bool,
    ) {
        let name = self.fact_name(label, span);
        let Some(l) = label else { return };
        if !verified {
            let line = self.line(span);
            self.failed_labels.insert(l.clone(), line);
            self.failed_reach.insert(l.clone(), Vec::new());
            return;
        }
        for (value, divisors) in new_facts {
            let fact = Fact {
                value,
                name: name.clone(),
            };
            let known = Known {
                label: Some(l.clone()),
                fact,
                divisors,
            };
            self.special.push((subs.clone(), known));
        }
    }

    /// The `where` substitutions of a claim; `None` after reporting a bad one.
    fn where_subs(&mut self, where_: &[Assign]) -> Option<Vec<(AtomId, Rat)>> {
        let mut subs: Vec<(AtomId, Rat)> = Vec::new();
        for a in where_ {
            let name = &a.name.name;
            let refuse = |why: String, hint: &str| Some((why, hint.to_string()));
            let problem = if !self.scope.is_declared(name) {
                self.declared(&Expr::new(ExprKind::Sym(name.clone()), a.name.span));
                return None;
            } else if self.scope.names.get(name) == Some(&Decl::Def) {
                refuse(
                    format!("`where` cannot set `{name}`: it is defined by `let`"),
                    "set the symbols its definition is made of instead",
                )
            } else if self.scope.is_unknown(name) {
                refuse(
                    format!("`where` cannot set the unknown `{name}`"),
                    "`where` picks a special case of the parameters; the facts determine the unknowns",
                )
            } else if subs.iter().any(|s| s.0 == atom::sym(name)) {
                refuse(format!("`{name}` is set twice in this `where`"), "")
            } else {
                None
            };
            if let Some((why, hint)) = problem {
                self.error(Code::BadWhere, why, a.name.span, &hint);
                return None;
            }
            let x = atom::sym(name);
            let v = self.lower(&a.value, &mut Vec::new())?;
            if let Err(m) = respects_sign(name, self.env.signs.declared(x), &v, &self.env.signs) {
                self.error(
                    Code::BadWhere,
                    m,
                    a.value.span,
                    "this value does not respect the declared sign",
                );
                return None;
            }
            if let Some(unit) = self.units.get(name).cloned() {
                if !self.value_in_unit(&format!("`where` gives `{name}`"), &unit, &a.value) {
                    return None;
                }
            }
            if let Some(why) = self.outside_range(x, &v) {
                self.error(
                    Code::BadWhere,
                    why,
                    a.value.span,
                    "this value is outside the declared interval",
                );
                return None;
            }
            subs.push((x, v));
        }
        Some(subs)
    }

    /// Why `v` is not shown to lie in the interval declared for `x`, if it is not.
    fn outside_range(&self, x: AtomId, v: &Rat) -> Option<String> {
        let r = self.env.signs.range(x)?;
        let signs = &self.env.signs;
        let inside = |d: Result<Rat, crate::normal::NormError>, strict: bool| {
            d.is_ok_and(|d| {
                let s = super::signs::sign_of(&d, signs);
                s == crate::normal::Sign::Pos || (!strict && s.is_nonneg())
            })
        };
        if inside(v.sub(&r.lo), r.lo_strict) && inside(r.hi.sub(v), r.hi_strict) {
            return None;
        }
        let (lo, hi) = (
            if r.lo_strict { "<" } else { "<=" },
            if r.hi_strict { "<" } else { "<=" },
        );
        Some(format!(
            "`{}` is declared in {} {lo} {} {hi} {}, but {} is not shown to lie there",
            atom::sym_name(x).unwrap_or_default(),
            plain(&r.lo),
            atom::sym_name(x).unwrap_or_default(),
            plain(&r.hi),
            plain(v)
        ))
    }

    /// "not checked: …" when the chain uses a name that a failed `use` would have
    /// defined (the `use` has the error).
    fn uses_failed_name(&self, chain: &Chain) -> Option<(String, Text)> {
        if self.failed_names.is_empty() {
            return None;
        }
        let all = |_: &str| None;
        let exprs = chain.exprs();
        let mut names: Vec<(usize, String, Text)> = exprs
            .flat_map(|e| super::scope::undeclared(e, &self.scope, &all))
            .filter_map(|(n, _)| {
                let (line, why) = self.failed_names.get(&n)?;
                Some((*line, n, why.clone()))
            })
            .collect();
        names.sort_by(|a, b| (a.0, &a.1).cmp(&(b.0, &b.1)));
        let (_, name, why) = names.into_iter().next()?;
        let msg = Text::from(format!("not checked: it uses `{name}`, ")).then(&why);
        Some((name, msg))
    }

    /// A claim not checked because it uses a name that failed (noted once per name).
    fn push_not_checked_use(
        &mut self,
        claim: ClaimReport,
        chain: &Chain,
        (name, msg): (String, Text),
    ) {
        self.noted_uses.insert(name);
        self.push_not_checked_claim(claim, chain, msg);
    }

    /// A claim none of whose links is checked (`msg` says why, as a note).
    fn push_not_checked_claim(&mut self, claim: ClaimReport, chain: &Chain, msg: Text) {
        let whole = chain
            .links
            .last()
            .map_or(chain.first.span, |l| chain.first.span.to(l.span));
        self.note_not_checked(msg, whole);
        self.push_undecided_links(claim, chain, Status::NotChecked);
    }

    /// A claim that could not be read (its error is reported): every link an error, or
    /// undecided when the time budget ran out.
    fn push_error_claim(&mut self, claim: ClaimReport, chain: &Chain) {
        let status = if self.timed_out {
            Status::Undecided
        } else {
            Status::Error
        };
        self.push_undecided_links(claim, chain, status);
    }

    /// The claim with every link given `status`; its label, if any, did not check.
    fn push_undecided_links(&mut self, mut claim: ClaimReport, chain: &Chain, status: Status) {
        if let Some(l) = &claim.label {
            self.failed_labels.insert(l.clone(), claim.line);
            // A chain with no `=` would have brought no fact.
            if !chain.links.iter().any(|k| k.op == RelOp::Eq) {
                self.failed_reach.insert(l.clone(), Vec::new());
            }
        }
        for (i, link) in chain.links.iter().enumerate() {
            let span = if i == 0 {
                chain.first.span.to(link.span)
            } else {
                link.span
            };
            claim.links.push(LinkReport {
                span,
                op: link.op,
                lhs: None,
                rhs: None,
                status: status.clone(),
                units: None,
                mistake: None,
            });
        }
        self.report.claims.push(claim);
    }

    /// The facts a link may use: all in scope, or those `by [..]` names (`Err` when a
    /// label names none; nothing is reported). Under `where` (`subs`), a label may also
    /// name a special case with the same substitutions.
    pub(super) fn facts_in(
        &self,
        by: Option<&By>,
        subs: &[(AtomId, Rat)],
    ) -> Result<Vec<Known>, ()> {
        let Some(By::Labels(ls)) = by else {
            return Ok(self.facts.clone());
        };
        let mut out = Vec::new();
        for l in ls {
            let named = |k: &&Known| k.label.as_deref() == Some(l.name.as_str());
            let before = out.len();
            out.extend(self.facts.iter().filter(named).cloned());
            if !subs.is_empty() {
                let special = self.special.iter().filter(|(s, _)| same_subs(s, subs));
                out.extend(special.map(|(_, k)| k).filter(named).cloned());
            }
            if out.len() == before {
                return Err(());
            }
        }
        Ok(out)
    }

    /// Why `label` names no fact a link under `where` (`subs`) may cite, when it names
    /// a special case (a claim with a different `where`).
    fn special_case_why(&self, label: &str, subs: &[(AtomId, Rat)]) -> Option<String> {
        let (theirs, _) = self
            .special
            .iter()
            .find(|(_, k)| k.label.as_deref() == Some(label))?;
        let show = |s: &[(AtomId, Rat)]| {
            s.iter()
                .map(|(a, v)| format!("{} = {}", atom::sym_name(*a).unwrap_or_default(), plain(v)))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let mine = if subs.is_empty() {
            "this step has none".to_string()
        } else {
            format!("this step's is `where {}`", show(subs))
        };
        Some(format!(
            "it holds only `where {}`, and {mine}: cite it from a claim with the same `where`, or claim the general result and cite that",
            show(theirs)
        ))
    }

    /// Like [`Checker::facts_in`], reporting every label that names no fact.
    ///
    /// `Err(true)` when every such label names a given or claim that did not hold:
    /// the link is not checked, and a note (not an error) says what it depends on —
    /// one mistake is reported once, where it was made.
    pub(super) fn facts_for(
        &mut self,
        by: Option<&By>,
        subs: &[(AtomId, Rat)],
        span: Span,
    ) -> Result<Vec<Known>, bool> {
        if let Ok(v) = self.facts_in(by, subs) {
            return Ok(v);
        }
        let Some(By::Labels(ls)) = by else {
            return Err(false);
        };
        let missing: Vec<&crate::syntax::ast::Label> = ls
            .iter()
            .filter(|l| {
                self.facts_in(Some(&By::Labels(vec![(*l).clone()])), subs)
                    .is_err()
            })
            .collect();
        if missing
            .iter()
            .all(|l| self.failed_labels.contains_key(&l.name))
        {
            let what: Vec<Text> = missing
                .iter()
                .map(|l| Text::label_at(&l.name, self.failed_labels[&l.name]))
                .collect();
            self.not_checked_note(
                Text::from("not checked: it cites ")
                    .then(&Text::join(&what, ", "))
                    .and(", which did not check"),
                span,
            );
            return Err(true);
        }
        for l in missing {
            if self.failed_labels.contains_key(&l.name) {
                continue;
            }
            if let Some(why) = self.special_case_why(&l.name, subs) {
                let msg = format!(
                    "[{}] is a special case, which this step cannot cite",
                    l.name
                );
                self.error(Code::UnknownLabel, msg, l.span, &why);
                continue;
            }
            let known: Vec<String> = self.labels.keys().cloned().collect();
            let hint = if self.labels.contains_key(&l.name) {
                "that label names an inequality or a statement with no equation; `by` cites equations"
                    .to_string()
            } else if known.is_empty() {
                "no labelled facts precede this line".into()
            } else {
                let mut sc = Scope::default();
                for k in &known {
                    sc.names.insert(k.clone(), Decl::Symbol);
                }
                sc.suggest(&l.name)
                    .map_or("no fact before this line has that label".into(), |s| {
                        format!("did you mean [{s}]?")
                    })
            };
            self.error(
                Code::UnknownLabel,
                format!("unknown label [{}]", l.name),
                l.span,
                &hint,
            );
        }
        Err(false)
    }
}

impl Checker<'_, '_> {
    /// The failed labels (with their lines) whose equations could have reached the
    /// quantities `about` through the facts in scope: those that would have brought
    /// no fact (a failed `~=`, a special case under `where`) or only facts about
    /// quantities no chain of facts ties to `about` are left out.
    pub(super) fn failed_needed(&self, about: &[String]) -> Vec<(String, usize)> {
        let mut tied: HashSet<&str> = about.iter().map(String::as_str).collect();
        let mut groups: Vec<Vec<String>> = self
            .facts
            .iter()
            .map(|k| {
                let mut q = Vec::new();
                quantities(&k.fact.value, &mut q);
                q
            })
            .collect();
        groups.extend(self.failed_reach.values().cloned());
        // Everything a chain of facts (or of failed equations) ties to `about`.
        let mut grown = true;
        while grown {
            grown = false;
            for g in &groups {
                if g.iter().any(|q| tied.contains(q.as_str()))
                    && g.iter().any(|q| !tied.contains(q.as_str()))
                {
                    tied.extend(g.iter().map(String::as_str));
                    grown = true;
                }
            }
        }
        self.failed_labels
            .iter()
            .filter(|(l, _)| {
                self.failed_reach
                    .get(*l)
                    .is_none_or(|r| r.iter().any(|q| tied.contains(q.as_str())))
            })
            .map(|(l, line)| (l.clone(), *line))
            .collect()
    }
}

/// The quantities `r` is about, by name, added to `out`: symbols with their primes
/// dropped (`x''` is about `x`), a symbol at an instant by its symbol, and the moments
/// of an abstract body by the body.
pub(super) fn quantities(r: &Rat, out: &mut Vec<String>) {
    for a in r.atoms() {
        quantities_of_atom(a, out);
    }
}

fn quantities_of_atom(a: AtomId, out: &mut Vec<String>) {
    use crate::normal::atom::Atom;
    let mut push = |q: String| {
        if !out.contains(&q) {
            out.push(q);
        }
    };
    match atom::get(a) {
        Atom::Sym(s) => push(s.trim_end_matches('\'').to_string()),
        Atom::At(s, u) => {
            push(s.trim_end_matches('\'').to_string());
            quantities(u, out);
        }
        Atom::Moment(body, _) => push(format!("\u{1}body {body}")),
        Atom::Pi => {}
        Atom::Sqrt(p) | Atom::Root(p, _) | Atom::Abs(p) | Atom::Factor(p) => {
            for b in p.atoms() {
                quantities_of_atom(b, out);
            }
        }
        Atom::Sin(u) | Atom::Cos(u) | Atom::Exp(u) | Atom::Ln(u) => quantities(u, out),
        Atom::Pow(b, e) => {
            quantities(b, out);
            quantities(e, out);
        }
    }
}

/// Whether two `where` substitutions set the same symbols to the same values.
fn same_subs(a: &[(AtomId, Rat)], b: &[(AtomId, Rat)]) -> bool {
    a.len() == b.len() && a.iter().all(|x| b.contains(x))
}

/// Member `k` of a chain: its first expression, or the right side of link `k − 1`.
fn member(chain: &Chain, k: usize) -> &Expr {
    match k.checked_sub(1).and_then(|j| chain.links.get(j)) {
        Some(l) => &l.rhs,
        None => &chain.first,
    }
}

/// The span of link `i`: the first one from the chain's first expression.
fn link_span(chain: &Chain, i: usize) -> Span {
    match chain.links.get(i) {
        Some(l) if i == 0 => chain.first.span.to(l.span),
        Some(l) => l.span,
        None => chain.first.span,
    }
}
