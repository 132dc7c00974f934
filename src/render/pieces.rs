//! How the pieces of a worked solution are written: a displayed row, broken across
//! lines when it is too wide for the page; words with maths between `$` (a `by` text,
//! prose); the notes of a failure, their expressions typeset. LaTeX and Markdown share
//! these, each passing its own escaper.

use super::expr::{chain_latex_in, expr_latex_in, Ctx};
use super::solution::{Inline, Just, Row};
use crate::diag::Note;

/// One line of an `align*`, in LaTeX or MathJax (`escape` sets words inside `\text`):
/// `lhs &= rhs \quad\text{(by …)}`, then its `where` and the mark of a link that did
/// not verify.
/// `page`: for a LaTeX page, where a wide left side is set with `\lefteqn` (MathJax,
/// which has no `\lefteqn`, keeps it in its column and scrolls).
pub(crate) fn row_math(escape: fn(&str) -> String, page: bool, row: &Row, out: &mut String) {
    // A right side too wide for the page goes on several lines, broken before a `+` or
    // `−` outside any bracket, each line after the first indented. A wide left side
    // takes no width of its own (`\lefteqn`) and the relation starts the next line.
    let first = row.lhs.as_deref().map_or(0, math_width);
    let tail = match &row.by {
        Some(Just::Text(parts)) => parts.iter().map(inline_width).sum::<usize>() + 6,
        Some(Just::Labels(ls)) => ls.iter().map(|l| l.len() + 3).sum::<usize>() + 4,
        None => 0,
    } + row.flag.map_or(0, |f| f.words().len() + 4);
    let wide_left =
        page && first > LINE_WIDTH / 3 && first + math_width(&row.rhs) + tail > LINE_WIDTH;
    if let Some(lhs) = &row.lhs {
        if wide_left {
            out.push_str(&format!("\\lefteqn{{{lhs}}} \\\\\n\\qquad "));
        } else {
            out.push_str(lhs);
            out.push(' ');
        }
    }
    let room = if wide_left { 4 } else { first };
    // A long justification that does not fit after the last line has a line of its own.
    let own_line = page && tail > LINE_WIDTH / 3 && room + math_width(&row.rhs) + tail > LINE_WIDTH;
    let tail_room = if own_line { 0 } else { tail };
    let width = LINE_WIDTH
        .saturating_sub(room + tail_room)
        .max(LINE_WIDTH / 3);
    let lines = break_sum(&row.rhs, width);
    out.push_str(&format!(
        "&{} {}",
        row.rel,
        lines.join(" \\\\\n&\\qquad {}")
    ));
    if own_line {
        out.push_str(" \\\\\n&\\qquad");
    }
    match &row.by {
        Some(Just::Text(parts)) => {
            // Maths leaves the `\text` and comes back: MathJax sets no `$` inside it.
            let words: String = parts
                .iter()
                .map(|p| match p {
                    Inline::Math(m) => format!("}}{m}\\text{{"),
                    Inline::Text(t) | Inline::Code(t) | Inline::Strong(t) => escape(t),
                })
                .collect();
            out.push_str(&format!(" \\quad\\text{{(by {words})}}"));
        }
        Some(Just::Labels(ls)) => {
            let ls: Vec<String> = ls.iter().map(|l| format!("({})", escape(l))).collect();
            out.push_str(&format!(" \\quad\\text{{by {}}}", ls.join(", ")));
        }
        None => {}
    }
    if let Some(w) = &row.where_ {
        out.push_str(&format!(" \\qquad {w}"));
    }
    if let Some(f) = row.flag {
        out.push_str(&format!(" \\quad\\textbf{{[{}]}}", f.words()));
    }
}

/// About how many characters of maths fit on a line of the page (an A4 page with
/// 2.5 cm margins at 11 pt, less the equation number).
const LINE_WIDTH: usize = 72;

/// Roughly how wide a piece of words or maths is, in characters.
fn inline_width(i: &Inline) -> usize {
    match i {
        Inline::Math(m) => math_width(m),
        Inline::Text(t) | Inline::Code(t) | Inline::Strong(t) => t.chars().count(),
    }
}

/// Roughly how wide a line of LaTeX maths is, in characters: a command counts as one
/// (a function name as its letters), braces and thin spaces as nothing, a fraction as
/// its wider part, a sub- or superscript as half.
pub(crate) fn math_width(s: &str) -> usize {
    fn width(s: &[u8], i: &mut usize, stop: u8) -> usize {
        let mut w = 0;
        while let Some(&c) = s.get(*i) {
            *i += 1;
            match c {
                _ if c == stop => return w,
                b'{' => w += width(s, i, b'}'),
                b' ' | b'}' => {}
                // A binary operator or relation with the space around it.
                b'+' | b'-' | b'=' | b'<' | b'>' => w += 2,
                b'^' | b'_' => {
                    let inner = if s.get(*i) == Some(&b'{') {
                        *i += 1;
                        width(s, i, b'}')
                    } else {
                        *i += 1;
                        1
                    };
                    w += inner.div_ceil(2);
                }
                b'\\' => {
                    let start = *i;
                    while s.get(*i).is_some_and(u8::is_ascii_alphabetic) {
                        *i += 1;
                    }
                    let name = &s[start..*i];
                    match name {
                        b"" => *i += 1,
                        b"frac" | b"dfrac" | b"tfrac" => {
                            let mut parts = [0; 2];
                            for p in &mut parts {
                                if s.get(*i) == Some(&b'{') {
                                    *i += 1;
                                    *p = width(s, i, b'}');
                                }
                            }
                            w += parts[0].max(parts[1]);
                        }
                        b"left" | b"right" | b"displaystyle" | b"mathit" | b"mathrm" => {}
                        b"sin" | b"cos" | b"tan" | b"ln" | b"exp" | b"sqrt" => w += name.len(),
                        _ => w += 1,
                    }
                }
                _ => w += 1,
            }
        }
        w
    }
    width(s.as_bytes(), &mut 0, 0)
}

/// `s` cut before its `+` and `−` outside any bracket into lines at most `width` wide
/// where the terms allow (a term wider than that has a line of its own); one line when
/// it fits.
pub(crate) fn break_sum(s: &str, width: usize) -> Vec<String> {
    if math_width(s) <= width {
        return vec![s.to_string()];
    }
    let b = s.as_bytes();
    let mut cuts = Vec::new();
    let mut depth = 0i32;
    for (i, &c) in b.iter().enumerate() {
        match c {
            b'{' | b'(' | b'[' => depth += 1,
            b'}' | b')' | b']' => depth -= 1,
            b' ' if depth == 0 && i > 0 => {
                let next = b.get(i + 1..i + 3);
                if next == Some(b"+ ") || next == Some(b"- ") {
                    cuts.push(i + 1);
                }
            }
            _ => {}
        }
    }
    let mut lines: Vec<String> = Vec::new();
    let mut from = 0;
    let mut line = String::new();
    for at in cuts.into_iter().chain(std::iter::once(s.len())) {
        let term = &s[from..at];
        from = at;
        if !line.is_empty() && math_width(&line) + math_width(term) > width {
            lines.push(line.trim_end().to_string());
            line = String::new();
        }
        line.push_str(term);
    }
    if !line.trim().is_empty() {
        lines.push(line.trim_end().to_string());
    }
    // A term wider than a line by itself is broken inside its widest bracket.
    lines
        .into_iter()
        .flat_map(|l| {
            if math_width(&l) > width {
                split_group(&l, width).unwrap_or_else(|| vec![l])
            } else {
                vec![l]
            }
        })
        .collect()
}

/// A term with a `\left( … \right)` group too wide for a line, broken inside the group
/// before its own `+` and `−` (`\left( a + b \right.` then `\left. {}+ c \right)`);
/// `None` when it has no such group.
fn split_group(term: &str, width: usize) -> Option<Vec<String>> {
    // Only a group outside braces: one inside a fraction cannot be broken across lines.
    let mut braces = 0i32;
    let open = (0..term.len()).find(|&i| {
        match term.as_bytes()[i] {
            b'{' => braces += 1,
            b'}' => braces -= 1,
            _ => {}
        }
        braces == 0 && term[i..].starts_with("\\left(")
    })?;
    let inner_start = open + "\\left(".len();
    // The matching `\right)`: brackets counted from the group's start.
    let b = term.as_bytes();
    let mut depth = 0i32;
    let mut close = None;
    let mut i = inner_start;
    while i < b.len() {
        if term[i..].starts_with("\\left") {
            depth += 1;
            i += "\\left".len();
            continue;
        }
        if term[i..].starts_with("\\right") {
            if depth == 0 {
                close = Some(i);
                break;
            }
            depth -= 1;
            i += "\\right".len();
            continue;
        }
        i += 1;
    }
    let close = close?;
    let inner = &term[inner_start..close];
    let parts = break_sum(inner, width.saturating_sub(4).max(8));
    if parts.len() < 2 {
        return None;
    }
    let (head, tail) = (&term[..open], &term[close + "\\right".len()..]);
    let last = parts.len() - 1;
    Some(
        parts
            .iter()
            .enumerate()
            .map(|(k, p)| {
                let l = if k == 0 {
                    format!("{head}\\left(")
                } else {
                    "\\left.{}".into()
                };
                let r = if k == last {
                    format!("\\right{tail}")
                } else {
                    "\\right.".into()
                };
                format!("{l}{p}{r}")
            })
            .collect(),
    )
}

/// Raw text with `$…$` math (rigor's syntax) as inlines: math typeset, the rest text;
/// `\$` is a dollar sign, and math that does not parse stays text.
pub(crate) fn rich(t: &str) -> Vec<Inline> {
    let mut out = Vec::new();
    let mut text = String::new();
    let mut rest = t;
    let opts = crate::syntax::ParseOptions::default();
    while let Some(i) = rest.find('$') {
        if rest[..i].ends_with('\\') {
            text.push_str(&rest[..i - 1]);
            text.push('$');
            rest = &rest[i + 1..];
            continue;
        }
        let after = &rest[i + 1..];
        let Some(j) = after.find('$') else {
            break;
        };
        let math = &after[..j];
        let typeset = crate::syntax::parse_chain(math, &opts)
            .map(|c| chain_latex_in(&c, &Ctx::default()))
            .or_else(|_| {
                crate::syntax::parse_expr(math, &opts).map(|e| expr_latex_in(&e, &Ctx::default()))
            });
        text.push_str(&rest[..i]);
        match typeset {
            Ok(m) => {
                if !text.is_empty() {
                    out.push(Inline::Text(std::mem::take(&mut text)));
                }
                out.push(Inline::Math(m));
            }
            Err(_) => {
                text.push('$');
                text.push_str(math);
                text.push('$');
            }
        }
        rest = &after[j + 1..];
    }
    text.push_str(rest);
    if !text.is_empty() {
        out.push(Inline::Text(text));
    }
    out
}

/// Words with their `…` spans as code (``did you mean `R`?``); with an odd number of
/// backticks, all words.
fn code_spans(t: &str) -> Vec<Inline> {
    let parts: Vec<&str> = t.split('`').collect();
    if parts.len() % 2 == 0 {
        return vec![Inline::Text(t.to_string())];
    }
    (parts.iter().enumerate())
        .filter(|(_, p)| !p.is_empty())
        .map(|(k, p)| match k % 2 {
            1 => Inline::Code(p.to_string()),
            _ => Inline::Text(p.to_string()),
        })
        .collect()
}

/// A note of a failure, typeset where it states expressions (a side, the difference
/// left after the facts, the values of a counterexample: normal forms in rigor's own
/// syntax). An expression that does not read stays words.
pub(crate) fn note_inlines(note: &Note) -> Vec<Inline> {
    let read = |t: &str| {
        crate::syntax::parse_expr(t.trim(), &crate::syntax::ParseOptions::default())
            .ok()
            .map(|e| super::expr::expr_latex(&e))
    };
    let words = || code_spans(&note.to_string());
    // Set as a display would set it, so fractions keep their size.
    let lead_and = |lead: &str, value: &str| match read(value) {
        Some(m) => vec![
            Inline::Text(format!("{lead} ")),
            Inline::Math(format!("\\displaystyle {m}")),
        ],
        None => words(),
    };
    match note {
        Note::Side { left: true, value } => lead_and("left side:", value),
        Note::Side { left: false, value } => lead_and("right side:", value),
        Note::Remainder { eliminated, value } => lead_and(
            if *eliminated {
                "after eliminating what the facts give, left − right ="
            } else {
                "after using the facts, left − right ="
            },
            value,
        ),
        Note::Reduced { using, left, right } => match (read(left), read(right)) {
            (Some(l), Some(r)) => {
                let lead = if using.is_empty() {
                    "with the facts: left ".to_string()
                } else {
                    format!(
                        "with the facts (after using {}): left ",
                        crate::diag::cite(using)
                    )
                };
                vec![
                    Inline::Text(lead),
                    Inline::Math(l),
                    Inline::Text(", right ".into()),
                    Inline::Math(r),
                ]
            }
            _ => words(),
        },
        Note::Counterexample { at, left, right } if !at.is_empty() => {
            let typeset: Option<Vec<String>> = at
                .iter()
                .map(|(name, value)| Some(format!("{} = {}", read(name)?, read(value)?)))
                .collect();
            match typeset {
                Some(t) => vec![
                    Inline::Text("counterexample: at ".into()),
                    Inline::Math(t.join(",\\ ")),
                    Inline::Text(format!(
                        " the left side is {left} and the right side {right}"
                    )),
                ],
                None => words(),
            }
        }
        _ => words(),
    }
}

/// Words with maths between `$` (rigor's syntax, as in prose): the maths typeset where it
/// reads, the rest kept as words (an unclosed `$` included).
pub(crate) fn words_and_math(t: &str, ctx: &Ctx) -> Vec<Inline> {
    let opts = crate::syntax::ParseOptions::default();
    let mut out = Vec::new();
    let mut pieces = t.split('$');
    let mut words = pieces.next().unwrap_or("").to_string();
    let mut rest: Vec<&str> = pieces.collect();
    // An odd `$` at the end opens nothing.
    let unclosed = (rest.len() % 2 == 1).then(|| rest.pop()).flatten();
    for pair in rest.chunks(2) {
        let (math, after) = (pair[0], pair.get(1).copied().unwrap_or(""));
        let typeset = crate::syntax::parse_chain(math, &opts)
            .ok()
            .filter(|c| !c.links.is_empty())
            .map(|c| chain_latex_in(&c, ctx))
            .or_else(|| {
                crate::syntax::parse_expr(math, &opts)
                    .ok()
                    .map(|e| expr_latex_in(&e, ctx))
            });
        match typeset {
            Some(m) => {
                if !words.is_empty() {
                    out.push(Inline::Text(std::mem::take(&mut words)));
                }
                out.push(Inline::Math(m));
            }
            None => words.push_str(&format!("${math}$")),
        }
        words.push_str(after);
    }
    if let Some(u) = unclosed {
        words.push('$');
        words.push_str(u);
    }
    if !words.is_empty() {
        out.push(Inline::Text(words));
    }
    out
}

/// A value the checker records, with its square roots as a person writes them
/// (`sqrt(3 g/(2 L))`, not `sqrt(6) sqrt(L) sqrt(g)/(2 L)`): the text is read in the
/// file's signs, without its definitions (a value names what the checker solved for,
/// never what a `let` stands for), and written by [`radicals`](crate::normal::present::radicals). A text that
/// does not read so is returned as recorded.
pub(crate) fn as_written(s: &str, env: &crate::lower::Env) -> String {
    if !s.contains("sqrt(") {
        return s.to_string();
    }
    let signs_only = crate::lower::Env {
        signs: env.signs.clone(),
        time: env.time.clone(),
        ..crate::lower::Env::default()
    };
    let parsed = crate::syntax::parse_expr(s, &crate::syntax::ParseOptions::default());
    match parsed.map(|e| crate::lower::lower(&e, &signs_only)) {
        Ok(Ok(r)) => crate::normal::present::radicals(&r, &env.signs),
        _ => s.to_string(),
    }
}
