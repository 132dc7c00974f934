//! What a chain's links may be held to. An approximation (`\approx`) is checked to
//! first order in the small quantities in scope (`\sin\theta \approx \theta` under
//! `small theta`), or at the precision written when both sides are numbers
//! (`\frac13 \approx 0.33`); any other (`\tan\phi \approx \phi` with nothing declared
//! small, `T \approx 6.28` with `T` given in prose, `1 - \cos\theta \approx
//! \theta^2/2` with `theta` kept to the first order only) is an approximation whose
//! reason the notes give in prose: it needs context and never fails. A relation written
//! before an implication arrow (`m h = 2 \Rightarrow 2 m h = 4`) is a premise the notes
//! impose, not a step: it needs context when it does not hold on its own, and what
//! follows the arrow is checked with it. And a chain that fails only because a symbol
//! the notes never declared might be negative (`\sqrt{R^2/2} = R/\sqrt{2}`) needs the
//! sign, which the report names as the `rigor:` comment that makes it checkable.

use super::{ChainReport, Verdict};
use crate::diag::{Code, Diagnostic};
use crate::syntax::ast::{BinOp, Chain, Expr, ExprKind, RelOp, Span};

/// The names a derivation declares small (`small theta phi to order 2`), each with the
/// order it is kept to.
fn small_names(deriv: &str) -> Vec<(&str, u32)> {
    let mut out = Vec::new();
    for rest in deriv
        .lines()
        .filter_map(|l| l.trim_start().strip_prefix("small "))
    {
        let (names, order) = rest.split_once(" to order ").unwrap_or((rest, "1"));
        let order = order.trim().parse().unwrap_or(1);
        out.extend(names.split_whitespace().map(|n| (n, order)));
    }
    out
}

/// The highest power of a small quantity `e` writes (`\theta^2` is 2), a quantity of
/// `small` alone counting 1.
fn highest_power(e: &Expr, small: &[(&str, u32)]) -> u32 {
    let is_small = |x: &Expr| matches!(&x.kind, ExprKind::Sym(s) if small.iter().any(|(n, _)| *n == s.trim_end_matches('\'')));
    let mut top = 0;
    let mut stack = vec![e];
    while let Some(x) = stack.pop() {
        match &x.kind {
            ExprKind::Bin(BinOp::Pow, base, exp) if is_small(base) => {
                let k = match &exp.kind {
                    ExprKind::Num(q) if q.is_integer() => {
                        q.to_integer().to_string().parse().unwrap_or(1)
                    }
                    _ => 1,
                };
                top = top.max(k);
            }
            ExprKind::Bin(_, a, b) => {
                stack.push(a);
                stack.push(b);
            }
            ExprKind::Neg(a) => stack.push(a),
            ExprKind::Call(_, args) => stack.extend(args.iter()),
            _ if is_small(x) => top = top.max(1),
            _ => {}
        }
    }
    top
}

/// Whether `e` names one of `names` (or a time derivative of one).
fn mentions(e: &Expr, names: &[(&str, u32)]) -> bool {
    e.any(&|n| matches!(&n.kind, ExprKind::Sym(s) if names.iter().any(|(m, _)| *m == s.trim_end_matches('\''))))
}

fn has_symbols(e: &Expr) -> bool {
    e.any(&|n| matches!(n.kind, ExprKind::Sym(_)))
}

/// The links of `chain` (their spans in the document, from the left side to the end of
/// the right side) that are approximations rigor may not fail: neither numbers on both
/// sides nor about a quantity `deriv` declares small.
pub(super) fn loose_approximations(chain: &Chain, deriv: &str) -> Vec<Loose> {
    let small = small_names(deriv);
    let mut out = Vec::new();
    let mut lhs = &chain.first;
    for l in &chain.links {
        if l.op == RelOp::Approx {
            let numbers = !has_symbols(lhs) && !has_symbols(&l.rhs);
            let in_series = mentions(lhs, &small) || mentions(&l.rhs, &small);
            // `1 - \cos\theta \approx \theta^2/2` means the second order: kept to the
            // first only, `\theta^2/3` would pass too.
            let kept = small.iter().map(|(_, o)| *o).min().unwrap_or(1);
            let written = highest_power(lhs, &small).max(highest_power(&l.rhs, &small));
            if !numbers && (!in_series || written > kept) {
                let mut names = Vec::new();
                super::free(lhs, &mut Vec::new(), &mut names);
                super::free(&l.rhs, &mut Vec::new(), &mut names);
                let names: Vec<&str> = names.iter().map(|n| n.trim_end_matches('\'')).collect();
                // The comment that makes it checkable: the order it is written to, or
                // the one quantity it is about (with several, which is small is the
                // author's to say).
                let comment = if in_series {
                    let small: Vec<&str> = small
                        .iter()
                        .map(|(n, _)| *n)
                        .filter(|n| names.contains(n))
                        .collect();
                    Some(format!(
                        "rigor: small {} to order {written}",
                        small.join(" ")
                    ))
                } else {
                    match names.as_slice() {
                        [one] => Some(format!("rigor: small {one}")),
                        _ => None,
                    }
                };
                out.push(Loose {
                    span: lhs.span.to(l.span),
                    comment,
                    order: in_series,
                });
            }
        }
        lhs = &l.rhs;
    }
    out
}

/// The `rigor:` comment that makes the loose approximation a diagnostic is about
/// checkable, where rigor knows it.
pub(super) fn small_comment(loose: &[Loose], diags: &[Diagnostic]) -> Option<String> {
    let at = diags
        .iter()
        .find_map(|d| d.primary.as_ref().map(|(s, _)| s.start))?;
    loose.iter().find(|l| l.holds(at))?.comment.clone()
}

/// A chain verified with an approximation written to a higher order than its small
/// quantities are kept to was checked to less than it says (`1 - \cos\theta \approx
/// \theta^2/3` agrees with `1 - \cos\theta` to the first order): it needs context.
pub(super) fn beyond_order(report: &mut ChainReport, loose: &[Loose]) {
    let Some(l) = loose.iter().find(|l| l.order) else {
        return;
    };
    if report.verdict != Verdict::Verified {
        return;
    }
    report.verdict = Verdict::NeedsContext;
    report.assuming.clear();
    report.reason = Some(super::Reason::Approximation);
    report.comment = l.comment.clone();
    report.diagnostics = vec![Diagnostic::error(
        Code::NotVerified,
        "needs context: this approximation is written to a higher order than its small quantities are kept to, and holds only to that lower order",
        l.span,
        "",
    )];
}

/// An approximation rigor may not fail (see [`loose_approximations`]).
pub(super) struct Loose {
    /// From its left side to the end of its right side, in the document.
    pub(super) span: Span,
    /// The `rigor:` comment that would make it checkable, where rigor knows it.
    pub(super) comment: Option<String>,
    /// Whether it is about a small quantity, written to a higher order than kept.
    pub(super) order: bool,
}

impl Loose {
    fn holds(&self, at: usize) -> bool {
        at >= self.span.start && at < self.span.end
    }
}

/// Diagnostics about loose approximations (see [`loose_approximations`]) say what the
/// link needs instead of failing it.
pub(super) fn loosen(diags: &mut [Diagnostic], loose: &[Loose]) {
    for d in diags {
        let at = d.primary.as_ref().map(|(s, _)| s.start);
        let inside = at.is_some_and(|a| loose.iter().any(|l| l.holds(a)));
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

/// The derivation with every symbol the linter declared (on a line ending in [`ROOM`])
/// declared nonzero instead.
pub(super) fn nonzero(deriv: &str) -> String {
    deriv
        .split_inclusive('\n')
        .map(|l| match l.strip_suffix(&format!("{ROOM}\n")) {
            Some(decl) if decl.starts_with("symbols ") => format!("{decl} != 0\n"),
            _ => l.to_string(),
        })
        .collect()
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
    report.comment = Some(format!("rigor: symbols {} > 0", names.join(" ")));
    report.needs_context(
        super::Reason::Sign,
        format!(
            "needs context: this holds where {} > 0, which the notes do not declare; `rigor: symbols {} > 0` in a comment makes it checkable",
            names.join(", "),
            names.join(" ")
        ),
    );
}
