//! Laws over arbitrary input: the parsers never panic, and every span they report lies on
//! character boundaries of the input.

use crate::syntax::ast::{Expr, ExprKind, Item, ProsePart, StmtKind};
use crate::syntax::{parse_expr, parse_file, ParseOptions};
use proptest::prelude::*;

/// Pieces that exercise every rule, glued at random.
const PIECES: [&str; 48] = [
    "claim ",
    "given ",
    "symbols ",
    "units ",
    "body ",
    "let ",
    "use ",
    "time ",
    "unknowns ",
    "constraint ",
    "[a]",
    "[",
    "]",
    "(",
    ")",
    "x",
    "β",
    "θ_G",
    "x''",
    "2",
    "0.5",
    "1e-3",
    "e",
    "+",
    "-",
    "−",
    "*",
    "/",
    "^",
    "²",
    "√",
    "=",
    "<=",
    "~=",
    ",",
    " by ",
    " where ",
    " from ",
    " to ",
    "sin(",
    "int(",
    "$",
    "> ",
    "# ",
    "%",
    "\n",
    "\n  ",
    "\"f\"",
];

/// Whether `span` is a valid range of `src`.
fn valid(src: &str, start: usize, end: usize) -> bool {
    start <= end && src.get(start..end).is_some()
}

/// Checks the spans of `e` and everything under it.
fn spans_ok(src: &str, e: &Expr) -> bool {
    let mut stack = vec![e];
    while let Some(e) = stack.pop() {
        if !valid(src, e.span.start, e.span.end) {
            return false;
        }
        match &e.kind {
            ExprKind::Neg(a) => stack.push(a),
            ExprKind::Bin(_, a, b) => stack.extend([a.as_ref(), b.as_ref()]),
            ExprKind::Call(_, args) => stack.extend(args.iter()),
            _ => {}
        }
    }
    true
}

proptest! {
    #[test]
    fn files_never_panic(pieces in prop::collection::vec(prop::sample::select(PIECES.to_vec()), 0..40)) {
        let src = pieces.concat();
        match parse_file(&src, &ParseOptions::default()) {
            Err(e) => prop_assert!(valid(&src, e.span.start, e.span.end), "{e:?}"),
            Ok(file) => {
                for item in &file.items {
                    match item {
                        Item::Stmt(s) => {
                            prop_assert!(valid(&src, s.span.start, s.span.end));
                            if let StmtKind::Let { value, .. } = &s.kind {
                                prop_assert!(spans_ok(&src, value));
                            }
                        }
                        Item::Prose { parts, .. } => {
                            for p in parts {
                                if let ProsePart::MathExpr(e) = p {
                                    prop_assert!(spans_ok(&src, e));
                                }
                            }
                        }
                        Item::Heading { .. } => {}
                    }
                }
            }
        }
    }

    #[test]
    fn expressions_never_panic(src in "[ a-z0-9+\\-*/^().,=<>~!'βπ²√−·%$\\[\\]_\n]{0,40}") {
        match parse_expr(&src, &ParseOptions::default()) {
            Ok(e) => prop_assert!(spans_ok(&src, &e)),
            Err(e) => prop_assert!(valid(&src, e.span.start, e.span.end), "{e:?}"),
        }
    }
}
