//! One mistake, one error: when several steps fail for one root cause — a body declared
//! with the wrong bounds, or not declared centred — each later failure is a consequence,
//! not a second mistake. After a file is checked, the first failed step suggests what
//! may be wrong at its root:
//!
//! - it states the value of a `let` (`claim [IO] I_O = … = m L^2/3`, whose later links
//!   hold): the definition of that name (or the body it integrates over) may be wrong;
//! - it is about an abstract body not declared `centred`: the declaration may lack it.
//!
//! The file is checked again with that changed, through the same entry (a `let` given
//! the value the step states; `, centred` added). When the first failed step then holds
//! and so do later failed steps, those later steps are consequences of the first
//! mistake: their errors become notes that say so, and the first error names the root.
//! Nothing is verified this way: a step that failed stays not verified.

use super::report::{FileReport, Status};
use crate::diag::Code;
use crate::diag::{Diagnostic, Severity, Text};
use crate::syntax::ast::{BodyDef, Expr, ExprKind, File, Item, Span, StmtKind};

/// A change to the file that may be the fix of the first mistake.
struct Change {
    /// Where the text is replaced, and with what.
    at: Span,
    text: String,
    /// What the change says, for the notes ("I_O = m L^2/3, as line 41 states").
    what: Text,
    /// Where the mistake probably is, for the first error's note.
    root: Text,
}

/// Turns later failures that the first mistake explains into notes. `recheck` checks a
/// changed text of the same file.
pub(super) fn one_mistake(
    report: &mut FileReport,
    ast: &File,
    recheck: &dyn Fn(&str) -> FileReport,
) {
    let failed: Vec<usize> = report
        .claims
        .iter()
        .enumerate()
        .filter(|(_, c)| c.links.iter().any(|l| l.status == Status::Failed))
        .map(|(i, _)| i)
        .collect();
    let [first, later @ ..] = failed.as_slice() else {
        return;
    };
    if later.is_empty() {
        return;
    }
    let claim_span = report.claims[*first].span;
    let text = report.source.clone();
    for change in changes(ast, report, *first, &text) {
        let mut changed = text.clone();
        changed.replace_range(change.at.start..change.at.end, &change.text);
        let again = recheck(&changed);
        if again.claims.len() != report.claims.len() || !again.claims[*first].verified() {
            continue;
        }
        let explained: Vec<usize> = later
            .iter()
            .copied()
            .filter(|&i| again.claims[i].verified())
            .collect();
        if explained.is_empty() {
            continue;
        }
        let first_line = report.claims[*first].line;
        let mut lines = Vec::new();
        for &i in &explained {
            let span = report.claims[i].span;
            let at = report.claims[i]
                .links
                .iter()
                .find(|l| l.status == Status::Failed)
                .map_or(span, |l| l.span);
            lines.push(report.claims[i].line);
            report.diagnostics.retain(|d| {
                !(d.severity == Severity::Error
                    && d.primary
                        .as_ref()
                        .is_some_and(|(s, _)| s.start >= span.start && s.start < span.end))
            });
            for l in &mut report.claims[i].links {
                if l.status == Status::Failed {
                    l.status = Status::NotChecked;
                }
            }
            let mut d = Diagnostic::error(
                Code::Consequence,
                Text::from("not counted as a second mistake: this step holds with ")
                    .then(&change.what)
                    .and(", so it fails because of the mistake reported at line ")
                    .line(first_line),
                at,
                "follows from the first mistake",
            );
            d.severity = Severity::Note;
            report.diagnostics.push(d);
        }
        if let Some(d) = report.diagnostics.iter_mut().find(|d| {
            d.severity == Severity::Error
                && d.primary
                    .as_ref()
                    .is_some_and(|(s, _)| s.start >= claim_span.start && s.start < claim_span.end)
        }) {
            let s = if lines.len() == 1 { "" } else { "s" };
            let mut t = Text::from("with ")
                .then(&change.what)
                .and(&format!(", this step and the step{s} at line{s} "));
            for (i, l) in lines.iter().enumerate() {
                t = if i == 0 { t } else { t.and(", ") }.line(*l);
            }
            d.add_note(t.and(" hold: ").then(&change.root));
        }
        report
            .diagnostics
            .sort_by_key(|d| d.primary.as_ref().map_or(usize::MAX, |p| p.0.start));
        return;
    }
}

/// The changes the first failed claim suggests.
fn changes(ast: &File, report: &FileReport, first: usize, text: &str) -> Vec<Change> {
    let line_of = |at: usize| text.get(..at).map_or(0, |t| t.matches('\n').count() + 1);
    let claim = &report.claims[first];
    let mut out = Vec::new();
    let stmts = ast.items.iter().filter_map(|i| match i {
        Item::Stmt(s) => Some(s),
        _ => None,
    });
    let mut bodies = Vec::new();
    let mut lets = Vec::new();
    let mut chain = None;
    for s in stmts {
        match &s.kind {
            StmtKind::Body { name, def } => bodies.push((name, def, s.span)),
            StmtKind::Let { name, value } => lets.push((name, value)),
            StmtKind::Claim { chain: c, .. } if s.span.start == claim.span.start => {
                chain = Some(c);
            }
            _ => {}
        }
    }
    let Some(chain) = chain else {
        return out;
    };
    let said = |e: &Expr| text.get(e.span.start..e.span.end).unwrap_or("").to_string();
    // `X = … = v` with every link after the first verified: v is what the step says X is.
    let rest_holds = claim.links.iter().skip(1).all(|l| l.status.is_verified());
    if let (ExprKind::Sym(x), Some(last), true) =
        (&chain.first.kind, chain.links.last(), rest_holds)
    {
        if let Some((name, value)) = lets.iter().find(|(n, _)| &n.name == x) {
            let mut root = Text::from(format!("check the definition of {x} at line "))
                .line(line_of(name.span.start));
            if let Some((b, _, span)) = bodies.iter().find(|(b, _, _)| mentions(value, &b.name)) {
                root = root
                    .and(&format!(
                        " and the body {} it integrates over (line ",
                        b.name
                    ))
                    .line(line_of(span.start))
                    .and("): its bounds or mass element");
            }
            out.push(Change {
                at: value.span,
                text: format!("({})", said(&last.rhs)),
                what: Text::from(format!("{x} = {}, as line ", said(&last.rhs)))
                    .line(claim.line)
                    .and(" states"),
                root,
            });
        }
    }
    // An abstract body not declared centred, named in the claim.
    let claimed = text.get(claim.span.start..claim.span.end).unwrap_or("");
    for (b, def, span) in &bodies {
        let named = claimed
            .split(|c: char| !c.is_alphanumeric() && c != '_')
            .any(|w| w == b.name);
        if let (BodyDef::Abstract { centred: false, .. }, true) = (def, named) {
            let end = text
                .get(span.start..span.end)
                .map_or(span.end, |t| span.start + t.trim_end().len());
            out.push(Change {
                at: Span::new(end, end),
                text: ", centred".into(),
                what: format!("the body {} declared `centred`", b.name).into(),
                root: Text::from(format!(
                    "the mistake is probably the declaration of {} at line ",
                    b.name
                ))
                .line(line_of(span.start))
                .and(" (its origin is not declared the centre of mass)"),
            });
        }
    }
    out
}

/// Whether a tree names `body` (as the body of an `int`).
fn mentions(e: &Expr, body: &str) -> bool {
    e.any(&|n| matches!(&n.kind, ExprKind::Sym(s) if s == body))
}
