//! The links of a chain after its first: what each brings in, whether a failure of one
//! is a mistake or something the notes take from prose, and a link `= 0` that imposes
//! a condition (`v = -v_{rot} + v_{CM} = 0`: rolling without slipping).

use super::{free, Placed};
use crate::diag::{Code, Diagnostic};
use crate::syntax::ast::{Chain, ExprKind, Span};
use foldhash::HashSet;
use num_traits::Zero;

/// A link after the first of a chain.
pub(super) struct Later {
    /// Where it is in the document (from its left side to the end of its right side).
    pub(super) span: Span,
    /// Where its right side starts.
    pub(super) rhs: usize,
    /// The symbols it brings in that nothing before it in the scope used.
    pub(super) fresh: Vec<String>,
    /// Whether every symbol of the chain up to it is one the document declared or defined.
    pub(super) firm: bool,
    /// Whether its right side is the number 0.
    pub(super) zero: bool,
    /// Whether its relation is not taken as stated (`sound::unfit`): with what was
    /// stated before it, it holds only where both its sides are zero, or it is a mistake.
    pub(super) skipped: bool,
}

/// The later link a diagnostic is about.
pub(super) fn later_link<'a>(p: &'a Placed, d: &Diagnostic) -> Option<&'a Later> {
    let at = d.primary.as_ref()?.0.start;
    p.later
        .iter()
        .find(|l| at >= l.span.start && at < l.span.end)
}

/// Whether a later link that does not hold is a mistake rather than something the
/// notes take from prose: every symbol of the chain up to it is one the document
/// declared or defined; or it brings in nothing new and fails as algebra, without the
/// relations the notes stated before (a step that contradicts only those states
/// something new: `N - m g cos(beta) = m y'' = 0`).
pub(super) fn later_is_a_mistake(p: &Placed, d: &Diagnostic) -> bool {
    let Some(link) = later_link(p, d) else {
        return true;
    };
    link.firm || (link.fresh.is_empty() && !d.message.cites_facts())
}

/// Why a later link that does not hold needs context.
pub(super) fn later_needs(p: &Placed, d: &Diagnostic) -> String {
    match later_link(p, d) {
        Some(l) if !l.fresh.is_empty() => format!(
            "needs context: this step brings in {}, which nothing before it defines; the notes must give {}",
            l.fresh.join(", "),
            if l.fresh.len() == 1 { "it" } else { "them" }
        ),
        _ => "needs context: this step does not follow from the relations before it; it states something new, which the notes must justify".into(),
    }
}

/// The links after the first, each with the symbols it brings in (`names`: those of
/// the links before, extended with its own). A later link that brings in a symbol
/// nothing before it in the scope used relies on something the notes say in prose
/// (`dA = 2 pi r dr`), not on the algebra.
pub(super) fn later_links(
    chain: &Chain,
    names: &mut Vec<String>,
    seen: &HashSet<String>,
    is_known: &dyn Fn(&String) -> bool,
) -> Vec<Later> {
    let mut later = Vec::new();
    for (prev, l) in chain.links.iter().zip(chain.links.iter().skip(1)) {
        let before = names.len();
        free(&l.rhs, &mut Vec::new(), names);
        let fresh: Vec<String> = names[before..]
            .iter()
            .filter(|n| !seen.contains(n.trim_end_matches('\'')) && !is_known(n))
            .cloned()
            .collect();
        later.push(Later {
            span: Span::new(prev.rhs.span.start, l.span.end),
            rhs: l.rhs.span.start,
            fresh,
            firm: names.iter().all(is_known),
            zero: matches!(&l.rhs.kind, ExprKind::Num(q) if q.is_zero()),
            skipped: false,
        });
    }
    later
}

/// A link's diagnostics after two readings: a link `= 0` the notes write where the
/// chain is not shown zero (`v = -v_{rot} + v_{CM} = 0`) imposes a condition (rolling
/// without slipping), so it needs context, never fails; and a link taken back because,
/// with what was stated before it, it holds only where both its sides are zero is false
/// under everything in scope: it does not hold.
pub(super) fn imposed_or_false(p: &Placed, diags: &mut [Diagnostic]) {
    for d in diags.iter_mut() {
        let Some(l) = later_link(p, d) else {
            continue;
        };
        let open = super::refuted(d) || d.code == Code::NotVerified;
        if open && l.zero && !l.firm {
            d.code = Code::NotVerified;
            d.mistake = None;
            d.message = format!(
                "needs context: the notes impose {} = 0 here (a condition, such as rolling without slipping, not a step that follows from the relations before it)",
                p.head
            )
            .into();
        } else if l.skipped && d.code == Code::NotVerified {
            d.code = Code::Refuted;
            d.message = "this step does not hold: with the relations stated before it, it holds only where both its sides are zero".into();
        }
    }
}

/// Whether a diagnostic is about a link `= 0` that imposes a condition.
pub(super) fn imposes(p: &Placed, d: &Diagnostic) -> bool {
    later_link(p, d).is_some_and(|l| l.zero && !l.firm)
}
