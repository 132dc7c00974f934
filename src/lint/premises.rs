//! What a chain's links may be held to. An approximation (`\approx`) is checked to
//! first order in the small quantities in scope (`\sin\theta \approx \theta` under
//! `small theta`), or at the precision written when both sides are numbers
//! (`\frac13 \approx 0.33`); any other (`\tan\phi \approx \phi` with nothing declared
//! small, `T \approx 6.28` with `T` given in prose) is an approximation whose reason
//! the notes give in prose: it needs context and never fails. A relation written
//! before an implication arrow (`m h = 2 \Rightarrow 2 m h = 4`) is a premise the notes
//! impose, not a step: it needs context when it does not hold on its own, and what
//! follows the arrow is checked with it. And a chain that fails only because a symbol
//! the notes never declared might be negative (`\sqrt{R^2/2} = R/\sqrt{2}`) needs the
//! sign, which the report names as the `rigor:` comment that makes it checkable.

use super::{ChainReport, Verdict};
use crate::diag::{Code, Diagnostic};
use crate::syntax::ast::{Chain, Expr, ExprKind, RelOp, Span};

/// The names a derivation declares small (`small theta phi to order 2`).
fn small_names(deriv: &str) -> Vec<&str> {
    deriv
        .lines()
        .filter_map(|l| l.trim_start().strip_prefix("small "))
        .flat_map(|rest| rest.split_whitespace().take_while(|w| *w != "to"))
        .collect()
}

/// Whether `e` names one of `names` (or a time derivative of one).
fn mentions(e: &Expr, names: &[&str]) -> bool {
    e.any(&|n| matches!(&n.kind, ExprKind::Sym(s) if names.contains(&s.trim_end_matches('\''))))
}

fn has_symbols(e: &Expr) -> bool {
    e.any(&|n| matches!(n.kind, ExprKind::Sym(_)))
}

/// The links of `chain` (their spans in the document, from the left side to the end of
/// the right side) that are approximations rigor may not fail: neither numbers on both
/// sides nor about a quantity `deriv` declares small.
pub(super) fn loose_approximations(chain: &Chain, deriv: &str) -> Vec<(Span, Vec<String>)> {
    let small = small_names(deriv);
    let mut out = Vec::new();
    let mut lhs = &chain.first;
    for l in &chain.links {
        if l.op == RelOp::Approx {
            let numbers = !has_symbols(lhs) && !has_symbols(&l.rhs);
            let in_series = mentions(lhs, &small) || mentions(&l.rhs, &small);
            if !numbers && !in_series {
                let mut names = Vec::new();
                super::free(lhs, &mut Vec::new(), &mut names);
                super::free(&l.rhs, &mut Vec::new(), &mut names);
                out.push((lhs.span.to(l.span), names));
            }
        }
        lhs = &l.rhs;
    }
    out
}

/// The `rigor:` comment that makes a loose approximation checkable: `small theta` when
/// it is about one quantity (with several, which is small is the author's to say).
pub(super) fn small_comment(loose: &[(Span, Vec<String>)], diags: &[Diagnostic]) -> Option<String> {
    let at = diags
        .iter()
        .find_map(|d| d.primary.as_ref().map(|(s, _)| s.start))?;
    let (_, names) = loose.iter().find(|(s, _)| at >= s.start && at < s.end)?;
    match names.as_slice() {
        [one] => Some(format!("rigor: small {}", one.trim_end_matches('\''))),
        _ => None,
    }
}

/// Diagnostics about loose approximations (see [`loose_approximations`]) say what the
/// link needs instead of failing it.
pub(super) fn loosen(diags: &mut [Diagnostic], loose: &[(Span, Vec<String>)]) {
    for d in diags {
        let at = d.primary.as_ref().map(|(s, _)| s.start);
        let inside = at.is_some_and(|a| loose.iter().any(|(s, _)| a >= s.start && a < s.end));
        if d.code == Code::Approximation && inside {
            d.code = Code::NotVerified;
            d.mistake = None;
            d.message = "needs context: an approximation that is neither between numbers nor in a quantity declared small; the notes must say what is small (`<!-- rigor: small theta -->`, or `\\theta \\ll 1` in the text) or give the values".into();
        }
    }
}

/// The message of a premise the notes impose that does not hold on its own.
pub(super) const IMPOSED: &str = "needs context: the notes impose this relation (it comes before an implication arrow); what follows the arrow is checked with it";

/// The room left after the symbols the linter declares, for ` > 0`.
pub(super) const ROOM: &str = "    ";

/// The derivation with every symbol the linter declared (on a line ending in [`ROOM`])
/// declared positive instead, offsets unchanged, and those names.
pub(super) fn positive(deriv: &str) -> (String, Vec<String>) {
    let mut names = Vec::new();
    let text = deriv
        .split_inclusive('\n')
        .map(|l| match l.strip_suffix(&format!("{ROOM}\n")) {
            Some(decl) if decl.starts_with("symbols ") => {
                names.extend(
                    decl["symbols ".len()..]
                        .split_whitespace()
                        .map(String::from),
                );
                format!("{decl} > 0\n")
            }
            _ => l.to_string(),
        })
        .collect();
    (text, names)
}

/// A failed chain that does not fail with the linter's symbols positive needs their
/// sign: its report says which, and the comment that gives it.
pub(super) fn unsigned(
    report: &mut ChainReport,
    again: ChainReport,
    (own, positive): (&[String], &[String]),
) {
    if report.verdict != Verdict::Failed || again.verdict == Verdict::Failed {
        return;
    }
    let mut names: Vec<&str> = own
        .iter()
        .map(|n| n.trim_end_matches('\''))
        .filter(|n| positive.iter().any(|p| p == n))
        .collect();
    names.dedup();
    let at = report
        .diagnostics
        .first()
        .and_then(|d| d.primary.as_ref())
        .map_or(report.span, |(s, _)| *s);
    report.verdict = Verdict::NeedsContext;
    report.reason = Some(super::Reason::Sign);
    report.comment = Some(format!("rigor: symbols {} > 0", names.join(" ")));
    report.diagnostics = vec![Diagnostic::error(
        Code::NotVerified,
        format!(
            "needs context: this holds where {} > 0, which the notes do not declare; `rigor: symbols {} > 0` in a comment makes it checkable",
            names.join(", "),
            names.join(" ")
        ),
        at,
        "",
    )];
}
