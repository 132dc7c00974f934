//! Why a chain needs context, as a kind the reports carry (`--format json` says it as
//! `"reason"`, GitHub annotations in their title), with the `rigor:` comment that would
//! make the chain checkable where rigor knows it.

use super::{later_link, part_outcome, refuted, Part, Placed};
use crate::check::FileReport;
use crate::diag::Diagnostic;

/// The class of a "needs context" verdict.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reason {
    /// LaTeX rigor does not read (an unknown macro, a vector).
    Unread,
    /// An integral over a mass element the notes define in prose.
    ProseMass,
    /// A step brings in a symbol nothing before it defines.
    NewSymbol,
    /// A relation stated, not derived: it does not hold for every value of its symbols.
    Stated,
    /// A premise the notes impose (before an implication arrow, or a link `= 0` that
    /// is a condition such as rolling without slipping).
    Imposed,
    /// A relation that does not fit those stated before it, or that uses one.
    Contradiction,
    /// An approximation with nothing declared small and not between numbers.
    Approximation,
    /// It holds where symbols the notes never declared are positive.
    Sign,
    /// The facts in scope do not settle it.
    Undetermined,
    /// It could not be written as a derivation, so it was not checked.
    Unchecked,
}

impl Reason {
    /// The name the JSON report and annotations use.
    pub fn as_str(self) -> &'static str {
        match self {
            Reason::Unread => "unread",
            Reason::ProseMass => "prose-mass",
            Reason::NewSymbol => "new-symbol",
            Reason::Stated => "stated",
            Reason::Imposed => "imposed",
            Reason::Contradiction => "contradiction",
            Reason::Approximation => "approximation",
            Reason::Sign => "sign",
            Reason::Undetermined => "undetermined",
            Reason::Unchecked => "unchecked",
        }
    }
}

/// Why a placed chain needs context (`diags`: its report's diagnostics).
pub(super) fn of(checked: &FileReport, p: &Placed, diags: &[Diagnostic]) -> Reason {
    let at = |d: &Diagnostic| d.primary.as_ref().map(|(s, _)| s.start);
    let refuted_in = |part: &Option<Part>| {
        part.as_ref()
            .is_some_and(|part| part_outcome(checked, part, p.span).1.iter().any(refuted))
    };
    if p.unwritten {
        Reason::Unchecked
    } else if p.imposed || diags.iter().any(|d| super::later::imposes(p, d)) {
        Reason::Imposed
    } else if p.contradicts {
        Reason::Contradiction
    } else if diags
        .iter()
        .any(|d| at(d).is_some_and(|a| p.loose.iter().any(|l| a >= l.span.start && a < l.span.end)))
    {
        Reason::Approximation
    } else if diags
        .iter()
        .any(|d| later_link(p, d).is_some_and(|l| !l.fresh.is_empty()))
    {
        Reason::NewSymbol
    } else if refuted_in(&p.first) || refuted_in(&p.rest) {
        Reason::Stated
    } else {
        Reason::Undetermined
    }
}
