use super::*;
use crate::syntax::parse_expr;

/// The tree without spans, to compare readings.
fn bare(e: &Expr) -> Expr {
    let kind = match &e.kind {
        ExprKind::Neg(a) => ExprKind::Neg(Box::new(bare(a))),
        ExprKind::Bin(op, a, b) => ExprKind::Bin(*op, Box::new(bare(a)), Box::new(bare(b))),
        ExprKind::Call(f, args) => ExprKind::Call(*f, args.iter().map(bare).collect()),
        k => k.clone(),
    };
    Expr::new(kind, Span::default())
}

fn latex(s: &str) -> Expr {
    let e = parse_latex_expr(s, 0, &ParseOptions::default())
        .unwrap_or_else(|e| panic!("{s}: {}", e.message));
    bare(&e)
}

fn ours(s: &str) -> Expr {
    bare(&parse_expr(s, &ParseOptions::default()).unwrap_or_else(|e| panic!("{s}: {}", e.message)))
}

fn same(l: &str, r: &str) {
    assert_eq!(latex(l), ours(r), "{l} should read as {r}");
}

#[test]
fn juxtaposed_letters_multiply_and_subscripts_make_one_symbol() {
    same("mL^2", "m*L^2");
    same("mgd", "m*g*d");
    same("2m", "2*m");
    same(r"\frac{1}{2}Mv^2", "1/2*M*v^2");
    same(r"\frac{mL^2}{12}", "(m*L^2)/12");
    same("I_G", "I_G");
    same("k_{G}^2", "k_G^2");
    same("I_{xx}", "I_xx");
    same(r"\theta_0", "theta_0");
    same("x_1 + x_{12}", "x_1 + x_12");
    same("-x^2", "-x^2");
    same(r"a \cdot b \times c", "a*b*c");
    same(r"m\,g\;\cos\beta", "m*g*cos(beta)");
}

#[test]
fn fractions_roots_and_functions() {
    same(r"\sqrt{\frac{I_G}{m}}", "sqrt(I_G/m)");
    same(r"\sqrt[3]{x}", "x^(1/3)");
    same(r"\dfrac{a}{b} + \tfrac12", "a/b + 1/2");
    same(r"\sin\beta\cos\beta", "sin(beta)*cos(beta)");
    same(r"\cos^2\theta", "cos(theta)^2");
    same(r"\sin 2\theta", "sin(2*theta)");
    same(r"\sin x^2", "sin(x^2)");
    same(r"\sin(\omega t)", "sin(omega*t)");
    same(
        r"\sin\left(\frac{\pi}{2} - \beta\right)",
        "sin(pi/2 - beta)",
    );
    same(r"\ln\left(1 + x\right)", "ln(1 + x)");
    same("e^{-kt}", "exp(-k*t)");
    same("|x|", "abs(x)");
    same(r"\left| a - b \right|", "abs(a - b)");
    same(r"\lvert x \rvert", "abs(x)");
}

#[test]
fn derivatives_integrals_and_evaluation_brackets() {
    same(r"\ddot\theta", "theta''");
    same(r"\dot{x}", "x'");
    same(r"\ddot{y}_B", "y_B''");
    same(r"\ddot{y}_{G} L", "y_G''*L");
    same(r"\dot{x}^2", "x'^2");
    same("x''", "x''");
    same(
        r"\int_{-L/2}^{L/2} y^2 \frac{m}{L}\,dy",
        "int(y^2*(m/L), y, -L/2, L/2)",
    );
    same(r"\int_0^R r^2 \, \mathrm{d}r", "int(r^2, r, 0, R)");
    same(r"\int r^2\,dm", "int(r^2, dm)");
    same(
        r"\int_0^{\pi} \sin\theta \, d\theta",
        "int(sin(theta), theta, 0, pi)",
    );
    same(
        r"\left[\frac{y^3}{3}\right]_{-L/2}^{L/2}",
        "eval(y^3/3, y, -L/2, L/2)",
    );
    same(
        r"\frac{m}{L}\left[\frac{y^3}{3}\right]_{-L/2}^{L/2}",
        "m/L*eval(y^3/3, y, -L/2, L/2)",
    );
    same(
        r"\Big[ \frac{x^2}{2} \Big]_{x=0}^{a}",
        "eval(x^2/2, x, 0, a)",
    );
    same(
        r"\left. \frac{y^3}{3} \right|_{0}^{h}",
        "eval(y^3/3, y, 0, h)",
    );
}

#[test]
fn chains_and_relations() {
    let c = parse_latex_chain(
        r"I_G = \int_{-L/2}^{L/2} y^2 \frac{m}{L}\,dy = \frac{mL^2}{12}",
        0,
        &ParseOptions::default(),
    )
    .unwrap_or_else(|e| panic!("{}", e.message));
    assert_eq!(c.links.len(), 2);
    assert_eq!(bare(&c.links[1].rhs), ours("(m*L^2)/12"));
    let ops = |s: &str| -> Vec<RelOp> {
        parse_latex_chain(s, 0, &ParseOptions::default())
            .unwrap_or_else(|e| panic!("{s}: {}", e.message))
            .links
            .iter()
            .map(|l| l.op)
            .collect()
    };
    assert_eq!(ops(r"k_G \approx 0.71 R"), [RelOp::Approx]);
    assert_eq!(ops(r"a &= b \\"), [RelOp::Eq]);
    assert_eq!(
        ops(r"a \neq b \le c \geq d < e"),
        [RelOp::Ne, RelOp::Le, RelOp::Ge, RelOp::Lt]
    );
    assert_eq!(ops(r"v = 3 \quad \text{(metres per second)}"), [RelOp::Eq]);
    assert_eq!(ops(r"E = mc^2 \tag{1}"), [RelOp::Eq]);
}

#[test]
fn spans_point_into_the_text_given() {
    let base = 100;
    let e = parse_latex_expr(r"\frac{a}{b}", base, &ParseOptions::default())
        .unwrap_or_else(|e| panic!("{}", e.message));
    assert!(
        e.span.start >= base && e.span.end <= base + 11,
        "{:?}",
        e.span
    );
    let err = parse_latex_expr(r"a + \foo", base, &ParseOptions::default()).unwrap_err();
    assert_eq!(err.span, Span::new(base + 4, base + 8));
    assert!(err.message.contains("\\foo"), "{}", err.message);
}

#[test]
fn bad_input_is_an_error_never_a_panic() {
    for s in [
        r"\foo",
        "{",
        "a + {b",
        r"\int f",
        r"\begin{tikzpicture}",
        r"\frac{a}",
        r"\left( a",
        "|x",
        r"\sin^{-1} x",
        "x^23",
        r"\int_0^L y\,dm",
        "",
        "= b",
        r"\left[ x \right]_{0}^{1} y",
    ] {
        let r = parse_latex_chain(s, 0, &ParseOptions::default());
        assert!(r.is_err(), "{s} should not parse");
    }
    let deep = format!("{}x{}", "{".repeat(100_000), "}".repeat(100_000));
    assert!(parse_latex_expr(&deep, 0, &ParseOptions::default()).is_err());
}

#[test]
fn equations_from_the_handout() {
    // Handout 5, the rod about its centre and the parallel axis theorem.
    same(
        r"\int_{-L/2}^{L/2} y^2 \frac{m}{L} \, dy",
        "int(y^2*(m/L), y, -L/2, L/2)",
    );
    same(
        r"\frac{m}{L}\left[\frac{y^3}{3}\right]_{-L/2}^{L/2}",
        "m/L*eval(y^3/3, y, -L/2, L/2)",
    );
    same(r"I_G + m d^2", "I_G + m*d^2");
    same(r"\frac{1}{2} m R^2", "1/2*m*R^2");
    same(r"\frac{2}{3} g \sin\beta", "2/3*g*sin(beta)");
}
