//! Diagnostics as data, and their rendering in the style of the Rust compiler.

use crate::syntax::ast::Span;

/// How serious a diagnostic is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Severity {
    /// A failed step or bad input.
    Error,
    /// Verified, but with something to note (a side condition).
    Warning,
    /// Information.
    Note,
}

impl Severity {
    /// `error`, `warning`, `note`.
    pub fn as_str(self) -> &'static str {
        match self {
            Severity::Error => "error",
            Severity::Warning => "warning",
            Severity::Note => "note",
        }
    }
}

/// A message about a spot in a source.
#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    /// Severity.
    pub severity: Severity,
    /// A stable code, e.g. `E0301`.
    pub code: &'static str,
    /// The headline; it makes sense on its own.
    pub message: String,
    /// The spot and what to say under it.
    pub primary: Option<(Span, String)>,
    /// Further lines (`= note: …`).
    pub notes: Vec<String>,
}

impl Diagnostic {
    /// An error with a primary span.
    pub fn error(
        code: &'static str,
        message: impl Into<String>,
        span: Span,
        label: impl Into<String>,
    ) -> Diagnostic {
        Diagnostic {
            severity: Severity::Error,
            code,
            message: message.into(),
            primary: Some((span, label.into())),
            notes: Vec::new(),
        }
    }

    /// Adds a note.
    pub fn note(mut self, n: impl Into<String>) -> Diagnostic {
        self.notes.push(n.into());
        self
    }

    /// Adds a note when `cond` holds.
    pub fn note_if(self, cond: bool, n: impl Into<String>) -> Diagnostic {
        if cond {
            self.note(n)
        } else {
            self
        }
    }
}

/// 1-based line and column (in characters) of byte offset `at`.
pub fn line_col(src: &str, at: usize) -> (usize, usize) {
    let at = at.min(src.len());
    let mut at = at;
    while !src.is_char_boundary(at) {
        at -= 1;
    }
    let before = &src[..at];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let col = src[line_start..at].chars().count() + 1;
    (line, col)
}

/// Renders a diagnostic against its source, without colour.
pub fn render(d: &Diagnostic, path: &str, src: &str) -> String {
    let mut out = format!("{}[{}]: {}\n", d.severity.as_str(), d.code, d.message);
    if let Some((span, label)) = &d.primary {
        let (line, col) = line_col(src, span.start);
        let gutter = line.to_string().len();
        let pad = " ".repeat(gutter);
        out.push_str(&format!("{pad}--> {path}:{line}:{col}\n"));
        out.push_str(&format!("{pad} |\n"));
        let text = src.lines().nth(line - 1).unwrap_or("");
        let text = text.trim_end_matches('\r');
        out.push_str(&format!("{line} | {text}\n"));
        let line_chars = text.chars().count();
        let start = col - 1;
        let (end_line, end_col) = line_col(src, span.end.max(span.start));
        let end = if end_line == line {
            end_col - 1
        } else {
            line_chars
        };
        let width = end.saturating_sub(start).max(1);
        let marker = if width == 1 {
            "^".to_string()
        } else {
            "^".repeat(width)
        };
        let indent: String = text
            .chars()
            .take(start)
            .map(|c| if c == '\t' { '\t' } else { ' ' })
            .collect();
        out.push_str(&format!("{pad} | {indent}{marker} {label}\n").replace(" \n", "\n"));
    }
    for n in &d.notes {
        let gutter = d
            .primary
            .as_ref()
            .map_or(1, |(s, _)| line_col(src, s.start).0.to_string().len());
        out.push_str(&format!("{} = {}\n", " ".repeat(gutter), n));
    }
    out
}

/// Levenshtein distance.
pub fn distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.iter().enumerate() {
        let mut cur = vec![i + 1];
        for (j, cb) in b.iter().enumerate() {
            let sub = prev[j] + usize::from(ca != cb);
            let del = prev[j + 1] + 1;
            let ins = cur[j] + 1;
            cur.push(sub.min(del).min(ins));
        }
        prev = cur;
    }
    prev[b.len()]
}

/// The candidate closest to `name` (edit distance within a third of its length, plus
/// one), for "did you mean …?".
pub fn closest<'c>(name: &str, candidates: &[&'c str]) -> Option<&'c str> {
    let limit = 2 + name.chars().count() / 3;
    candidates
        .iter()
        .map(|c| (distance(name, c), *c))
        .filter(|(d, _)| *d <= limit)
        .min()
        .map(|(_, c)| c)
}
