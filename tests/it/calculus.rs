//! Calculus: the integrals, derivatives, `eval` and `subs` of
//! `tests/data/integrals.txt` as one "written ⇒ exact result" snapshot, the
//! library functions called directly, and the cases that must be errors.

use crate::normal::{data_path, env_with, norm, norm_in};
use rigor::calculus::{antiderivative, definite, diff, Wrt};
use rigor::lower::{build_body, Env};
use rigor::normal::atom;
use rigor::normal::print::plain;
use rigor::normal::Assumptions;
use rigor::syntax::ast::{Item, StmtKind};
use rigor::syntax::{parse_file, ParseOptions};

/// Adds the body declared by `def` (`rod: dm = …`) to `env`.
fn add_body(env: &mut Env, def: &str) -> Result<(), String> {
    let src = format!("body {def}");
    let file = parse_file(&src, &ParseOptions::default()).map_err(|e| format!("syntax: {e}"))?;
    for item in file.items {
        if let Item::Stmt(s) = item {
            if let StmtKind::Body { name, def } = s.kind {
                let b = build_body(&name.name, &def, env).map_err(|e| e.to_string())?;
                env.bodies.insert(name.name, b);
            }
        }
    }
    Ok(())
}

/// The environment of a data line's fields after the expression.
fn env_of(fields: &[&str]) -> Result<Env, String> {
    let assume: Vec<&str> = fields
        .iter()
        .filter_map(|f| f.strip_prefix("assume:"))
        .collect();
    let mut env = env_with(&assume.join(";"));
    for f in fields {
        if let Some(t) = f.strip_prefix("time:") {
            env.time.extend(t.split_whitespace().map(String::from));
        }
    }
    for f in fields {
        if let Some(b) = f.strip_prefix("body:") {
            add_body(&mut env, b.trim())?;
        }
    }
    Ok(env)
}

/// `src` lowered with `fields` (`body: …`, `time: …`, `assume: …`), as plain text.
fn eval_line(src: &str, fields: &[&str]) -> Result<String, String> {
    let env = env_of(fields)?;
    norm_in(src, &env).map(|r| plain(&r))
}

#[test]
fn integrals() {
    let text = std::fs::read_to_string(data_path("integrals.txt")).unwrap();
    let mut out = String::new();
    for line in text.lines().map(str::trim) {
        if line.starts_with("# ---") {
            out.push_str(&format!("\n{line}\n"));
            continue;
        }
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line.split(";;").map(str::trim).collect();
        let result = match eval_line(fields[0], &fields[1..]) {
            Ok(r) => r,
            Err(e) => format!("error: {e}"),
        };
        out.push_str(&format!("{line}\n    ⇒ {result}\n"));
    }
    insta::assert_snapshot!(out.trim_start());
}

/// Asserts that `src` with `fields` gives `expected` (compared as normal forms).
#[track_caller]
fn check(src: &str, fields: &[&str], expected: &str) {
    let env = env_of(fields).unwrap();
    let got = norm_in(src, &env).unwrap_or_else(|e| panic!("{src}: {e}"));
    let want = norm_in(expected, &env).unwrap_or_else(|e| panic!("{expected}: {e}"));
    assert_eq!(plain(&got), plain(&want), "{src} with {fields:?}");
}

#[track_caller]
fn check_err(src: &str, fields: &[&str]) {
    if let Ok(r) = eval_line(src, fields) {
        panic!("{src} should be an error, got {r}");
    }
}

const ROD: &str = "body: rod: dm = m/L dy, y from -L/2 to L/2";
const BOX: &str = "body: box: dm = m/(a b c) dx dy dz, x from -a/2 to a/2, y from -b/2 to b/2, z from -c/2 to c/2";
const CORNER: &str =
    "body: box: dm = m/(a b c) dx dy dz, x from 0 to a, y from 0 to b, z from 0 to c";

#[test]
fn textbook_moments_of_inertia() {
    check("int(y^2, rod)", &[ROD], "m L^2/12");
    check("int(1, rod)", &[ROD], "m");
    check("int(y, rod)", &[ROD], "0");
    check(
        "int(y^2, rod)",
        &["body: rod: dm = m/L dy, y from 0 to L"],
        "m L^2/3",
    );
    // Parallel axis theorem, by integration.
    check("int((y + d)^2, rod)", &[ROD], "m L^2/12 + m d^2");
    check(
        "int(r^2, disk)",
        &["body: disk: dm = 2 m/R^2 r dr, r from 0 to R"],
        "m R^2/2",
    );
    check(
        "int(r^2, disk)",
        &["body: disk: dm = m/(pi R^2) 2 pi r dr, r from 0 to R"],
        "m R^2/2",
    );
    check("int(R^2 m/(2 pi), phi, 0, 2 pi)", &[], "m R^2");
    check(
        "int(pi rho (R^2 - z^2)^2/2, z, -R, R)/int(pi rho (R^2 - z^2), z, -R, R)",
        &[],
        "2 R^2/5",
    );
    check("int(pi rho (R^2 - z^2), z, -R, R)", &[], "4 pi rho R^3/3");
    check(
        "int(rho pi (R z/h)^4/2, z, 0, h)/int(rho pi (R z/h)^2, z, 0, h)",
        &[],
        "3 R^2/10",
    );
}

#[test]
fn box_inertia_tensor() {
    check("int(y^2 + z^2, box)", &[BOX], "m (b^2 + c^2)/12");
    check("int(x^2 + z^2, box)", &[BOX], "m (a^2 + c^2)/12");
    check("int(x^2 + y^2, box)", &[BOX], "m (a^2 + b^2)/12");
    for p in ["x y", "x z", "y z"] {
        check(&format!("int({p}, box)"), &[BOX], "0");
    }
    check("int(y^2 + z^2, box)", &[CORNER], "m (b^2 + c^2)/3");
    check("int(x^2 + z^2, box)", &[CORNER], "m (a^2 + c^2)/3");
    check("int(x^2 + y^2, box)", &[CORNER], "m (a^2 + b^2)/3");
    check("int(x y, box)", &[CORNER], "m a b/4");
    check("int(x z, box)", &[CORNER], "m a c/4");
    check("int(y z, box)", &[CORNER], "m b c/4");
}

#[test]
fn nested_bounds() {
    let plate = "body: plate: dm = rho dx dy, x from 0 to a, y from 0 to b x/a";
    check("int(1, plate)", &[plate], "rho a b/2");
    check("int(x, plate)/int(1, plate)", &[plate], "2 a/3");
    check("int(y, plate)/int(1, plate)", &[plate], "b/3");
    check("int(y^2, plate)", &[plate], "rho a b^3/12");
}

#[test]
fn time_integrals() {
    check("int(F_0 sin(pi t/T), t, 0, T)", &[], "2 F_0 T/pi");
    check("int(exp(-t/tau), t, 0, T)", &[], "tau (1 - exp(-T/tau))");
    check("int(x sin(x), x, 0, pi)", &[], "pi");
    check("int(cos(omega t), t, 0, pi/(2 omega))", &[], "1/omega");
}

#[test]
fn derivatives() {
    check("diff(x^2 sin(x), x)", &[], "2 x sin(x) + x^2 cos(x)");
    check("diff(x/(1 + x), x)", &[], "1/(1 + x)^2");
    check("diff(sqrt(1 + x^2), x)", &[], "x/sqrt(1 + x^2)");
    check("diff(exp(-x^2), x)", &[], "-2 x exp(-x^2)");
    check("diff(ln(x), x)", &[], "1/x");
    check("diff(tan(x), x)", &[], "1/cos(x)^2");
    check("diff(x, t)", &["time: x"], "x'");
    check("diff(x, t, 2)", &["time: x"], "x''");
    check("diff(x + theta R, t)", &["time: x theta"], "x' + theta' R");
    check("diff(sin(theta), t)", &["time: theta"], "cos(theta) theta'");
    // x is not a time symbol here: it is a constant.
    check("diff(x, t)", &[], "0");
}

#[test]
fn eval_and_subs() {
    check("eval(x^2/2, x, 0, L)", &[], "L^2/2");
    check("subs(m g sin(beta), beta, pi/6)", &[], "m g/2");
    check("subs(sqrt(x^2), x, -3)", &[], "3");
    check(
        "subs(m g sin(beta)/(m + I_G/R^2), I_G, m R^2/2)",
        &[],
        "2 g sin(beta)/3",
    );
}

#[test]
fn errors() {
    check_err("int(1/x, x, 1, 2)", &[]);
    check_err("int(sin(x^2), x, 0, 1)", &[]);
    check_err("int(x, x, 0, x)", &[]);
    check_err("diff(x^2, 2)", &[]);
    check_err("int(y^2, rod)", &["body: rod: dm = m/L dy, y from 0 to y"]);
    check_err("int(y^2, rod)", &["body: rod: dm = m/L, y from 0 to L"]);
    check_err(
        "int(y, dm)",
        &[ROD, "body: rod2: dm = m/L dy, y from 0 to L"],
    );
}

#[test]
fn library_calls() {
    let s = Assumptions::new();
    let x = atom::sym("x");
    let p = norm("3 x^2 + 2 a x + 1");
    let big_p = antiderivative(&p, x, &s).unwrap();
    assert_eq!(plain(&big_p), plain(&norm("x^3 + a x^2 + x")));
    let wrt = Wrt { var: x, time: None };
    assert_eq!(plain(&diff(&big_p, &wrt, &s).unwrap()), plain(&p));
    let d = definite(&p, x, &norm("0"), &norm("1"), &s).unwrap();
    assert_eq!(plain(&d), plain(&norm("2 + a")));
    assert!(antiderivative(&norm("1/x"), x, &s).is_err());
    assert!(antiderivative(&norm("sin(x^2)"), x, &s).is_err());
    assert!(antiderivative(&norm("exp(x^2)"), x, &s).is_err());
}
