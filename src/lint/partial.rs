//! The reports of a scope's chains, and the parts of a chain that needs context which
//! hold on their own, reported as chains of their own: the links from its start up to
//! the first that does not hold (with nothing assumed), and from its last failing link
//! to its end.

use super::{
    document_lines, part_outcome, premises, sound, verdict, Build, ChainReport, Checked, Placed,
    Verdict,
};
use crate::check::{FileReport, Options, Status};
use crate::diag::LineIndex;
use crate::syntax::ast::Span;
use foldhash::{HashSet, HashSetExt};

/// The links of a chain that needs context, from the last that does not hold on: a
/// chain of their own when they all hold (`dm = m dA/A = m 2 pi r dr/(pi R^2) = 2 m r
/// dr/R^2`: the last link is algebra, and verified).
pub(super) fn verified_tail(checked: &FileReport, p: &Placed) -> Option<ChainReport> {
    let (statuses, _) = part_outcome(checked, p.rest.as_ref()?, p.span);
    if statuses.len() != p.later.len() {
        return None;
    }
    let j = statuses.iter().rposition(|s| !s.is_verified())?;
    let from = p.later.get(j)?.rhs;
    (j + 1 < statuses.len()).then(|| ChainReport {
        assuming: once(conditions(statuses.get(j + 1..).unwrap_or_default())),
        ..ChainReport::new(Span::new(from, p.span.end), Verdict::Verified, Vec::new())
    })
}

/// The side conditions verified links assume.
pub(super) fn conditions(statuses: &[Status]) -> Vec<String> {
    statuses
        .iter()
        .flat_map(|s| match s {
            Status::Verified {
                side_conditions, ..
            } => side_conditions.clone(),
            _ => Vec::new(),
        })
        .collect()
}

/// Each string once, in first-seen order.
pub(super) fn once(v: Vec<String>) -> Vec<String> {
    let mut seen = HashSet::new();
    v.into_iter().filter(|c| seen.insert(c.clone())).collect()
}

/// The links of a chain that needs context, from the first up to the first that does
/// not hold, when the first is a step that holds (not only a relation the notes state):
/// a chain of their own, and where the rest of the chain starts (`a b = I_G/m = k_G^2`:
/// the first link follows from the relation before it; the second brings in `k_G`).
/// Only links that hold with nothing assumed count: a head verified assuming a divisor
/// nonzero (`dm = m dA/A`, read as products, needs `A != 0`) stays with the chain.
pub(super) fn verified_head(checked: &FileReport, p: &Placed) -> Option<(ChainReport, usize)> {
    let settled = |s: &Status| matches!(s, Status::Verified { side_conditions, .. } if side_conditions.is_empty());
    let (first, _) = part_outcome(checked, p.first.as_ref()?, p.span);
    if first.is_empty() || !first.iter().all(settled) {
        return None;
    }
    let (statuses, _) = part_outcome(checked, p.rest.as_ref()?, p.span);
    if statuses.len() != p.later.len() {
        return None;
    }
    let k = statuses.iter().position(|s| !settled(s))?;
    let (end, from) = match k.checked_sub(1) {
        None => (p.first_link.end, p.first_link.start),
        Some(i) => (p.later.get(i)?.span.end, p.later.get(i)?.rhs),
    };
    let head = ChainReport::new(Span::new(p.span.start, end), Verdict::Verified, Vec::new());
    Some((head, from))
}

/// Each chain of a scope's derivation with its verdict, in document terms.
pub(super) fn report_all(
    b: &Build<'_>,
    checked: &FileReport,
    (name, doc): (&str, &LineIndex<'_>),
    (opts, cache): (&Options, &Checked),
    out: &mut Vec<ChainReport>,
) {
    // A failure that positive values of the symbols the linter declared
    // would remove is a sign the notes do not state, not a slip.
    let positive = b
        .placed
        .iter()
        .any(|p| verdict(checked, p).verdict == Verdict::Failed)
        .then(|| premises::positive(&b.deriv))
        .map(|(deriv, names)| (cache.report(name, &deriv, opts), names));
    for p in &b.placed {
        let mut report = verdict(checked, p);
        if let Some((again, names)) = &positive {
            premises::unsigned(&mut report, verdict(again, p), (&p.symbols, names));
        }
        for d in &mut report.diagnostics {
            document_lines(d, &b.deriv, &b.placed, doc);
        }
        let needs = report.verdict == Verdict::NeedsContext;
        let tail = needs.then(|| verified_tail(checked, p)).flatten();
        // A verified head is reported on its own; the rest of the chain,
        // from the head's last expression, is what needs context.
        if let Some((head, from)) = needs.then(|| verified_head(checked, p)).flatten() {
            report.span = Span::new(from, report.span.end);
            out.push(head);
        }
        sound::premises_of(&mut report, (checked, p), (b, doc));
        out.push(report);
        out.extend(tail);
    }
}
