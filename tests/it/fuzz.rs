//! Property-based fuzzing of the parsers and the checker: random text, grammar-shaped
//! expressions and grammar-shaped derivation files (with `time` symbols, a body,
//! bound variables that reuse declared names, givens, constraints, `where`, and every
//! relation). Nothing may panic, and every link the checker verifies, whatever its
//! justification, must hold at a random point made to satisfy the facts it used: both
//! sides are evaluated by the guard's independent evaluator (`rigor::guard`: straight
//! from the syntax tree, its own derivatives, quadrature and trigonometry, in ball
//! arithmetic), which shares nothing with the lowering under test.
//!
//! The fast set runs in `cargo test`; `cargo test -- --ignored` runs the long set.

use foldhash::{HashMap, HashMapExt};
use proptest::prelude::*;
use rigor::check::{check_source, Justification, MemoryResolver, Options, Status};
use rigor::diag::FactRef;
use rigor::guard::{self, Ball, GuardEnv};
use rigor::lower::{lower, Env};
use rigor::syntax::ast::{Item, Stmt as Stmt_, StmtKind};
use rigor::syntax::{parse_expr, parse_file, ParseOptions};
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

/// Declared symbols: `a`, `b` positive, `x`, `y` any real; `q` a `time` symbol.
const POSITIVE: &[&str] = &["a", "b"];
const REAL: &[&str] = &["x", "y"];

/// The body every generated file declares (coordinate `v`).
const BODY: &str = "body rod: dm = a/b dv, v from -b/2 to b/2";

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

/// A grammar-shaped expression over `names`, small enough that normalising it is quick.
fn expr_over(names: Vec<&'static str>) -> BoxedStrategy<String> {
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
            1 => inner.clone().prop_map(|p| format!("({p})^(-1/3)")),
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

/// Bound variables: a fresh name, a declared symbol of either sign (its sign must not
/// leak into the bound one), the coordinate of the body, and `t` (over which `time`
/// symbols vary).
const BOUND: &[&str] = &["u", "x", "a", "v", "t"];

/// An expression of the free symbols with the bound variable `var` (and `q`, whose
/// integral over `t` is refused).
fn integrand(var: &'static str) -> BoxedStrategy<String> {
    let mut names = vec!["a", "x", var];
    if var == "t" {
        names.push("q");
    }
    expr_over(names)
}

/// A grammar-shaped expression: symbols, the `time` symbol `q` and its derivatives,
/// `let` names, integrals over the body, and calculus over several bound variables.
fn expr() -> BoxedStrategy<String> {
    // `D_0` is the first `let` of a generated file (undeclared where it is not defined).
    let plain = expr_over(vec!["a", "b", "x", "y", "D_0", "q", "q'", "q''"]);
    let var = || prop::sample::select(BOUND);
    prop_oneof![
        8 => plain.clone(),
        1 => (var(), plain.clone(), plain.clone()).prop_flat_map(|(v, lo, hi)| {
            integrand(v).prop_map(move |f| format!("int({f}, {v}, {lo}, {hi})"))
        }),
        1 => (var(), plain.clone()).prop_flat_map(|(v, at)| {
            integrand(v).prop_map(move |f| format!("subs(diff({f}, {v}), {v}, {at})"))
        }),
        1 => (var(), plain.clone(), plain.clone()).prop_flat_map(|(v, lo, hi)| {
            integrand(v).prop_map(move |f| format!("eval({f}, {v}, {lo}, {hi})"))
        }),
        1 => (var(), plain.clone()).prop_flat_map(|(v, at)| {
            integrand(v).prop_map(move |f| format!("subs({f}, {v}, {at})"))
        }),
        1 => integrand("v").prop_map(|f| format!("int({f}, rod)")),
        1 => expr_over(vec!["q", "q'", "a"]).prop_map(|f| format!("diff({f}, t)")),
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
        Just(format!("({e}) + diff(q^2, t) - 2 q q'")),
        Just(format!("({e}) + int(1, rod) - a")),
        Just(format!("({e}) + int(u, u, 0, x) - x^2/2")),
        Just(format!("({e}) + int(x, x, 0, a) - a^2/2")),
    ]
    .boxed()
}

/// The relation of one link: `=` mostly, sometimes an inequality, `!=` or `~=`.
#[derive(Clone, Debug)]
struct Rel {
    op: &'static str,
    /// For `~=`: the number written and half its last digit.
    approx: Option<(f64, f64)>,
}

fn eq() -> Rel {
    Rel {
        op: "=",
        approx: None,
    }
}

/// One element of a claim chain with its relation to the previous one: an equal
/// variant, a fresh expression (which usually fails), or another relation.
fn next_element(prev: String) -> BoxedStrategy<(Rel, String)> {
    let rel = |op: &'static str| Rel { op, approx: None };
    let p = prev.clone();
    let p2 = prev.clone();
    prop_oneof![
        12 => equal_variant(prev.clone()).prop_map(|e| (eq(), e)),
        4 => expr().prop_map(|e| (eq(), e)),
        1 => (prop::sample::select(&["<", "<=", ">", ">="][..]), prop::sample::select(&["1", "a", "x^2", "-1"][..]))
            .prop_map(move |(op, d)| (rel(op), format!("{p} + {d}"))),
        1 => (prop::sample::select(&["<", "<=", ">", ">=", "!="][..]), expr())
            .prop_map(move |(op, e)| (rel(op), e)),
        1 => (prop::sample::select(&["1.0", "1.00", "0.99", "1.01", "1.1", "2.0"][..]), equal_variant(p2))
            .prop_map(|(c, e)| {
                let digits = c.split('.').nth(1).map_or(0, str::len);
                let half = 0.5 * 10f64.powi(-(digits as i32));
                let value: f64 = c.parse().unwrap_or(1.0);
                (Rel { op: "~=", approx: Some((value, half)) }, format!("{c} ({e})"))
            }),
    ]
    .boxed()
}

/// A claim: its chain of expressions (at least two), the relation and a `by` text per
/// link, and an optional `where`.
#[derive(Clone, Debug)]
struct Claim {
    chain: Vec<String>,
    rels: Vec<Rel>,
    by: Vec<Option<String>>,
    where_: Option<&'static str>,
}

fn claim() -> impl Strategy<Value = Claim> {
    (expr(), 1usize..=3)
        .prop_flat_map(|(first, n)| {
            let mut chain: BoxedStrategy<(Vec<String>, Vec<Rel>)> =
                Just((vec![first], Vec::new())).boxed();
            for _ in 0..n {
                chain = chain
                    .prop_flat_map(|(v, rels)| {
                        let last = v.last().cloned().unwrap_or_default();
                        next_element(last).prop_map(move |(r, e)| {
                            let (mut v, mut rels) = (v.clone(), rels.clone());
                            v.push(e);
                            rels.push(r);
                            (v, rels)
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
                            &[
                                "algebra",
                                "[g0]",
                                "[g1]",
                                "[g0], [c0]",
                                "the chain rule",
                                "[zz]",
                            ][..],
                        ),
                    ),
                    n,
                ),
                prop::option::weighted(
                    0.2,
                    prop::sample::select(
                        &[
                            "a = 2",
                            "x = 1/2, y = 3",
                            "b = a",
                            "x = 0",
                            "y = -x",
                            "a = b^2",
                        ][..],
                    ),
                ),
            )
        })
        .prop_map(|((chain, rels), by, where_)| Claim {
            chain,
            rels,
            by: by
                .into_iter()
                .map(|b| b.map(|s| format!("by {s}")))
                .collect(),
            where_,
        })
}

/// Constants and their values, for `~=` claims.
const APPROX: &[(&str, f64)] = &[
    ("sqrt(2)/2", std::f64::consts::FRAC_1_SQRT_2),
    ("pi/3", std::f64::consts::FRAC_PI_3),
    ("1/3", 1.0 / 3.0),
    ("sqrt(3)", 1.732_050_807_568_877_2),
    ("exp(1)", std::f64::consts::E),
    ("ln(2)", std::f64::consts::LN_2),
    ("cos(pi/5)", 0.809_016_994_374_947_4),
];

/// A claim of one link.
fn one_link(l: String, op: &'static str, r: String, by: Option<String>) -> Claim {
    Claim {
        chain: vec![l, r],
        rels: vec![Rel { op, approx: None }],
        by: vec![by],
        where_: None,
    }
}

/// One statement of a generated file.
#[derive(Clone, Debug)]
enum Stmt {
    Let(String),
    /// `given F + l = r`, and maybe a claim that follows from it (`F = r - (l)`, or a
    /// variant, some false).
    Given(String, String, Option<u8>),
    /// `constraint e = q'` (or `= F`), and maybe the claim `q' = e` (or `F = e`).
    Constraint(String, bool, bool),
    Claim(Claim),
    /// `claim K a x ~= c a x`, `K` of [`APPROX`], `c` written with some digits and
    /// maybe off by one in the last.
    Approx(usize, u32, u8),
    Prose(String),
    Comment,
    Noise(String),
}

fn stmt() -> impl Strategy<Value = Stmt> {
    // Facts are about constants and `F` (and `q'` through the constraint).
    let fact = || expr_over(vec!["a", "b", "x", "y", "D_0"]);
    prop_oneof![
        1 => fact().prop_map(Stmt::Let),
        2 => (fact(), fact(), prop::option::weighted(0.6, 0u8..4))
            .prop_map(|(l, r, k)| Stmt::Given(l, r, k)),
        1 => (fact(), any::<bool>(), any::<bool>())
            .prop_map(|(e, q, follow)| Stmt::Constraint(e, q, follow)),
        6 => claim().prop_map(Stmt::Claim),
        1 => (0usize..APPROX.len(), 0u32..=4, 0u8..4).prop_map(|(k, d, off)| Stmt::Approx(k, d, off)),
        1 => expr().prop_map(Stmt::Prose),
        1 => Just(Stmt::Comment),
        1 => soup().prop_map(Stmt::Noise),
    ]
}

/// A fact of a generated file, by label: `F + l = r`, or the constraint `e = F` or
/// `e = q'`.
#[derive(Clone, Debug)]
enum Fact {
    Given(String, String),
    Constraint(String, bool),
}

/// A generated file: its text, each claim with its 1-based line, the `let`s and facts.
#[derive(Clone, Debug)]
struct GenFile {
    text: String,
    claims: Vec<(usize, Claim)>,
    lets: Vec<(String, String)>,
    facts: HashMap<String, Fact>,
}

fn file() -> impl Strategy<Value = GenFile> {
    prop::collection::vec(stmt(), 1..6).prop_map(|stmts| {
        let mut lines: Vec<String> = vec![
            "# A generated derivation".into(),
            format!("symbols {} > 0", POSITIVE.join(" ")),
            format!("symbols {}", REAL.join(" ")),
            "unknowns F".into(),
            "time q".into(),
            BODY.into(),
        ];
        let mut claims = Vec::new();
        let mut lets = Vec::new();
        let mut facts = HashMap::new();
        let mut n_let = 0;
        let mut n_given = 0;
        let mut constrained = false;
        let mut pending: Vec<Claim> = Vec::new();
        for s in stmts {
            match s {
                Stmt::Let(e) => {
                    let name = format!("D_{n_let}");
                    n_let += 1;
                    lines.push(format!("let {name} = {e}"));
                    lets.push((name, e));
                }
                Stmt::Given(l, r, follow) => {
                    let label = format!("g{n_given}");
                    lines.push(format!("given [{label}] F + {l} = {r}"));
                    facts.insert(label.clone(), Fact::Given(l.clone(), r.clone()));
                    n_given += 1;
                    let by = Some(format!("by [{label}]"));
                    let c = match follow {
                        Some(0) => Some(one_link("F".into(), "=", format!("({r}) - ({l})"), None)),
                        Some(1) => Some(one_link(
                            "F y".into(),
                            "=",
                            format!("(({r}) - ({l})) y"),
                            by,
                        )),
                        Some(2) => {
                            Some(one_link("F + a".into(), ">", format!("({r}) - ({l})"), by))
                        }
                        Some(_) => Some(one_link("F".into(), "=", format!("({r}) + ({l})"), by)),
                        None => None,
                    };
                    if let Some(c) = c {
                        pending.push(c);
                    }
                }
                Stmt::Constraint(e, on_q, follow) => {
                    let rhs = if on_q { "q'" } else { "F" };
                    lines.push(format!("constraint [c0] {e} = {rhs}"));
                    // A second `[c0]` is an error (labels are unique): the first stands.
                    if !constrained {
                        facts.insert("c0".into(), Fact::Constraint(e.clone(), on_q));
                    }
                    constrained = true;
                    if follow {
                        let lhs = if on_q { "q'' + q'" } else { "F" };
                        pending.push(one_link(lhs.into(), "=", e.clone(), None));
                    }
                }
                Stmt::Approx(k, digits, off) => {
                    let (text, v) = APPROX[k];
                    let d = digits as usize;
                    let ulp = 10f64.powi(-(digits as i32));
                    let c = match off {
                        0 => v + ulp,
                        _ => v,
                    };
                    let written = format!("{c:.d$}");
                    let value: f64 = written.parse().unwrap_or(v);
                    pending.push(Claim {
                        chain: vec![format!("({text}) a x"), format!("{written} a x")],
                        rels: vec![Rel {
                            op: "~=",
                            approx: Some((value, ulp / 2.0)),
                        }],
                        by: vec![None],
                        where_: None,
                    });
                }
                Stmt::Claim(c) => pending.push(c),
                Stmt::Prose(e) => lines.push(format!("> prose with ${e}$ inside")),
                Stmt::Comment => lines.push("% a comment".into()),
                Stmt::Noise(s) => lines.push(s.replace('\n', " ")),
            }
            for c in pending.drain(..) {
                let line = lines.len() + 1;
                let mut first = format!("claim {} {} {}", c.chain[0], c.rels[0].op, c.chain[1]);
                if let Some(b) = &c.by[0] {
                    first.push(' ');
                    first.push_str(b);
                }
                lines.push(first);
                for (i, e) in c.chain.iter().enumerate().skip(2) {
                    let mut l = format!("  {} {e}", c.rels[i - 1].op);
                    if let Some(b) = &c.by[i - 1] {
                        l.push(' ');
                        l.push_str(b);
                    }
                    lines.push(l);
                }
                if let Some(w) = &c.where_ {
                    lines.push(format!("  where {w}"));
                }
                claims.push((line, c));
            }
        }
        let mut text = lines.join("\n");
        text.push('\n');
        GenFile {
            text,
            claims,
            lets,
            facts,
        }
    })
}

// ---------------------------------------------------------------- the oracle

/// A point: a value for every declared symbol (respecting the declared signs), for
/// `q`, `q'`, `q''` and for the unknown `F`.
fn point() -> impl Strategy<Value = Vec<f64>> {
    let pos = (1i64..=40).prop_map(|k| k as f64 / 8.0 + 0.0371);
    let real = (-40i64..=40).prop_map(|k| k as f64 / 8.0 - 0.0137);
    (
        prop::collection::vec(pos, POSITIVE.len()),
        prop::collection::vec(real, REAL.len() + 4),
    )
        .prop_map(|(p, r)| p.into_iter().chain(r).collect())
}

/// The names of a point's values, in order.
const POINT_NAMES: &[&str] = &["a", "b", "x", "y", "q", "q'", "q''", "F"];

/// What the oracle knows about a generated file: its definitions and body as written,
/// for the independent evaluator.
fn guard_env(g: &GenFile) -> GuardEnv {
    let opts = ParseOptions::default();
    let mut env = GuardEnv::default();
    env.time.insert("q".into());
    for (name, e) in &g.lets {
        if let Ok(x) = parse_expr(e, &opts) {
            env.defs.insert(name.clone(), x);
        }
    }
    if let Ok(f) = parse_file(&format!("{BODY}\n"), &opts) {
        for item in f.items {
            if let Item::Stmt(Stmt_ {
                kind: StmtKind::Body { name, def },
                ..
            }) = item
            {
                env.bodies.insert(name.name, def);
            }
        }
    }
    env
}

/// The independent value of `src` at `pt`, `None` where the guard cannot evaluate it
/// (undefined there, an antiderivative, a time symbol at another instant).
fn value(src: &str, env: &GuardEnv, pt: &HashMap<String, f64>) -> Option<Ball> {
    let e = parse_expr(src, &ParseOptions::default()).ok()?;
    guard::eval(&e, env, pt).ok()
}

/// The point with a claim's `where` values put in: `None` if a value cannot be
/// evaluated.
fn with_where(
    pt: &HashMap<String, f64>,
    w: Option<&str>,
    env: &GuardEnv,
) -> Option<HashMap<String, f64>> {
    let mut out = pt.clone();
    let Some(w) = w else {
        return Some(out);
    };
    for assign in w.split(", ") {
        let (name, v) = assign.split_once(" = ")?;
        out.insert(name.to_string(), value(v, env, pt)?.mid);
    }
    Some(out)
}

fn close(a: &Ball, b: &Ball) -> bool {
    !a.clearly_differs(b)
}

/// The point made to satisfy the facts a link used (the unknown `F` and `q'`, `q''`
/// set from them), `None` if it cannot be: a fact that is not the generator's, a claim
/// used as a fact that does not hold there, facts that disagree.
fn satisfy(
    g: &GenFile,
    used: &[FactRef],
    env: &GuardEnv,
    mut pt: HashMap<String, f64>,
) -> Option<HashMap<String, f64>> {
    let mut checks: Vec<(String, String)> = Vec::new();
    let mut f_set = false;
    for fact in used {
        let label = match fact {
            FactRef::Label(l) => l.as_str(),
            FactRef::Line(line) => {
                // An earlier verified claim: every element of its chain equal there.
                let (_, c) = g.claims.iter().find(|(l, _)| l == line)?;
                if c.where_.is_some() || c.rels.iter().any(|r| r.op != "=") {
                    return None;
                }
                for e in &c.chain[1..] {
                    checks.push((c.chain[0].clone(), e.clone()));
                }
                continue;
            }
        };
        match g.facts.get(label)? {
            Fact::Given(l, r) => {
                let f = value(&format!("({r}) - ({l})"), env, &pt)?;
                if f_set {
                    checks.push((format!("F + {l}"), r.clone()));
                } else {
                    pt.insert("F".into(), f.mid);
                    f_set = true;
                }
            }
            Fact::Constraint(e, true) => {
                let v = value(e, env, &pt)?;
                pt.insert("q'".into(), v.mid);
                pt.insert("q''".into(), 0.0);
                pt.insert("q'''".into(), 0.0);
            }
            Fact::Constraint(e, false) => {
                let v = value(e, env, &pt)?;
                if f_set {
                    checks.push((e.clone(), "F".into()));
                } else {
                    pt.insert("F".into(), v.mid);
                    f_set = true;
                }
            }
        }
    }
    for (l, r) in &checks {
        let (a, b) = (value(l, env, &pt)?, value(r, env, &pt)?);
        if !close(&a, &b) || a.rad > 1e-9 * a.mid.abs().max(1.0) {
            return None;
        }
    }
    Some(pt)
}

/// Whether a verified `lhs rel rhs` is consistent with the values `a`, `b` of its sides.
fn consistent(rel: &Rel, a: &Ball, b: &Ball) -> bool {
    let scale = a.mid.abs().max(b.mid.abs()).max(1.0);
    let sharp = a.rad + b.rad < 1e-12 * scale;
    match rel.op {
        "=" => close(a, b),
        "<" | "<=" => !(a.mid > b.mid && a.clearly_differs(b)),
        ">" | ">=" => !(a.mid < b.mid && a.clearly_differs(b)),
        // Verified `!=`: the sides differ wherever the signs allow.
        "!=" => !(sharp && (a.mid - b.mid).abs() <= 1e-12 * scale),
        _ => {
            // `~=`: c·A/B rounds to c at the precision written.
            let Some((c, half)) = rel.approx else {
                return true;
            };
            if !sharp || b.mid == 0.0 {
                return true;
            }
            (c * a.mid / b.mid - c).abs() <= half * (1.0 + 1e-9) + 1e-9
        }
    }
}

/// Checks `text` and asserts: no panic (the test harness catches it); every verified
/// link, whatever its justification, holds at the point (made to satisfy the facts the
/// link used, with the claim's `where` values), both sides evaluated independently of
/// the engine, from the syntax tree; the printed normal forms have the sides' values;
/// and the guard never had to withdraw a verification.
fn check_and_validate(g: &GenFile, pt: &[f64]) -> Result<(), TestCaseError> {
    let opts = Options {
        timeout: Duration::from_secs(2),
        ..Options::default()
    };
    let report = check_source("generated.deriv", &g.text, &opts, &MemoryResolver::new());
    // Rendering must not panic either.
    let _ = rigor::render::human::report(&report, true);
    let _ = rigor::render::json::report(&report);
    let env = guard_env(g);
    let base: HashMap<String, f64> = POINT_NAMES
        .iter()
        .zip(pt)
        .map(|(n, v)| (n.to_string(), *v))
        .collect();
    for c in &report.claims {
        let Some((_, gen)) = g.claims.iter().find(|(line, _)| *line == c.line) else {
            continue;
        };
        if c.links.len() + 1 != gen.chain.len() {
            continue;
        }
        for (i, link) in c.links.iter().enumerate() {
            if link.status == Status::Undecided {
                let withdrawn = report.diagnostics.iter().any(|d| {
                    d.code.as_str() == "E0903"
                        && d.primary.as_ref().is_some_and(|p| p.0 == link.span)
                });
                prop_assert!(
                    !withdrawn,
                    "the engine verified link {} of line {}, but its guard found the sides differ:\n{}",
                    i + 1,
                    c.line,
                    g.text
                );
            }
            let Status::Verified { how, .. } = &link.status else {
                continue;
            };
            let used: &[FactRef] = match how {
                Justification::Facts(f) | Justification::Signs(f) => f,
                _ => &[],
            };
            let Some(at) = with_where(&base, gen.where_, &env) else {
                continue;
            };
            let Some(at) = satisfy(g, used, &env, at) else {
                continue;
            };
            let (l, r) = (&gen.chain[i], &gen.chain[i + 1]);
            let (Some(lv), Some(rv)) = (value(l, &env, &at), value(r, &env, &at)) else {
                continue;
            };
            let rel = &gen.rels[i];
            prop_assert!(
                consistent(rel, &lv, &rv),
                "verified ({how}), but at {at:?} `{l}` = {lv:?} and `{r}` = {rv:?}\n{}",
                g.text
            );
            // The printed normal forms have the same value (as written, before `where`).
            if gen.where_.is_some() || rel.op != "=" {
                continue;
            }
            for (printed, side, v) in [(&link.lhs, l, &lv), (&link.rhs, r, &rv)] {
                let Some(p) = printed else { continue };
                if let Some(pv) = value(p, &env, &at) {
                    prop_assert!(
                        close(&pv, v),
                        "normal form `{p}` of `{side}` is {pv:?} at {at:?}, the source {v:?}\n{}",
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
        let _deadline = rigor::normal::limits::until(rigor::clock::Deadline::after(
            Duration::from_millis(500),
            rigor::clock::system(),
        ));
        let _ = lower(&e, &Env::default());
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
}

proptest! {
    #![proptest_config(crate::config(256))]

    #[test]
    fn verified_links_hold_at_a_point(g in file(), pt in point()) {
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
    fn long_verified_links_hold_at_a_point(g in file(), pt in point()) {
        check_and_validate(&g, &pt)?;
    }
}
