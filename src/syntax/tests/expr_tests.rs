//! Expression and chain tests: precedence, numbers, names, calls, errors and limits.

use super::{assert_err, at, check, check_chain, check_err, expr};
use crate::syntax::ast::ExprKind;
use crate::syntax::{parse_chain, parse_expr, ParseOptions, SyntaxErrorKind};

#[test]
fn precedence() {
    check("a + b*c", "(+ a (* b c))");
    check("a*b + c", "(+ (* a b) c)");
    check("a - b - c", "(- (- a b) c)");
    check("a / b / c", "(/ (/ a b) c)");
    check("-x^2", "(- (^ x 2))");
    check("2^-1", "(^ 2 (- 1))");
    check("x^-2", "(^ x (- 2))");
    check("a^b^c", "(^ a (^ b c))");
    check("-a^-b^c", "(- (^ a (- (^ b c))))");
    check("a * -b", "(* a (- b))");
    check("a / -b c", "(* (/ a (- b)) c)");
    check("a - -b", "(- a (- b))");
    check("- - a", "(- (- a))");
    check("+a", "a");
    check("(a + b)^2", "(^ (+ a b) 2)");
    check("x^(1/2)", "(^ x (/ 1 2))");
    check("2^x y", "(* (^ 2 x) y)");
}

#[test]
fn juxtaposition() {
    check("m L^2/12", "(/ (* m (^ L 2)) 12)");
    check("m/L dy", "(* (/ m L) dy)");
    check("2m", "(* 2 m)");
    check("2 pi r dr", "(* (* (* 2 pi) r) dr)");
    check("(a+b)(a-b)", "(* (+ a b) (- a b))");
    check("m (L/2)^2", "(* m (^ (/ L 2) 2))");
    check("m g cos(beta)", "(* (* m g) (call cos beta))");
    check("a -b", "(- a b)");
    check("a +b", "(+ a b)");
    check("mg", "mg");
    check("2 3", "(* 2 3)");
    check("-a b", "(* (- a) b)");
    check("a b^2 c", "(* (* a (^ b 2)) c)");
    check("x_1 y_2", "(* x_1 y_2)");
    check("a\n + b", "(+ a b)");
    check_err(
        "a\n b",
        "expected an operator or the end of the expression, found `b`",
        "3..4",
    );
}

#[test]
fn numbers() {
    check("12", "12");
    check("0.71", "71/100");
    check("1.5e-3", "3/2000");
    check("2e5", "200000");
    check("2E+2", "200");
    check(".5", "1/2");
    check("2e", "(* 2 e)");
    check("2e-x", "(- (* 2 e) x)");
    check("3ex", "(* 3 ex)");
    check("1.50", "3/2");
    check("007", "7");
    check("2.5m", "(* 5/2 m)");
    // Either side of the machine-word fast path (18 digits) reads the same way.
    check("999999999999999999", "999999999999999999");
    check("1000000000000000000", "1000000000000000000");
    check("12345678901234567890", "12345678901234567890");
    check("99999999999999999.9", "999999999999999999/10");
    check("0.000000000000000001", "1/1000000000000000000");
    match expr("0.71").map(|e| e.kind) {
        Ok(ExprKind::Num(n)) => {
            assert_eq!(n, num_rational::BigRational::new(71.into(), 100.into()))
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn names_and_unicode() {
    check("x''", "x''");
    check("theta' + x''", "(+ theta' x'')");
    check("I_G", "I_G");
    check("β", "beta");
    check("θ_G", "theta_G");
    check("π r²", "(* pi (^ r 2))");
    check("pi", "pi");
    check("pi_1", "pi_1");
    check("a · b × c", "(* (* a b) c)");
    check("a − b", "(- a b)");
    check("−x", "(- x)");
    check("x³ y", "(* (^ x 3) y)");
    check("(a+b)²", "(^ (+ a b) 2)");
    check("√(a+b)", "(call sqrt (+ a b))");
    check("√2 x", "(* (call sqrt 2) x)");
    check("μ m g", "(* (* mu m) g)");
    check("ω² r", "(* (^ omega 2) r)");
    check("Δx", "Deltax");
}

#[test]
fn calls() {
    check("sin(beta)", "(call sin beta)");
    check("sqrt(x)^2", "(^ (call sqrt x) 2)");
    check(
        "int(y^2 m/L, y, -L/2, L/2)",
        "(call int (/ (* (^ y 2) m) L) y (/ (- L) 2) (/ L 2))",
    );
    check("int(y^2, rod)", "(call int (^ y 2) rod)");
    check("diff(x, t, 2)", "(call diff x t 2)");
    check("eval(F, x, 0, L)", "(call eval F x 0 L)");
    check("subs(f, x, 2 a)", "(call subs f x (* 2 a))");
    check(
        "exp(-x) ln(abs(x))",
        "(* (call exp (- x)) (call ln (call abs x)))",
    );
    check("diff(int(f, x), x)", "(call diff (call int f x) x)");
    check("sin(a)cos(b)", "(* (call sin a) (call cos b))");
}

#[test]
fn relations_and_chains() {
    check_chain("a = b", "a = b");
    check_chain("a != b", "a != b");
    check_chain("a ≠ b ≤ c ≥ d ≈ e", "a != b <= c >= d ~= e");
    check_chain("a < b <= c > d >= e ~= f", "a < b <= c > d >= e ~= f");
    check_chain("k_G ~= 0.71 R", "k_G ~= (* 71/100 R)");
    check_chain(" x = -theta R ", "x = (* (- theta) R)");
}

#[test]
fn chain_errors() {
    let opts = ParseOptions::default();
    let src = "a + b";
    let e = parse_chain(src, &opts).expect_err("no relation");
    assert_err(src, &e, "expected an operator or a relation (`=`, `!=`, `<`, `<=`, `>`, `>=`, `~=`), found the end of the input", "5..5");
    let src = "a = ";
    let e = parse_chain(src, &opts).expect_err("no rhs");
    assert_err(src, &e, "expected an expression after `=`", "3..3");
    let src = "a = b by [x]";
    let e = parse_chain(src, &opts).expect_err("no by in plain chains");
    assert_err(
        src,
        &e,
        "expected an operator, a relation or the end of the input, found `by`",
        "6..8",
    );
}

#[test]
fn errors() {
    check_err("a +", "expected an expression after `+`", "3..3");
    check_err(
        "a + * b",
        "expected an expression after `+`, found `*`",
        "4..5",
    );
    check_err("", "expected an expression", "0..0");
    check_err("  ", "expected an expression", "0..0");
    check_err("(a + b", "unclosed `(`", "0..1");
    check_err("(a + b]", "expected `)`, found `]`", "6..7");
    check_err("a + b)", "unmatched `)`", "5..6");
    check_err(
        "f(x)",
        "unknown function f; write f*(x) or f (x) for a product",
        "0..1",
    );
    check_err(
        "2 k_G(x)",
        "unknown function k_G; write k_G*(x) or k_G (x) for a product",
        "2..5",
    );
    check_err(
        "sin x",
        "`sin` needs its argument in parentheses: sin(…)",
        "0..3",
    );
    check_err(
        "tan (x)",
        "`tan` needs its argument in parentheses: tan(…)",
        "0..3",
    );
    check_err(
        "sin^2(x)",
        "`sin` needs its argument in parentheses: sin(…); write sin(x)^2 for a power of sin",
        "0..3",
    );
    check_err("sin(a, b)", "`sin` takes 1 argument, found 2", "0..9");
    check_err(
        "1 + int(f, x, a)",
        "`int` takes 2 or 4 arguments: int(f, x), int(f, B) or int(f, x, a, b), found 3",
        "4..16",
    );
    check_err(
        "diff(f)",
        "`diff` takes 2 or 3 arguments: diff(f, x) or diff(f, x, n), found 1",
        "0..7",
    );
    check_err(
        "eval(F, x, a)",
        "`eval` takes 4 arguments: eval(F, x, a, b), found 3",
        "0..13",
    );
    check_err(
        "subs(f, x)",
        "`subs` takes 3 arguments: subs(f, x, v), found 2",
        "0..10",
    );
    check_err(
        "sin()",
        "expected an expression after `(`, found `)`",
        "4..5",
    );
    check_err(
        "int(f, )",
        "expected an expression after `,`, found `)`",
        "7..8",
    );
    check_err("int(f, x", "unclosed `(`", "3..4");
    check_err(
        "int(f x]",
        "expected `,` or `)` in the arguments of `int`, found `]`",
        "7..8",
    );
    check_err(
        "a by b",
        "expected an operator or the end of the expression, found `by`",
        "2..4",
    );
    check_err(
        "x = 1",
        "expected an operator or the end of the expression, found `=`",
        "2..3",
    );
    check_err("to", "expected an expression, found `to`", "0..2");
    check_err(
        "2.",
        "expected an operator or the end of the expression, found `.`",
        "1..2",
    );
    check_err("x^", "expected an expression after `^`", "2..2");
    check_err("-", "expected an expression after `-`", "1..1");
    check_err("√", "expected `(` after `√`: √(…)", "0..3");
    check_err(
        "a ** b",
        "expected an expression after `*`, found `*`",
        "3..4",
    );
    check_err(
        "pi(2)",
        "unknown function pi; write pi*(x) or pi (x) for a product",
        "0..2",
    );
    check_err(
        "1e99999",
        "number out of range: powers of ten go up to 1e10000",
        "0..7",
    );
    check_err(
        "2 1e-99999",
        "number out of range: powers of ten go up to 1e10000",
        "2..10",
    );
    check_err(
        &"9".repeat(10_001),
        "number too long: at most 10000 digits",
        "0..10001",
    );
    check_err(
        "a # b",
        "expected an operator or the end of the expression, found `#`",
        "2..3",
    );
    check_err(
        "a % b",
        "expected an operator or the end of the expression, found `%`",
        "2..3",
    );
}

#[test]
fn spans() {
    let src = "  m g sin(beta) + (a - b)";
    let e = expr(src).expect("parses");
    assert_eq!(at(src, e.span), "m g sin(beta) + (a - b)");
    let ExprKind::Bin(_, lhs, rhs) = &e.kind else {
        panic!("{e:?}")
    };
    assert_eq!(at(src, lhs.span), "m g sin(beta)");
    assert_eq!(at(src, rhs.span), "(a - b)");
    let ExprKind::Bin(_, _, call) = &lhs.kind else {
        panic!("{lhs:?}")
    };
    assert_eq!(at(src, call.span), "sin(beta)");
    let src = "-x^2";
    let e = expr(src).expect("parses");
    let ExprKind::Neg(p) = &e.kind else {
        panic!("{e:?}")
    };
    assert_eq!((at(src, e.span), at(src, p.span)), ("-x^2", "x^2"));
    let src = "β² + √x";
    let e = expr(src).expect("parses");
    let ExprKind::Bin(_, a, b) = &e.kind else {
        panic!("{e:?}")
    };
    assert_eq!((at(src, a.span), at(src, b.span)), ("β²", "√x"));
    let src = "a = b = c";
    let c = parse_chain(src, &ParseOptions::default()).expect("parses");
    let spans: Vec<&str> = c.links.iter().map(|l| at(src, l.span)).collect();
    assert_eq!(spans, ["= b", "= c"]);
}

#[test]
fn nesting_limit() {
    let deep = "(".repeat(1_000_000);
    let e = expr(&deep).expect_err("too deep");
    assert_eq!(e.kind, SyntaxErrorKind::NestingLimit);
    assert_eq!((e.span.start, e.span.end), (200, 201));
    let ok = format!("{}x{}", "(".repeat(200), ")".repeat(200));
    check(&ok, "x");
    let too_deep = format!("{}x{}", "(".repeat(201), ")".repeat(201));
    assert_eq!(
        expr(&too_deep).map_err(|e| e.kind),
        Err(SyntaxErrorKind::NestingLimit)
    );
    // each kind of nesting counts
    for unit in ["-", "sin(", "√", "2^"] {
        let src = unit.repeat(1_000_000);
        let e = expr(&src).expect_err("too deep");
        assert_eq!(e.kind, SyntaxErrorKind::NestingLimit, "{unit}");
    }
    assert!(expr(&format!("{}x", "-".repeat(200))).is_ok());
    assert!(expr(&format!("{}x", "x^".repeat(200))).is_ok());
    let small = ParseOptions { max_depth: 3 };
    assert!(parse_expr("((x))", &small).is_ok());
    let e = parse_expr("(((-x)))", &small).expect_err("too deep");
    assert_eq!((e.kind, e.span.start), (SyntaxErrorKind::NestingLimit, 3));
    // The message says the limit in force.
    assert!(e.message.contains(" 3 levels"), "{}", e.message);
}

#[test]
fn long_flat_expressions_are_bounded() {
    let sum = vec!["x"; 1000].join(" + ");
    assert!(expr(&sum).is_ok());
    let sum = vec!["x"; 1_000_000].join(" + ");
    let e = expr(&sum).expect_err("too long");
    assert_eq!(e.kind, SyntaxErrorKind::TooLarge, "{}", e.message);
    let product = "x ".repeat(1_000_000);
    assert_eq!(
        expr(&product).map_err(|e| e.kind),
        Err(SyntaxErrorKind::TooLarge)
    );
    let squares = format!("x{}", "²".repeat(100_000));
    assert!(expr(&squares).is_err());
}

#[test]
fn other_syntax_errors_are_of_the_kind_other() {
    for src in ["a +", "(a", "a )", "sin(", "2 = "] {
        let e = expr(src).expect_err(src);
        assert_eq!(e.kind, SyntaxErrorKind::Other, "{src}: {}", e.message);
    }
}
