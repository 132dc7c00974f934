//! Expression and chain tests: precedence, numbers, names, calls, errors and limits.

use super::{at, check, check_chain, check_err, expr};
use crate::syntax::ast::ExprKind;
use crate::syntax::{parse_chain, parse_expr, ParseOptions};

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
    match expr("0.71").map(|e| e.kind) {
        Ok(ExprKind::Num(n)) => assert_eq!(n, num_rational::BigRational::new(71.into(), 100.into())),
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
    check("int(y^2 m/L, y, -L/2, L/2)", "(call int (* (^ y 2) (/ m L)) y (- (/ L 2)) (/ L 2))");
    check("int(y^2, rod)", "(call int (^ y 2) rod)");
    check("diff(x, t, 2)", "(call diff x t 2)");
    check("eval(F, x, 0, L)", "(call eval F x 0 L)");
    check("subs(f, x, 2 a)", "(call subs f x (* 2 a))");
    check("exp(-x) ln(abs(x))", "(* (call exp (- x)) (call ln (call abs x)))");
    check("tan (x)", "ERROR");
}
