//! Derivation files (FORMAT.md §2): lines sorted into headings, prose with `$…$` math,
//! comments and statements with their continuation lines.

use super::ast::{Chain, File, Item, ProsePart, Span};
use super::chain::{chain_or_expr, ChainRules};
use super::error::{ParseOptions, SyntaxError};
use super::lex::{end, ident, token_len, Cx};
use super::stmt::{statement, KEYWORDS};

/// Parses a whole derivation file.
///
/// Spans are byte offsets into `src`.
///
/// # Errors
///
/// The first [`SyntaxError`] of the file.
pub fn parse_file(src: &str, opts: &ParseOptions) -> Result<File, SyntaxError> {
    let mut items = Vec::new();
    // The statement being read: the offset of its keyword and of the end of its last line so far.
    let mut open: Option<(usize, usize)> = None;
    for (start, line) in lines(src) {
        let content = line.trim();
        if content.is_empty() || content.starts_with('%') {
            continue;
        }
        let line_end = start.saturating_add(line.trim_end().len());
        if line.starts_with([' ', '\t']) {
            match &mut open {
                Some((_, last)) => *last = line_end,
                None => {
                    let span = Span::new(line_end.saturating_sub(content.len()), line_end);
                    return Err(orphan(span, items.last()));
                }
            }
            continue;
        }
        if let Some(region) = open.take() {
            items.push(Item::Stmt(stmt(src, opts, region)?));
        }
        if let Some(hashes) = line.strip_prefix('#') {
            items.push(heading(hashes, Span::new(start, line_end)));
        } else if let Some(text) = line.strip_prefix('>') {
            items.push(prose(
                src,
                opts,
                start.saturating_add(1),
                text,
                Span::new(start, line_end),
            )?);
        } else if matches!(ident(line), Ok((_, id)) if KEYWORDS.contains(&id.raw)) {
            open = Some((start, line_end));
        } else {
            let message =
                "expected a statement (symbols, time, unknowns, units, body, let, given, \
                 constraint, claim, use), a heading `#`, prose `>` or a comment `%`";
            let span = Span::new(start, start.saturating_add(token_len(line)));
            return Err(SyntaxError::new(span, message));
        }
    }
    if let Some(region) = open {
        items.push(Item::Stmt(stmt(src, opts, region)?));
    }
    Ok(File { items })
}

/// The lines of `src` without their `\n` or `\r\n`, each with its offset.
fn lines(src: &str) -> impl Iterator<Item = (usize, &str)> {
    src.split_inclusive('\n').scan(0usize, |offset, l| {
        let start = *offset;
        *offset = offset.saturating_add(l.len());
        let l = l.strip_suffix('\n').unwrap_or(l);
        Some((start, l.strip_suffix('\r').unwrap_or(l)))
    })
}

/// Parses the statement at `start..end` of `src`.
fn stmt(
    src: &str,
    opts: &ParseOptions,
    (start, end): (usize, usize),
) -> Result<super::ast::Stmt, SyntaxError> {
    let cx = Cx::new(src, end, opts, true, "the end of the statement");
    statement(&cx, src.get(start..end).unwrap_or(""))
}

/// The error for an indented line (at `span`) with no statement above it to continue.
fn orphan(span: Span, previous: Option<&Item>) -> SyntaxError {
    let message = match previous {
        Some(Item::Heading { .. } | Item::Prose { .. }) => {
            "an indented line continues a statement, but the line above is a heading or prose; \
             start statements at the beginning of the line"
        }
        _ => {
            "an indented line continues a statement, but there is none above it; \
              start statements at the beginning of the line"
        }
    };
    SyntaxError::new(span, message)
}

/// `heading = "#"+ text`: the level is the number of `#`; `hashes` follows the first `#`.
fn heading(hashes: &str, span: Span) -> Item {
    let text = hashes.trim_start_matches('#');
    let level = hashes.len().saturating_sub(text.len()).saturating_add(1);
    Item::Heading {
        level,
        text: text.trim().to_string(),
        span,
    }
}

/// `prose = ">" (text | "$" math "$")*`; `text` follows the `>` and starts at byte `start`.
fn prose(
    src: &str,
    opts: &ParseOptions,
    start: usize,
    text: &str,
    span: Span,
) -> Result<Item, SyntaxError> {
    let body = text.trim();
    let body_start = start.saturating_add(text.len().saturating_sub(text.trim_start().len()));
    let piece = |from: usize, to: usize| body.get(from..to).unwrap_or("");
    let mut parts = Vec::new();
    let mut dollars = body.match_indices('$').map(|(k, _)| k);
    let mut text_from = 0;
    while let Some(open) = dollars.next() {
        if open > text_from {
            parts.push(ProsePart::Text(piece(text_from, open).to_string()));
        }
        let Some(close) = dollars.next() else {
            let at = body_start.saturating_add(open);
            return Err(SyntaxError::new(
                Span::new(at, at.saturating_add(1)),
                "unclosed `$`",
            ));
        };
        let cx = Cx::new(
            src,
            body_start.saturating_add(close),
            opts,
            false,
            "the closing `$`",
        );
        parts.push(math(&cx, piece(open.saturating_add(1), close))?);
        text_from = close.saturating_add(1);
    }
    if text_from < body.len() {
        parts.push(ProsePart::Text(piece(text_from, body.len()).to_string()));
    }
    Ok(Item::Prose { parts, span })
}

/// `math = expr link*` between `$`s: a chain when it holds a relation, else an expression.
fn math<'a>(cx: &Cx<'a>, src: &'a str) -> Result<ProsePart, SyntaxError> {
    let rules = ChainRules {
        after: "$",
        by: false,
        where_: false,
    };
    let parsed = chain_or_expr(cx, src, rules).and_then(|(rest, parts)| {
        end(cx, rest, "an operator, a relation or the closing `$`")?;
        Ok((rest, parts))
    });
    let (_, (first, links)) = parsed.map_err(|e| cx.error(e))?;
    Ok(if links.is_empty() {
        ProsePart::MathExpr(first)
    } else {
        ProsePart::Math(Chain { first, links })
    })
}
