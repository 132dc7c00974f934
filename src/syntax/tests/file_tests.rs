//! File tests: every line kind and statement, continuation lines, comments, prose, `by` and
//! `where`, spans, and the errors of each.

use super::{assert_err, at, chain_sexpr, sexpr};
use crate::syntax::ast::{Assign, BodyDef, By, Item, Label, Name, ProsePart, SignDecl, StmtKind};
use crate::syntax::{parse_file, ParseOptions, SyntaxErrorKind};

/// `[a],[b]` for labels.
fn labels(ls: &[Label]) -> String {
    ls.iter()
        .map(|l| format!("[{}]", l.name))
        .collect::<Vec<_>>()
        .join(",")
}

/// `a b c` for names.
fn names(ns: &[Name]) -> String {
    ns.iter()
        .map(|n| n.name.as_str())
        .collect::<Vec<_>>()
        .join(" ")
}

/// `x=(/ L 2),…` for substitutions.
fn assigns(a: &[Assign]) -> String {
    a.iter()
        .map(|a| format!("{}={}", a.name.name, sexpr(&a.value)))
        .collect::<Vec<_>>()
        .join(",")
}

/// ` [label]` or nothing.
fn opt_label(l: &Option<Label>) -> String {
    l.as_ref()
        .map_or(String::new(), |l| format!(" [{}]", l.name))
}

/// One line per item, compact.
fn show(src: &str) -> String {
    let file = match parse_file(src, &ParseOptions::default()) {
        Ok(f) => f,
        Err(e) => panic!("{src:?} failed: {e}"),
    };
    let lines: Vec<String> = file.items.iter().map(item).collect();
    lines.join("\n")
}

/// The compact form of one item.
fn item(i: &Item) -> String {
    match i {
        Item::Heading { level, text, .. } => format!("(h{level} {text})"),
        Item::Prose { parts, .. } => {
            let parts: Vec<String> = parts
                .iter()
                .map(|p| match p {
                    ProsePart::Text(t) => format!("{t:?}"),
                    ProsePart::Math(c) => format!("${}$", chain_sexpr(c)),
                    ProsePart::MathExpr(e) => format!("${}$", sexpr(e)),
                })
                .collect();
            format!("(prose {})", parts.join(" "))
        }
        Item::Stmt(s) => match &s.kind {
            StmtKind::Symbols { names: ns, sign } => {
                let sign = match sign {
                    SignDecl::Any => "",
                    SignDecl::Positive => " >0",
                    SignDecl::Nonnegative => " >=0",
                    SignDecl::Nonzero => " !=0",
                };
                format!("(symbols {}{sign})", names(ns))
            }
            StmtKind::Range {
                names: ns,
                lo,
                lo_strict,
                hi,
                hi_strict,
            } => {
                let op = |s: &bool| if *s { "<" } else { "<=" };
                format!(
                    "(range {} {} {} {} {})",
                    sexpr(lo),
                    op(lo_strict),
                    names(ns),
                    op(hi_strict),
                    sexpr(hi)
                )
            }
            StmtKind::Small { names: ns, order } => format!("(small {} {order})", names(ns)),
            StmtKind::Result { labels: ls } => format!("(result {})", labels(ls)),
            StmtKind::Time { names: ns } => format!("(time {})", names(ns)),
            StmtKind::Unknowns { names: ns } => format!("(unknowns {})", names(ns)),
            StmtKind::Units { decls } => {
                let d: Vec<String> = decls
                    .iter()
                    .map(|d| format!("{}:{}", d.name.name, d.unit))
                    .collect();
                format!("(units {})", d.join(" "))
            }
            StmtKind::Body {
                name,
                def: BodyDef::Concrete { dm, ranges },
            } => {
                let r: Vec<String> = ranges
                    .iter()
                    .map(|r| format!(" {}:[{} .. {}]", r.var.name, sexpr(&r.from), sexpr(&r.to)))
                    .collect();
                format!("(body {} dm={}{})", name.name, sexpr(dm), r.concat())
            }
            StmtKind::Body {
                name,
                def:
                    BodyDef::Abstract {
                        mass,
                        coords,
                        centred,
                    },
            } => {
                let c = if *centred { " centred" } else { "" };
                format!(
                    "(body {} mass={} coords {}{c})",
                    name.name,
                    sexpr(mass),
                    names(coords)
                )
            }
            StmtKind::Let { name, value } => format!("(let {} {})", name.name, sexpr(value)),
            StmtKind::Given { label, chain } => {
                format!("(given{} {})", opt_label(label), chain_sexpr(chain))
            }
            StmtKind::Constraint { label, chain } => {
                format!("(constraint{} {})", opt_label(label), chain_sexpr(chain))
            }
            StmtKind::Claim {
                label,
                chain,
                where_,
            } => {
                let w = if where_.is_empty() {
                    String::new()
                } else {
                    format!(" where {}", assigns(where_))
                };
                format!("(claim{} {}{w})", opt_label(label), chain_sexpr(chain))
            }
            StmtKind::Use {
                labels: ls,
                path,
                with,
                ..
            } => {
                let w = if with.is_empty() {
                    String::new()
                } else {
                    format!(" with {}", assigns(with))
                };
                format!("(use {} {path:?}{w})", labels(ls))
            }
        },
    }
}

/// Asserts that `src` parses to the items `expected` (one per line).
#[track_caller]
fn check_file(src: &str, expected: &str) {
    assert_eq!(show(src), expected.trim(), "input:\n{src}");
}

/// Asserts that `src` fails with `message` at `span`.
#[track_caller]
fn check_file_err(src: &str, message: &str, span: &str) {
    match parse_file(src, &ParseOptions::default()) {
        Ok(f) => panic!("{src:?} parsed: {f:?}"),
        Err(e) => assert_err(src, &e, message, span),
    }
}

#[test]
fn declarations() {
    check_file("symbols m L g > 0", "(symbols m L g >0)");
    check_file(
        "symbols a b >= 0\nsymbols c ≥ 0\nsymbols d != 0\nsymbols e ≠ 0",
        "(symbols a b >=0)\n(symbols c >=0)\n(symbols d !=0)\n(symbols e !=0)",
    );
    check_file("symbols β θ_G, k_G", "(symbols beta theta_G k_G)");
    check_file("time x theta", "(time x theta)");
    check_file("unknowns F N x''", "(unknowns F N x'')");
    check_file("units m: kg, L: m, g: m/s^2", "(units m:kg L:m g:m/s^2)");
    check_file(
        "units m: kg m^2 % a comment\n  , F: kg m/s^2",
        "(units m:kg m^2 F:kg m/s^2)",
    );
    check_file(
        "let I_G = int(y^2, rod)",
        "(let I_G (call int (^ y 2) rod))",
    );
}

#[test]
fn ranges_small_quantities_and_results() {
    check_file("symbols 0 < beta < pi/2", "(range 0 < beta < (/ pi 2))");
    check_file("symbols -1 <= x, y < a", "(range (- 1) <= x y < a)");
    check_file("symbols m g > 0", "(symbols m g >0)");
    check_file("small theta", "(small theta 1)");
    check_file("small theta, phi to order 2", "(small theta phi 2)");
    check_file("result [xdd], [N]", "(result [xdd],[N])");
    for bad in [
        "symbols 0 < beta",
        "small theta to order 9",
        "small theta to",
        "result",
    ] {
        assert!(parse_file(bad, &ParseOptions::default()).is_err(), "{bad}");
    }
}

#[test]
fn bodies() {
    check_file(
        "body rod: dm = m/L dy, y from -L/2 to L/2",
        "(body rod dm=(* (/ m L) dy) y:[(/ (- L) 2) .. (/ L 2)])",
    );
    check_file(
        "body plate: dm = rho dx dy, x from 0 to a,\n    y from 0 to b x/a",
        "(body plate dm=(* (* rho dx) dy) x:[0 .. a] y:[0 .. (/ (* b x) a)])",
    );
    check_file(
        "body B: mass m, coordinates x y, centred",
        "(body B mass=m coords x y centred)",
    );
    check_file(
        "body B: mass 2 m, coordinates x, centered",
        "(body B mass=(* 2 m) coords x centred)",
    );
    check_file(
        "body B: mass m, coordinates x y",
        "(body B mass=m coords x y)",
    );
}

#[test]
fn facts_and_claims() {
    check_file(
        "given [Fx] F - m g sin(beta) = m x''",
        "(given [Fx] (- F (* (* m g) (call sin beta))) = (* m x''))",
    );
    check_file("given N = m g", "(given N = (* m g))");
    check_file(
        "constraint [noslip] x = -theta R",
        "(constraint [noslip] x = (* (- theta) R))",
    );
    check_file(
        "claim [a.1-b'] k_G ~= 0.71 R",
        "(claim [a.1-b'] k_G ~= (* 71/100 R))",
    );
    check_file("claim x > 0", "(claim x > 0)");
    check_file(
        "claim [IG] I_G = int(y^2, rod)\n  = int(y^2 m/L, y, -L/2, L/2)   by definition of dm\n  = m L^2/12                     by [Fx], [MG]\n",
        "(claim [IG] I_G = (call int (^ y 2) rod) = (call int (/ (* (^ y 2) m) L) y (/ (- L) 2) (/ L 2)) by'definition of dm' = (/ (* m (^ L 2)) 12) by[Fx,MG])",
    );
    check_file(
        "claim a = b by [x] and [y], and [z]",
        "(claim a = b by[x,y,z])",
    );
    check_file(
        "claim a = b by [x] applied twice",
        "(claim a = b by'[x] applied twice')",
    );
    check_file(
        "claim a = b by algebra % not by magic\n  = c",
        "(claim a = b by'algebra' = c)",
    );
}

#[test]
fn where_and_use() {
    check_file(
        "claim [s] T = m g where beta = pi/2",
        "(claim [s] T = (* m g) where beta=(/ pi 2))",
    );
    check_file(
        "claim T = m g by [Fx] where beta = pi/2, I_G = m R^2/2",
        "(claim T = (* m g) by[Fx] where beta=(/ pi 2),I_G=(/ (* m (^ R 2)) 2))",
    );
    check_file(
        "claim T = m g by statics where nothing moves\n  where x' = 0",
        "(claim T = (* m g) by'statics where nothing moves' where x'=0)",
    );
    check_file(
        "claim T = m g by resolving where theta = 0",
        "(claim T = (* m g) by'resolving' where theta=0)",
    );
    check_file(
        "claim a = b by looking where it is\n  = c",
        "(claim a = b by'looking where it is' = c)",
    );
    check_file(
        "claim a = b\n  where b = a,\n    c = 1",
        "(claim a = b where b=a,c=1)",
    );
    check_file("use [IO] from \"rod.deriv\"", "(use [IO] \"rod.deriv\")");
    check_file(
        "use [IO], [IG] and [k] from \"../a b.deriv\" with d = L/2, m = 2 M",
        "(use [IO],[IG],[k] \"../a b.deriv\" with d=(/ L 2),m=(* 2 M))",
    );
}

#[test]
fn lines_comments_headings_prose() {
    let src = "\
# Rod on a hinge
% a comment
## Setup   

symbols m L % mass and length
  % a comment inside
  , g > 0
> The rod has mass $m$ and length $L$; we show $I_G = m L^2/12$.
> 100% sure, no math here
### Done
";
    check_file(
        src,
        r#"
(h1 Rod on a hinge)
(h2 Setup)
(symbols m L g >0)
(prose "The rod has mass " $m$ " and length " $L$ "; we show " $I_G = (/ (* m (^ L 2)) 12)$ ".")
(prose "100% sure, no math here")
(h3 Done)
"#,
    );
    check_file("", "");
    check_file("\n\n  \n% only comments\n   % indented\n", "");
    check_file("symbols m\r\nlet a = m\r\n", "(symbols m)\n(let a m)");
    check_file(">$x$", "(prose $x$)");
}

#[test]
fn spans() {
    let src = "% intro\nclaim [IG] I_G = a  % note\n   = b by [Fx], [MG]  % why\n\nlet k = 2";
    let file = parse_file(src, &ParseOptions::default()).expect("parses");
    let Some(Item::Stmt(claim)) = file.items.first() else {
        panic!("{file:?}")
    };
    assert_eq!(
        at(src, claim.span),
        "claim [IG] I_G = a  % note\n   = b by [Fx], [MG]"
    );
    let StmtKind::Claim {
        label: Some(label),
        chain,
        ..
    } = &claim.kind
    else {
        panic!("{claim:?}")
    };
    assert_eq!(at(src, label.span), "[IG]");
    assert_eq!(at(src, chain.first.span), "I_G");
    let links: Vec<&str> = chain.links.iter().map(|l| at(src, l.span)).collect();
    assert_eq!(links, ["= a", "= b by [Fx], [MG]"]);
    let Some((By::Labels(ls), by_span)) = &chain.links.get(1).and_then(|l| l.by.clone()) else {
        panic!()
    };
    assert_eq!(at(src, *by_span), "by [Fx], [MG]");
    assert_eq!(
        ls.iter().map(|l| at(src, l.span)).collect::<Vec<_>>(),
        ["[Fx]", "[MG]"]
    );
    let Some(Item::Stmt(k)) = file.items.get(1) else {
        panic!("{file:?}")
    };
    assert_eq!(at(src, k.span), "let k = 2");

    let src = "# T\n> so $a + b$ holds";
    let file = parse_file(src, &ParseOptions::default()).expect("parses");
    let Some(Item::Prose { parts, span }) = file.items.get(1) else {
        panic!("{file:?}")
    };
    assert_eq!(at(src, *span), "> so $a + b$ holds");
    let Some(ProsePart::MathExpr(e)) = parts.get(1) else {
        panic!("{parts:?}")
    };
    assert_eq!(at(src, e.span), "a + b");

    let src = "units g: m/s^2 , L: m\nuse [a] from \"x.deriv\"";
    let file = parse_file(src, &ParseOptions::default()).expect("parses");
    let Some(Item::Stmt(u)) = file.items.first() else {
        panic!()
    };
    let StmtKind::Units { decls } = &u.kind else {
        panic!()
    };
    assert_eq!(
        decls
            .iter()
            .map(|d| at(src, d.unit_span))
            .collect::<Vec<_>>(),
        ["m/s^2", "m"]
    );
    let Some(Item::Stmt(u)) = file.items.get(1) else {
        panic!()
    };
    let StmtKind::Use { path_span, .. } = &u.kind else {
        panic!()
    };
    assert_eq!(at(src, *path_span), "\"x.deriv\"");
}

#[test]
fn line_errors() {
    let stmt = "expected a statement (symbols, time, unknowns, units, body, let, given, constraint, claim, use), a heading `#`, prose `>` or a comment `%`";
    check_file_err("symbols m\nfoo bar", stmt, "10..13");
    check_file_err("Claim x = 1", stmt, "0..5");
    check_file_err("symbols m\n= x", stmt, "10..11");
    check_file_err(
        "  x = 1",
        "an indented line continues a statement, but there is none above it; start statements at the beginning of the line",
        "2..7",
    );
    check_file_err(
        "# T\n  claim x = 1",
        "an indented line continues a statement, but the line above is a heading or prose; start statements at the beginning of the line",
        "6..17",
    );
    check_file_err("> price $5 only", "unclosed `$`", "8..9");
    check_file_err("> so $a +$ ok", "expected an expression after `+`", "9..9");
    check_file_err("> so $$", "expected an expression after `$`", "6..6");
    check_file_err("> so $a = b c)$", "unmatched `)`", "13..14");
    check_file_err(
        "> so $a by b$",
        "expected an operator, a relation or the closing `$`, found `by`",
        "8..10",
    );
}

#[test]
fn statement_errors() {
    check_file_err(
        "claim [a] x =",
        "expected an expression after `=`",
        "13..13",
    );
    check_file_err(
        "claim [a] x = % nothing\n",
        "expected an expression after `=`",
        "13..13",
    );
    check_file_err(
        "claim a = b where % c = 1\n  % d = 2\n",
        "expected a symbol name after `where`, found the end of the statement",
        "17..17",
    );
    check_file_err(
        "claim [a] x =\n  = y",
        "expected an expression after `=`, found `=`",
        "16..17",
    );
    check_file_err(
        "body rod dm = m/L dy, y from 0 to L",
        "expected `:` after the body name, found `dm`",
        "9..11",
    );
    check_file_err(
        "symbols",
        "expected a symbol name after `symbols`, found the end of the statement",
        "7..7",
    );
    check_file_err(
        "symbols m > 1",
        "expected `0` after `>`: signs are `> 0`, `>= 0` or `!= 0`, found `1`",
        "12..13",
    );
    check_file_err("symbols m < 0", "expected a symbol name, a sign (`> 0`, `>= 0`, `!= 0`) or the end of the statement, found `<`", "10..11");
    check_file_err(
        "symbols sin",
        "expected a symbol name after `symbols`, found the function `sin`",
        "8..11",
    );
    check_file_err(
        "symbols pi",
        "expected a symbol name after `symbols`, found the constant `pi`",
        "8..10",
    );
    check_file_err(
        "time x'",
        "expected a symbol name after `time`, found `x'`: primes mark time derivatives",
        "5..7",
    );
    check_file_err(
        "units m kg",
        "expected `:` after `m`, as in `units m: kg`, found `kg`",
        "8..10",
    );
    check_file_err(
        "units m:",
        "expected a unit after `m:`, such as `kg` or `m/s^2`, found the end of the statement",
        "8..8",
    );
    check_file_err(
        "body rod: dm = m/L dy",
        "expected an operator, or `,` and the range of a coordinate as in `dm = m/L dy, y from -L/2 to L/2`, found the end of the statement",
        "21..21",
    );
    check_file_err(
        "body rod: dm = m/L dy, y to L",
        "expected `from` after the coordinate `y`, found `to`",
        "25..27",
    );
    check_file_err(
        "body rod: dm = m/L dy, y from 0 L",
        "expected an operator or `to` in the range of `y`, found the end of the statement",
        "33..33",
    );
    check_file_err(
        "body rod: dm m/L dy",
        "expected `=` after `dm`, found `m`",
        "13..14",
    );
    check_file_err(
        "body B: volume V",
        "expected `dm = …` or `mass …` after `body B:`, found `volume`",
        "8..14",
    );
    check_file_err(
        "body B: mass m",
        "expected an operator, or `, coordinates …` after the mass, found the end of the statement",
        "14..14",
    );
    check_file_err(
        "body B: mass m, coordinates x, center",
        "expected `centred` after `,`, found `center`",
        "31..37",
    );
    check_file_err("let x 2", "expected `=` after `let x`, found `2`", "6..7");
    check_file_err("let = 2", "expected a name after `let`, found `=`", "4..5");
    check_file_err("let x = 2 y)", "unmatched `)`", "11..12");
    check_file_err("given [Fx] F", "expected an operator or a relation (`=`, `!=`, `<`, `<=`, `>`, `>=`, `~=`), found the end of the statement", "12..12");
    check_file_err(
        "given [F x] a = b",
        "unexpected ` ` in a label: labels hold letters, digits, `_`, `-`, `.` and `'`",
        "8..9",
    );
    check_file_err("given [Fx a = b", "unclosed `[`", "6..7");
    check_file_err(
        "given [] a = b",
        "expected a label name between `[` and `]`",
        "6..8",
    );
    check_file_err("given [a]", "expected an expression after `[a]`", "9..9");
    check_file_err(
        "given a = b where c = 1",
        "expected an operator, a relation, `by` or the end of the statement, found `where`",
        "12..17",
    );
    check_file_err(
        "claim a = b where",
        "expected a symbol name after `where`, found the end of the statement",
        "17..17",
    );
    check_file_err(
        "claim a = b where c 1",
        "expected `=` after `c`, found `1`",
        "20..21",
    );
    check_file_err(
        "claim a = b where c = 1, ",
        "expected a symbol name after `,`, found the end of the statement",
        "24..24",
    );
    check_file_err(
        "claim a = b by",
        "expected a justification after `by`: `by [label], …` or `by some words`",
        "14..14",
    );
    check_file_err("claim a = (b\n  = c", "expected `)`, found `=`", "15..16");
    check_file_err("claim a = (b", "unclosed `(`", "10..11");
    check_file_err(
        "claim x = sin x",
        "`sin` needs its argument in parentheses: sin(…)",
        "10..13",
    );
    check_file_err(
        "given [a] x = y\n  z = w",
        "expected an operator, a relation, `by` or the end of the statement, found `z`",
        "18..19",
    );
    check_file("given [a] x = y\n  + z", "(given [a] x = (+ y z))");
    check_file("given [a] x = y *\n  z", "(given [a] x = (* y z))");
    check_file_err(
        "given F = f(x)",
        "unknown function f; write f*(x) or f (x) for a product",
        "10..11",
    );
    check_file_err(
        "use IO from \"x\"",
        "expected a label such as `[IO]` after `use`, found `IO`",
        "4..6",
    );
    check_file_err(
        "use [IO] \"x\"",
        "expected `,` and another label, or `from \"file.deriv\"`, found `\"`",
        "9..10",
    );
    check_file_err(
        "use [IO] from x.deriv",
        "expected a quoted path after `from`, as in `from \"rod.deriv\"`, found `x`",
        "14..15",
    );
    check_file_err("use [IO] from \"x.deriv", "unclosed `\"`", "14..15");
    check_file_err(
        "use [IO] from \"x\" with",
        "expected a symbol name after `with`, found the end of the statement",
        "22..22",
    );
    check_file_err(
        "use [IO], from \"x\"",
        "expected a label `[…]`, found `from`",
        "10..14",
    );
}

#[test]
fn deep_nesting_in_a_file() {
    let src = format!("claim x = {}", "(".repeat(1_000_000));
    let e = parse_file(&src, &ParseOptions::default()).expect_err("too deep");
    assert_eq!(e.kind, SyntaxErrorKind::NestingLimit);
    assert_eq!((e.span.start, e.span.end), (210, 211));
    let src = format!("> ${}$", "-".repeat(1_000_000));
    let e = parse_file(&src, &ParseOptions::default()).expect_err("too deep");
    assert_eq!(e.kind, SyntaxErrorKind::NestingLimit);
    // LaTeX between `$$` on a claim line has the same limit.
    let src = format!("claim [x] $$x = {}$$", "(".repeat(1_000));
    let e = parse_file(&src, &ParseOptions::default()).expect_err("too deep");
    assert_eq!(e.kind, SyntaxErrorKind::NestingLimit, "{}", e.message);
    let src = format!("claim [x] x = {}", vec!["x"; 1_000_000].join(" + "));
    let e = parse_file(&src, &ParseOptions::default()).expect_err("too large");
    assert_eq!(e.kind, SyntaxErrorKind::TooLarge, "{}", e.message);
    for src in ["claim [x] x = ", "frobnicate x", "> $x"] {
        let e = parse_file(src, &ParseOptions::default()).expect_err(src);
        assert_eq!(e.kind, SyntaxErrorKind::Other, "{src}: {}", e.message);
    }
}

#[test]
fn comparing_coefficients_is_labels_and_a_name() {
    let link = |src: &str| {
        let file = parse_file(src, &ParseOptions::default()).expect("parses");
        let Some(Item::Stmt(claim)) = file.items.first() else {
            panic!("{file:?}")
        };
        let StmtKind::Claim { chain, .. } = &claim.kind else {
            panic!("{claim:?}")
        };
        chain.links.last().cloned().expect("a link")
    };
    let src = "claim [w] w^2 = k/I by [eom], [shm] comparing coefficients of θ  % why";
    let l = link(src);
    let Some((By::Labels(ls), by_span)) = &l.by else {
        panic!("{l:?}")
    };
    assert_eq!(
        at(src, *by_span),
        "by [eom], [shm] comparing coefficients of θ"
    );
    assert_eq!(
        ls.iter().map(|l| l.name.as_str()).collect::<Vec<_>>(),
        ["eom", "shm"]
    );
    let name = l.compare.expect("a name compared");
    assert_eq!((name.name.as_str(), at(src, name.span)), ("theta", "θ"));
    // Before `where`, too.
    let l = link("claim [w] w^2 = k/I by [eom] comparing coefficients of x where k = 2");
    assert_eq!(l.compare.map(|n| n.name), Some("x".to_string()));
    // Anything else after the labels is words.
    for words in [
        "by [eom] comparing coefficients",
        "by [eom] comparing coefficients of x and y",
        "by [eom] comparing terms of x",
        "by comparing coefficients of x",
    ] {
        let l = link(&format!("claim a = b {words}"));
        assert!(matches!(l.by, Some((By::Text(_), _))), "{words}: {l:?}");
        assert_eq!(l.compare, None, "{words}");
    }
}
