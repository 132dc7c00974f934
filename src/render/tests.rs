//! Tests of the renderers.
use super::expr::expr_latex;
use crate::syntax::{parse_expr, ParseOptions};

#[test]
fn dump() {
    for s in [
        "a + b*c", "(a + b) c", "a - (b - c)", "a - (b + c)", "a + (b + c)", "a + (-b)", "-(a + b)", "-x^2", "(-x)^2",
        "2^-1", "a^b^c", "(a^b)^c", "m L^2/12", "m/L dy", "(a+b)/(c-d)", "(a/b)^2", "(a+b)^2", "2 3", "2 m", "m g cos(beta)",
        "sin(beta)", "sin(2 theta)", "sin(x) y", "sin(beta)^2", "sqrt(a)^2", "sqrt(a^2 + b^2)", "exp(-t/tau)", "abs(F)", "ln(x)", "tan(pi/4)",
        "pi R^2", "0.71 R", "1.5e-3", "1e-20", "x'", "theta''", "I_G", "I_xx", "x_1", "k_G^2", "omega", "mg",
        "int(y^2, y, -L/2, L/2)", "int(x, x)", "int(y^2, rod)", "int(1, B)", "int(x^2, dm)", "int(y^2 + z^2, theta)", "int(a + b, x, 0, 1)",
        "diff(x^2, x)", "diff(sin(t), t, 2)", "eval(y^3/3, y, -L/2, L/2)", "subs(x^2, x, a + 1)", "m (L/2)^2", "(a+b)(a-b)", "-2/3 g sin(beta)",
        "a b / c d", "x''^2", "-(-x)", "a * -b", "2 (a+b)", "x^(1/2)", "2^x", "x 2", "cos(beta) x",
    ] {
        let e = parse_expr(s, &ParseOptions::default()).unwrap();
        println!("{s:30} => {}", expr_latex(&e));
    }
}
