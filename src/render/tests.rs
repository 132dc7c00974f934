//! Tests of the renderers: expression LaTeX as data, escaping, the summary line,
//! JSON fields, and documents that must compile with pdflatex.

use super::expr::{chain_latex, expr_latex, expr_latex_in, number_latex, Ctx};
use super::text::{latex_text, markdown_text, mathjax_text};
use super::{github, human, json, latex, markdown, Detail};
use crate::check::report::{ClaimReport, FileReport, Justification, LinkReport, Status};
use crate::diag::Code;
use crate::diag::{Diagnostic, FactRef, Severity};
use crate::syntax::ast::{Item, Span, StmtKind};
use crate::syntax::{parse_chain, parse_expr, parse_file, ParseOptions};
use num_bigint::BigInt;
use num_rational::BigRational;
use std::path::Path;
use std::process::Command;

/// Parses `src` and checks its LaTeX.
fn check(src: &str, expected: &str) {
    let e = parse_expr(src, &ParseOptions::default()).unwrap_or_else(|err| panic!("{src}: {err}"));
    assert_eq!(expr_latex(&e), expected, "LaTeX of `{src}`");
}

#[test]
fn precedence_and_parentheses() {
    check("a + b*c", "a + b\\,c");
    check("(a + b) c", "\\left(a + b\\right) c");
    check("a - (b - c)", "a - \\left(b - c\\right)");
    check("a - (b + c)", "a - \\left(b + c\\right)");
    check("a + (b + c)", "a + b + c");
    check("a + (-b)", "a + \\left(-b\\right)");
    check("a * -b", "a \\left(-b\\right)");
    check("-(a + b)", "-\\left(a + b\\right)");
    check("-(-x)", "-\\left(-x\\right)");
    check("-x^2", "-x^{2}");
    check("(-x)^2", "\\left(-x\\right)^{2}");
    check("(a+b)(a-b)", "\\left(a + b\\right) \\left(a - b\\right)");
    check("2 (a+b)", "2 \\left(a + b\\right)");
}

#[test]
fn products_and_fractions() {
    check("m g", "m\\,g");
    check("2 m", "2 m");
    check("2 3", "2 \\cdot 3");
    check("m L^2/12", "\\frac{m\\,L^{2}}{12}");
    check("m/L dy", "\\frac{m}{L}\\,\\mathit{dy}");
    check("(a+b)/(c-d)", "\\frac{a + b}{c - d}");
    check("-L/2", "-\\frac{L}{2}");
    check("-2/3 g sin(beta)", "-\\frac{2}{3}\\,g\\,\\sin\\beta");
    check("a b / c d", "\\frac{a\\,b}{c}\\,d");
    check("-(a + b)/2", "-\\frac{a + b}{2}");
    check("-I_G x''/R^2", "-\\frac{I_{G}\\,\\ddot{x}}{R^{2}}");
    check("(-a + b)/2", "\\frac{-a + b}{2}");
    check("m (L/2)^2", "m \\left(\\frac{L}{2}\\right)^{2}");
}

#[test]
fn powers() {
    check("2^-1", "2^{-1}");
    check("a^b^c", "a^{b^{c}}");
    check("(a^b)^c", "\\left(a^{b}\\right)^{c}");
    check("(a/b)^2", "\\left(\\frac{a}{b}\\right)^{2}");
    check("(a+b)^2", "\\left(a + b\\right)^{2}");
    check("x^(1/2)", "x^{\\frac{1}{2}}");
    check("sqrt(a)^2", "\\left(\\sqrt{a}\\right)^{2}");
    check("sin(beta)^2", "\\sin^{2}\\beta");
    check("x''^2", "\\ddot{x}^{2}");
    check("k_G^2", "k_{G}^{2}");
}

#[test]
fn functions() {
    check("sin(beta)", "\\sin\\beta");
    check("cos(x)", "\\cos x");
    check("sin(2 theta)", "\\sin\\left(2 \\theta\\right)");
    check("tan(pi/4)", "\\tan\\left(\\frac{\\pi}{4}\\right)");
    check("ln(x)", "\\ln x");
    check("m g cos(beta)", "m\\,g\\,\\cos\\beta");
    check("cos(beta) x", "\\cos\\left(\\beta\\right) x");
    check("sqrt(a^2 + b^2)", "\\sqrt{a^{2} + b^{2}}");
    check("exp(-t/tau)", "e^{-\\frac{t}{\\tau}}");
    check("abs(F)", "\\left|F\\right|");
    check("pi R^2", "\\pi\\,R^{2}");
}

#[test]
fn calculus_forms() {
    check(
        "int(y^2, y, -L/2, L/2)",
        "\\int_{-\\frac{L}{2}}^{\\frac{L}{2}} y^{2} \\, dy",
    );
    check(
        "int(a + b, x, 0, 1)",
        "\\int_{0}^{1} \\left(a + b\\right) \\, dx",
    );
    check("int(x, x)", "\\int x \\, dx");
    check("int(x, theta)", "\\int x \\, d\\theta");
    check("int(y^2, rod)", "\\int_{\\mathit{rod}} y^{2} \\, dm");
    check("int(1, B)", "\\int_{B} 1 \\, dm");
    check("int(x^2, dm)", "\\int x^{2} \\, dm");
    check("diff(x^2, x)", "\\frac{d}{dx}\\left(x^{2}\\right)");
    check(
        "diff(sin(t), t, 2)",
        "\\frac{d^{2}}{dt^{2}}\\left(\\sin t\\right)",
    );
    check(
        "eval(y^3/3, y, -L/2, L/2)",
        "\\Big[\\frac{y^{3}}{3}\\Big]_{y=-\\frac{L}{2}}^{y=\\frac{L}{2}}",
    );
    check("subs(x^2, x, a + 1)", "\\left.x^{2}\\right|_{x=a + 1}");
}

#[test]
fn symbols_and_numbers() {
    check("x'", "\\dot{x}");
    check("theta''", "\\ddot{\\theta}");
    check("I_G", "I_{G}");
    check("x_1", "x_{1}");
    check("omega", "\\omega");
    check("β", "\\beta");
    check("mg", "\\mathit{mg}");
    check("0.71 R", "0.71 R");
    check("1.5e-3", "0.0015");
    check("12", "12");
    check("1e-20", "1 \\times 10^{-20}");
    let q = |n: i64, d: i64| BigRational::new(BigInt::from(n), BigInt::from(d));
    assert_eq!(number_latex(&q(71, 100)), "0.71");
    assert_eq!(number_latex(&q(-1, 8)), "-0.125");
    assert_eq!(number_latex(&q(1, 3)), "\\frac{1}{3}");
    assert_eq!(number_latex(&q(-7, 6)), "-\\frac{7}{6}");
    assert_eq!(number_latex(&q(5, 1)), "5");
}

#[test]
fn relations_and_chains() {
    let chain = |s: &str| chain_latex(&parse_chain(s, &ParseOptions::default()).unwrap());
    assert_eq!(chain("a = b != c"), "a = b \\neq c");
    assert_eq!(chain("a < b <= c"), "a < b \\leq c");
    assert_eq!(chain("a > b >= c"), "a > b \\geq c");
    assert_eq!(chain("k_G ~= 0.71 R"), "k_{G} \\approx 0.71 R");
}

#[test]
fn file_context_knows_bodies_and_differentials() {
    let src = "symbols m L > 0\nbody b: dm = m/L dy, y from 0 to L\nlet I = int(y^2, b)\n";
    let file = parse_file(src, &ParseOptions::default()).unwrap();
    let ctx = Ctx::from_file(&file);
    let e = |s: &str| parse_expr(s, &ParseOptions::default()).unwrap();
    assert_eq!(
        expr_latex_in(&e("int(y^2, b)"), &ctx),
        "\\int_{b} y^{2} \\, dm"
    );
    assert_eq!(
        expr_latex_in(&e("int(y^2, rod)"), &ctx),
        "\\int y^{2} \\, d\\mathit{rod}"
    );
    assert_eq!(expr_latex_in(&e("m/L dy"), &ctx), "\\frac{m}{L}\\,dy");
}

#[test]
fn deep_nesting_is_cut() {
    let deep = format!("{}x{}", "sqrt(".repeat(150), ")".repeat(150));
    let e = parse_expr(&deep, &ParseOptions::default()).unwrap();
    let s = expr_latex(&e);
    assert!(s.contains("\\cdots"));
    assert_eq!(s.matches('{').count(), s.matches('}').count());
}

#[test]
fn latex_escaping() {
    assert_eq!(
        latex_text("100% & {x} \\ ~ ^ _ # $"),
        "100\\% \\& \\{x\\} \\textbackslash{} \\textasciitilde{} \\textasciicircum{} \\_ \\# \\$"
    );
    assert_eq!(latex_text("é ü ç 中"), "\\'{e} \\\"{u} \\c{c} ?");
    assert_eq!(latex_text("β ≈ 2×θ – “x”"), "\\ensuremath{\\beta} \\ensuremath{\\approx} 2\\ensuremath{\\times}\\ensuremath{\\theta} -- ``x''");
    assert_eq!(
        latex_text("the \"some algebra\" (\"x\")"),
        "the ``some algebra'' (``x'')"
    );
    assert_eq!(markdown_text("# a*b_c $x$"), "\\# a\\*b\\_c \\$x\\$");
    assert_eq!(markdown_text("1. x"), "1\\. x");
    assert_eq!(markdown_text("> x"), "\\> x");
    assert_eq!(mathjax_text("{a}\\b 5%"), "(a)/b 5 percent");
    // KaTeX refuses ^ and _ in text mode, and & is an alignment tab in `aligned`.
    assert_eq!(mathjax_text("y^2 & I_G"), "y\u{2c6}2 and I\u{2cd}G");
}

#[test]
fn github_commands() {
    assert_eq!(github::escape_data("50%\r\nx:y,z"), "50%25%0D%0Ax:y,z");
    assert_eq!(github::escape_property("a:b,c%"), "a%3Ab%2Cc%25");
    let src = "symbols a\nclaim a = 2 a\n";
    let r = FileReport {
        path: "dir/x,y.deriv".into(),
        source: src.into(),
        diagnostics: vec![
            Diagnostic::error(
                Code::Refuted,
                "not equal: 100% wrong",
                Span::new(18, 21),
                "here",
            )
            .note("at a = 1"),
            Diagnostic {
                severity: Severity::Warning,
                code: Code::Reading,
                message: "assuming a != 0".into(),
                primary: None,
                notes: vec![],
                mistake: None,
                reached: None,
            },
        ],
        ..Default::default()
    };
    assert_eq!(
        github::report(&r),
        "::error file=dir/x%2Cy.deriv,line=2,col=9,endLine=2,endColumn=12,title=E0301::not equal: 100%25 wrong%0Ahere%0Aat a = 1\n\
         ::warning file=dir/x%2Cy.deriv,title=W0101::assuming a != 0\n"
    );
}

/// A report of `src` with one claim whose links have the given statuses, and a
/// diagnostic for each link that is not verified.
fn report_with(path: &str, src: &str, statuses: Vec<Status>) -> FileReport {
    let ast = parse_file(src, &ParseOptions::default()).unwrap();
    let mut claims = Vec::new();
    let mut diagnostics = Vec::new();
    let mut statuses = statuses.into_iter();
    for item in &ast.items {
        if let Item::Stmt(stmt) = item {
            if let StmtKind::Claim { label, chain, .. } = &stmt.kind {
                let mut links = Vec::new();
                for link in &chain.links {
                    let status = statuses.next().unwrap_or(Status::Verified {
                        how: Justification::Identity,
                        side_conditions: vec![],
                    });
                    if !status.is_verified() {
                        diagnostics.push(
                            Diagnostic::error(
                                Code::Refuted,
                                "the two sides differ by a factor {2} & 100%",
                                link.span,
                                "here",
                            )
                            .note("at m = 1"),
                        );
                    }
                    links.push(LinkReport {
                        span: link.span,
                        op: link.op,
                        lhs: None,
                        rhs: None,
                        status,
                        units: None,
                        mistake: None,
                    });
                }
                let line = crate::diag::line_col(src, stmt.span.start).0;
                claims.push(ClaimReport {
                    label: label.as_ref().map(|l| l.name.clone()),
                    span: stmt.span,
                    line,
                    links,
                });
            }
        }
    }
    FileReport {
        path: path.into(),
        guarded: 0,
        source: src.into(),
        ast: Some(ast),
        claims,
        diagnostics,
        ..Default::default()
    }
}

const SMALL: &str = "# Small\nsymbols m g > 0\nunknowns F\ngiven [Fx] F = m g\n\
claim [two] F = m g by [Fx]\n  = 2 m g by doubling it\n  = m g + m g\n";

#[test]
fn summary_line() {
    let r = report_with(
        "a.deriv",
        SMALL,
        vec![
            Status::Verified {
                how: Justification::Facts(vec![FactRef::Label("Fx".into())]),
                side_conditions: vec![],
            },
            Status::Failed,
            Status::Undecided,
        ],
    );
    let bad = FileReport {
        path: "b.deriv".into(),
        input_error: true,
        diagnostics: vec![Diagnostic::error(
            Code::Syntax,
            "cannot read b.deriv",
            Span::new(0, 0),
            "",
        )],
        ..Default::default()
    };
    assert_eq!(
        human::summary(&[r, bad]),
        "files: 2, claims: 1, links: 3, verified: 1, failed: 1, undecided: 1, errors: 1\n"
    );
    assert_eq!(
        human::summary(&[]),
        "files: 0, claims: 0, links: 0, verified: 0, failed: 0, undecided: 0, errors: 0\n"
    );
}

#[test]
fn human_verbose_lines() {
    let r = report_with(
        "a.deriv",
        SMALL,
        vec![
            Status::Verified {
                how: Justification::Facts(vec![FactRef::Label("Fx".into()), FactRef::Line(3)]),
                side_conditions: vec![],
            },
            Status::Verified {
                how: Justification::Identity,
                side_conditions: vec!["g != 0".into()],
            },
            Status::Failed,
        ],
    );
    let out = human::report(&r, true);
    assert!(out.starts_with("a.deriv:5:"), "{out}");
    assert!(out.contains(": verified (from [Fx], line 3)\n"), "{out}");
    assert!(
        out.contains(": verified (identity), assuming g != 0\n"),
        "{out}"
    );
    assert!(out.contains("error[E0301]: the two sides differ"), "{out}");
    assert!(!human::report(&r, false).contains("verified ("));
}

#[test]
fn json_fields() {
    let r = report_with(
        "a.deriv",
        SMALL,
        vec![
            Status::Verified {
                how: Justification::Facts(vec![FactRef::Label("Fx".into())]),
                side_conditions: vec!["m != 0".into()],
            },
            Status::Failed,
        ],
    );
    let v = json::report(&r);
    for key in ["path", "ok", "input_error", "claims", "diagnostics"] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    assert_eq!(v["ok"], false);
    let link = &v["claims"][0]["links"][0];
    for key in [
        "line",
        "column",
        "end_line",
        "end_column",
        "op",
        "lhs",
        "rhs",
        "status",
        "justification",
        "side_conditions",
    ] {
        assert!(link.get(key).is_some(), "missing link.{key}");
    }
    assert_eq!(v["claims"][0]["label"], "two");
    assert_eq!(v["claims"][0]["line"], 5);
    assert_eq!(link["status"], "verified");
    assert_eq!(link["justification"]["kind"], "facts");
    assert_eq!(link["justification"]["facts"][0], "Fx");
    assert_eq!(link["side_conditions"][0], "m != 0");
    assert_eq!(v["claims"][0]["links"][1]["status"], "failed");
    assert!(v["claims"][0]["links"][1]["justification"].is_null());
    let d = &v["diagnostics"][0];
    for key in [
        "severity",
        "code",
        "message",
        "line",
        "column",
        "end_line",
        "end_column",
        "label",
        "notes",
    ] {
        assert!(d.get(key).is_some(), "missing diagnostic.{key}");
    }
    assert_eq!(d["severity"], "error");
    assert_eq!(d["line"], 6);
}

#[test]
fn failures_are_marked_in_documents() {
    let r = report_with(
        "a.deriv",
        SMALL,
        vec![
            Status::Verified {
                how: Justification::Identity,
                side_conditions: vec![],
            },
            Status::Failed,
        ],
    );
    let tex = latex::document(&r);
    assert!(tex.contains("\\title{Small}"), "{tex}");
    // Labels become equation numbers in document order; labels never show.
    assert!(tex.contains("\\tag{1}"), "{tex}");
    assert!(tex.contains("\\tag{2}"), "{tex}");
    assert!(!tex.contains("Fx") && !tex.contains("{two}"), "{tex}");
    assert!(tex.contains("rigor verified 2 of 3 steps."), "{tex}");
    assert!(
        tex.contains("&= 2 m\\,g \\quad\\text{(by doubling it)} \\quad\\textbf{[does not hold]}"),
        "{tex}"
    );
    assert!(tex.contains("\\text{by (1)}"), "{tex}");
    assert!(
        tex.contains(
            "\\textbf{Does not hold (line 6):} the two sides differ by a factor \\{2\\} \\& 100\\%"
        ),
        "{tex}"
    );
    // The hint under the caret leads the notes (a document has no caret).
    assert!(
        tex.contains("\\hspace*{1em}here\\par\n\\hspace*{1em}at m = 1"),
        "{tex}"
    );
    compile("failures", &tex);
    let md = markdown::document(&r);
    assert!(md.starts_with("# Small\n"), "{md}");
    assert!(
        md.contains(
            "> **does not hold** (line 6): the two sides differ by a factor {2} & 100%\n>\n> here\n>\n> at m = 1\n"
        ),
        "{md}"
    );
    assert!(
        md.contains("$$\n\\begin{aligned}\nF &= m\\,g \\quad\\text{by (1)} \\\\\n"),
        "{md}"
    );
    // Markdown numbers without \tag (GitHub does not draw it); the playground keeps it.
    assert!(
        md.contains("\\end{aligned} \\qquad\\text{(2)}\n$$\n"),
        "{md}"
    );
    assert!(!md.contains("\\tag"), "{md}");
    assert!(md.contains("**Find:** $F$."), "{md}");
}

#[test]
fn unreadable_file_document_compiles() {
    let r = FileReport {
        path: "dir/we{i}rd_%name.deriv".into(),
        source: "claim [x] a = = b\n".into(),
        input_error: true,
        diagnostics: vec![Diagnostic::error(
            Code::NoValue,
            "expected an expression after `=` \\end{verbatim}",
            Span::new(14, 15),
            "here",
        )],
        ..Default::default()
    };
    let tex = latex::document(&r);
    assert!(tex.contains("could not be read"));
    compile("unreadable", &tex);
    let md = markdown::document(&r);
    assert!(md.contains("```text\nerror[E0101]"), "{md}");
}

#[test]
fn hostile_prose_compiles() {
    let src = "# Title with $ & % # _ { } ~ ^ \\ \\end{document}\n\
               ## Section {\n\
               > 100% of $x$ & {weird} \\ ~ ^ _ # é ü 中文 \\end{document}\n\
               > more – “quoted” ≈ β θ μ π ρ λ ω ≤ ≥ × · − — ’ < > |\n\
               symbols x y_1 > 0\n\
               units x: m/s^2, y_1: {kg}%\n\
               given [a_b] x = y_1 by {}\\\n\
               claim [c_d] x = y_1 by [a_b]\n  = y_1 by 100% {sure} \\ ~ ^ _ # é\n\
               use [E_1] from \"we{i}rd_%$.deriv\" with x = 2 y_1\n";
    let ast = parse_file(src, &ParseOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    let r = FileReport {
        path: "h.deriv".into(),
        source: src.into(),
        ast: Some(ast),
        ..Default::default()
    };
    let tex = latex::document(&r);
    assert!(
        tex.contains("100\\% of $x$ \\& \\{weird\\} \\textbackslash{}"),
        "{tex}"
    );
    compile("hostile", &tex);
}

#[test]
fn deep_expression_compiles() {
    let deep = format!(
        "symbols x > 0\nclaim {}x{} = x\nclaim {}x{} = x\n",
        "sqrt(1/(".repeat(60),
        "))".repeat(60),
        "(1+x)^(".repeat(60),
        ")".repeat(60)
    );
    let ast = parse_file(&deep, &ParseOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    let r = FileReport {
        path: "deep.deriv".into(),
        source: deep.clone(),
        ast: Some(ast),
        ..Default::default()
    };
    // Sixty levels of nesting cannot fit on a line: this test is about TeX's capacity
    // (nesting, grouping), not layout, so the width is not checked.
    pdflatex("deep", &latex::document(&r));
}

#[test]
fn every_derivation_compiles() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("derivations");
    let mut entries: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "deriv"))
        .collect();
    entries.sort();
    assert!(!entries.is_empty());
    for path in entries {
        // Documents of checked reports: every link verified, so nothing is marked.
        let r = crate::files::check_file(&path, &dir, &crate::check::Options::default());
        assert!(r.ok() && r.links() > 0, "{}", r.path);
        let name = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let md = markdown::document(&r);
        let tex = latex::document(&r);
        let md_steps = markdown::document_with(&r, Detail::Steps);
        let tex_steps = latex::document_with(&r, Detail::Steps);
        assert!(md.starts_with("# "), "{name}: {md}");
        for doc in [&md, &tex, &md_steps, &tex_steps] {
            assert!(
                !doc.contains("not verified"),
                "{name}: a verified file is marked:\n{doc}"
            );
        }
        compile(&name, &tex);
        compile(&format!("{name}-steps"), &tex_steps);
    }
}

#[test]
fn steps_fill_in_integrals_from_the_engine() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("derivations");
    let opts = crate::check::Options::default();
    let r = crate::files::check_file(&dir.join("rod.deriv"), &dir, &opts);
    let written = latex::document(&r);
    let tex = latex::document_with(&r, Detail::Steps);
    // The mass element substituted, the antiderivative between its bounds, the value.
    let work = "\\int_{\\mathit{rod}} y^{2} \\, dm &= \\int_{-\\frac{L}{2}}^{\\frac{L}{2}} y^{2}\\,\\frac{m}{L} \\, dy \\\\\n \
                &= \\Big[\\frac{m\\,y^{3}}{3 L}\\Big]_{y=-\\frac{L}{2}}^{y=\\frac{L}{2}} \\\\\n \
                &= \\frac{L^{2}\\,m}{24} - \\left(-\\frac{L^{2}\\,m}{24}\\right) \\\\\n \
                &= \\frac{L^{2}\\,m}{12}\n";
    assert!(tex.contains(work), "{tex}");
    assert!(!written.contains("\\Big[\\frac{m\\,y^{3}}{3 L}") && !written.contains("Working"));
    // Worked once: `int(y^2, rod)` again, or as `int(y^2 m/L, y, -L/2, L/2)`, is not.
    let bracket = "\\Big[\\frac{m\\,y^{3}}{3 L}\\Big]_{y=-\\frac{L}{2}}";
    assert_eq!(tex.matches(bracket).count(), 1, "{tex}");
    // A box: each coordinate in turn, innermost first.
    let r = crate::files::check_file(&dir.join("inertia_tensor.deriv"), &dir, &opts);
    let tex = latex::document_with(&r, Detail::Steps);
    assert!(
        tex.contains("integrating over $z$, then $y$, then $x$:"),
        "{tex}"
    );
    assert!(
        tex.contains("\\Big]_{z=-\\frac{c}{2}}^{z=\\frac{c}{2}} \\, dy \\, dx"),
        "{tex}"
    );
    // An abstract body: moments, then its mass and its first moments.
    let r = crate::files::check_file(&dir.join("parallel_axis.deriv"), &dir, &opts);
    let md = markdown::document_with(&r, Detail::Steps);
    assert!(md.contains("> *Working.* By linearity, in moments of $B$, with $\\int_{B} 1 \\, dm = m$ and, the body being centred, $\\int_{B} x \\, dm = \\int_{B} y \\, dm = 0$:"), "{md}");
    assert!(
        md.contains("&= a^{2}\\,m + b^{2}\\,m + \\int_{B} y^{2} \\, dm + \\int_{B} x^{2} \\, dm"),
        "{md}"
    );
}

#[test]
fn steps_show_the_unknowns_solved_and_substituted() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("derivations");
    let r = crate::files::check_file(
        &dir.join("trapdoor.deriv"),
        &dir,
        &crate::check::Options::default(),
    );
    let tex = latex::document_with(&r, Detail::Steps);
    // [thdd]: theta'' solved from [MA] (equation 2), then both sides agree.
    assert!(tex.contains("Line 1: solving the facts this step uses for the unknown:\n\\begin{align*}\n\\ddot{\\theta} &= -\\frac{3\\,g}{2 L} \\quad\\text{from (2)}\n\\end{align*}\n\\par\nSubstituted, both sides are\n"), "{tex}");
    // [faster]: two unknowns in turn, and the inequality once they are substituted.
    assert!(
        tex.contains("\\ddot{y}_{B} &= L\\,\\ddot{\\theta} \\quad\\text{from (6)}"),
        "{tex}"
    );
    assert!(
        tex.contains("Substituted, the step reads\n\\begin{align*}\n\\frac{3 g}{2} &> g\n"),
        "{tex}"
    );
    // A constraint differentiated, cited by its equation number.
    let r = crate::files::check_file(
        &dir.join("rolling_cylinder.deriv"),
        &dir,
        &crate::check::Options::default(),
    );
    let md = markdown::document_with(&r, Detail::Steps);
    assert!(md.contains("\\text{by (1) differentiated twice}"), "{md}");
    assert!(
        !md.contains("[noslip]") && !md.contains("onslope"),
        "labels never show: {md}"
    );
}

#[test]
fn steps_of_hostile_files_stay_escaped() {
    let src = "# T & 100% {x}\nsymbols m L > 0\nunknowns F\nbody rod: dm = m/L dy, y from 0 to L\n\
               given [Fx] F = m L\nclaim [two] 2 F = 2 m L by [Fx]\n\
               claim int(y, rod) = m L/2 by {sure} & $x$ \\ ~ ^ _ # \\end{document}\n";
    let r = crate::check::check_source(
        "h.deriv",
        src,
        &crate::check::Options::default(),
        &crate::check::MemoryResolver::new(),
    );
    assert!(r.ok(), "{:?}", r.diagnostics);
    let tex = latex::document_with(&r, Detail::Steps);
    assert_eq!(tex.matches("\\textit{Working.}").count(), 2, "{tex}");
    assert!(
        tex.contains("(by \\{sure\\} \\& }x\\text{ \\textbackslash{}"),
        "{tex}"
    );
    compile("hostile-steps", &tex);
    let md = markdown::document_with(&r, Detail::Steps);
    assert_eq!(md.matches("> *Working.*").count(), 2, "{md}");
}

/// Compiles `tex` with pdflatex and asserts success, and that no line is overfull by
/// more than 10 pt.
fn compile(name: &str, tex: &str) -> String {
    let (log, text) = pdflatex(name, tex);
    let worst = overfull(&log);
    assert!(
        worst <= 10.0,
        "{name}: a line is {worst} pt too wide:\n{log}\n--- document ---\n{tex}"
    );
    text
}

/// Compiles `tex` with pdflatex in a fresh temporary folder, asserts success and
/// returns the log and the PDF's text (by pdftotext). Without pdflatex or pdftotext the
/// test fails, unless `RIGOR_SKIP_PDFLATEX=1` (then both are empty).
fn pdflatex(name: &str, tex: &str) -> (String, String) {
    let missing = ["pdflatex", "pdftotext"]
        .into_iter()
        .find(|t| Command::new(t).arg("-v").output().is_err());
    if let Some(tool) = missing {
        if std::env::var("RIGOR_SKIP_PDFLATEX").is_ok_and(|v| v == "1") {
            return (String::new(), String::new());
        }
        panic!("{tool} is not on PATH: install TeX Live and poppler-utils, or set RIGOR_SKIP_PDFLATEX=1");
    }
    let dir = std::env::temp_dir().join(format!("rigor-render-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("doc.tex"), tex).unwrap();
    let out = Command::new("pdflatex")
        .args([
            "-interaction=nonstopmode",
            "-halt-on-error",
            "-no-shell-escape",
            "doc.tex",
        ])
        .current_dir(&dir)
        .output()
        .unwrap();
    let ok = out.status.success() && dir.join("doc.pdf").exists();
    let log = String::from_utf8_lossy(&out.stdout).into_owned();
    let text = Command::new("pdftotext")
        .args(["-enc", "UTF-8", "doc.pdf", "-"])
        .current_dir(&dir)
        .output()
        .map(|o| String::from_utf8_lossy(&o.stdout).into_owned())
        .unwrap_or_default();
    let _ = std::fs::remove_dir_all(&dir);
    assert!(
        ok,
        "pdflatex failed on {name}:\n{log}\n--- document ---\n{tex}"
    );
    (log, text)
}

/// Lines of a PDF's text that show rigor's own syntax rather than typeset maths: a
/// caret, a function applied with parentheses, `int(`, `eval(`, or a mass element
/// written `m/L dy`.
fn source_syntax(text: &str) -> Vec<&str> {
    let leaks = [
        "^", "sqrt(", "sin(", "cos(", "int(", "eval(", "/L d", " pi ", "''",
    ];
    text.lines()
        .filter(|l| leaks.iter().any(|k| l.contains(k)))
        .collect()
}

/// The widest `Overfull \hbox (X pt too wide)` of a pdflatex log, in pt (0 if none).
fn overfull(log: &str) -> f64 {
    log.split("Overfull \\hbox (")
        .skip(1)
        .filter_map(|rest| rest.split("pt too wide").next()?.trim().parse::<f64>().ok())
        .fold(0.0, f64::max)
}

#[test]
fn overfull_lines_are_measured() {
    let log = "Overfull \\hbox (3.2pt too wide) in paragraph\nOverfull \\hbox (720.5pt too wide) detected";
    assert_eq!(overfull(log), 720.5);
    assert_eq!(overfull("Underfull \\hbox (badness 10000)"), 0.0);
}

#[test]
fn a_folder_is_one_book_in_its_order_with_cross_references() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/book");
    let reports = crate::files::check_paths(
        std::slice::from_ref(&dir),
        &crate::check::Options::default(),
    );
    let reports = crate::files::in_book_order(&dir, reports).expect("ORDER");
    let names: Vec<_> = reports
        .iter()
        .map(|r| {
            Path::new(&r.path)
                .file_name()
                .unwrap()
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    // ORDER lists end.deriv first; unlisted files follow in path order.
    assert_eq!(names, ["end.deriv", "centre.deriv", "extra.deriv"]);
    let tex = latex::book(&reports, "Rods & $m$");
    assert!(tex.contains("\\title{Rods \\& $m$}"), "{tex}");
    assert!(tex.contains("\\tableofcontents"), "{tex}");
    let sections: Vec<_> = tex
        .lines()
        .filter(|l| l.starts_with("\\section{"))
        .collect();
    assert_eq!(
        sections,
        [
            "\\section{The rod about its end}",
            "\\section{The rod about its centre}",
            "\\section{An extra}"
        ]
    );
    // Equations are numbered by section; the import is a cross-reference.
    assert!(tex.contains("\\tag{2.1}"), "{tex}");
    assert!(tex.contains("From Section 2 we use (2.1)"), "{tex}");
    assert!(tex.contains("\\text{by (1.1)}"), "{tex}");
    assert!(
        !tex.contains("IG") && !tex.contains("centre.deriv"),
        "{tex}"
    );
    compile("book", &tex);
    let md = markdown::book(&reports, "Rods");
    assert!(
        md.starts_with("# Rods\n\n1. The rod about its end\n2. The rod about its centre\n3. An extra\n\n## 1. The rod about its end\n"),
        "{md}"
    );
    assert!(md.contains("From Section 2 we use (2.1)"), "{md}");
    // The whole handout as a book compiles, nothing overfull.
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("derivations");
    let reports = crate::files::check_paths(
        std::slice::from_ref(&dir),
        &crate::check::Options::default(),
    );
    let reports = crate::files::in_book_order(&dir, reports).expect("derivations/ORDER");
    assert!(reports.iter().all(|r| r.ok()));
    assert!(
        reports[0].path.ends_with("rod.deriv"),
        "{}",
        reports[0].path
    );
    let text = compile("handout-book", &latex::book(&reports, "Handout 5"));
    let leaks = source_syntax(&text);
    assert!(
        leaks.is_empty(),
        "source syntax in the book's PDF: {leaks:#?}"
    );
    let steps = latex::book_with(&reports, "Handout 5", Detail::Steps);
    assert!(steps.contains("\\textit{Working.}"));
    let text = compile("handout-book-steps", &steps);
    let leaks = source_syntax(&text);
    assert!(
        leaks.is_empty(),
        "source syntax in the book's PDF with --steps: {leaks:#?}"
    );
}

#[test]
fn checked_documents_compile() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let paths = vec![
        root.join("derivations"),
        root.join("tests/check/fail"),
        root.join("tests/check/pass"),
    ];
    let reports = crate::files::check_paths(&paths, &crate::check::Options::default());
    assert!(!reports.is_empty());
    let mut all = String::new();
    for r in &reports {
        let name = Path::new(&r.path)
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let tex = latex::document(r);
        if r.ast.is_some() && !r.diagnostics.is_empty() {
            assert!(
                tex.contains("\\begin{quote}"),
                "{name}: diagnostics not shown\n{tex}"
            );
        }
        if r.failed() > 0 {
            assert!(
                tex.contains("[does not hold]"),
                "{name}: failures not marked\n{tex}"
            );
        }
        compile(&format!("checked-{name}"), &tex);
        // The filled-in work of every fixture, readable or not, renders (the two
        // failing fixtures with snapshots in tests/it/documents.rs also compile).
        let steps = latex::document_with(r, Detail::Steps);
        if ["rod_factor_two", "rolling_cylinder_wrong_sign"].contains(&name.as_str()) {
            compile(&format!("checked-{name}-steps"), &steps);
        }
        all.push_str(&markdown::document_with(r, Detail::Steps));
        all.push_str(&markdown::document(r));
        all.push_str(&human::report(r, true));
        all.push_str(&github::report(r));
        all.push_str(&json::report(r).to_string());
    }
    all.push_str(&human::summary(&reports));
    if let Ok(dir) = std::env::var("RIGOR_RENDER_DUMP") {
        for r in &reports {
            let name = Path::new(&r.path)
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default();
            let _ = std::fs::write(
                Path::new(&dir).join(format!("{name}.tex")),
                latex::document(r),
            );
            let _ = std::fs::write(
                Path::new(&dir).join(format!("{name}.md")),
                markdown::document(r),
            );
        }
        let _ = std::fs::write(Path::new(&dir).join("all.txt"), &all);
    }
}

#[test]
fn math_in_titles_and_headings_is_typeset() {
    let src = "# Rolling with $I_G = m R^2$\nsymbols m R > 0\n## The case $R = 2$, theta'' in words, \\$5\nclaim [a] m R^2 = R^2 m\n";
    let r = crate::check::check_source(
        "t.deriv",
        src,
        &crate::check::Options::default(),
        &crate::check::MemoryResolver::new(),
    );
    let tex = latex::document(&r);
    assert!(
        tex.contains("\\title{Rolling with $I_{G} = m\\,R^{2}$}"),
        "{tex}"
    );
    assert!(
        tex.contains("\\section*{The case $R = 2$, theta'{}' in words, \\$5}"),
        "{tex}"
    );
    compile("titles", &tex);
    let md = markdown::document(&r);
    assert!(
        md.starts_with("# Rolling with $I_{G} = m\\,R^{2}$\n"),
        "{md}"
    );
}

#[test]
fn failure_notes_typeset_their_expressions_and_keep_words_as_words() {
    use super::solution::{note_inlines, Inline};
    use crate::diag::Note;
    let left = note_inlines(&Note::Side {
        left: true,
        value: "L^2 m/12".into(),
    });
    assert_eq!(
        left,
        vec![
            Inline::Text("left side: ".into()),
            Inline::Math("\\displaystyle \\frac{L^{2}\\,m}{12}".into())
        ]
    );
    let cx = note_inlines(&Note::Counterexample {
        at: vec![("L".into(), "2".into()), ("m".into(), "11/4".into())],
        left: "11/12".into(),
        right: "1".into(),
    });
    assert!(
        matches!(&cx[1], Inline::Math(m) if m == "L = 2,\\ m = \\frac{11}{4}"),
        "{cx:?}"
    );
    // What does not read as an expression stays text (escaped where it is written).
    let hostile = Note::Side {
        left: true,
        value: "\\input{/etc/passwd}".into(),
    };
    assert_eq!(
        note_inlines(&hostile),
        vec![Inline::Text("left side:  \\input{/etc/passwd}".into())]
    );
    let words = "the two sides have opposite signs (a sign error?)";
    assert_eq!(
        note_inlines(&words.into()),
        vec![Inline::Text(words.into())]
    );
}

/// A file whose results verify, fail, and are undecided, with hostile `by` text.
const RESULTS: &str = "# Results that do not all hold
symbols m g R > 0
symbols beta
symbols x_0
time x theta
unknowns F
result [und], [xdd], [ok], [neg]

claim [und] sqrt(x_0)^2 = abs(x_0)

given [Fx] F - m g sin(beta) = m x''
given [MG] F R = -(m R^2/2) theta''
constraint [roll] x = R theta

claim [xdd] x'' = -1/2 g sin(beta) by <img src=x onerror=alert(1)> & `<b>`
claim [ok] x'' = -2/3 g sin(beta) by [Fx], [MG], [roll]
claim [neg] m g < 0
";

fn results_report() -> FileReport {
    let opts = crate::check::Options {
        clock: None,
        ..Default::default()
    };
    let r = crate::check::check_source(
        "results.deriv",
        RESULTS,
        &opts,
        &crate::check::MemoryResolver::new(),
    );
    let status = |label: &str| {
        r.claims
            .iter()
            .find(|c| c.label.as_deref() == Some(label))
            .map(|c| c.links[0].status.clone())
    };
    assert_eq!(
        status("und"),
        Some(Status::Undecided),
        "{:?}",
        r.diagnostics
    );
    assert_eq!(status("xdd"), Some(Status::Failed), "{:?}", r.diagnostics);
    assert!(status("ok").is_some_and(|s| s.is_verified()));
    assert_eq!(status("neg"), Some(Status::Failed), "{:?}", r.diagnostics);
    r
}

/// The text of the "Results" section (from its heading to the closing line).
fn results_section<'t>(doc: &'t str, heading: &str) -> &'t str {
    let start = doc
        .find(heading)
        .unwrap_or_else(|| panic!("no Results in:\n{doc}"));
    let rest = &doc[start..];
    &rest[..rest.find("rigor verified").unwrap_or(rest.len())]
}

#[test]
fn only_verified_results_are_boxed_and_the_others_carry_their_verdict() {
    let r = results_report();
    let tex = latex::document(&r);
    let results = results_section(&tex, "\\section*{Results}");
    // One box, for the one result that verified.
    assert_eq!(results.matches("\\boxed").count(), 1, "{results}");
    assert!(
        results.contains("\\boxed{\\ddot{x} = -\\frac{2}{3}\\,g\\,\\sin\\beta}"),
        "{results}"
    );
    // The failed equation and inequality "do not hold"; the undecided one is "not verified".
    assert!(
        results.contains(
            "\\ddot{x} &= -\\frac{1}{2}\\,g\\,\\sin\\beta \\quad\\textbf{[does not hold]}"
        ),
        "{results}"
    );
    assert!(
        results.contains("m\\,g &< 0 \\quad\\textbf{[does not hold]}"),
        "{results}"
    );
    assert!(
        results.contains("\\left|x_{0}\\right| \\quad\\textbf{[not verified]}"),
        "{results}"
    );
    // The same words on the steps themselves and in the problems after them.
    assert!(tex.contains("\\textbf{Does not hold (line 15):}"), "{tex}");
    assert!(tex.contains("\\textbf{Not verified (line 9):}"), "{tex}");
    assert!(!tex.contains("<img"), "{tex}");
    compile("results", &tex);

    let md = markdown::document(&r);
    let results = results_section(&md, "## Results");
    assert_eq!(results.matches("\\boxed").count(), 1, "{results}");
    assert!(
        results.contains(
            "\\ddot{x} &= -\\frac{1}{2}\\,g\\,\\sin\\beta \\quad\\textbf{[does not hold]}"
        ),
        "{results}"
    );
    assert!(
        results.contains("m\\,g &< 0 \\quad\\textbf{[does not hold]}"),
        "{results}"
    );
    assert!(
        results.contains("\\left|x_{0}\\right| \\quad\\textbf{[not verified]}"),
        "{results}"
    );
    assert!(md.contains("> **does not hold** (line 15):"), "{md}");
    assert!(md.contains("> **not verified** (line 9):"), "{md}");
    // `by` text reaches Markdown with no tag a renderer would keep live.
    assert!(!md.contains("<img") && !md.contains("<b>"), "{md}");
    assert!(
        md.contains(
            "(by \u{2039}img src=x onerror=alert(1)\u{203a} and \u{2018}\u{2039}b\u{203a}\u{2018})"
        ),
        "{md}"
    );

    // The playground shows the same blocks.
    let page = super::web::page(&r);
    let blocks = page["solution"]["blocks"].as_array().expect("blocks");
    let at = blocks
        .iter()
        .position(|b| b["kind"] == "heading" && b["parts"][0]["text"] == "Results")
        .expect("a Results heading");
    let shown: Vec<&str> = blocks[at + 1..at + 5]
        .iter()
        .map(|b| b["latex"].as_str().unwrap_or(""))
        .collect();
    assert!(shown[0].contains("[not verified]"), "{shown:?}");
    assert!(shown[1].contains("[does not hold]"), "{shown:?}");
    assert!(shown[2].starts_with("\\boxed"), "{shown:?}");
    assert!(shown[3].contains("[does not hold]"), "{shown:?}");
}

#[test]
fn user_text_never_reaches_markdown_as_html() {
    // Every place user text reaches a Markdown document: title, headings, prose, `by`,
    // labels, `where` values, file names, messages with code spans.
    let src = "# T <img src=a onerror=alert(1)>\n\
               ## H <img src=b onerror=alert(1)>\n\
               > P <img src=c onerror=alert(1)> `<img src=d onerror=alert(1)>`\n\
               symbols m > 0\n\
               given [g1] m = m by <img src=e onerror=alert(1)>\n\
               claim [c1] m = m by ```<img src=f onerror=alert(1)>`\n\
               claim [c2] m = 2 m by <script>alert(1)</script>\n\
               use [X] from \"<img src=g onerror=alert(1)>.deriv\"\n";
    let opts = crate::check::Options {
        clock: None,
        ..Default::default()
    };
    let r = crate::check::check_source("h.deriv", src, &opts, &crate::check::MemoryResolver::new());
    for md in [
        markdown::document(&r),
        markdown::document_with(&r, Detail::Steps),
        markdown::book(std::slice::from_ref(&r), "B <img src=h onerror=alert(1)>"),
    ] {
        assert!(md.contains("onerror"), "the text is kept:\n{md}");
        for tag in ["<img", "<script", "</script"] {
            // Only escaped, or inside a code span, may it appear as written.
            for (k, _) in md.match_indices(tag) {
                let before = &md[..k];
                if before.ends_with('\\') {
                    continue;
                }
                let line_start = before.rfind('\n').map_or(0, |i| i + 1);
                let ticks = before[line_start..].matches('`').count()
                    - before[line_start..].matches("\\`").count();
                assert!(ticks % 2 == 1, "a live {tag} at {k}:\n{md}");
            }
        }
    }
    // A message whose backticks a renderer would pair otherwise: every stray backtick
    // is escaped, so the tag is text.
    let msg = super::text::markdown_message("```<img src=x onerror=alert(1)>`");
    assert_eq!(msg, "\\`\\``<img src=x onerror=alert(1)>`");
}

#[test]
fn find_names_what_the_derivation_finds_and_by_words_typeset_their_maths() {
    let src = "# Slope\nsymbols m g > 0\nsymbols beta\nunknowns F, N\ngiven [Fx] F = m g sin(beta)\ngiven [Fy] N = m g cos(beta)\nclaim [a] F/m = g sin(beta) by the balance along $x$ with $F = m g sin(beta)$, not $ alone\nresult [a]\n";
    let report = crate::check_source(
        "s.deriv",
        src,
        &crate::Options::default(),
        &crate::MemoryResolver::new(),
    );
    let md = markdown::document(&report);
    // The result's quantity, not the unknowns F and N.
    assert!(md.contains("**Find:** $\\frac{F}{m}$."), "{md}");
    let tex = latex::document(&report);
    assert!(
        tex.contains("\\text{(by the balance along }x\\text{ with }F = m\\,g\\,\\sin\\beta\\text{, not \\$ alone)}"),
        "{tex}"
    );
    // With no `result`, the claims whose left side is one quantity.
    let plain = src.replace("result [a]\n", "claim [b] F = m g sin(beta) by [Fx]\n");
    let report = crate::check_source(
        "s.deriv",
        &plain,
        &crate::Options::default(),
        &crate::MemoryResolver::new(),
    );
    assert!(markdown::document(&report).contains("**Find:** $F$."));
}

#[test]
fn the_sides_after_the_facts_are_typeset_in_a_failure_note() {
    use super::solution::{note_inlines, Inline};
    use crate::diag::Note;
    let note = Note::Reduced {
        using: vec![FactRef::Label("Fx".into())],
        left: "g m sin(beta)".into(),
        right: "2 g m sin(beta)".into(),
    };
    let inl = note_inlines(&note);
    assert_eq!(
        inl[0],
        Inline::Text("with the facts (after using [Fx]): left ".into())
    );
    assert!(
        matches!(&inl[1], Inline::Math(m) if m.contains("\\sin\\beta")),
        "{inl:?}"
    );
    assert!(
        matches!(&inl[3], Inline::Math(m) if m.starts_with('2')),
        "{inl:?}"
    );
}
