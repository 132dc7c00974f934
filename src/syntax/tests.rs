//! Tests of the parsers: one-line "input ⇒ S-expression" data, errors with their spans, and files.

mod expr_tests;
mod file_tests;
mod prop_tests;

use super::ast::{By, Chain, Expr, ExprKind, Span};
use super::{parse_chain, parse_expr, ParseOptions, SyntaxError};
use std::fmt::Write;

/// A compact S-expression of `e`: `(* (/ m L) dy)`, `(- (^ x 2))`, `(call sin beta)`, `3/2000`.
pub(crate) fn sexpr(e: &Expr) -> String {
    let mut out = String::new();
    write_sexpr(&mut out, e);
    out
}

/// Appends the S-expression of `e` to `out`.
fn write_sexpr(out: &mut String, e: &Expr) {
    match &e.kind {
        ExprKind::Num(n) => {
            let _ = write!(out, "{n}");
        }
        ExprKind::Sym(s) => out.push_str(s),
        ExprKind::Pi => out.push_str("pi"),
        ExprKind::Neg(a) => {
            out.push_str("(- ");
            write_sexpr(out, a);
            out.push(')');
        }
        ExprKind::Bin(op, a, b) => {
            let op = match op {
                super::ast::BinOp::Add => "+",
                super::ast::BinOp::Sub => "-",
                super::ast::BinOp::Mul => "*",
                super::ast::BinOp::Div => "/",
                super::ast::BinOp::Pow => "^",
            };
            let _ = write!(out, "({op} ");
            write_sexpr(out, a);
            out.push(' ');
            write_sexpr(out, b);
            out.push(')');
        }
        ExprKind::Call(f, args) => {
            let _ = write!(out, "(call {}", f.name());
            for a in args {
                out.push(' ');
                write_sexpr(out, a);
            }
            out.push(')');
        }
    }
}

/// The S-expression of a chain: `(= a b [by ...])`, links in order.
pub(crate) fn chain_sexpr(c: &Chain) -> String {
    let mut out = sexpr(&c.first);
    for link in &c.links {
        let _ = write!(out, " {} {}", link.op, sexpr(&link.rhs));
        match &link.by {
            Some((By::Labels(ls), _)) => {
                let names: Vec<&str> = ls.iter().map(|l| l.name.as_str()).collect();
                let _ = write!(out, " by[{}]", names.join(","));
            }
            Some((By::Text(t), _)) => {
                let _ = write!(out, " by'{t}'");
            }
            None => {}
        }
    }
    out
}

/// Parses `src` as an expression with the default options.
pub(crate) fn expr(src: &str) -> Result<Expr, SyntaxError> {
    parse_expr(src, &ParseOptions::default())
}

/// Asserts that `src` parses to the S-expression `expected`.
#[track_caller]
pub(crate) fn check(src: &str, expected: &str) {
    match expr(src) {
        Ok(e) => assert_eq!(sexpr(&e), expected, "input: {src}"),
        Err(e) => panic!("input {src:?} failed: {e}"),
    }
}

/// Asserts that `src` parses as a chain to `expected`.
#[track_caller]
pub(crate) fn check_chain(src: &str, expected: &str) {
    match parse_chain(src, &ParseOptions::default()) {
        Ok(c) => assert_eq!(chain_sexpr(&c), expected, "input: {src}"),
        Err(e) => panic!("input {src:?} failed: {e}"),
    }
}

/// Asserts that `src` is a syntax error saying `message` at the bytes `span` of `src`.
#[track_caller]
pub(crate) fn check_err(src: &str, message: &str, span: &str) {
    match expr(src) {
        Ok(e) => panic!("input {src:?} parsed as {}", sexpr(&e)),
        Err(e) => assert_err(src, &e, message, span),
    }
}

/// Asserts that `e`, an error in `src`, says `message` at `span` (written `start..end`).
#[track_caller]
pub(crate) fn assert_err(src: &str, e: &SyntaxError, message: &str, span: &str) {
    let shown = format!("{}..{}", e.span.start, e.span.end);
    let text = src
        .get(e.span.start..e.span.end)
        .unwrap_or("<not a char boundary>");
    assert_eq!(
        (e.message.as_str(), shown.as_str()),
        (message, span),
        "input {src:?}, error at {text:?}"
    );
}

/// The text of `src` at `span`.
pub(crate) fn at(src: &str, span: Span) -> &str {
    src.get(span.start..span.end).unwrap_or("<bad span>")
}
