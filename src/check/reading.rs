//! Readings a writer may not have meant: `3 g/2L` is read as (3 g/2) L, because
//! juxtaposition binds no tighter than `/` (FORMAT.md §1). When the factor after the
//! `/` is glued to the next one, the writer very likely meant them together below the
//! line, so rigor says how it read the expression (warning W0101) and how to write
//! the other reading.

use crate::diag::Code;
use crate::diag::{Diagnostic, Severity};
use crate::syntax::ast::{BinOp, BodyDef, Expr, ExprKind, Func, Reading, StmtKind};

/// Every expression written in a statement.
pub(super) fn exprs_of(kind: &StmtKind) -> Vec<&Expr> {
    fn chain(c: &crate::syntax::ast::Chain) -> Vec<&Expr> {
        c.exprs().collect()
    }
    match kind {
        StmtKind::Range { lo, hi, .. } => vec![lo, hi],
        StmtKind::Let { value, .. } => vec![value],
        StmtKind::Given { chain: c, .. } | StmtKind::Constraint { chain: c, .. } => chain(c),
        StmtKind::Claim {
            chain: c, where_, ..
        } => {
            let mut v = chain(c);
            v.extend(where_.iter().map(|a| &a.value));
            v
        }
        StmtKind::Use { with, .. } => with.iter().map(|a| &a.value).collect(),
        StmtKind::Body {
            def: BodyDef::Concrete { dm, ranges },
            ..
        } => {
            let mut v = vec![dm];
            for r in ranges {
                v.push(&r.from);
                v.push(&r.to);
            }
            v
        }
        StmtKind::Body {
            def: BodyDef::Abstract { mass, .. },
            ..
        } => vec![mass],
        _ => Vec::new(),
    }
}

/// Every expression written in a statement, to change.
fn exprs_of_mut(kind: &mut StmtKind) -> Vec<&mut Expr> {
    fn chain(c: &mut crate::syntax::ast::Chain) -> Vec<&mut Expr> {
        std::iter::once(&mut c.first)
            .chain(c.links.iter_mut().map(|l| &mut l.rhs))
            .collect()
    }
    match kind {
        StmtKind::Range { lo, hi, .. } => vec![lo, hi],
        StmtKind::Let { value, .. } => vec![value],
        StmtKind::Given { chain: c, .. } | StmtKind::Constraint { chain: c, .. } => chain(c),
        StmtKind::Claim {
            chain: c, where_, ..
        } => {
            let mut v = chain(c);
            v.extend(where_.iter_mut().map(|a| &mut a.value));
            v
        }
        StmtKind::Use { with, .. } => with.iter_mut().map(|a| &mut a.value).collect(),
        StmtKind::Body {
            def: BodyDef::Concrete { dm, ranges },
            ..
        } => {
            let mut v = vec![dm];
            for r in ranges {
                v.push(&mut r.from);
                v.push(&mut r.to);
            }
            v
        }
        StmtKind::Body {
            def: BodyDef::Abstract { mass, .. },
            ..
        } => vec![mass],
        _ => Vec::new(),
    }
}

/// Reads LaTeX's `e^{x}` in a statement as the declarations say: Euler's number only
/// while no `e` is declared; where `e` is declared (a coefficient of restitution), it
/// is a power of that symbol (`e^2 = e \cdot e`). The parser, which does not know the
/// declarations, marks `exp(x)` read from `e^{x}` with [`Reading::EulerE`].
pub(super) fn euler_e_as_declared(kind: &mut StmtKind, e_declared: bool) {
    if !e_declared {
        return;
    }
    for e in exprs_of_mut(kind) {
        power_of_e(e);
    }
}

/// `exp(x)` read from `e^{x}` turned back into the power `e^x` of the symbol `e`.
fn power_of_e(e: &mut Expr) {
    match &mut e.kind {
        ExprKind::Num(_) | ExprKind::Sym(_) | ExprKind::Pi => {}
        ExprKind::Neg(a) => power_of_e(a),
        ExprKind::Bin(_, a, b) => {
            power_of_e(a);
            power_of_e(b);
        }
        ExprKind::Call(f, args) => {
            args.iter_mut().for_each(power_of_e);
            if *f == Func::Exp && e.reading == Reading::EulerE && args.len() == 1 {
                let x = args.remove(0);
                // `e` is the first byte of the span: `e^{x}` as written.
                let at = crate::syntax::ast::Span::new(e.span.start, e.span.start + 1);
                let base = Expr::new(ExprKind::Sym("e".into()), at);
                e.kind = ExprKind::Bin(BinOp::Pow, Box::new(base), Box::new(x));
                e.reading = Reading::AsWritten;
            }
        }
    }
}

/// A warning for each `a/b c` in `e` written with `b` and `c` glued together (`g/2L`).
pub(super) fn glued_after_slash(e: &Expr, src: &str, out: &mut Vec<Diagnostic>) {
    match &e.kind {
        ExprKind::Bin(op, l, r) => {
            if *op == BinOp::Mul {
                if let Some(d) = glued(l, r, src) {
                    out.push(d);
                }
            }
            glued_after_slash(l, src, out);
            glued_after_slash(r, src, out);
        }
        ExprKind::Neg(x) => glued_after_slash(x, src, out),
        ExprKind::Call(_, args) => args.iter().for_each(|a| glued_after_slash(a, src, out)),
        ExprKind::Num(_) | ExprKind::Sym(_) | ExprKind::Pi => {}
    }
}

/// `l r` where `l` is `a/b`, written `a/b` with a plain `/` and `r` glued to `b`.
fn glued(l: &Expr, r: &Expr, src: &str) -> Option<Diagnostic> {
    let ExprKind::Bin(BinOp::Div, num, den) = &l.kind else {
        return None;
    };
    // The denominator is a number or a symbol written straight after the `/`
    // (not `\frac`, not a parenthesised group) …
    if !matches!(den.kind, ExprKind::Num(_) | ExprKind::Sym(_)) {
        return None;
    }
    if src.get(num.span.end..den.span.start)?.trim() != "/" {
        return None;
    }
    // … and the next factor starts at once after it, with a letter: `2L`, `2 L` is not
    // glued (`1/2 m v^2` is the usual way to write m v²/2).
    if den.span.end != r.span.start || !src.get(r.span.start..)?.starts_with(char::is_alphabetic) {
        return None;
    }
    let written = src.get(l.span.start..r.span.end)?;
    let a = src.get(num.span.start..num.span.end)?;
    let b = src.get(den.span.start..den.span.end)?;
    let c = src.get(r.span.start..r.span.end)?;
    let span = crate::syntax::ast::Span::new(den.span.start, r.span.end);
    let mut d = Diagnostic::error(
        Code::Reading,
        format!("`{written}` is read as ({a}/{b}) {c}, with {c} above the line"),
        span,
        format!("if {b} {c} is the denominator, write `{a}/({b} {c})`"),
    );
    d.severity = Severity::Warning;
    Some(d.note(format!(
        "juxtaposition binds no tighter than `/`: write `{a} {c}/{b}` for the reading rigor takes"
    )))
}
