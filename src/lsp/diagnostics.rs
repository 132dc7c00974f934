//! rigor's diagnostics as the protocol's: every error, warning and note with its range,
//! its code and rigor's own message; the words under the spot and the notes (the
//! counterexample, both sides, the facts used) as related information, each fact used
//! also at the statement that states it. Notes (`.md`, `.tex`) get `rigor lint`'s
//! findings, each at its own line.

use super::nav;
use super::text::Lines;
use crate::check::FileReport;
use crate::diag::{Diagnostic as Diag, FactRef, Note, Severity};
use crate::lint::{LintReport, Verdict};
use crate::syntax::ast::{File, Span};
use lsp_types::{
    Diagnostic, DiagnosticRelatedInformation, DiagnosticSeverity, Location, NumberOrString, Uri,
};

/// The diagnostics of a derivation's report.
pub fn of_report(r: &FileReport, uri: &Uri) -> Vec<Diagnostic> {
    let lines = Lines::new(&r.source);
    r.diagnostics
        .iter()
        .map(|d| convert(d, uri, &lines, r.ast.as_ref()))
        .collect()
}

/// The diagnostics of notes: a failed chain's own diagnostics where its mistakes are,
/// a chain that needs context as information at its line.
pub fn of_lint(r: &LintReport, uri: &Uri) -> Vec<Diagnostic> {
    let lines = Lines::new(&r.source);
    let mut out = Vec::new();
    for c in &r.chains {
        match c.verdict {
            Verdict::Failed => {
                out.extend(c.diagnostics.iter().map(|d| convert(d, uri, &lines, None)))
            }
            Verdict::NeedsContext => {
                let why = c
                    .diagnostics
                    .first()
                    .map_or("needs context".to_string(), |d| d.message.to_string());
                let mut d = Diagnostic {
                    range: lines.range(Span::new(c.span.start, c.span.start)),
                    severity: Some(DiagnosticSeverity::INFORMATION),
                    code: c
                        .diagnostics
                        .first()
                        .map(|d| NumberOrString::String(d.code.as_str().into())),
                    source: Some("rigor lint".into()),
                    message: why,
                    ..Diagnostic::default()
                };
                if let Some(comment) = &c.comment {
                    d.message
                        .push_str(&format!("\n(a comment that makes it checkable: {comment})"));
                }
                // The whole first line of the chain, so the editor marks where it starts.
                let line = lines.position(c.span.start).line as usize;
                let span = lines.line_span(line);
                d.range = lines.range(Span::new(
                    c.span.start.max(span.start),
                    span.end.max(c.span.start),
                ));
                out.push(d);
            }
            Verdict::Verified | Verdict::Defined => {}
        }
    }
    out
}

/// One diagnostic, against the text indexed by `lines` (and its syntax tree, to find the
/// statements of the facts its notes cite).
pub fn convert(d: &Diag, uri: &Uri, lines: &Lines<'_>, ast: Option<&File>) -> Diagnostic {
    let span = d.primary.as_ref().map_or(Span::new(0, 0), |(s, _)| *s);
    let here = Location::new(uri.clone(), lines.range(span));
    let mut related = Vec::new();
    if let Some((_, label)) = &d.primary {
        if !label.is_empty() {
            related.push(info(&here, label.clone()));
        }
    }
    for n in &d.notes {
        related.push(info(&here, n.to_string()));
        if let (Note::Reduced { using, .. }, Some(file)) = (n, ast) {
            for f in using {
                if let Some(at) = fact_location(f, file, uri, lines) {
                    related.push(info(&at, format!("{f}: a fact used")));
                }
            }
        }
    }
    Diagnostic {
        range: here.range,
        severity: Some(match d.severity {
            Severity::Error => DiagnosticSeverity::ERROR,
            Severity::Warning => DiagnosticSeverity::WARNING,
            Severity::Note => DiagnosticSeverity::INFORMATION,
        }),
        code: Some(NumberOrString::String(d.code.as_str().into())),
        source: Some("rigor".into()),
        message: d.message.to_string(),
        related_information: (!related.is_empty()).then_some(related),
        ..Diagnostic::default()
    }
}

fn info(at: &Location, message: String) -> DiagnosticRelatedInformation {
    DiagnosticRelatedInformation {
        location: at.clone(),
        message,
    }
}

/// Where a fact cited by a note is stated: its labelled statement, or its line.
fn fact_location(f: &FactRef, file: &File, uri: &Uri, lines: &Lines<'_>) -> Option<Location> {
    let span = match f {
        FactRef::Label(l) => nav::labelled(file, l).map(|(_, s)| s.span)?,
        FactRef::Line(n) => lines.line_span(n.checked_sub(1)?),
    };
    Some(Location::new(uri.clone(), lines.range(span)))
}
