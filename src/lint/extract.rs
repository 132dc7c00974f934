//! Finding the displayed equations of a document, and the `rigor:` comments that
//! declare what they use. Markdown goes through a CommonMark parser (pulldown-cmark,
//! with its math extension), so code blocks, inline code and `\$` are never math.

use pulldown_cmark::{Event, Options, Parser};

/// The kind of document.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DocKind {
    /// Markdown with `$$…$$` display math.
    Markdown,
    /// LaTeX.
    Latex,
}

impl DocKind {
    /// The kind a file name says (`.tex` is LaTeX, anything else Markdown).
    pub fn of(path: &str) -> DocKind {
        if path.ends_with(".tex") {
            DocKind::Latex
        } else {
            DocKind::Markdown
        }
    }
}

/// A part of a document that matters to the linter, in document order.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Piece {
    /// A `rigor:` comment: a derivation statement.
    Directive(String),
    /// Display math: its text and the byte offset where it starts.
    Math {
        /// The math between the delimiters.
        text: String,
        /// Where it starts in the document.
        start: usize,
    },
}

/// The pieces of `doc`.
pub fn pieces(doc: &str, kind: DocKind) -> Vec<Piece> {
    match kind {
        DocKind::Markdown => markdown(doc),
        DocKind::Latex => latex(doc),
    }
}

fn directive(comment: &str) -> Option<String> {
    let rest = comment.trim().strip_prefix("rigor:")?;
    Some(rest.trim().to_string())
}

fn markdown(doc: &str) -> Vec<Piece> {
    let mut out = Vec::new();
    let parser = Parser::new_ext(doc, Options::ENABLE_MATH).into_offset_iter();
    for (event, range) in parser {
        match event {
            Event::DisplayMath(text) => {
                let whole = doc.get(range.clone()).unwrap_or("");
                let start = range.start + whole.find(text.as_ref()).unwrap_or(0);
                out.push(Piece::Math {
                    text: text.to_string(),
                    start,
                });
            }
            Event::Html(h) | Event::InlineHtml(h) => {
                let mut rest = h.as_ref();
                while let Some(i) = rest.find("<!--") {
                    let after = &rest[i + 4..];
                    let Some(j) = after.find("-->") else { break };
                    if let Some(d) = directive(&after[..j]) {
                        out.push(Piece::Directive(d));
                    }
                    rest = &after[j + 3..];
                }
            }
            _ => {}
        }
    }
    out
}

/// The environments whose content is display math.
const ENVIRONMENTS: [&str; 8] = [
    "equation",
    "equation*",
    "align",
    "align*",
    "gather",
    "gather*",
    "multline",
    "multline*",
];

fn latex(doc: &str) -> Vec<Piece> {
    let mut out = Vec::new();
    let mut i = 0;
    let bytes = doc.as_bytes();
    while i < doc.len() {
        let rest = &doc[i..];
        // A comment runs to the end of its line; `rigor:` comments are directives.
        if rest.starts_with('%') && (i == 0 || bytes[i - 1] != b'\\') {
            let end = rest.find('\n').unwrap_or(rest.len());
            if let Some(d) = directive(&rest[1..end]) {
                out.push(Piece::Directive(d));
            }
            i += end.max(1);
            continue;
        }
        let open = [("\\[", "\\]"), ("$$", "$$")]
            .into_iter()
            .find(|(o, _)| rest.starts_with(o))
            .map(|(o, c)| (o.len(), c.to_string()))
            .or_else(|| {
                let env = ENVIRONMENTS
                    .iter()
                    .find(|e| rest.starts_with(&format!("\\begin{{{e}}}")))?;
                Some((env.len() + 8, format!("\\end{{{env}}}")))
            });
        if let Some((olen, close)) = open {
            let body_start = i + olen;
            let Some(k) = doc[body_start..].find(&close) else {
                break;
            };
            out.push(Piece::Math {
                text: doc[body_start..body_start + k].to_string(),
                start: body_start,
            });
            i = body_start + k + close.len();
            continue;
        }
        i += rest.chars().next().map_or(1, char::len_utf8);
    }
    out
}

/// The chains of one display: one per line of an `align` (split at `\\`, outside
/// braces), each with its offset in the display's text.
pub fn chain_lines(text: &str) -> Vec<(&str, usize)> {
    let mut out = Vec::new();
    let mut depth = 0i32;
    let mut start = 0;
    let mut escaped = false;
    let mut chars = text.char_indices().peekable();
    while let Some((k, c)) = chars.next() {
        if escaped {
            escaped = false;
            continue;
        }
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            '\\' if depth == 0 && chars.peek().is_some_and(|(_, n)| *n == '\\') => {
                out.push((text.get(start..k).unwrap_or(""), start));
                chars.next();
                start = k + 2;
            }
            '\\' => escaped = true,
            _ => {}
        }
    }
    out.push((text.get(start..).unwrap_or(""), start));
    out.retain(|(s, _)| !s.trim().is_empty());
    out
}
