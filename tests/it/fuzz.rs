//! Property-based fuzzing of the parsers and the checker: random text, grammar-shaped
//! expressions and grammar-shaped derivation files. Nothing may panic, and a link that
//! the checker verifies as an identity must hold at a random rational point where both
//! sides are defined (both sides evaluated by substituting numbers *before* normalising,
//! with rigorous interval enclosures for what stays irrational).
//!
//! The fast set runs in `cargo test`; `cargo test -- --ignored` runs the long set.

use proptest::prelude::*;
use rigor::check::{check_source, Justification, MemoryResolver, Options, Status};
use rigor::decide::Evaluator;
use rigor::interval::Interval;
use rigor::lower::{lower, Env};
use rigor::normal::{Rat, Q};
use rigor::syntax::{parse_expr, parse_file, ParseOptions};
use std::collections::HashMap;
use std::time::Duration;

// ---------------------------------------------------------------- random text

/// Fragments that the grammar cares about, for ASCII-weighted soup.
const SOUP: &[&str] = &[
    "x",
    "y",
    "m",
    "L",
    "theta",
    "x'",
    "x''",
    "u",
    "0",
    "1",
    "2",
    "12",
    "0.5",
    "1.5e-3",
    "1e9",
    "pi",
    "(",
    ")",
    "(",
    ")",
    "+",
    "-",
    "*",
    "/",
    "^",
    "^-",
    "=",
    "!=",
    "<",
    "<=",
    ">",
    ">=",
    "~=",
    ",",
    " ",
    " ",
    " ",
    "\n",
    "\n  ",
    "\n  = ",
    "sqrt(",
    "sin(",
    "cos(",
    "tan(",
    "exp(",
    "ln(",
    "abs(",
    "int(",
    "diff(",
    "eval(",
    "subs(",
    "f(",
    "claim ",
    "symbols ",
    "time ",
    "unknowns ",
    "units ",
    "body ",
    "let ",
    "given ",
    "constraint ",
    "use ",
    " from ",
    " with ",
    " by ",
    " where ",
    "[a]",
    "[b]",
    "[",
    "]",
    "% ",
    "# ",
    "## ",
    "> ",
    "$",
    "\"",
    "\"a.deriv\"",
    ": ",
    "dm",
    " = ",
    "mass",
    "coordinates",
    "centred",
    "from",
    "to",
    "β",
    "θ",
    "π",
    "·",
    "×",
    "−",
    "²",
    "³",
    "√(",
    "\t",
    "\r\n",
    "\u{0}",
    "é",
    "🎉",
];

/// Soup of grammar fragments, mostly ASCII.
fn soup() -> impl Strategy<Value = String> {
    prop::collection::vec(prop::sample::select(SOUP), 0..40).prop_map(|v| v.concat())
}

/// Arbitrary text, mixing arbitrary Unicode with soup.
fn text() -> impl Strategy<Value = String> {
    prop_oneof![
        1 => any::<String>(),
        1 => "[ -~\\n]{0,60}",
        3 => soup(),
    ]
}

// ---------------------------------------------------------------- grammar-shaped input

/// Declared symbols: `a`, `b` positive, `x`, `y` any real.
const POSITIVE: &[&str] = &["a", "b"];
const REAL: &[&str] = &["x", "y"];

/// A small number in one of the written forms.
fn number() -> impl Strategy<Value = String> {
    prop_oneof![
        (0i64..=12).prop_map(|n| n.to_string()),
        (1i64..=9, 1i64..=9).prop_map(|(n, d)| format!("{n}/{d}")),
        Just("0.5".to_string()),
        Just("1.25".to_string()),
        Just("2e-1".to_string()),
        Just("pi".to_string()),
    ]
}

/// A grammar-shaped expression over `symbols` (and the bound variable `u` when
/// `bound`), small enough that normalising it is quick.
fn expr_over(symbols: &'static [&'static str], bound: bool) -> BoxedStrategy<String> {
    let mut names: Vec<&'static str> = symbols.to_vec();
    if bound {
        names.push("u");
    }
    let leaf = prop_oneof![
        3 => prop::sample::select(names).prop_map(str::to_string),
        2 => number(),
    ];
    leaf.prop_recursive(4, 20, 3, |inner| {
        prop_oneof![
            3 => (inner.clone(), inner.clone()).prop_map(|(p, q)| format!("{p} + {q}")),
            2 => (inner.clone(), inner.clone()).prop_map(|(p, q)| format!("{p} - ({q})")),
            3 => (inner.clone(), inner.clone()).prop_map(|(p, q)| format!("({p}) ({q})")),
            1 => (inner.clone(), inner.clone()).prop_map(|(p, q)| format!("{p}*{q}")),
            2 => (inner.clone(), inner.clone()).prop_map(|(p, q)| format!("({p})/({q})")),
            2 => (inner.clone(), -2i64..=4).prop_map(|(p, k)| format!("({p})^{k}")),
            1 => inner.clone().prop_map(|p| format!("({p})^(1/2)")),
            1 => inner.clone().prop_map(|p| format!("-({p})")),
            1 => (
                prop::sample::select(&["sqrt", "sin", "cos", "tan", "exp", "ln", "abs"][..]),
                inner.clone()
            )
                .prop_map(|(f, p)| format!("{f}({p})")),
            1 => inner.clone().prop_map(|p| format!("sin({p})^2 + cos({p})^2")),
            1 => inner.clone().prop_map(|p| format!("sin(2 ({p}))")),
        ]
    })
    .boxed()
}

/// A grammar-shaped expression, with calculus over the bound variable `u`.
fn expr() -> BoxedStrategy<String> {
    // `D_0` is the first `let` of a generated file (undeclared where it is not defined).
    let plain = expr_over(&["a", "b", "x", "y", "D_0"], false);
    let with_u = expr_over(&["a", "x"], true);
    prop_oneof![
        6 => plain.clone(),
        1 => (with_u.clone(), plain.clone(), plain.clone())
            .prop_map(|(f, lo, hi)| format!("int({f}, u, {lo}, {hi})")),
        1 => (with_u.clone(), plain.clone())
            .prop_map(|(f, v)| format!("subs(diff({f}, u), u, {v})")),
        1 => (with_u.clone(), plain.clone(), plain.clone())
            .prop_map(|(f, lo, hi)| format!("eval({f}, u, {lo}, {hi})")),
        1 => (with_u, plain).prop_map(|(f, v)| format!("subs({f}, u, {v})")),
    ]
    .boxed()
}

/// Rewrites of `e`, nearly all equal to it (so that chains have links that verify);
/// `sqrt(e^2)` is `abs(e)`, equal only where `e >= 0`.
fn equal_variant(e: String) -> BoxedStrategy<String> {
    prop_oneof![
        Just(format!("({e}) + 0")),
        Just(format!("1 ({e})")),
        Just(format!("({e}) + x - x")),
        Just(format!("(({e}) a)/a")),
        Just(format!("2 ({e})/2")),
        Just(format!("(({e}) + b)^2 - b^2 - 2 b ({e}) - ({e})^2 + ({e})")),
        Just(format!("({e})^2/({e})")),
        Just(format!("sqrt(({e})^2)")),
        Just(format!("({e}) (sin(x)^2 + cos(x)^2)")),
        Just(format!("({e}) + sin(2 x) - 2 sin(x) cos(x)")),
        Just(format!("({e}) + exp(x) exp(y) - exp(x + y)")),
        Just(format!("({e}) + ln(a b) - ln(a) - ln(b)")),
        Just(format!("({e}) + sqrt(a^2) - a")),
    ]
    .boxed()
}

/// One element of a claim chain: an equal variant of the previous element, or a fresh
/// expression (which usually fails).
fn next_element(prev: String) -> BoxedStrategy<String> {
    prop_oneof![3 => equal_variant(prev), 1 => expr()].boxed()
}

/// A claim: its label, its chain of expressions (at least two), a `by` text per link
/// and an optional `where`.
#[derive(Clone, Debug)]
struct Claim {
    chain: Vec<String>,
    by: Vec<Option<String>>,
    where_: Option<String>,
}

fn claim() -> impl Strategy<Value = Claim> {
    (expr(), 1usize..=3)
        .prop_flat_map(|(first, n)| {
            let mut chain: BoxedStrategy<Vec<String>> = Just(vec![first]).boxed();
            for _ in 0..n {
                chain = chain
                    .prop_flat_map(|v| {
                        let last = v.last().cloned().unwrap_or_default();
                        next_element(last).prop_map(move |e| {
                            let mut v = v.clone();
                            v.push(e);
                            v
                        })
                    })
                    .boxed();
            }
            (
                chain,
                prop::collection::vec(
                    prop::option::weighted(
                        0.3,
                        prop::sample::select(
                            &["algebra", "[g1]", "[g1], [c0]", "the chain rule", "[zz]"][..],
                        ),
                    ),
                    n,
                ),
                prop::option::weighted(
                    0.15,
                    prop::sample::select(&["a = 2", "x = 1/2, y = 3", "b = a", "x = 0"][..]),
                ),
            )
        })
        .prop_map(|(chain, by, where_)| Claim {
            chain,
            by: by
                .into_iter()
                .map(|b| b.map(|s| format!("by {s}")))
                .collect(),
            where_: where_.map(|w| format!("where {w}")),
        })
}

/// One statement of a generated file.
#[derive(Clone, Debug)]
enum Stmt {
    Let(String),
    Given(String, String),
    Constraint(String),
    Claim(Claim),
    Prose(String),
    Comment,
    Noise(String),
}

fn stmt() -> impl Strategy<Value = Stmt> {
    prop_oneof![
        1 => expr().prop_map(Stmt::Let),
        1 => (expr(), expr()).prop_map(|(l, r)| Stmt::Given(l, r)),
        1 => expr().prop_map(Stmt::Constraint),
        6 => claim().prop_map(Stmt::Claim),
        1 => expr().prop_map(Stmt::Prose),
        1 => Just(Stmt::Comment),
        1 => soup().prop_map(Stmt::Noise),
    ]
}

/// A generated file: its text, and for each claim its 1-based line and the claim.
#[derive(Clone, Debug)]
struct GenFile {
    text: String,
    claims: Vec<(usize, Claim)>,
    lets: Vec<(String, String)>,
}

fn file() -> impl Strategy<Value = GenFile> {
    (
        prop::collection::vec(stmt(), 1..6),
        any::<bool>(),
        any::<bool>(),
    )
        .prop_map(|(stmts, time, body)| {
            let mut lines: Vec<String> = vec![
                "# A generated derivation".into(),
                format!("symbols {} > 0", POSITIVE.join(" ")),
                format!("symbols {}", REAL.join(" ")),
                "unknowns F".into(),
            ];
            if time {
                lines.push("time q".into());
            }
            if body {
                lines.push("body rod: dm = a/b dv, v from -b/2 to b/2".into());
            }
            let mut claims = Vec::new();
            let mut lets = Vec::new();
            let mut n_let = 0;
            let mut n_given = 0;
            for s in stmts {
                match s {
                    Stmt::Let(e) => {
                        let name = format!("D_{n_let}");
                        n_let += 1;
                        lines.push(format!("let {name} = {e}"));
                        lets.push((name, e));
                    }
                    Stmt::Given(l, r) => {
                        lines.push(format!("given [g{n_given}] F + {l} = {r}"));
                        n_given += 1;
                    }
                    Stmt::Constraint(e) => {
                        let rhs = if time { "q'" } else { "F" };
                        lines.push(format!("constraint [c0] {e} = {rhs}"));
                    }
                    Stmt::Claim(c) => {
                        let line = lines.len() + 1;
                        let mut first = format!("claim {} = {}", c.chain[0], c.chain[1]);
                        if let Some(b) = &c.by[0] {
                            first.push(' ');
                            first.push_str(b);
                        }
                        lines.push(first);
                        for (i, e) in c.chain.iter().enumerate().skip(2) {
                            let mut l = format!("  = {e}");
                            if let Some(b) = &c.by[i - 1] {
                                l.push(' ');
                                l.push_str(b);
                            }
                            lines.push(l);
                        }
                        if let Some(w) = &c.where_ {
                            lines.push(format!("  {w}"));
                        }
                        claims.push((line, c));
                    }
                    Stmt::Prose(e) => lines.push(format!("> prose with ${e}$ inside")),
                    Stmt::Comment => lines.push("% a comment".into()),
                    Stmt::Noise(s) => lines.push(s.replace('\n', " ")),
                }
            }
            let mut text = lines.join("\n");
            text.push('\n');
            GenFile { text, claims, lets }
        })
}

// ---------------------------------------------------------------- the oracle

/// A point: a value for every declared symbol, respecting the declared signs.
fn point() -> impl Strategy<Value = Vec<(i64, i64)>> {
    (
        prop::collection::vec((1i64..=9, 1i64..=4), POSITIVE.len()),
        prop::collection::vec((-9i64..=9, 1i64..=4), REAL.len()),
    )
        .prop_map(|(p, r)| p.into_iter().chain(r).collect())
}

/// The numeric environment of a point: symbols, then the `let`s in order, all numbers.
fn numeric_env(pt: &[(i64, i64)], lets: &[(String, String)]) -> Env {
    let mut env = Env::default();
    for (name, (n, d)) in POSITIVE.iter().chain(REAL).zip(pt) {
        env.defs.insert(
            name.to_string(),
            Rat::constant(Q::new((*n).into(), (*d).into())),
        );
    }
    for (name, e) in lets {
        if let Some(v) = lowered(e, &env) {
            env.defs.insert(name.clone(), v);
        }
    }
    env
}

fn lowered(src: &str, env: &Env) -> Option<Rat> {
    let e = parse_expr(src, &ParseOptions::default()).ok()?;
    lower(&e, env).ok()
}

/// A rigorous enclosure of the value of `src` in `env`, `None` where undefined or not
/// evaluable (an unknown, a time derivative, a moment of a body).
fn enclosure(src: &str, env: &Env) -> Option<Interval> {
    let r = lowered(src, env)?;
    let none = HashMap::new();
    Evaluator::new(&none).rat(&r)
}

/// Checks `text` and asserts: no panic (the test harness catches it), and every link
/// verified as an identity holds at `pt` (source sides and printed normal forms).
fn check_and_validate(g: &GenFile, pt: &[(i64, i64)]) -> Result<(), TestCaseError> {
    let opts = Options {
        timeout: Duration::from_secs(2),
        ..Options::default()
    };
    let report = check_source("generated.deriv", &g.text, &opts, &MemoryResolver::new());
    // Rendering must not panic either.
    let _ = rigor::render::human::report(&report, true);
    let _ = rigor::render::json::report(&report);
    let env = numeric_env(pt, &g.lets);
    for c in &report.claims {
        let Some((_, gen)) = g.claims.iter().find(|(line, _)| *line == c.line) else {
            continue;
        };
        if gen.where_.is_some() || c.links.len() + 1 != gen.chain.len() {
            continue;
        }
        for (i, link) in c.links.iter().enumerate() {
            let Status::Verified {
                how: Justification::Identity,
                ..
            } = &link.status
            else {
                continue;
            };
            let (l, r) = (&gen.chain[i], &gen.chain[i + 1]);
            let (Some(lv), Some(rv)) = (enclosure(l, &env), enclosure(r, &env)) else {
                continue;
            };
            prop_assert!(
                !lv.disjoint(&rv),
                "verified as an identity, but at {pt:?} `{l}` = {lv} and `{r}` = {rv}\n{}",
                g.text
            );
            // The printed normal forms have the same value.
            for (printed, side, v) in [(&link.lhs, l, &lv), (&link.rhs, r, &rv)] {
                let Some(p) = printed else { continue };
                if let Some(pv) = enclosure(p, &env) {
                    prop_assert!(
                        !pv.disjoint(v),
                        "normal form `{p}` of `{side}` is {pv} at {pt:?}, the source {v}\n{}",
                        g.text
                    );
                }
            }
        }
    }
    Ok(())
}

/// Parses an expression and, if it parses, lowers it: nothing may panic.
fn expr_survives(s: &str) {
    if let Ok(e) = parse_expr(s, &ParseOptions::default()) {
        rigor::normal::poly::set_deadline(rigor::clock::Deadline::after(
            Duration::from_millis(500),
            rigor::clock::system(),
        ));
        let _ = lower(&e, &Env::default());
        rigor::normal::poly::set_deadline(None);
    }
}

/// Parses and checks a file: nothing may panic.
fn file_survives(s: &str) {
    let _ = parse_file(s, &ParseOptions::default());
    let opts = Options {
        timeout: Duration::from_secs(1),
        ..Options::default()
    };
    let report = check_source("generated.deriv", s, &opts, &MemoryResolver::new());
    let _ = rigor::render::human::report(&report, true);
    let _ = rigor::render::json::report(&report);
    let _ = rigor::render::github::report(&report);
}

// ---------------------------------------------------------------- the fast set

proptest! {
    #![proptest_config(crate::config(200))]

    #[test]
    fn random_text_never_panics_the_parsers(s in text()) {
        expr_survives(&s);
        let _ = parse_file(&s, &ParseOptions::default());
    }

    #[test]
    fn grammar_expressions_never_panic(e in expr()) {
        expr_survives(&e);
        // Every generated expression is well formed.
        prop_assert!(parse_expr(&e, &ParseOptions::default()).is_ok(), "{e}");
    }
}

proptest! {
    #![proptest_config(crate::config(60))]

    #[test]
    fn random_text_never_panics_the_checker(s in text()) {
        file_survives(&s);
    }

    #[test]
    fn verified_identities_hold_at_a_point(g in file(), pt in point()) {
        check_and_validate(&g, &pt)?;
    }
}

// ---------------------------------------------------------------- the long set

proptest! {
    #![proptest_config(crate::config(5_000))]

    #[test]
    #[ignore = "long fuzzing run: cargo test -- --ignored"]
    fn long_random_text(s in text()) {
        expr_survives(&s);
        file_survives(&s);
    }

    #[test]
    #[ignore = "long fuzzing run: cargo test -- --ignored"]
    fn long_grammar_expressions(e in expr()) {
        expr_survives(&e);
    }
}

proptest! {
    #![proptest_config(crate::config(2_000))]

    #[test]
    #[ignore = "long fuzzing run: cargo test -- --ignored"]
    fn long_verified_identities_hold_at_a_point(g in file(), pt in point()) {
        check_and_validate(&g, &pt)?;
    }
}
