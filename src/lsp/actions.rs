//! Quick fixes: the changes rigor's own diagnostics suggest, made into edits. A name
//! glued or mistyped (`did you mean `m g d`?`), a label mistyped (`did you mean
//! [Fx]?`), a derivative of a constant (`declare it with `time theta``), a `use` of a
//! label the imported file does not have (the closest one it has), a `use` of a `let`
//! (the definition written here). The suggestion is read from the words under the
//! diagnostic's spot, which the tests of each fix tie to the checker's output.

use super::diagnostics::convert;
use super::nav;
use super::text::Lines;
use super::world::Open;
use crate::check::FileReport;
use crate::diag::{Code, Diagnostic as Diag};
use crate::syntax::ast::{Span, StmtKind};
use lsp_types::{CodeAction, CodeActionKind, Position, Range, TextEdit, Uri, WorkspaceEdit};
use std::collections::HashMap;
use std::path::Path;

/// The fixes for the diagnostics that touch the byte range `want` of the report's text.
pub fn actions(
    r: &FileReport,
    want: Span,
    uri: &Uri,
    doc: Option<&Path>,
    open: &Open,
) -> Vec<CodeAction> {
    let lines = Lines::new(&r.source);
    let mut out = Vec::new();
    for d in &r.diagnostics {
        let Some((span, label)) = &d.primary else {
            continue;
        };
        if span.end < want.start || span.start > want.end {
            continue;
        }
        let fixes = fixes(r, d, *span, label, doc, open);
        for (title, edits) in fixes {
            let edits = edits
                .into_iter()
                .map(|(s, new_text)| TextEdit {
                    range: lines.range(s),
                    new_text,
                })
                .collect();
            out.push(CodeAction {
                title,
                kind: Some(CodeActionKind::QUICKFIX),
                diagnostics: Some(vec![convert(d, uri, &lines, r.ast.as_ref())]),
                edit: Some(WorkspaceEdit::new(HashMap::from([(uri.clone(), edits)]))),
                is_preferred: Some(true),
                ..CodeAction::default()
            });
        }
    }
    out
}

/// A fix: its title and its edits (byte range → new text).
type Fix = (String, Vec<(Span, String)>);

fn fixes(
    r: &FileReport,
    d: &Diag,
    span: Span,
    label: &str,
    doc: Option<&Path>,
    open: &Open,
) -> Vec<Fix> {
    let written = r.source.get(span.start..span.end).unwrap_or("");
    let mut out = Vec::new();
    match d.code {
        Code::Undeclared => {
            if let Some(s) = between(label, "did you mean `", "`?") {
                out.push((
                    format!("Replace `{written}` with `{s}`"),
                    vec![(span, s.to_string())],
                ));
            }
            if let Some(name) = between(label, "with `time ", "`") {
                out.extend(declare_time(r, name));
            }
        }
        Code::UnknownLabel => {
            if let Some(s) = between(label, "did you mean [", "]?") {
                out.push((
                    format!("Replace {written} with [{s}]"),
                    vec![(span, format!("[{s}]"))],
                ));
            }
        }
        Code::ImportFailed => {
            if let Some(def) = between(label, "define it here too: `", "`") {
                out.extend(define_here(r, span, def));
            } else if let Some(fix) = closest_import(r, span, doc, open) {
                out.push(fix);
            }
        }
        _ => {}
    }
    out
}

/// The text of `s` between `start` and the next `end` after it.
fn between<'s>(s: &'s str, start: &str, end: &str) -> Option<&'s str> {
    let from = s.find(start)? + start.len();
    let len = s[from..].find(end)?;
    Some(&s[from..from + len]).filter(|x| !x.is_empty())
}

/// The byte offset where the line after the one holding `at` starts.
fn next_line(text: &str, at: usize) -> usize {
    text[at.min(text.len())..]
        .find('\n')
        .map_or(text.len(), |i| at + i + 1)
}

/// Edits that make `name` a `time` symbol: taken out of the `symbols` or `unknowns`
/// that declares it (the whole statement when it is the only name), and declared on a
/// line of its own; a name declared nowhere gets its line after the declarations.
fn declare_time(r: &FileReport, name: &str) -> Option<Fix> {
    let file = r.ast.as_ref()?;
    let text = &r.source;
    let line = |at: usize| {
        let before = if at > 0 && !text[..at].ends_with('\n') {
            "\n"
        } else {
            ""
        };
        (Span::new(at, at), format!("{before}time {name}\n"))
    };
    let title = format!("Declare `{name}` with `time {name}`");
    let Some((n, s)) = nav::declaration(file, name) else {
        let last = nav::statements(file)
            .filter(|s| {
                matches!(
                    s.kind,
                    StmtKind::Symbols { .. }
                        | StmtKind::Time { .. }
                        | StmtKind::Unknowns { .. }
                        | StmtKind::Range { .. }
                )
            })
            .last()?;
        return Some((title, vec![line(next_line(text, last.span.end))]));
    };
    let names = match &s.kind {
        StmtKind::Symbols { names, .. } | StmtKind::Unknowns { names } => names,
        _ => return None,
    };
    if names.len() == 1 {
        return Some((title, vec![(s.span, format!("time {name}"))]));
    }
    let i = names.iter().position(|m| m.span == n.span)?;
    // The name and the space after it; the last name, the space before it.
    let cut = match names.get(i + 1) {
        Some(next) => Span::new(n.span.start, next.span.start),
        None => Span::new(names[i - 1].span.end, n.span.end),
    };
    let end = s.span.end.min(text.len());
    Some((
        title,
        vec![
            (cut, String::new()),
            line(next_line(text, end.saturating_sub(1))),
        ],
    ))
}

/// The `let` a `use` named, written here on the line after the `use`.
fn define_here(r: &FileReport, at: Span, def: &str) -> Option<Fix> {
    let file = r.ast.as_ref()?;
    let stmt = nav::statements(file).find(|s| s.span.start <= at.start && at.end <= s.span.end)?;
    let after = next_line(&r.source, stmt.span.end.saturating_sub(1));
    let before = if r.source[..after].ends_with('\n') {
        ""
    } else {
        "\n"
    };
    Some((
        format!("Write `{def}` here"),
        vec![(Span::new(after, after), format!("{before}{def}\n"))],
    ))
}

/// The label of the imported file closest to the one a `use` names that it lacks.
fn closest_import(r: &FileReport, at: Span, doc: Option<&Path>, open: &Open) -> Option<Fix> {
    let file = r.ast.as_ref()?;
    let (label, path) = nav::statements(file).find_map(|s| match &s.kind {
        StmtKind::Use { labels, path, .. } => labels
            .iter()
            .find(|l| l.span == at)
            .map(|l| (l, path.as_str())),
        _ => None,
    })?;
    let imported = nav::import(doc?, path, open)?;
    let theirs = imported.file.as_ref()?;
    let names: Vec<&str> = nav::statements(theirs)
        .filter(|s| matches!(s.kind, StmtKind::Claim { .. }))
        .filter_map(|s| nav::fact(s).and_then(|(l, _)| l).map(|l| l.name.as_str()))
        .collect();
    let best = crate::diag::closest(&label.name, &names)?;
    Some((
        format!("Use [{best}], which \"{path}\" has"),
        vec![(label.span, format!("[{best}]"))],
    ))
}

/// The byte range of a protocol range in `text`.
pub fn span_of(text: &str, range: Range) -> Span {
    let lines = Lines::new(text);
    let at = |p: Position| lines.offset(p);
    Span::new(at(range.start), at(range.end))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suggestions_are_read_between_their_marks() {
        let glued = "did you mean `m g d`? (a product needs a space between its factors)";
        assert_eq!(between(glued, "did you mean `", "`?"), Some("m g d"));
        let time = "`theta` is declared with `symbols`, so it has no time derivative: declare it with `time theta`";
        assert_eq!(between(time, "with `time ", "`"), Some("theta"));
        assert_eq!(
            between("did you mean [Fx]?", "did you mean [", "]?"),
            Some("Fx")
        );
        assert_eq!(
            between(
                "declare it with `symbols`, `time` or `unknowns`",
                "with `time ",
                "`"
            ),
            None
        );
        assert_eq!(between("did you mean ``?", "did you mean `", "`?"), None);
    }
}
