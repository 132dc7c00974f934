//! Relations and chains (`a = b by [Fx] = c`), their `by` justifications, labels, and
//! the `NAME = EXPR, …` lists of `where` and `with`.

use super::ast::{Assign, By, Expr, Func, Label, Link, Name, RelOp, Span};
use super::error::{failure, no_match, PResult};
use super::expr::expr;
use super::lex::{
    describe, expected, hspace, ident, is_reserved, keyword, punct, token_len, ws, Cx,
};

/// What a chain may contain where it is parsed.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ChainRules<'r> {
    /// What came before the first expression, for "expected an expression after …".
    pub after: &'r str,
    /// Whether links may end with `by …` (statements).
    pub by: bool,
    /// Whether a `where` clause may follow (claims): `by` text then stops at ` where `
    /// on the last link's line.
    pub where_: bool,
}

/// The relation operators as written, longest first.
const RELOPS: [(&str, RelOp); 11] = [
    ("<=", RelOp::Le),
    (">=", RelOp::Ge),
    ("!=", RelOp::Ne),
    ("~=", RelOp::Approx),
    ("≤", RelOp::Le),
    ("≥", RelOp::Ge),
    ("≠", RelOp::Ne),
    ("≈", RelOp::Approx),
    ("=", RelOp::Eq),
    ("<", RelOp::Lt),
    (">", RelOp::Gt),
];

/// `relop`: after whitespace, a relation operator: its kind, text, the input at it and after it.
pub(crate) fn relop<'a>(
    cx: &Cx<'a>,
    i: &'a str,
) -> Option<(RelOp, &'static str, &'a str, &'a str)> {
    let at = ws(cx, i);
    RELOPS
        .iter()
        .find_map(|&(text, op)| at.strip_prefix(text).map(|rest| (op, text, at, rest)))
}

/// `chain-or-expr = expr link*`: an expression followed by any number of links.
pub(crate) fn chain_or_expr<'a>(
    cx: &Cx<'a>,
    i: &'a str,
    rules: ChainRules<'_>,
) -> PResult<'a, (Expr, Vec<Link>)> {
    let (mut i, first) = expr(cx, i, rules.after)?;
    let mut links = Vec::new();
    while let Some((op, text, at, rest)) = relop(cx, i) {
        let (rest, link) = link(cx, at, op, text, rest, rules)?;
        links.push(link);
        i = rest;
    }
    Ok((i, (first, links)))
}

/// `link = relop expr ["by" justification]`; `at` is the operator, `rest` what follows it.
fn link<'a>(
    cx: &Cx<'a>,
    at: &'a str,
    op: RelOp,
    text: &str,
    rest: &'a str,
    rules: ChainRules<'_>,
) -> PResult<'a, Link> {
    let (rest, rhs) = expr(cx, rest, text)?;
    let start = cx.pos(at);
    match keyword(cx, rest, "by").filter(|_| rules.by) {
        Some((by_at, after_by)) => {
            let (rest, (by, by_span, compare)) = by_clause(cx, by_at, after_by, rules)?;
            let span = Span::new(start, by_span.end);
            Ok((
                rest,
                Link {
                    op,
                    rhs,
                    by: Some((by, by_span)),
                    compare,
                    span,
                },
            ))
        }
        None => {
            let span = Span::new(start, rhs.span.end);
            Ok((
                rest,
                Link {
                    op,
                    rhs,
                    by: None,
                    compare: None,
                    span,
                },
            ))
        }
    }
}

/// `justification`: the rest of the line after `by` (up to a comment), as labels
/// `[a], [b] and [c]` when it is exactly that (or labels followed by `comparing
/// coefficients of NAME`, the name returned too), else as text. In a claim, a whole word
/// `where` ends the text unless the next line starts another link or the `where` clause.
pub(crate) fn by_clause<'a>(
    cx: &Cx<'a>,
    by_at: &'a str,
    after_by: &'a str,
    rules: ChainRules<'_>,
) -> PResult<'a, (By, Span, Option<Name>)> {
    let text_at = hspace(after_by);
    let line_len = text_at
        .find(|c| c == '\n' || (cx.comments && c == '%'))
        .unwrap_or(text_at.len());
    let line = text_at.get(..line_len).unwrap_or("");
    let mut raw = line.trim_end();
    if rules.where_ {
        let after_line = text_at.get(line_len..).unwrap_or("");
        if relop(cx, after_line).is_none() && keyword(cx, after_line, "where").is_none() {
            if let Some(k) = find_word(raw, "where") {
                raw = raw.get(..k).unwrap_or(raw).trim_end();
            }
        }
    }
    if raw.is_empty() {
        let message = "expected a justification after `by`: `by [label], …` or `by some words`";
        return failure(text_at, token_len(text_at), message);
    }
    let rest = text_at.get(raw.len()..).unwrap_or("");
    let span = Span::new(cx.pos(by_at), cx.pos(rest));
    let (by, compare) = match label_list(cx, text_at) {
        Ok((after, labels)) if cx.pos(after) == cx.pos(rest) => (By::Labels(labels), None),
        Ok((after, labels)) => match comparing(cx, after, rest) {
            Some(name) => (By::Labels(labels), Some(name)),
            None => (By::Text(raw.to_string()), None),
        },
        _ => (By::Text(raw.to_string()), None),
    };
    Ok((rest, (by, span, compare)))
}

/// `by [a], [b] comparing coefficients of NAME`, after the labels (`after`): the
/// name whose coefficients are compared, when the justification ends with it (at
/// `end`, a suffix of the region).
fn comparing<'a>(cx: &Cx<'a>, after: &'a str, end: &'a str) -> Option<Name> {
    let mut rest = after;
    for w in ["comparing", "coefficients", "of"] {
        rest = keyword(cx, rest, w)?.1;
    }
    let name_at = hspace(rest);
    let (after_name, id) = ident(name_at).ok()?;
    (cx.pos(after_name) == cx.pos(end)).then(|| Name {
        name: id.name,
        span: cx.span(name_at, after_name),
    })
}

/// The byte offset of the first whole-word occurrence of `word` in `text`.
fn find_word(text: &str, word: &str) -> Option<usize> {
    let is_name = |c: char| c.is_alphanumeric() || c == '_' || c == '\'';
    text.match_indices(word).map(|(k, _)| k).find(|&k| {
        let before = text.get(..k).and_then(|s| s.chars().next_back());
        let after = text
            .get(k.saturating_add(word.len())..)
            .and_then(|s| s.chars().next());
        !before.is_some_and(is_name) && !after.is_some_and(is_name)
    })
}

/// Whether `c` may appear in a label.
fn label_char(c: char) -> bool {
    c.is_alphanumeric() || matches!(c, '_' | '-' | '.' | '\'')
}

/// `label = "[" (letter | digit | "_" | "-" | "." | "'")+ "]"`; no match without a `[`.
pub(crate) fn label<'a>(cx: &Cx<'a>, i: &'a str) -> PResult<'a, Label> {
    let at = ws(cx, i);
    let Some(inner) = at.strip_prefix('[') else {
        return no_match(at);
    };
    let name_len = inner.find(|c| !label_char(c)).unwrap_or(inner.len());
    let name = inner.get(..name_len).unwrap_or("");
    let after = inner.get(name_len..).unwrap_or("");
    match after.strip_prefix(']') {
        Some(_) if name.is_empty() => failure(at, 2, "expected a label name between `[` and `]`"),
        Some(rest) => Ok((
            rest,
            Label {
                name: name.to_string(),
                span: cx.span(at, rest),
            },
        )),
        None if !after.split('\n').next().unwrap_or("").contains(']') => {
            failure(at, 1, "unclosed `[`")
        }
        None => {
            let message = format!(
                "unexpected {} in a label: labels hold letters, digits, `_`, `-`, `.` and `'`",
                describe(cx, after)
            );
            failure(
                after,
                after.chars().next().map_or(0, char::len_utf8),
                message,
            )
        }
    }
}

/// `labels = label (("," ["and"] | "and") label)*`; no match without a first `[`.
pub(crate) fn label_list<'a>(cx: &Cx<'a>, i: &'a str) -> PResult<'a, Vec<Label>> {
    let (mut i, first) = label(cx, i)?;
    let mut labels = vec![first];
    loop {
        let sep = match punct(cx, i, ",") {
            Some((_, rest)) => keyword(cx, rest, "and").map_or(rest, |(_, r)| r),
            None => match keyword(cx, i, "and") {
                Some((_, rest)) => rest,
                None => return Ok((i, labels)),
            },
        };
        let (rest, next) = match label(cx, sep) {
            Err(nom::Err::Error(_)) => return expected(cx, sep, "a label `[…]`"),
            other => other?,
        };
        labels.push(next);
        i = rest;
    }
}

/// `name`: a symbol name to declare or assign (not a reserved word, function or `pi`);
/// `what` completes "expected …"; primes are accepted only when `primes`.
pub(crate) fn name<'a>(cx: &Cx<'a>, i: &'a str, what: &str, primes: bool) -> PResult<'a, Name> {
    let at = ws(cx, i);
    let (rest, id) = match ident(at) {
        Ok((rest, id)) if !is_reserved(&id.name) => (rest, id),
        _ => return expected(cx, i, what),
    };
    let len = id.raw.len();
    if Func::from_name(&id.name).is_some() {
        return failure(
            at,
            len,
            format!("expected {what}, found the function `{}`", id.raw),
        );
    }
    if id.name == "pi" {
        return failure(
            at,
            len,
            format!("expected {what}, found the constant `{}`", id.raw),
        );
    }
    if !primes && id.name.ends_with('\'') {
        let message = format!(
            "expected {what}, found `{}`: primes mark time derivatives",
            id.raw
        );
        return failure(at, len, message);
    }
    Ok((
        rest,
        Name {
            name: id.name,
            span: cx.span(at, rest),
        },
    ))
}

/// `assignments = name "=" expr ("," name "=" expr)*` after `where` or `with` (the `keyword`).
pub(crate) fn assignments<'a>(cx: &Cx<'a>, i: &'a str, keyword: &str) -> PResult<'a, Vec<Assign>> {
    let mut what = format!("a symbol name after `{keyword}`");
    let mut i = i;
    let mut out = Vec::new();
    loop {
        let (rest, target) = name(cx, i, &what, true)?;
        let Some((_, rest)) = punct(cx, rest, "=").filter(|(at, _)| !at.starts_with("==")) else {
            return expected(cx, rest, &format!("`=` after `{}`", target.name));
        };
        let (rest, value) = expr(cx, rest, "=")?;
        out.push(Assign {
            name: target,
            value,
        });
        match punct(cx, rest, ",") {
            Some((_, next)) => i = next,
            None => return Ok((rest, out)),
        }
        what = "a symbol name after `,`".to_string();
    }
}
