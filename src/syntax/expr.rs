//! Expressions (FORMAT.md §1): the entry points, and the operands of the precedence climber
//! (numbers, names, `pi`, parentheses, calls, `√`, postfix `²` `³`).

use super::ast::{BinOp, Chain, Expr, ExprKind, Func, Span};
use super::chain::{chain_or_expr, ChainRules};
use super::error::{no_match, Fail, PError, PResult, ParseOptions, SyntaxError};
use super::lex::{describe, end, expected, ident, is_reserved, number, token_len, ws, Cx, Ident};
use super::prec::climb;
use num_rational::BigRational;

/// Parses `src` as one expression (surrounding whitespace allowed).
///
/// Spans are byte offsets into `src`.
///
/// # Errors
///
/// A [`SyntaxError`] saying what was expected where, when `src` is not exactly one
/// expression or nests deeper than `opts.max_depth`.
pub fn parse_expr(src: &str, opts: &ParseOptions) -> Result<Expr, SyntaxError> {
    let cx = Cx::new(src, src.len(), opts, false, "the end of the input");
    let parsed = expr(&cx, src, "").and_then(|(rest, e)| {
        let (rest, ()) = end(&cx, rest, "an operator or the end of the expression")?;
        Ok((rest, e))
    });
    parsed.map(|(_, e)| e).map_err(|e| cx.error(e))
}

/// Parses `src` as a relation or chain of relations, `expr (relop expr)+`.
///
/// Spans are byte offsets into `src`.
///
/// # Errors
///
/// A [`SyntaxError`] as for [`parse_expr`], also when there is no relation.
pub fn parse_chain(src: &str, opts: &ParseOptions) -> Result<Chain, SyntaxError> {
    let cx = Cx::new(src, src.len(), opts, false, "the end of the input");
    let rules = ChainRules {
        after: "",
        by: false,
        where_: false,
    };
    let parsed = chain_or_expr(&cx, src, rules).and_then(|(rest, (first, links))| {
        if links.is_empty() {
            return expected(
                &cx,
                rest,
                "an operator or a relation (`=`, `!=`, `<`, `<=`, `>`, `>=`, `~=`)",
            );
        }
        let (rest, ()) = end(&cx, rest, "an operator, a relation or the end of the input")?;
        Ok((rest, Chain { first, links }))
    });
    parsed.map(|(_, c)| c).map_err(|e| cx.error(e))
}

/// `expr`: a whole expression at the start of `i` (after whitespace); `after` names what
/// came before it for the "expected an expression after `=`" message.
pub(crate) fn expr<'a>(cx: &Cx<'a>, i: &'a str, after: &str) -> PResult<'a, Expr> {
    let (rest, (e, _height)) = climb(cx, i, 0, after)?;
    Ok((rest, *e))
}

/// An expression with the height of its tree; the height is bounded like the nesting
/// depth so that no later recursive pass over the tree (or its drop) can overflow.
/// Boxed, because the box is what the parent node holds and because small results keep
/// the frames of the recursive parsers small.
pub(crate) type Tree = (Box<Expr>, usize);

/// A node over children of height `below`, unless the tree gets too tall (error at `at`).
pub(crate) fn node<'a>(
    cx: &Cx<'a>,
    at: &'a str,
    kind: ExprKind,
    span: Span,
    below: usize,
) -> Result<Tree, Fail<'a>> {
    let height = below.saturating_add(1);
    if height > cx.max_height {
        return Err(too_large(cx, at));
    }
    Ok((Box::new(Expr::new(kind, span)), height))
}

/// "expression too large" at `at`.
#[cold]
#[inline(never)]
fn too_large<'a>(cx: &Cx<'a>, at: &'a str) -> Fail<'a> {
    let message = format!(
        "expression too large: more than {} operations inside one another; split it with `let`",
        cx.max_height
    );
    nom::Err::Failure(PError {
        at,
        len: token_len(at).max(1),
        message: Some(message),
        kind: super::error::SyntaxErrorKind::TooLarge,
    })
}

/// "expected an expression after `…`" at `at`. Errors are built out of line, keeping the
/// frames of the recursive parsers small.
#[cold]
#[inline(never)]
/// At the end of the region the error sits where the expression should start, `i`.
pub(crate) fn no_expression<'a>(cx: &Cx<'a>, i: &'a str, at: &'a str, after: &str) -> Fail<'a> {
    let what = if after.is_empty() {
        "expected an expression".to_string()
    } else {
        format!("expected an expression after `{after}`")
    };
    if at.is_empty() {
        return fail(i, 0, what);
    }
    fail(
        at,
        token_len(at),
        format!("{what}, found {}", describe(cx, at)),
    )
}

/// A committed failure, as a value.
#[cold]
#[inline(never)]
pub(crate) fn fail(at: &str, len: usize, message: String) -> Fail<'_> {
    nom::Err::Failure(PError {
        at,
        len,
        message: Some(message),
        kind: super::error::SyntaxErrorKind::Other,
    })
}

/// `postfixed = primary ("²" | "³")*`.
pub(crate) fn postfixed<'a>(cx: &Cx<'a>, at: &'a str, depth: usize) -> PResult<'a, Tree> {
    let (mut i, mut tree) = primary(cx, at, depth)?;
    loop {
        let (power, c) = match i.chars().next() {
            Some(c @ '²') => (2u8, c),
            Some(c @ '³') => (3u8, c),
            _ => return Ok((i, tree)),
        };
        let rest = i.get(c.len_utf8()..).unwrap_or("");
        let exponent = Expr::new(
            ExprKind::Num(BigRational::from_integer(power.into())),
            cx.span(i, rest),
        );
        let span = tree.0.span.to(exponent.span);
        let kind = ExprKind::Bin(BinOp::Pow, tree.0, Box::new(exponent));
        tree = node(cx, i, kind, span, tree.1)?;
        i = rest;
    }
}

/// `primary = number | "(" expr ")" | "√" primary | name | call`; `at` is past whitespace.
/// Anything else is a recoverable no-match, so the caller can say what it expected.
fn primary<'a>(cx: &Cx<'a>, at: &'a str, depth: usize) -> PResult<'a, Tree> {
    match number(at) {
        Ok((rest, n)) => {
            return Ok((
                rest,
                (Box::new(Expr::new(ExprKind::Num(n), cx.span(at, rest))), 1),
            ))
        }
        Err(nom::Err::Error(_)) => {}
        Err(e) => return Err(e),
    }
    if let Some(inner) = at.strip_prefix('(') {
        return group(cx, at, inner, depth);
    }
    if let Some(rest) = at.strip_prefix('√') {
        return root(cx, at, rest, depth);
    }
    match ident(at) {
        Ok((rest, id)) => name(cx, at, rest, id, depth),
        Err(_) => no_match(at),
    }
}

/// `group = "(" expr ")"`; the node keeps the inner kind and spans the parentheses.
fn group<'a>(cx: &Cx<'a>, open: &'a str, inner: &'a str, depth: usize) -> PResult<'a, Tree> {
    let (_, deeper) = cx.enter(open, depth)?;
    let (rest, (mut e, height)) = climb(cx, inner, deeper, "(")?;
    let rest = close(cx, open, rest)?;
    e.span = cx.span(open, rest);
    Ok((rest, (e, height)))
}

/// The `)` matching the `(` at `open`: "unclosed `(`" at the end, "expected `)`" elsewhere.
fn close<'a>(cx: &Cx<'a>, open: &'a str, i: &'a str) -> Result<&'a str, Fail<'a>> {
    let at = ws(cx, i);
    at.strip_prefix(')').ok_or_else(|| unclosed(cx, open, at))
}

/// The error when the group opened at `open` goes on with `at` instead of `)`.
#[cold]
#[inline(never)]
fn unclosed<'a>(cx: &Cx<'a>, open: &'a str, at: &'a str) -> Fail<'a> {
    if at.is_empty() {
        fail(open, 1, "unclosed `(`".to_string())
    } else {
        fail(
            at,
            token_len(at),
            format!("expected `)`, found {}", describe(cx, at)),
        )
    }
}

/// `root = "√" primary`: `√(a+b)`, `√2`, `√x` are `sqrt(…)`.
fn root<'a>(cx: &Cx<'a>, at: &'a str, rest: &'a str, depth: usize) -> PResult<'a, Tree> {
    let (_, deeper) = cx.enter(at, depth)?;
    let (rest, (arg, height)) = match primary(cx, rest, deeper) {
        Err(nom::Err::Error(_)) => {
            return Err(fail(
                at,
                '√'.len_utf8(),
                "expected `(` after `√`: √(…)".to_string(),
            ))
        }
        other => other?,
    };
    let span = Span::new(cx.pos(at), arg.span.end);
    let tree = node(cx, at, ExprKind::Call(Func::Sqrt, vec![*arg]), span, height)?;
    Ok((rest, tree))
}

/// `name`: a symbol, `pi`, or a function call when a known function touches its `(`.
fn name<'a>(
    cx: &Cx<'a>,
    at: &'a str,
    rest: &'a str,
    id: Ident<'a>,
    depth: usize,
) -> PResult<'a, Tree> {
    if is_reserved(&id.name) {
        return no_match(at);
    }
    let len = id.raw.len();
    let touches_paren = rest.starts_with('(');
    if let Some(f) = Func::from_name(&id.name) {
        if touches_paren {
            return call(cx, at, f, rest, depth);
        }
        return Err(bare_function(at, rest, id.raw));
    }
    if touches_paren {
        let message = format!(
            "unknown function {0}; write {0}*(x) or {0} (x) for a product",
            id.raw
        );
        return Err(fail(at, len, message));
    }
    let kind = if id.name == "pi" {
        ExprKind::Pi
    } else {
        ExprKind::Sym(id.name)
    };
    Ok((rest, (Box::new(Expr::new(kind, cx.span(at, rest))), 1)))
}

/// "`sin` needs its argument in parentheses" for the function name `raw` at `at`.
#[cold]
#[inline(never)]
fn bare_function<'a>(at: &'a str, rest: &'a str, raw: &str) -> Fail<'a> {
    let hint = if rest.starts_with(['^', '²', '³']) {
        format!("; write {raw}(x)^2 for a power of {raw}")
    } else {
        String::new()
    };
    fail(
        at,
        raw.len(),
        format!("`{raw}` needs its argument in parentheses: {raw}(…){hint}"),
    )
}

/// `call = func "(" expr ("," expr)* ")"`, with the number of arguments checked.
fn call<'a>(cx: &Cx<'a>, at: &'a str, f: Func, open: &'a str, depth: usize) -> PResult<'a, Tree> {
    let (_, deeper) = cx.enter(open, depth)?;
    let mut args = Vec::new();
    let mut height = 0;
    let mut i = open.get(1..).unwrap_or("");
    let mut after = "(";
    loop {
        let (rest, (arg, h)) = climb(cx, i, deeper, after)?;
        args.push(*arg);
        height = height.max(h);
        let next = ws(cx, rest);
        if let Some(rest) = next.strip_prefix(',') {
            (i, after) = (rest, ",");
        } else if let Some(rest) = next.strip_prefix(')') {
            i = rest;
            break;
        } else {
            return Err(bad_argument_list(cx, f, open, next));
        }
    }
    let span = cx.span(at, i);
    if !arity_ok(f, args.len()) {
        let message = format!("`{}` takes {}, found {}", f.name(), arity(f), args.len());
        return Err(fail(at, span.end.saturating_sub(span.start), message));
    }
    let tree = node(cx, at, ExprKind::Call(f, args), span, height)?;
    Ok((i, tree))
}

/// The error when the arguments of `f`, opened at `open`, go on with `next`.
#[cold]
#[inline(never)]
fn bad_argument_list<'a>(cx: &Cx<'a>, f: Func, open: &'a str, next: &'a str) -> Fail<'a> {
    if next.is_empty() {
        return fail(open, 1, "unclosed `(`".to_string());
    }
    let message = format!(
        "expected `,` or `)` in the arguments of `{}`, found {}",
        f.name(),
        describe(cx, next)
    );
    fail(next, token_len(next), message)
}

/// Whether `f` accepts `n` arguments.
fn arity_ok(f: Func, n: usize) -> bool {
    match f {
        Func::Int => n == 2 || n == 4,
        Func::Diff => n == 2 || n == 3,
        Func::Eval => n == 4,
        Func::Subs => n == 3,
        _ => n == 1,
    }
}

/// The accepted argument counts of `f`, for messages.
fn arity(f: Func) -> &'static str {
    match f {
        Func::Int => "2 or 4 arguments: int(f, x), int(f, B) or int(f, x, a, b)",
        Func::Diff => "2 or 3 arguments: diff(f, x) or diff(f, x, n)",
        Func::Eval => "4 arguments: eval(F, x, a, b)",
        Func::Subs => "3 arguments: subs(f, x, v)",
        _ => "1 argument",
    }
}
