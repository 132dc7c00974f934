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

/// Where the lines of a text start: line and column lookups by binary search, so that a
/// report of many diagnostics on a large file is not quadratic.
pub struct LineIndex<'a> {
    src: &'a str,
    starts: Vec<usize>,
}

impl<'a> LineIndex<'a> {
    /// The index of `src`.
    pub fn new(src: &'a str) -> LineIndex<'a> {
        let starts = std::iter::once(0)
            .chain(src.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        LineIndex { src, starts }
    }

    /// The text indexed.
    pub fn text(&self) -> &'a str {
        self.src
    }

    /// 1-based line and column (in characters) of byte offset `at`, as [`line_col`].
    pub fn line_col(&self, at: usize) -> (usize, usize) {
        let mut at = at.min(self.src.len());
        while !self.src.is_char_boundary(at) {
            at -= 1;
        }
        let line = self.starts.partition_point(|&s| s <= at).max(1);
        let start = self.starts[line - 1];
        (line, self.src[start..at].chars().count() + 1)
    }

    /// The text of 1-based line `line`, without its line ending.
    pub fn line(&self, line: usize) -> &'a str {
        let Some(&start) = self.starts.get(line.saturating_sub(1)) else {
            return "";
        };
        let end = self.starts.get(line).map_or(self.src.len(), |e| e - 1);
        self.src.get(start..end.max(start)).unwrap_or("")
    }
}

/// Renders a diagnostic against its source, without colour.
pub fn render(d: &Diagnostic, path: &str, src: &str) -> String {
    render_in(d, path, &LineIndex::new(src))
}

/// Renders a diagnostic against an indexed source (for many diagnostics of one file).
pub fn render_in(d: &Diagnostic, path: &str, idx: &LineIndex<'_>) -> String {
    let mut out = format!("{}[{}]: {}\n", d.severity.as_str(), d.code, d.message);
    if let Some((span, label)) = &d.primary {
        let (line, col) = idx.line_col(span.start);
        let gutter = line.to_string().len();
        let pad = " ".repeat(gutter);
        out.push_str(&format!("{pad}--> {path}:{line}:{col}\n"));
        out.push_str(&format!("{pad} |\n"));
        let text = idx.line(line);
        let text = text.trim_end_matches('\r');
        out.push_str(&format!("{line} | {text}\n"));
        let line_chars = text.chars().count();
        let start = col - 1;
        let (end_line, end_col) = idx.line_col(span.end.max(span.start));
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
            .map_or(1, |(s, _)| idx.line_col(s.start).0.to_string().len());
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
