//! A syntax tree written back in rigor's own syntax (FORMAT.md §1), fully
//! parenthesised, so that reading the text gives the same tree.

use super::ast::{BinOp, Expr, ExprKind};
use num_traits::Signed;

/// The expression in rigor's own syntax.
pub fn source(e: &Expr) -> String {
    match &e.kind {
        ExprKind::Num(q) => {
            let n = q.numer().abs().to_string();
            let n = if q.is_negative() {
                format!("(-{n})")
            } else {
                n
            };
            if q.is_integer() {
                n
            } else {
                format!("({n}/{})", q.denom())
            }
        }
        ExprKind::Sym(n) => n.clone(),
        ExprKind::Pi => "pi".into(),
        ExprKind::Neg(a) => format!("(-({}))", source(a)),
        ExprKind::Bin(op, a, b) => {
            let op = match op {
                BinOp::Add => "+",
                BinOp::Sub => "-",
                BinOp::Mul => "*",
                BinOp::Div => "/",
                BinOp::Pow => "^",
            };
            format!("(({}) {op} ({}))", source(a), source(b))
        }
        ExprKind::Call(f, args) => {
            let args: Vec<String> = args.iter().map(source).collect();
            format!("{}({})", f.name(), args.join(", "))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::source;
    use crate::syntax::{parse_expr, ParseOptions};

    fn printed(text: &str) -> String {
        source(&parse_expr(text, &ParseOptions::default()).expect("reads"))
    }

    #[test]
    fn written_back_it_reads_as_the_same_tree() {
        // Read again, the text prints the same (a number's fraction reads as a division
        // of two integers, which prints as it was written).
        for t in [
            "m L^2/12 + m (L/2)^2",
            "-3/2 g/L",
            "x'' + 2 theta' - sin(beta)^2",
            "int(y^2 * m/L, y, -L/2, L/2)",
            "0.25 a - (-2)",
            "I_G + d^2 m",
        ] {
            let once = printed(t);
            let twice = printed(&once);
            assert_eq!(printed(&twice), twice, "{t} → {once} → {twice}");
        }
        assert_eq!(printed("a - b c"), "((a) - (((b) * (c))))");
        assert_eq!(printed("-x^2"), "(-(((x) ^ (2))))");
        assert_eq!(printed("0.25"), "(1/4)");
        assert_eq!(printed("2^(-1)"), "((2) ^ ((-(1))))");
        assert_eq!(printed("sqrt(a b)"), "sqrt(((a) * (b)))");
    }
}
