//! Derivation files (FORMAT.md §2): lines sorted into headings, prose with `$…$` math,
//! comments and statements with their continuation lines.

use super::ast::{File, Item, ProsePart, Span};
use super::chain::{chain_or_expr, ChainRules};
use super::ast::Chain;
use super::error::{ParseOptions, SyntaxError};
use super::lex::{end, ident, token_len, Cx};
use super::stmt::{statement, KEYWORDS};

/// Parses a whole derivation file; the first syntax error is returned.
///
/// Spans are byte offsets into `src`.
pub fn parse_file(src: &str, opts: &ParseOptions) -> Result<File, SyntaxError> {
    let stmt_cx = Cx::new(src, opts.max_depth, true, "the end of the statement");
    let math_cx = Cx::new(src, opts.max_depth, false, "the closing `$`");
    let mut items = Vec::new();
    // The statement being read: its first line and its last continuation line so far.
    let mut open: Option<(&str, &str)> = None;
    for line in lines(src) {
        let content = line.trim();
        if content.is_empty() || content.starts_with('%') {
            continue;
        }
        if line.starts_with([' ', '\t']) {
            match &mut open {
                Some((_, last)) => *last = line,
                None => return Err(orphan(&stmt_cx, content, items.last())),
            }
            continue;
        }
        if let Some((first, last)) = open.take() {
            items.push(Item::Stmt(statement(&stmt_cx, region(&stmt_cx, first, last))?));
        }
        if line.starts_with('#') {
            items.push(heading(&stmt_cx, content));
        } else if let Some(text) = content.strip_prefix('>') {
            items.push(prose(&math_cx, content, text)?);
        } else if matches!(ident(line), Ok((_, id)) if KEYWORDS.contains(&id.raw)) {
            open = Some((line, line));
        } else {
            let message = "expected a statement (symbols, time, unknowns, units, body, let, given, \
                 constraint, claim, use), a heading `#`, prose `>` or a comment `%`";
            return Err(SyntaxError::new(stmt_cx.span_len(line, token_len(line)), message));
        }
    }
    if let Some((first, last)) = open {
        items.push(Item::Stmt(statement(&stmt_cx, region(&stmt_cx, first, last))?));
    }
    Ok(File { items })
}

/// The lines of `src` without their `\n` or `\r\n`, as subslices of `src`.
fn lines(src: &str) -> impl Iterator<Item = &str> {
    src.split_inclusive('\n').map(|l| {
        let l = l.strip_suffix('\n').unwrap_or(l);
        l.strip_suffix('\r').unwrap_or(l)
    })
}

/// The text from the start of line `first` to the end of line `last`.
fn region<'a>(cx: &Cx<'a>, first: &'a str, last: &'a str) -> &'a str {
    let (start, end) = (cx.pos(first), cx.pos(last).saturating_add(last.len()));
    cx.base.get(start..end).unwrap_or(first)
}

/// The error for an indented line with no statement above it to continue.
fn orphan(cx: &Cx<'_>, content: &str, previous: Option<&Item>) -> SyntaxError {
    let message = match previous {
        Some(Item::Heading { .. }) | Some(Item::Prose { .. }) => {
            "an indented line continues a statement, but the line above is a heading or prose; \
             start statements at the beginning of the line"
        }
        _ => "an indented line continues a statement, but there is none above it; \
              start statements at the beginning of the line",
    };
    SyntaxError::new(cx.span_len(content, content.len()), message)
}

/// `heading = "#"+ text`: the level is the number of `#`.
fn heading(cx: &Cx<'_>, content: &str) -> Item {
    let text = content.trim_start_matches('#');
    let level = content.len().saturating_sub(text.len());
    Item::Heading { level, text: text.trim().to_string(), span: cx.span_len(content, content.len()) }
}

/// `prose = ">" (text | "$" math "$")*`; `content` is the trimmed line, `text` what follows `>`.
fn prose<'a>(cx: &Cx<'a>, content: &'a str, text: &'a str) -> Result<Item, SyntaxError> {
    let mut parts = Vec::new();
    let mut rest = text.trim_start();
    while let Some((before, after)) = rest.split_once('$') {
        if !before.is_empty() {
            parts.push(ProsePart::Text(before.to_string()));
        }
        let Some((math_src, next)) = after.split_once('$') else {
            let dollar = cx.pos(after).saturating_sub(1);
            return Err(SyntaxError::new(Span::new(dollar, dollar.saturating_add(1)), "unclosed `$`"));
        };
        parts.push(math(cx, math_src)?);
        rest = next;
    }
    if !rest.is_empty() {
        parts.push(ProsePart::Text(rest.to_string()));
    }
    Ok(Item::Prose { parts, span: cx.span_len(content, content.len()) })
}

/// `math = expr link*` between `$`s: a chain when it holds a relation, else an expression.
fn math<'a>(cx: &Cx<'a>, src: &'a str) -> Result<ProsePart, SyntaxError> {
    let rules = ChainRules { after: "$", by: false, where_: false };
    let parsed = chain_or_expr(cx, src, rules).and_then(|(rest, parts)| {
        end(cx, rest, "an operator, a relation or the closing `$`")?;
        Ok((rest, parts))
    });
    let (_, (first, links)) = parsed.map_err(|e| cx.error(e))?;
    Ok(if links.is_empty() { ProsePart::MathExpr(first) } else { ProsePart::Math(Chain { first, links }) })
}
