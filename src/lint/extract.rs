//! Finding the displayed equations of a document, and the `rigor:` comments that
//! declare what they use. Markdown goes through a CommonMark parser (pulldown-cmark,
//! with its math extension), so code blocks, inline code and `\$` are never math.

use pulldown_cmark::{CodeBlockKind, Event, Options, Parser, Tag, TagEnd};

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
    /// A heading: what the notes derive under one heading is one scope (its
    /// definitions and stated relations do not reach the next).
    Heading,
    /// Math: its text and the byte offset where it starts.
    Math {
        /// The math between the delimiters.
        text: String,
        /// Where it starts in the document.
        start: usize,
        /// Whether it is inline math in prose (`$a = b$`), not a display.
        inline: bool,
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

/// The pieces of a Markdown document: `$$…$$` and `$…$` math (pulldown-cmark's), MyST
/// ```` ```{math} ```` fences and `` {math}`…` `` roles, and the `\[…\]`, `\(…\)` and
/// `\begin{align}…` math that MathJax reads in the text; each with its offset, in
/// document order.
fn markdown(doc: &str) -> Vec<Piece> {
    let mut out: Vec<(usize, Piece)> = Vec::new();
    // What the parser already read as math, code or HTML: never scanned for `\[`.
    let mut covered: Vec<std::ops::Range<usize>> = Vec::new();
    // Inside a MyST math fence: where its text starts and ends so far.
    let mut fence: Option<Option<(usize, usize)>> = None;
    let mut role = false;
    let parser = Parser::new_ext(doc, Options::ENABLE_MATH).into_offset_iter();
    for (event, range) in parser {
        let at = range.start;
        let whole = doc.get(range.clone()).unwrap_or("");
        let was_role = std::mem::take(&mut role);
        match event {
            Event::DisplayMath(text) => {
                let start = at + whole.find(text.as_ref()).unwrap_or(0);
                out.push((at, math(text.to_string(), start, false)));
                covered.push(range);
            }
            Event::InlineMath(text) => {
                let start = at + whole.find(text.as_ref()).unwrap_or(0);
                out.push((at, math(text.to_string(), start, true)));
                covered.push(range);
            }
            Event::Start(Tag::CodeBlock(kind)) => {
                fence = matches!(&kind, CodeBlockKind::Fenced(info)
                    if info.trim_start().starts_with("{math}"))
                .then_some(None);
                covered.push(range);
            }
            // A MyST math block: its lines, as one display.
            Event::Text(_) if fence.is_some() => {
                let (from, _) = fence.flatten().unwrap_or((range.start, range.end));
                fence = Some(Some((from, range.end)));
            }
            Event::End(TagEnd::CodeBlock) => {
                if let Some(Some((from, to))) = fence.take() {
                    out.push((from, math(myst_body(&doc[from..to]), from, false)));
                }
            }
            Event::Text(t) => role = t.ends_with("{math}"),
            Event::Code(text) => {
                if was_role {
                    let start = at + whole.find(text.as_ref()).unwrap_or(0);
                    out.push((at, math(text.to_string(), start, true)));
                }
                covered.push(range);
            }
            Event::Start(Tag::Heading { .. }) => out.push((at, Piece::Heading)),
            Event::Start(Tag::Paragraph) if numbered_heading(whole) => {
                out.push((at, Piece::Heading));
            }
            Event::Html(h) | Event::InlineHtml(h) => {
                covered.push(range);
                let mut rest = h.as_ref();
                while let Some(i) = rest.find("<!--") {
                    let after = &rest[i + 4..];
                    let Some(j) = after.find("-->") else { break };
                    if let Some(d) = directive(&after[..j]) {
                        out.push((at, Piece::Directive(d)));
                    }
                    rest = &after[j + 3..];
                }
            }
            _ => {}
        }
    }
    out.extend(mathjax(doc, &covered));
    // Stable: pieces at one offset keep the parser's order.
    out.sort_by_key(|(at, _)| *at);
    out.into_iter().map(|(_, p)| p).collect()
}

/// The body of a MyST math block with its option lines (`:label: eq-1`) blanked.
fn myst_body(text: &str) -> String {
    text.split_inclusive('\n')
        .map(|l| {
            let body = l.trim_end_matches(['\n', '\r']);
            if body.trim_start().starts_with(':') {
                " ".repeat(body.len()) + &l[body.len()..]
            } else {
                l.to_string()
            }
        })
        .collect()
}

fn math(text: String, start: usize, inline: bool) -> Piece {
    Piece::Math {
        text,
        start,
        inline,
    }
}

/// The math MathJax reads in Markdown text outside what the parser read as math, code
/// or HTML: `\[…\]`, `\(…\)` and display environments written bare.
fn mathjax(doc: &str, covered: &[std::ops::Range<usize>]) -> Vec<(usize, Piece)> {
    let mut out = Vec::new();
    // The covered ranges sorted and merged, so that each backslash finds its range by
    // binary search (a document of many displays stays linear).
    let mut merged: Vec<std::ops::Range<usize>> = covered.to_vec();
    merged.sort_by_key(|r| r.start);
    let mut disjoint: Vec<std::ops::Range<usize>> = Vec::with_capacity(merged.len());
    for r in merged {
        match disjoint.last_mut() {
            Some(last) if r.start <= last.end => last.end = last.end.max(r.end),
            _ => disjoint.push(r),
        }
    }
    let covering = |k: usize| {
        let n = disjoint.partition_point(|r| r.start <= k);
        n.checked_sub(1)
            .and_then(|j| disjoint.get(j))
            .filter(|r| r.contains(&k))
    };
    let mut i = 0;
    while let Some(k) = doc[i..].find('\\').map(|k| k + i) {
        if let Some(r) = covering(k) {
            i = r.end.max(k + 1);
            continue;
        }
        let rest = &doc[k..];
        let open = [("\\[", "\\]"), ("\\(", "\\)")]
            .into_iter()
            .find(|(o, _)| rest.starts_with(o))
            .map(|(o, c)| (o.len(), c.to_string(), 0))
            .or_else(|| environment(rest).map(|close| (0, close.clone(), close.len())));
        let escaped = k > 0 && doc.as_bytes()[k - 1] == b'\\';
        match open {
            Some((olen, close, keep)) if !escaped => {
                let body = k + olen;
                let Some(e) = doc[body..].find(&close) else {
                    break;
                };
                let text = doc[body..body + e + keep].to_string();
                out.push((k, math(text, body, rest.starts_with("\\("))));
                i = body + e + close.len();
            }
            _ => i = k + 1,
        }
    }
    out
}

/// The LaTeX sectioning commands: each starts a scope.
const SECTIONS: [&str; 5] = [
    "\\chapter",
    "\\section",
    "\\subsection",
    "\\subsubsection",
    "\\paragraph",
];

/// Whether a Markdown paragraph is a heading written as plain text, as notes converted
/// from PDF have them: one short line that starts with a section number (`5.1.2 Radius
/// of gyration`) or with `Example`, `Exercise`, `Problem` and a number (`Example 5.1 –
/// Rolling cylinder`), and does not end as a sentence does.
fn numbered_heading(paragraph: &str) -> bool {
    let line = paragraph.trim();
    if line.contains('\n') || line.len() > 80 || line.ends_with(['.', ':', ',', ';']) {
        return false;
    }
    let mut words = line.split_whitespace();
    let Some(first) = words.next() else {
        return false;
    };
    let numbered = |w: &str| {
        let w = w.trim_end_matches(['.', ':']);
        !w.is_empty()
            && w.split('.')
                .all(|p| !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit()))
    };
    let titled = |w: Option<&str>| {
        w.and_then(|w| w.chars().next())
            .is_some_and(char::is_uppercase)
    };
    if numbered(first) && first.contains('.') {
        return titled(words.next());
    }
    let keyword = ["example", "exercise", "problem", "worked example"]
        .iter()
        .any(|k| first.eq_ignore_ascii_case(k));
    keyword && words.next().is_some_and(numbered)
}

/// Where an inline `$…$` that starts `text` ends: the next `$` not escaped, before a
/// blank line.
fn inline_end(text: &str) -> Option<usize> {
    let para = text.find("\n\n").unwrap_or(text.len());
    let bytes = text.as_bytes();
    (0..para).find(|&k| bytes[k] == b'$' && (k == 0 || bytes[k - 1] != b'\\'))
}

/// The environments whose content is display math (each also starred).
const ENVIRONMENTS: [&str; 8] = [
    "equation",
    "displaymath",
    "align",
    "alignat",
    "flalign",
    "gather",
    "multline",
    "eqnarray",
];

/// The display environment that opens at the start of `rest`, and the text that closes
/// it.
fn environment(rest: &str) -> Option<String> {
    let tail = rest.strip_prefix("\\begin{")?;
    let name = &tail[..tail.find('}')?];
    ENVIRONMENTS
        .contains(&name.trim_end_matches('*'))
        .then(|| format!("\\end{{{name}}}"))
}

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
        if SECTIONS.iter().any(|c| {
            rest.strip_prefix(c)
                .is_some_and(|r| r.starts_with(['{', '*', '[']))
        }) {
            out.push(Piece::Heading);
            i += 1;
            continue;
        }
        // An environment is read whole, `\begin{…}` and `\end{…}` included: how its rows
        // go together depends on its name.
        let escaped = i > 0 && bytes[i - 1] == b'\\';
        let open = [("\\[", "\\]"), ("$$", "$$"), ("\\(", "\\)"), ("$", "$")]
            .into_iter()
            .find(|(o, _)| rest.starts_with(o) && !escaped)
            .map(|(o, c)| (o.len(), c.to_string(), 0))
            .or_else(|| environment(rest).map(|close| (0, close.clone(), close.len())));
        if let Some((1, _, _)) = open {
            // Inline `$…$`, within its paragraph, to the next `$` not escaped.
            if let Some(e) = inline_end(&doc[i + 1..]) {
                out.push(math(doc[i + 1..i + 1 + e].to_string(), i + 1, true));
                i += e + 2;
            } else {
                i += 1;
            }
            continue;
        }
        if let Some((olen, close, keep)) = open {
            let body_start = i + olen;
            let Some(k) = doc[body_start..].find(&close) else {
                break;
            };
            let text = doc[body_start..body_start + k + keep].to_string();
            out.push(math(text, body_start, olen == 2 && rest.starts_with("\\(")));
            i = body_start + k + close.len();
            continue;
        }
        i += rest.chars().next().map_or(1, char::len_utf8);
    }
    out
}

/// The relations of one cleaned display (see `display::clean`), each with its offset
/// in it. A display may hold several, set apart by [`super::display::SEP`], by
/// `\quad`/`\qquad`, by a run of `~` between two relations, or joined by an arrow (`\rightarrow`,
/// `\Rightarrow`, `\implies`); a part with no relation is a label (`\sum F_x`,
/// `(5.1)`) and is left out, as is a label before a colon (`\sum M(A): …`). Each comes
/// with whether an implication arrow follows it (`\Rightarrow`, `\implies`,
/// `\therefore`, `\rightarrow`): then it is a premise of what follows.
pub fn relations(line: &str) -> Vec<(&str, usize, bool)> {
    const BREAKS: [&str; 9] = [
        "qquad",
        "quad",
        "rightarrow",
        "Rightarrow",
        "longrightarrow",
        "Longrightarrow",
        "implies",
        "iff",
        "therefore",
    ];
    const ARROWS: [&str; 6] = [
        "rightarrow",
        "Rightarrow",
        "longrightarrow",
        "Longrightarrow",
        "implies",
        "therefore",
    ];
    let mut parts = Vec::new();
    let mut start = 0;
    let mut depth = 0i32;
    let bytes = line.as_bytes();
    let mut k = 0;
    while k < line.len() {
        match bytes[k] {
            b'{' => depth += 1,
            b'}' => depth -= 1,
            super::display::SEP => {
                parts.push((start, k, false));
                start = k + 1;
            }
            // A run of `~` between two relations sets them apart; elsewhere it is a space.
            b'~' if depth == 0 => {
                let run = line[k..].bytes().take_while(|b| *b == b'~').count();
                if has_relation(&line[start..k]) && has_relation(&line[k + run..]) {
                    parts.push((start, k, false));
                    start = k + run;
                }
                k += run;
                continue;
            }
            b'\\' => {
                let name_len = line[k + 1..]
                    .bytes()
                    .take_while(u8::is_ascii_alphabetic)
                    .count();
                let name = &line[k + 1..k + 1 + name_len];
                if depth == 0 && BREAKS.contains(&name) {
                    parts.push((start, k, ARROWS.contains(&name)));
                    start = k + 1 + name_len;
                }
                k += 1 + name_len.max(1);
                continue;
            }
            _ => {}
        }
        k += 1;
    }
    parts.push((start, line.len(), false));
    let mut out: Vec<(&str, usize, bool)> = Vec::new();
    for (a, b, arrow) in parts {
        let mut a = a;
        let part = &line[a..b];
        if let Some(colon) = top_level_colon(part) {
            if !has_relation(&part[..colon]) {
                a += colon + 1;
            }
        }
        // The relation starts at its first character, not at the spaces before it.
        a += line[a..b].len() - line[a..b].trim_start().len();
        let text = &line[a..b];
        if has_relation(text) {
            out.push((text, a, false));
        }
        // An arrow after a relation, before the next one, makes it a premise.
        if arrow {
            if let Some(last) = out.last_mut() {
                last.2 = true;
            }
        }
    }
    out
}

/// The first `:` outside braces (not `:=`).
fn top_level_colon(text: &str) -> Option<usize> {
    let mut depth = 0i32;
    for (k, c) in text.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ':' if depth == 0 && !text[k + 1..].starts_with('=') => return Some(k),
            _ => {}
        }
    }
    None
}

/// The relation commands of LaTeX that rigor reads, by name (without the backslash).
pub(super) const RELATIONS: [&str; 11] = [
    "approx",
    "simeq",
    "thickapprox",
    "neq",
    "ne",
    "le",
    "leq",
    "leqslant",
    "ge",
    "geq",
    "geqslant",
];

/// Whether a piece of LaTeX math holds a relation outside braces.
pub(super) fn has_relation(text: &str) -> bool {
    let mut depth = 0i32;
    let bytes = text.as_bytes();
    let mut k = 0;
    while k < text.len() {
        match bytes[k] {
            b'{' => depth += 1,
            b'}' => depth -= 1,
            b'=' | b'<' | b'>' if depth == 0 => return true,
            b'\\' => {
                let name_len = text[k + 1..]
                    .bytes()
                    .take_while(u8::is_ascii_alphabetic)
                    .count();
                if depth == 0 && RELATIONS.contains(&&text[k + 1..k + 1 + name_len]) {
                    return true;
                }
                k += 1 + name_len.max(1);
                continue;
            }
            _ => {}
        }
        k += 1;
    }
    false
}

/// The offset of the first `=` outside braces at or after `from`.
pub fn equals_after(text: &str, from: usize) -> Option<usize> {
    let mut depth = 0i32;
    for (k, c) in text.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            '=' if depth == 0 && k >= from => return Some(k),
            _ => {}
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn texts(line: &str) -> Vec<&str> {
        relations(line)
            .into_iter()
            .map(|(t, _, _)| t.trim())
            .collect()
    }

    #[test]
    fn labels_spacing_and_arrows_part_the_relations_of_a_line() {
        assert_eq!(
            texts(r"\sum F_{y} \qquad N - mg \cos \beta = m \ddot{y} = 0"),
            [r"N - mg \cos \beta = m \ddot{y} = 0"]
        );
        assert_eq!(
            texts(
                r"\sum M(A): \qquad -mg = I_A \ddot\theta \qquad \rightarrow \qquad \ddot\theta = -g"
            ),
            [r"-mg = I_A \ddot\theta", r"\ddot\theta = -g"]
        );
        assert_eq!(texts(r"\int x\,dm = 0 \qquad \int y\,dm = 0").len(), 2);
        // A colon after a relation is not a label's.
        assert_eq!(texts(r"a = b : c"), [r"a = b : c"]);
        // Braces hide what is inside them; a label alone is no relation.
        assert_eq!(texts(r"\text{see \quad below}"), Vec::<&str>::new());
        assert_eq!(texts(r"v = 3 \quad \text{(m/s)}"), ["v = 3"]);
        // Offsets point into the line.
        let line = r"x = 1 \implies y = 2";
        let (t, at, _) = relations(line)[1];
        assert!(relations(line)[0].2 && !relations(line)[1].2, "a premise");
        assert_eq!(&line[at..at + t.len()], t);
    }

    #[test]
    fn numbered_plain_text_lines_are_headings_and_sentences_are_not() {
        for h in [
            "5.1 Moment of Inertia",
            "5.1.2 Standard Cases",
            "Example 5.1 – Rolling Cylinder",
            "Problem 3 A ladder",
        ] {
            assert!(numbered_heading(h), "{h}");
        }
        for p in [
            "5 apples fell.",
            "5.1 is the number of the section.",
            "The moment of inertia 5.1 Moment",
            "Example: a rod",
            "3.5 kg",
            "5.1 Moment of Inertia\nand more text on a second line",
        ] {
            assert!(!numbered_heading(p), "{p}");
        }
    }

    #[test]
    fn headings_are_pieces_in_both_kinds_of_document() {
        let md = "# Title\n\n5.2 General Motion\n\n$$a = b$$\n";
        let kinds: Vec<bool> = pieces(md, DocKind::Markdown)
            .iter()
            .map(|p| matches!(p, Piece::Heading))
            .collect();
        assert_eq!(kinds, [true, true, false]);
        let tex = "\\section{One}\n\\[a = b\\]\n\\subsection*{Two}\n";
        let kinds: Vec<bool> = pieces(tex, DocKind::Latex)
            .iter()
            .map(|p| matches!(p, Piece::Heading))
            .collect();
        assert_eq!(kinds, [true, false, true]);
    }

    #[test]
    fn the_equals_sign_after_a_place_is_found_outside_braces() {
        assert_eq!(equals_after(r"\int_0^R r^2 dm = x = y", 10), Some(16));
        assert_eq!(equals_after(r"\frac{a=b}{c} = d", 0), Some(14));
        assert_eq!(equals_after("a = b", 4), None);
    }
}
