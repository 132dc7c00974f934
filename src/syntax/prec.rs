//! The precedence climber: every operator's precedence and associativity, in one place.
//!
//! `+ -` < `* /` and juxtaposition < unary sign < `^` (right-associative). The climber keeps
//! its operators on an explicit stack, so only parentheses and calls recurse; signs and
//! powers waiting on the stack still count towards the nesting limit.

use super::ast::{BinOp, ExprKind, Span};
use super::error::{Fail, PResult};
use super::expr::{fail, no_expression, node, postfixed, Tree};
use super::lex::{ident, is_reserved, ws, Cx};

/// An operator of the climber.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Op {
    /// A written binary operator.
    Infix(BinOp),
    /// Two factors side by side: `2 m`, `(a+b)(a-b)`, a product.
    Juxt,
    /// A sign in front of an operand: `-` (true) or `+` (false).
    Sign(bool),
}

impl Op {
    /// Binding strength.
    fn prec(self) -> u8 {
        match self {
            Op::Infix(BinOp::Add | BinOp::Sub) => 1,
            Op::Infix(BinOp::Mul | BinOp::Div) | Op::Juxt => 2,
            Op::Sign(_) => 3,
            Op::Infix(BinOp::Pow) => 4,
        }
    }

    /// Whether `self`, waiting on the stack, takes its operands before `next` is pushed:
    /// it binds tighter, or as tight and `next` groups to the left.
    fn applies_before(self, next: Op) -> bool {
        let right_assoc = next == Op::Infix(BinOp::Pow);
        self.prec() > next.prec() || (self.prec() == next.prec() && !right_assoc)
    }

    /// Whether the operator nests its operand (signs and powers count towards the depth).
    fn nests(self) -> bool {
        matches!(self, Op::Sign(_) | Op::Infix(BinOp::Pow))
    }
}

/// The written forms of the binary operators.
const INFIX: [(&str, BinOp); 9] = [
    ("+", BinOp::Add),
    ("-", BinOp::Sub),
    ("−", BinOp::Sub),
    ("*", BinOp::Mul),
    ("·", BinOp::Mul),
    ("⋅", BinOp::Mul),
    ("×", BinOp::Mul),
    ("/", BinOp::Div),
    ("^", BinOp::Pow),
];

/// The written forms of the signs.
const SIGNS: [(&str, bool); 3] = [("-", true), ("−", true), ("+", false)];

/// The operator after whitespace: the operator, its text, the input at it and after it.
/// A factor that could start a product (never `-` or `+`) on the same line is
/// juxtaposition, consuming nothing; a line break never multiplies.
fn infix<'a>(cx: &Cx<'a>, i: &'a str) -> Option<(Op, &'static str, &'a str, &'a str)> {
    let at = ws(cx, i);
    for (text, op) in INFIX {
        if let Some(rest) = at.strip_prefix(text) {
            return Some((Op::Infix(op), text, at, rest));
        }
    }
    let skipped = i.get(..i.len().saturating_sub(at.len())).unwrap_or("");
    let same_line = !skipped.contains('\n');
    (same_line && starts_factor(at)).then_some((Op::Juxt, "", at, at))
}

/// A sign at `at`: the operator, its text, and the input after it.
fn sign(at: &str) -> Option<(Op, &'static str, &str)> {
    SIGNS.iter().find_map(|&(text, negate)| {
        at.strip_prefix(text)
            .map(|rest| (Op::Sign(negate), text, rest))
    })
}

/// Whether `i` starts a primary: a number, a name that is not a reserved word, `(` or `√`.
fn starts_factor(i: &str) -> bool {
    let mut chars = i.chars();
    match chars.next() {
        Some(c) if c.is_ascii_digit() || c == '(' || c == '√' => true,
        Some('.') => chars.next().is_some_and(|c| c.is_ascii_digit()),
        _ => matches!(ident(i), Ok((_, id)) if !is_reserved(&id.name)),
    }
}

/// `expr = sign* operand (infix sign* operand)*`, with the tree built by precedence.
///
/// `depth` is the nesting of the parentheses and calls around the expression; `after`
/// names what came before it, for "expected an expression after `=`".
pub(crate) fn climb<'a>(cx: &Cx<'a>, i: &'a str, depth: usize, after: &str) -> PResult<'a, Tree> {
    let mut operands: Vec<Tree> = Vec::new();
    let mut ops: Vec<(Op, &'a str)> = Vec::new();
    let mut nested = 0usize;
    let (mut i, mut after) = (i, after);
    loop {
        let at = ws(cx, i);
        if let Some((op, text, rest)) = sign(at) {
            nested = nest(cx, at, depth, nested)?;
            ops.push((op, at));
            (i, after) = (rest, text);
            continue;
        }
        let (rest, operand) = match postfixed(cx, at, depth.saturating_add(nested)) {
            Err(nom::Err::Error(_)) => return Err(no_expression(cx, i, at, after)),
            other => other?,
        };
        operands.push(operand);
        i = rest;
        let Some((op, text, op_at, rest)) = infix(cx, i) else {
            break;
        };
        while let Some(&(top, top_at)) = ops.last().filter(|(top, _)| top.applies_before(op)) {
            ops.pop();
            if top.nests() {
                nested = nested.saturating_sub(1);
            }
            apply(cx, &mut operands, top, top_at)?;
        }
        if op.nests() {
            nested = nest(cx, op_at, depth, nested)?;
        }
        ops.push((op, op_at));
        (i, after) = (rest, text);
    }
    while let Some((top, top_at)) = ops.pop() {
        apply(cx, &mut operands, top, top_at)?;
    }
    match (operands.pop(), operands.is_empty()) {
        (Some(tree), true) => Ok((i, tree)),
        _ => Err(internal(i)),
    }
}

/// `nested + 1` for one more sign or power at `at`, unless that nests too deeply.
fn nest<'a>(cx: &Cx<'a>, at: &'a str, depth: usize, nested: usize) -> Result<usize, Fail<'a>> {
    let (_, deeper) = cx.enter(at, depth.saturating_add(nested))?;
    Ok(deeper.saturating_sub(depth))
}

/// Replaces the operands of `op` (written at `at`) on top of the stack with its node.
fn apply<'a>(cx: &Cx<'a>, operands: &mut Vec<Tree>, op: Op, at: &'a str) -> Result<(), Fail<'a>> {
    let (rhs, below) = operands.pop().ok_or_else(|| internal(at))?;
    let tree = match op {
        Op::Sign(negate) => {
            let span = Span::new(cx.pos(at), rhs.span.end);
            if negate {
                node(cx, at, ExprKind::Neg(rhs), span, below)?
            } else {
                let mut e = rhs;
                e.span = span;
                (e, below)
            }
        }
        Op::Infix(_) | Op::Juxt => {
            let (lhs, left) = operands.pop().ok_or_else(|| internal(at))?;
            let bin = if let Op::Infix(b) = op { b } else { BinOp::Mul };
            let span = lhs.span.to(rhs.span);
            node(cx, at, ExprKind::Bin(bin, lhs, rhs), span, left.max(below))?
        }
    };
    operands.push(tree);
    Ok(())
}

/// An operand stack out of step with its operators, which the climber never produces.
#[cold]
#[inline(never)]
fn internal(at: &str) -> Fail<'_> {
    fail(
        at,
        0,
        "internal error: the expression parser lost an operand".to_string(),
    )
}
