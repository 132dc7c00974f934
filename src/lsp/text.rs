//! Positions and names as the protocol has them: a [`Lines`] index turns byte offsets
//! into line and UTF-16 column and back (the protocol counts columns in UTF-16 code
//! units), and file URIs turn into paths and back.

use crate::syntax::ast::Span;
use lsp_types::{Position, Range, Uri};
use std::path::{Path, PathBuf};

/// Where the lines of a text start, for conversions both ways.
pub struct Lines<'a> {
    text: &'a str,
    starts: Vec<usize>,
}

impl<'a> Lines<'a> {
    /// The index of `text`.
    pub fn new(text: &'a str) -> Lines<'a> {
        let starts = std::iter::once(0)
            .chain(text.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        Lines { text, starts }
    }

    /// The position of byte offset `at` (clamped to the text, and back to a character
    /// boundary).
    pub fn position(&self, at: usize) -> Position {
        let mut at = at.min(self.text.len());
        while !self.text.is_char_boundary(at) {
            at -= 1;
        }
        let line = self.starts.partition_point(|&s| s <= at).max(1) - 1;
        let start = self.starts[line];
        let col: usize = self.text[start..at].chars().map(char::len_utf16).sum();
        Position::new(to_u32(line), to_u32(col))
    }

    /// The range of a span.
    pub fn range(&self, span: Span) -> Range {
        Range::new(
            self.position(span.start),
            self.position(span.end.max(span.start)),
        )
    }

    /// The byte offset of a position: a column past the end of its line is the line's
    /// end, a line past the end of the text is the text's end.
    pub fn offset(&self, p: Position) -> usize {
        let Some(&start) = self.starts.get(p.line as usize) else {
            return self.text.len();
        };
        let end = self
            .starts
            .get(p.line as usize + 1)
            .map_or(self.text.len(), |e| e - 1);
        let mut units = 0usize;
        for (i, c) in self.text[start..end].char_indices() {
            if units >= p.character as usize {
                return start + i;
            }
            units += c.len_utf16();
        }
        end
    }

    /// The byte range of 0-based line `line`, without its line ending.
    pub fn line_span(&self, line: usize) -> Span {
        let start = self.starts.get(line).copied().unwrap_or(self.text.len());
        let end = self.starts.get(line + 1).map_or(self.text.len(), |e| e - 1);
        let end = if self.text[..end.max(start)].ends_with('\r') {
            end - 1
        } else {
            end
        };
        Span::new(start, end.max(start))
    }
}

fn to_u32(n: usize) -> u32 {
    u32::try_from(n).unwrap_or(u32::MAX)
}

/// The path of a `file:` URI (percent-escapes decoded); `None` for any other scheme.
pub fn path_of(uri: &Uri) -> Option<PathBuf> {
    let s = uri.as_str();
    let rest = s.strip_prefix("file://")?;
    // `file:///home/…` (empty authority) or `file://localhost/home/…`.
    let rest = rest.strip_prefix("localhost").unwrap_or(rest);
    let bytes = rest.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' && i + 2 < bytes.len() {
            let hex = std::str::from_utf8(&bytes[i + 1..i + 3]).ok();
            if let Some(b) = hex.and_then(|h| u8::from_str_radix(h, 16).ok()) {
                out.push(b);
                i += 3;
                continue;
            }
        }
        out.push(bytes[i]);
        i += 1;
    }
    let path = String::from_utf8(out).ok()?;
    // `file:///C:/…` on Windows.
    let path = match path.as_bytes() {
        [b'/', d, b':', ..] if d.is_ascii_alphabetic() => path[1..].to_string(),
        _ => path,
    };
    Some(PathBuf::from(path))
}

/// The `file:` URI of an absolute path, with the characters a URI path may not hold
/// escaped.
pub fn uri_of(path: &Path) -> Option<Uri> {
    let text = path.to_str()?;
    let mut s = String::from("file://");
    if !text.starts_with('/') {
        s.push('/');
    }
    for b in text.bytes() {
        let keep = b.is_ascii_alphanumeric() || b"/-._~:@!$&'()*+,;=".contains(&b);
        if keep && b != b'\\' {
            s.push(char::from(b));
        } else if b == b'\\' {
            s.push('/');
        } else {
            s.push_str(&format!("%{b:02X}"));
        }
    }
    s.parse().ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn positions_count_utf16_units_and_round_trip() {
        let text = "a θ b\n𝑥 = 1\r\nlast";
        let lines = Lines::new(text);
        // `b` is the fourth character: a, space, θ (one unit), space.
        let b = text.find('b').unwrap();
        assert_eq!(lines.position(b), Position::new(0, 4));
        // `=` follows 𝑥 (two UTF-16 units) and a space.
        let eq = text.find('=').unwrap();
        assert_eq!(lines.position(eq), Position::new(1, 3));
        for at in [0, b, eq, text.len()] {
            assert_eq!(lines.offset(lines.position(at)), at);
        }
        assert_eq!(lines.offset(Position::new(0, 99)), text.find('\n').unwrap());
        assert_eq!(lines.offset(Position::new(9, 0)), text.len());
        assert_eq!(
            &text[lines.line_span(1).start..lines.line_span(1).end],
            "𝑥 = 1"
        );
    }

    #[test]
    fn file_uris_and_paths_round_trip() {
        let p = Path::new("/tmp/a folder/rod θ.deriv");
        let uri = uri_of(p).unwrap();
        assert_eq!(uri.as_str(), "file:///tmp/a%20folder/rod%20%CE%B8.deriv");
        assert_eq!(path_of(&uri).unwrap(), p);
        let other: Uri = "untitled:Untitled-1".parse().unwrap();
        assert_eq!(path_of(&other), None);
    }
}
