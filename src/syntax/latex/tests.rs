//! Tests of the LaTeX reader: each LaTeX form against the tree of rigor's own syntax it
//! means, spans, errors, and the physicist's readings of `physics.rs`.

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
    same(r"a \cdot b \times 2", "a*b*2");
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
fn a_chain_read_again_has_spans_at_its_new_offset() {
    // The first reading (at 50) and the remembered one (at 0, then at 9) each point into
    // the text where they were given: `q_7` at 0..3, `=` at 4, `r` at 6..7.
    let (text, opts) = ("q_7 = r", ParseOptions::default());
    for base in [50, 0, 9] {
        let c = parse_latex_chain(text, base, &opts).unwrap_or_else(|e| panic!("{}", e.message));
        assert_eq!(c.first.span, Span::new(base, base + 3));
        assert_eq!(c.links[0].span, Span::new(base + 4, base + 7));
        assert_eq!(c.links[0].rhs.span, Span::new(base + 6, base + 7));
    }
    // An error's span moves too: `)` at 7..8 has nothing to close.
    for base in [31, 2] {
        let err = parse_latex_chain("p_8 = a)", base, &opts).unwrap_err();
        assert_eq!(err.span, Span::new(base + 7, base + 8), "{}", err.message);
    }
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

fn refused(s: &str) -> String {
    match parse_latex_chain(s, 0, &ParseOptions::default()) {
        Ok(c) => panic!("{s} should be refused, read as {:?}", bare(&c.first)),
        Err(e) => e.message,
    }
}

/// The tree with its reading marks, spans dropped.
fn marked(s: &str) -> Expr {
    fn strip(e: &Expr) -> Expr {
        let kind = match &e.kind {
            ExprKind::Neg(a) => ExprKind::Neg(Box::new(strip(a))),
            ExprKind::Bin(op, a, b) => ExprKind::Bin(*op, Box::new(strip(a)), Box::new(strip(b))),
            ExprKind::Call(f, args) => ExprKind::Call(*f, args.iter().map(strip).collect()),
            k => k.clone(),
        };
        Expr::new(kind, Span::default()).read_as(e.reading)
    }
    strip(
        &parse_latex_expr(s, 0, &ParseOptions::default())
            .unwrap_or_else(|e| panic!("{s}: {}", e.message)),
    )
}

fn leibniz(of: &str) -> Expr {
    ours(of).read_as(Reading::Leibniz)
}

#[test]
fn leibniz_notation_with_respect_to_time_is_a_prime() {
    for (tex, plain) in [
        (r"\frac{dx}{dt}", "x'"),
        (r"\frac{d x}{d t}", "x'"),
        (r"\frac{d\theta}{dt}", "theta'"),
        (r"\frac{dx_B}{dt}", "x_B'"),
        (r"\frac{d^2x}{dt^2}", "x''"),
        (r"\frac{d^{2} x}{d t^{2}}", "x''"),
        (r"\frac{\mathrm{d}x}{\mathrm{d}t}", "x'"),
        (r"\frac{\mathrm{d}^2\theta}{\mathrm{d}t^2}", "theta''"),
        (r"\frac{\text{d}v}{\text{d}t}", "v'"),
        (r"\frac{\operatorname{d}v}{\operatorname{d}t}", "v'"),
        (r"\dfrac{dv}{dt}", "v'"),
        (r"\frac{d\dot x}{dt}", "x''"),
        (r"m\frac{dv}{dt}", "m*v'"),
        (r"\frac{d}{dt} x", "x'"),
        (r"\frac{d}{dt}\theta", "theta'"),
    ] {
        same(tex, plain);
    }
    // Never the quotient of products: `\frac{dx}{dt}` is not x/t.
    assert_ne!(latex(r"\frac{dx}{dt}"), ours("(d*x)/(d*t)"));
}

#[test]
fn leibniz_operators_differentiate_what_follows() {
    assert_eq!(marked(r"\frac{d}{dt}(m v)"), leibniz("diff(m*v, t)"));
    assert_eq!(
        marked(r"\frac{d}{dt}\left(\frac{1}{2} m v^2\right)"),
        leibniz("diff(1/2*m*v^2, t)")
    );
    assert_eq!(
        marked(r"\frac{\mathrm{d}}{\mathrm{d}t}[x y]"),
        leibniz("diff(x*y, t)")
    );
    assert_eq!(marked(r"\frac{d}{dt} m v"), leibniz("diff(m*v, t)"));
    assert_eq!(marked(r"\frac{d(mv)}{dt}"), leibniz("diff(m*v, t)"));
    assert_eq!(marked(r"\frac{d^2}{dt^2}(x y)"), leibniz("diff(x*y, t, 2)"));
    // The operand ends at the next operator.
    let sum = marked(r"\frac{d}{dt}(m v) + F");
    let ExprKind::Bin(BinOp::Add, d, _) = &sum.kind else {
        panic!("{sum:?}")
    };
    assert_eq!(**d, leibniz("diff(m*v, t)"));
}

#[test]
fn leibniz_notation_with_respect_to_another_variable_is_diff() {
    assert_eq!(marked(r"\frac{dy}{dx}"), leibniz("diff(y, x)"));
    assert_eq!(marked(r"\frac{dm}{dx}"), leibniz("diff(m, x)"));
    assert_eq!(marked(r"\frac{d^2y}{dx^2}"), leibniz("diff(y, x, 2)"));
    assert_eq!(
        marked(r"\frac{d}{d\theta}\sin\theta"),
        leibniz("diff(sin(theta), theta)")
    );
    assert_eq!(marked(r"\frac{dt}{dt}"), leibniz("diff(t, t)"));
    // Plain `diff` in rigor's own syntax carries no mark.
    assert_eq!(ours("diff(y, x)").reading, Reading::AsWritten);
}

#[test]
fn a_d_that_is_not_a_differential_stays_a_quotient() {
    same(r"\frac{d}{2}", "d/2");
    same(r"\frac{d^2}{4}", "d^2/4");
    same(r"\frac{\pi d^2}{4}", "(pi*d^2)/4");
    same(r"\frac{2}{d}", "2/d");
    same(r"\frac{F}{d t}", "F/(d*t)");
    same(r"\frac{d_1}{dt}", "d_1/(d*t)");
    same(r"\frac{d}{d}", "d/d");
    same(r"\frac{dx}{2}", "(d*x)/2");
    same(r"\frac{d + x}{dt}", "(d + x)/(d*t)");
    // Orders that disagree, or nothing to differentiate, are errors, never products.
    refused(r"\frac{d^2x}{dt} = a");
    refused(r"\frac{d}{dt} = a");
    refused(r"\frac{d^{12}x}{dt^{12}} = a");
}

#[test]
fn increments_are_one_symbol() {
    same(r"\Delta x", "Delta_x");
    same(r"\delta x", "delta_x");
    same(r"\Delta\theta", "Delta_theta");
    same(r"\Delta x_B", "Delta_x_B");
    same(r"\frac{\Delta x}{\Delta t}", "Delta_x/Delta_t");
    same(r"\Delta x^2", "Delta_x^2");
    same(r"F\Delta t", "F*Delta_t");
    // A lone Delta or delta is the symbol itself.
    same(r"\delta", "delta");
    same(r"k\delta^2", "k*delta^2");
    same(r"\Delta_1 + 1", "Delta_1 + 1");
    assert_ne!(latex(r"\Delta x"), ours("Delta*x"));
    refused(r"\Delta(m v) = F");
    refused(r"\Delta\dot x = a");
}

#[test]
fn euler_e_is_marked_for_the_checker() {
    assert_eq!(marked("e^{x}"), ours("exp(x)").read_as(Reading::EulerE));
    assert_eq!(marked(r"\exp(x)").reading, Reading::AsWritten);
    same("e", "e");
    same(r"e \cdot e", "e*e");
}

#[test]
fn a_function_takes_the_factors_juxtaposed_after_it() {
    same(r"\cos\omega t", "cos(omega*t)");
    same(r"A \cos\omega t", "A*cos(omega*t)");
    same(r"\sin 2\pi f t", "sin(2*pi*f*t)");
    same(r"\cos\omega_n t", "cos(omega_n*t)");
    same(r"\sin k x^2", "sin(k*x^2)");
    same(r"\cos^2\omega t", "cos(omega*t)^2");
    // ... up to an operator, a function, a fraction, a dotted symbol, a bracket, a
    // differential or an explicit space.
    same(r"\cos\omega t + 1", "cos(omega*t) + 1");
    same(r"\sin\theta\cos\theta", "sin(theta)*cos(theta)");
    same(r"\sin\theta\frac{a}{b}", "sin(theta)*(a/b)");
    same(r"\sin\theta\dot\theta", "sin(theta)*theta'");
    same(r"\sin\theta(1 - x)", "sin(theta)*(1 - x)");
    same(r"\cos\omega\,t", "cos(omega)*t");
    same(r"\cos\omega\; t", "cos(omega)*t");
    same(r"\cos\omega\quad t", "cos(omega)*t");
    same(r"\cos\omega~t", "cos(omega)*t");
    same(r"\cos\omega \cdot t", "cos(omega)*t");
    same(r"\cos\omega_d t e^{-k t}", "cos(omega_d*t)*exp(-k*t)");
    same(r"\int_0^T \cos\omega t\,dt", "int(cos(omega*t), t, 0, T)");
    same(r"\int_0^T \cos\omega t dt", "int(cos(omega*t), t, 0, T)");
    assert_ne!(latex(r"\cos\omega t"), ours("cos(omega)*t"));
}

#[test]
fn times_between_two_quantities_is_a_cross_product() {
    same(r"3 \times 10^{4}", "3*10^4");
    same(r"2 \times m", "2*m");
    same(r"m \times 2", "m*2");
    same(r"\frac{1}{2} \times m v^2", "1/2*(m*v^2)");
    same(r"\pi \times r^2", "pi*r^2");
    for s in [
        r"\omega \times r = - r \times \omega",
        r"a \times b = c",
        r"r \times F = M",
        r"\omega \times 2 r = 0",
        r"2 m \times v = 0",
    ] {
        let m = refused(s);
        assert!(m.contains("cross product"), "{s}: {m}");
    }
}

#[test]
fn leibniz_notation_with_a_slash() {
    same("dx/dt", "x'");
    same(r"m\,dv/dt", "m*v'");
    same(r"\mathrm{d}\theta/\mathrm{d}t", "theta'");
    same("d^2x/dt^2", "x''");
    same("dx/dt + 1", "x' + 1");
    assert_eq!(marked("dy/dx"), leibniz("diff(y, x)"));
    // Not a differential: a quotient, as written.
    same("d/2", "d/2");
    same("dx/2", "d*x/2");
    same("d/2", "d/2");
    assert_eq!(marked("d/dt (m v)"), leibniz("diff(m*v, t)"));
    same(r"d/dt\,x", "x'");
    refused("d/dt = a");
    refused("d^2x/dt = a");
}
