//! What a scope's stated relations may be used for. A relation the notes state is a
//! premise of the chains after it only when it fits with those stated before it: one
//! that could hold with them only where its sides are zero (`a = g\sin\beta/2`, then
//! `a = g\sin\beta/3`: together they force `g \sin\beta = 0`) contradicts them,
//! and a link shown to be a mistake is no premise either; both are taken back and the
//! scope checked again, so two slips under one heading never make a third line follow.
//! A verified chain names the lines of the premises its links were verified from, and
//! the definitions of earlier sections it used.

use super::{
    doc_line, later_is_a_mistake, later_link, part_outcome, refuted, Build, ChainReport, Checked,
    Placed, Reason, Verdict,
};
use crate::check::{FileReport, Justification, Options, Status};
use crate::diag::{Code, Diagnostic, FactRef, LineIndex};
use crate::syntax::ast::{ExprKind, Span};

/// Whether the relation stated by the statement taken from the link at `link` (its
/// start in the document), with everything stated before it, forces its right side
/// `rhs` to zero where what was stated before it does not: then it could hold only
/// where both its sides vanish, which contradicts what was stated before for the values
/// notes mean (`a = g\sin\beta/2`, then `a = g\sin\beta/3`, force `g \sin\beta = 0`).
/// A right side that is a number is never forced to zero by a relation that holds.
fn forces_zero(
    b: &Build<'_>,
    (link, rhs): (usize, Span),
    (name, doc): (&str, &str),
    opts: &Options,
) -> bool {
    let text = super::flat(doc, rhs);
    let popts = crate::syntax::ParseOptions {
        max_depth: opts.parse.max_depth,
    };
    let symbolic = crate::syntax::latex::parse_latex_expr(&text, 0, &popts)
        .is_ok_and(|e| e.any(&|n| matches!(n.kind, ExprKind::Sym(_))));
    let part = b
        .placed
        .iter()
        .flat_map(|p| p.stated.iter().chain(p.givens.iter()))
        .find(|part| part.first().is_some_and(|x| x.1 == link));
    let (Some(part), true) = (part, symbolic) else {
        return false;
    };
    let stmt = format!("claim $$ {text} = 0 $$\n");
    let line = |at: usize| {
        let start = b.deriv.get(..at)?.rfind('\n').map_or(0, |k| k + 1);
        let end = at + b.deriv.get(at..)?.find('\n')? + 1;
        Some((start, end))
    };
    let Some((start, end)) = part.first().and_then(|x| line(x.0)) else {
        return false;
    };
    if !b.cache.parses(&stmt) {
        return false;
    }
    // The symbols the linter declared are taken nonzero, as notes mean them: a
    // relation that forces `m g \sin\beta` to zero is then seen to force `\sin\beta`
    // to zero (or contradicts the signs), with no division left in doubt.
    let nonzero = |upto: usize| super::premises::nonzero(b.deriv.get(..upto).unwrap_or_default());
    // The claims a given restates bring nothing the given does not: they are left out.
    let (before, with) = (
        restated_left_out(&nonzero(start)),
        restated_left_out(&nonzero(end)),
    );
    // The stated relation's own line, the last of `with`.
    let own = with.len().saturating_sub(end - start);
    // Only whether links hold matters here, not why the others fail.
    let lean = Options {
        verdicts_only: true,
        ..opts.clone()
    };
    let zero_after = |prefix: &str| {
        let deriv = format!("{prefix}{stmt}");
        let report = b.cache.report(name, &deriv, &lean);
        let claimed = report
            .claims
            .iter()
            .find(|c| c.span.start >= prefix.len())
            .is_some_and(|c| !c.links.is_empty() && c.links.iter().all(|l| l.status.is_verified()));
        let contradicts = report.diagnostics.iter().any(|d| {
            d.code == Code::FalseFacts
                && d.primary
                    .as_ref()
                    .is_some_and(|(s, _)| s.start >= own && s.start < prefix.len())
        });
        (claimed, contradicts)
    };
    let (zero, contradicts) = zero_after(&with);
    (zero || contradicts) && !zero_after(&before).0
}

/// `deriv` without each claim that the line after it states again as a given (the
/// linter writes a chain's first link as both): the given brings the same relation
/// whether or not the claim holds, so what follows the pair is checked as before, and
/// the claim is not checked for nothing.
fn restated_left_out(deriv: &str) -> String {
    let lines: Vec<&str> = deriv.split_inclusive('\n').collect();
    let mut out = String::with_capacity(deriv.len());
    for (i, l) in lines.iter().enumerate() {
        let restated = l.strip_prefix("claim ").is_some_and(|rest| {
            lines
                .get(i + 1)
                .and_then(|n| n.strip_prefix("given "))
                .is_some_and(|g| g == rest)
        });
        if !restated {
            out.push_str(l);
        }
    }
    out
}

/// The links (their starts in the document) whose stated relations must not be
/// premises: a stated link that, with what was stated before it, forces its sides to
/// zero, and a later link shown to be a mistake.
pub(super) fn unfit(
    checked: &FileReport,
    b: &Build<'_>,
    (name, doc): (&str, &str),
    opts: &Options,
) -> Vec<usize> {
    let mut out = Vec::new();
    for p in &b.placed {
        if let Some(first) = &p.first {
            let (_, mut diags) = part_outcome(checked, first, p.span);
            super::premises::loosen(&mut diags, &p.loose);
            let rhs = Span::new(p.first_link.start, p.first_link.end);
            if p.stated.is_some()
                && diags.iter().any(refuted)
                && forces_zero(b, (p.span.start, rhs), (name, doc), opts)
            {
                out.push(p.span.start);
            }
        }
        if let Some(rest) = &p.rest {
            let (_, mut diags) = part_outcome(checked, rest, p.span);
            super::premises::loosen(&mut diags, &p.loose);
            for d in &diags {
                let Some(l) = later_link(p, d) else {
                    continue;
                };
                // A link `= 0` imposes a condition: a premise, whatever it reads.
                if l.zero && !l.firm {
                    continue;
                }
                let open = refuted(d) || (d.code == Code::NotVerified && l.fresh.is_empty());
                let rhs = Span::new(l.rhs, l.span.end);
                if open
                    && ((refuted(d) && later_is_a_mistake(p, d))
                        || forces_zero(b, (l.span.start, rhs), (name, doc), opts))
                {
                    out.push(l.span.start);
                }
            }
        }
    }
    out.sort_unstable();
    out.dedup();
    out
}

/// The message of a stated relation that contradicts those before it.
pub(super) const CONTRADICTS: &str = "needs context: with the relations stated before it, this holds only where both its sides are zero, so it contradicts them; it is not taken as a premise";

/// The scope's chains when its stated relations never came to fit together: nothing
/// is verified from them.
pub(super) fn distrust(
    b: &Build<'_>,
    checked: &FileReport,
    (name, doc): (&str, &LineIndex<'_>),
    (opts, cache): (&Options, &Checked),
    out: &mut Vec<ChainReport>,
) {
    let start = out.len();
    super::partial::report_all(b, checked, (name, doc), (opts, cache), out);
    for r in out.iter_mut().skip(start) {
        if r.verdict == Verdict::Verified && !r.from.is_empty() {
            r.verdict = Verdict::NeedsContext;
            r.reason = Some(Reason::Contradiction);
            r.diagnostics = vec![Diagnostic::error(
                Code::NotVerified,
                "needs context: the relations stated before it do not fit together, so nothing is verified from them",
                r.span,
                "",
            )];
            r.from.clear();
            r.assuming.clear();
        }
    }
}

/// The document lines of the facts verified links rest on.
fn cited_lines(statuses: &[Status]) -> Vec<usize> {
    statuses
        .iter()
        .flat_map(|s| match s {
            Status::Verified {
                how: Justification::Facts(fs) | Justification::Signs(fs),
                ..
            } => fs.clone(),
            _ => Vec::new(),
        })
        .filter_map(|f| match f {
            FactRef::Line(n) => Some(n),
            FactRef::Label(_) => None,
        })
        .collect()
}

/// Completes a chain's report with what it rests on: for a verified chain, the lines
/// of the premises its links were verified from (its own lines left out) and the
/// definitions of earlier sections it uses; a failure that uses a symbol the scope
/// states in two ways that do not fit needs context instead.
pub(super) fn premises_of(
    report: &mut ChainReport,
    (checked, p): (&FileReport, &Placed),
    (b, doc): (&Build<'_>, &LineIndex<'_>),
) {
    match report.verdict {
        Verdict::Verified => {
            let mut statuses = Vec::new();
            for part in p.first.iter().chain(p.rest.iter()) {
                statuses.extend(part_outcome(checked, part, p.span).0);
            }
            let (first, last) = (
                doc.line_col(p.span.start).0,
                doc.line_col(p.span.end.max(p.span.start)).0,
            );
            let mut lines: Vec<usize> = cited_lines(&statuses)
                .into_iter()
                .filter_map(|n| doc_line(n, &b.deriv, &b.placed, doc))
                .filter(|l| *l < first || *l > last)
                .collect();
            lines.sort_unstable();
            lines.dedup();
            report.from = lines;
            report.using = b
                .carried
                .iter()
                .filter(|(n, _, _)| p.symbols.iter().any(|s| s.trim_end_matches('\'') == n))
                .map(|(_, text, at)| (text.clone(), doc.line_col(*at).0))
                .collect();
        }
        Verdict::Failed => {
            let clash = b.placed.iter().find_map(|q| {
                let lhs = q.symbols.first().filter(|_| q.contradicts && q.states)?;
                (q.span.start < p.span.start && p.symbols.contains(lhs))
                    .then(|| (lhs.clone(), doc.line_col(q.span.start).0))
            });
            if let Some((name, line)) = clash {
                report.needs_context(
                    Reason::Contradiction,
                    format!("needs context: this uses {name}, which line {line} states in a way that does not fit what was stated before it"),
                );
            }
        }
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::restated_left_out;

    #[test]
    fn only_claims_the_next_given_restates_are_left_out() {
        let deriv = "symbols m g\n\
                     claim $$ a = g/2 $$\n\
                     given $$ a = g/2 $$\n\
                     claim $$ b = 2 a $$\n\
                     given $$ b = 3 a $$\n\
                     claim $$ c = a $$\n\
                     constraint $$ c = a $$\n\
                     claim $$ d = b $$\n";
        assert_eq!(
            restated_left_out(deriv),
            "symbols m g\n\
             given $$ a = g/2 $$\n\
             claim $$ b = 2 a $$\n\
             given $$ b = 3 a $$\n\
             claim $$ c = a $$\n\
             constraint $$ c = a $$\n\
             claim $$ d = b $$\n"
        );
    }
}
