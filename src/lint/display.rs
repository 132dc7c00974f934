//! Display math as authors write it, made ready for the chain reader with every byte
//! offset kept: markup that carries no maths (`\begin{align}`, `\label{…}`, `\tag{…}`,
//! `\nonumber`, `\boxed{…}`'s braces, empty groups `{}`, a row's trailing comma) becomes
//! spaces of the same length, and the rows and columns of an environment become one
//! chain or several. In `align`, `aligned`, `split`, `alignat`, `eqnarray` and a MyST
//! `{math}` block, a row that starts with a relation (`&= …`) or an operator goes on
//! with the row before (`I_H &= … \\ &= …` is one chain, one link per line); in
//! `gather` every row is its own chain; `multline` is one equation over several rows.
//! Where a display holds several chains, they are set apart by [`SEP`], which the
//! reader splits at.

/// The byte that sets two chains of a cleaned display apart (a column separator `&`, a
/// row break between rows that do not go on): a control character, never in maths.
pub const SEP: u8 = 0x01;

/// How the rows of a display go together.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Rows {
    /// A row that starts with a relation or an operator continues the one before.
    Align,
    /// Every row is its own chain.
    Gather,
    /// Every row continues the one before.
    Multline,
    /// `x &=& y`: the `&` around the relation are not column separators.
    Eqnarray,
}

/// The environments of display math, and how their rows go together.
const MATH_ENVS: [(&str, Rows); 12] = [
    ("equation", Rows::Align),
    ("displaymath", Rows::Align),
    ("align", Rows::Align),
    ("aligned", Rows::Align),
    ("alignat", Rows::Align),
    ("alignedat", Rows::Align),
    ("flalign", Rows::Align),
    ("split", Rows::Align),
    ("gather", Rows::Gather),
    ("gathered", Rows::Gather),
    ("multline", Rows::Multline),
    ("eqnarray", Rows::Eqnarray),
];

/// Markup that carries no maths and takes one braced argument: dropped whole.
const DROPPED_WITH_ARG: [&str; 4] = ["label", "tag", "tag*", "eqref"];

/// Markup with no argument that carries no maths.
const DROPPED: [&str; 9] = [
    "nonumber",
    "notag",
    "displaystyle",
    "Huge",
    "huge",
    "LARGE",
    "Large",
    "large",
    "normalsize",
];

/// The environments named in `text`'s `\begin{…}`, each with its rows' kind; `None`
/// for an environment that is not an equation's (`cases`, `pmatrix`, `array`).
fn env_at(text: &str, k: usize) -> Option<(usize, Option<Rows>, bool)> {
    let rest = &text[k..];
    let (open, tail) = if let Some(t) = rest.strip_prefix("\\begin{") {
        (true, t)
    } else {
        (false, rest.strip_prefix("\\end{")?)
    };
    let close = tail.find('}')?;
    let name = &tail[..close];
    let base = name.trim_end_matches('*');
    let rows = MATH_ENVS.iter().find(|(n, _)| *n == base).map(|(_, r)| *r);
    let mut len = rest.len() - tail.len() + close + 1;
    if open && rows.is_some() {
        // `\begin{alignat}{2}`, `\begin{aligned}[t]`: the argument is layout.
        let after = &rest[len..];
        for (o, c) in [('{', '}'), ('[', ']')] {
            if after.starts_with(o) {
                if let Some(e) = after.find(c) {
                    len += e + 1;
                }
            }
        }
    }
    Some((len, rows, open))
}

/// `text` with the markup blanked and rows joined or set apart (see the module's
/// header), as long as `text`, byte for byte.
pub fn clean(text: &str) -> String {
    let mut out: Vec<u8> = text.as_bytes().to_vec();
    let bytes = text.as_bytes();
    let blank = |out: &mut Vec<u8>, a: usize, b: usize| {
        for x in out.iter_mut().take(b.min(text.len())).skip(a) {
            if *x != b'\n' {
                *x = b' ';
            }
        }
    };
    // The stack of open environments: Some(rows) for an equation's, None for another.
    let mut envs: Vec<Option<Rows>> = Vec::new();
    let mut rows = Rows::Align;
    // Braces opened by `\boxed{`, whose closing brace goes too; the depth of braces.
    let mut boxed: Vec<i32> = Vec::new();
    let mut depth = 0i32;
    // The `&` of the current row so far, and where the row started.
    let mut amps = 0usize;
    let mut row_start = 0usize;
    let mut k = 0;
    while k < text.len() {
        let inner = envs.last().is_some_and(Option::is_none);
        match bytes[k] {
            b'{' => {
                if let Some(e) = empty_group_end(text, k) {
                    blank(&mut out, k, e);
                    k = e;
                    continue;
                }
                depth += 1;
            }
            b'}' => {
                if boxed.last() == Some(&depth) {
                    boxed.pop();
                    blank(&mut out, k, k + 1);
                }
                depth -= 1;
            }
            b'&' if depth == 0 && !inner => {
                amps += 1;
                // Column separators: the second, fourth… `&` of an `align` row.
                if rows == Rows::Eqnarray || amps % 2 == 1 {
                    blank(&mut out, k, k + 1);
                } else {
                    out[k] = SEP;
                }
            }
            b'\\' => {
                let name_len = text[k + 1..]
                    .bytes()
                    .take_while(u8::is_ascii_alphabetic)
                    .count();
                let name = &text[k + 1..k + 1 + name_len];
                if let Some((len, r, open)) = env_at(text, k) {
                    if open {
                        envs.push(r);
                    } else {
                        envs.pop();
                    }
                    if r.is_some() {
                        blank(&mut out, k, k + len);
                        rows = envs.iter().rev().find_map(|e| *e).unwrap_or(rows);
                        if let Some(r) = r.filter(|_| open) {
                            rows = r;
                        }
                    }
                    k += len;
                    continue;
                }
                if name_len == 0 && text[k + 1..].starts_with('\\') {
                    if depth == 0 && !inner {
                        let end = row_break_end(text, k);
                        row_end_punctuation(&mut out, k);
                        let joins = joins(rows, &text[row_start..k], &text[end..]);
                        blank(&mut out, k, end);
                        if !joins {
                            out[k] = SEP;
                        }
                        row_start = end;
                        amps = 0;
                        k = end;
                        continue;
                    }
                    k += 2;
                    continue;
                }
                let star = text[k + 1 + name_len..].starts_with('*');
                let full = if star && name == "tag" { "tag*" } else { name };
                if DROPPED_WITH_ARG.contains(&full) {
                    let arg = k + 1 + full.len();
                    let end = group_end(text, arg).unwrap_or(arg);
                    blank(&mut out, k, end);
                    k = end;
                    continue;
                }
                if DROPPED.contains(&name) {
                    blank(&mut out, k, k + 1 + name_len);
                    k += 1 + name_len;
                    continue;
                }
                if name == "boxed" && text[k + 1 + name_len..].starts_with('{') {
                    blank(&mut out, k, k + 2 + name_len);
                    depth += 1;
                    boxed.push(depth);
                    k += 2 + name_len;
                    continue;
                }
                k += 1 + name_len.max(1);
                continue;
            }
            _ => {}
        }
        k += 1;
    }
    trailing_punctuation(&mut out);
    String::from_utf8(out).unwrap_or_else(|_| text.to_string())
}

/// The end of an empty group `{}` (or `{ }`) opened at `k`, past its closing brace.
fn empty_group_end(text: &str, k: usize) -> Option<usize> {
    let rest = &text[k + 1..];
    rest.trim_start_matches([' ', '\t'])
        .starts_with('}')
        .then(|| k + 1 + rest.find('}').unwrap_or(0) + 1)
}

/// Blanks a `,` `.` or `;` that ends the row before a row break at `k`.
fn row_end_punctuation(out: &mut [u8], k: usize) {
    let Some(p) = out[..k].iter().rposition(|b| !b.is_ascii_whitespace()) else {
        return;
    };
    if matches!(out[p], b',' | b'.' | b';') {
        out[p] = b' ';
    }
}

/// Where a row break `\\` at `k` ends, with its optional spacing `[2pt]` and `*`.
fn row_break_end(text: &str, k: usize) -> usize {
    let mut end = k + 2;
    if text[end..].starts_with('*') {
        end += 1;
    }
    if text[end..].trim_start_matches([' ', '\t']).starts_with('[') {
        if let Some(c) = text[end..].find(']') {
            end += c + 1;
        }
    }
    end
}

/// Where the braced group that starts at `at` (after spaces) ends.
fn group_end(text: &str, at: usize) -> Option<usize> {
    let open = at + text.get(at..)?.find('{')?;
    if !text[at..open].trim().is_empty() {
        return None;
    }
    let mut depth = 0i32;
    for (i, c) in text[open..].char_indices() {
        match c {
            '{' => depth += 1,
            '}' => {
                depth -= 1;
                if depth == 0 {
                    return Some(open + i + 1);
                }
            }
            _ => {}
        }
    }
    None
}

/// Whether the row after a `\\` goes on with the row before it.
fn joins(rows: Rows, before: &str, after: &str) -> bool {
    match rows {
        Rows::Gather => false,
        Rows::Multline => true,
        Rows::Align | Rows::Eqnarray => {
            let mut next = after.trim_start_matches(|c: char| c.is_whitespace() || c == '&');
            // Spacing at the start of a row (`&\quad + c`) is layout.
            while let Some(r) = ["\\quad", "\\qquad", "\\;", "\\,", "\\!", "\\:", "~"]
                .iter()
                .find_map(|s| next.strip_prefix(s))
            {
                next = r.trim_start_matches(|c: char| c.is_whitespace() || c == '&');
            }
            let prev = before.trim_end();
            // A row that starts with an operator goes on with the expression before it
            // when its operator comes after the alignment point (`& + c`) or it holds no
            // relation of its own; `-F a &= I_G \ddot\theta` is an equation of its own.
            let row = &after[..after.find("\\\\").unwrap_or(after.len())];
            let operator = next.starts_with(['+', '-'])
                || ["\\cdot", "\\times"].iter().any(|o| next.starts_with(o));
            let after_amp = row.trim_start().starts_with('&');
            starts_with_relation(next)
                || (operator && (after_amp || !super::extract::has_relation(row)))
                || prev.ends_with(['+', '-', '=', '('])
                || prev.ends_with("\\cdot")
        }
    }
}

/// The relations a continuation may start with (`= …`, `\le …`), a command's name read
/// whole (`\left` is no `\le`).
pub fn starts_with_relation(text: &str) -> bool {
    use super::extract::RELATIONS;
    let t = text.trim_start();
    if t.starts_with(['=', '<', '>']) {
        return true;
    }
    let Some(rest) = t.strip_prefix('\\') else {
        return false;
    };
    let name: String = rest.chars().take_while(char::is_ascii_alphabetic).collect();
    RELATIONS.contains(&name.as_str())
}

/// Punctuation that ends a row or a chain set apart (`= B, \\ &= C.`) is prose, not
/// maths: a `,` `.` or `;` followed only by spaces and a separator, or by the end.
fn trailing_punctuation(out: &mut [u8]) {
    let mut k = out.len();
    // Scanning backwards: `after` is whether only spaces and separators follow.
    let mut after = true;
    while k > 0 {
        k -= 1;
        match out[k] {
            b' ' | b'\n' | b'\t' | b'\r' => {}
            SEP => after = true,
            b',' | b'.' | b';' if after => {
                // A decimal point between digits is a number's.
                let digit_before = k > 0 && out[k - 1].is_ascii_digit();
                let digit_after = out.get(k + 1).is_some_and(u8::is_ascii_digit);
                if !(digit_before && digit_after) {
                    out[k] = b' ';
                }
            }
            _ => after = false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parts(text: &str) -> Vec<String> {
        let c = clean(text);
        assert_eq!(c.len(), text.len(), "offsets are kept");
        c.split(char::from(SEP))
            .map(|p| p.split_whitespace().collect::<Vec<_>>().join(" "))
            .filter(|p| !p.is_empty())
            .collect()
    }

    #[test]
    fn an_aligned_chain_is_one_chain_over_its_rows() {
        assert_eq!(
            parts("\\begin{align*}\n I_H &= I_G + m d^2 \\\\\n &= \\frac{mL^2}{3}, \\label{x}\n\\end{align*}"),
            ["I_H = I_G + m d^2 = \\frac{mL^2}{3}"]
        );
        assert_eq!(
            parts("\\begin{eqnarray} x &=& y \\nonumber \\\\ &=& z. \\end{eqnarray}"),
            ["x = y = z"]
        );
        // A row with its own left side is a chain of its own; so is every row of a gather.
        assert_eq!(parts("a &= b \\\\ c &= d"), ["a = b", "c = d"]);
        assert_eq!(
            parts("\\begin{gather} a = b \\\\ = c \\end{gather}"),
            ["a = b", "= c"]
        );
        // An equation whose left side starts with a minus sign is a row of its own.
        assert_eq!(
            parts("F &= m a \\\\ -F b &= I \\alpha"),
            ["F = m a", "-F b = I \\alpha"]
        );
        // A multline is one equation; a row that starts with `+` goes on.
        assert_eq!(
            parts("\\begin{multline} u = a + b \\\\ c + d \\end{multline}"),
            ["u = a + b c + d"]
        );
        assert_eq!(
            parts("u &= a + b \\\\ &\\quad + c"),
            ["u = a + b \\quad + c"]
        );
        // Two columns of an align are two chains.
        assert_eq!(parts("x &= 1 & y &= 2"), ["x = 1", "y = 2"]);
    }

    #[test]
    fn markup_that_carries_no_maths_is_blanked() {
        assert_eq!(parts("\\boxed{a = b^{2}} \\tag{3}"), ["a = b^{2}"]);
        assert_eq!(parts("\\rho{} V = m"), ["\\rho V = m"]);
        assert_eq!(parts("v = 3.5."), ["v = 3.5"]);
        assert_eq!(
            parts("\\begin{alignat}{2} a &= b &\\quad& \\text{by (1)} \\end{alignat}"),
            ["a = b", "\\quad \\text{by (1)}"]
        );
        // A matrix keeps its rows and columns (and is not read).
        assert_eq!(
            parts("A = \\begin{pmatrix} 1 & 2 \\\\ 3 & 4 \\end{pmatrix}").len(),
            1
        );
    }

    #[test]
    fn a_relation_is_a_command_read_whole() {
        assert!(starts_with_relation(" \\le 3"));
        assert!(starts_with_relation("= 3"));
        assert!(!starts_with_relation("\\left. x \\right|_0^1"));
    }
}
