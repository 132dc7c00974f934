//! Tests of the guard: integrals, derivatives and bodies evaluated in ball arithmetic, odd
//! and even roots, identities under cancellation, what it skips, and its depth budget.

use super::*;
use crate::syntax::{parse_expr, parse_file, ParseOptions};

fn e(s: &str) -> Expr {
    parse_expr(s, &ParseOptions::default()).unwrap_or_else(|err| panic!("{s}: {err}"))
}

fn at(pairs: &[(&str, f64)]) -> HashMap<String, f64> {
    pairs.iter().map(|(n, v)| (n.to_string(), *v)).collect()
}

fn value(s: &str, env: &GuardEnv, pt: &HashMap<String, f64>) -> Ball {
    eval(&e(s), env, pt).unwrap_or_else(|err| panic!("{s}: {err:?}"))
}

fn same(a: &str, b: &str, env: &GuardEnv, pt: &HashMap<String, f64>) -> bool {
    !value(a, env, pt).clearly_differs(&value(b, env, pt))
}

#[test]
fn integrals_of_polynomials_are_exact_up_to_rounding() {
    let env = GuardEnv::default();
    let pt = at(&[("m", 3.0), ("L", 2.0)]);
    let v = value("int(y^2 m/L, y, -L/2, L/2)", &env, &pt);
    assert!((v.mid - 1.0).abs() < 1e-12 && v.rad < 1e-9, "{v:?}");
    assert!(same("int(y^2 m/L, y, -L/2, L/2)", "m L^2/12", &env, &pt));
    assert!(!same("int(y^2 m/L, y, -L/2, L/2)", "m L^2/3", &env, &pt));
    assert!(same(
        "int(exp(x) sin(x), x, 0, 2)",
        "(exp(2) (sin(2) - cos(2)) + 1)/2",
        &env,
        &pt
    ));
}

#[test]
fn derivatives_follow_the_textbook_rules() {
    let mut env = GuardEnv::default();
    env.time.extend(["x".to_string(), "theta".to_string()]);
    let pt = at(&[
        ("x", 0.7),
        ("x'", -1.3),
        ("theta'", 0.4),
        ("theta''", 2.5),
        ("a", 1.1),
    ]);
    assert!(same("diff(sin(a)^2, a)", "2 sin(a) cos(a)", &env, &pt));
    assert!(same(
        "diff(x^2 theta', t)",
        "2 x x' theta' + x^2 theta''",
        &env,
        &pt
    ));
    assert!(!same("diff(x^2 theta', t)", "2 x x' theta'", &env, &pt));
    assert!(same("diff(a^3, a, 2)", "6 a", &env, &pt));
    assert!(same("diff(abs(a - 2), a)", "-1", &env, &pt));
}

#[test]
fn bodies_are_integrated_over_their_regions() {
    let src = "symbols m a b > 0\nbody plate: dm = m/(a b) dx dy, x from 0 to a, y from 0 to b\nbody tri: dm = 2 m/(a b) dx dy, x from 0 to a, y from 0 to b x/a\n";
    let file = parse_file(src, &ParseOptions::default()).unwrap();
    let mut env = GuardEnv::default();
    for item in &file.items {
        if let crate::syntax::ast::Item::Stmt(st) = item {
            if let crate::syntax::ast::StmtKind::Body { name, def } = &st.kind {
                env.bodies.insert(name.name.clone(), def.clone());
            }
        }
    }
    let pt = at(&[("m", 2.0), ("a", 3.0), ("b", 0.5)]);
    assert!(same("int(x^2 + y^2, plate)", "m (a^2 + b^2)/3", &env, &pt));
    assert!(same("int(x, tri)", "2 m a/3", &env, &pt));
    assert!(!same("int(x, tri)", "m a/2", &env, &pt));
}

#[test]
fn odd_roots_are_odd_and_even_roots_need_nonnegative_values() {
    let env = GuardEnv::default();
    let pt = at(&[("x", -8.0)]);
    assert!(same("(1/x)^(1/3)", "-1/2", &env, &pt));
    assert!(same("x^(2/3)", "4", &env, &pt));
    assert!(matches!(
        eval(&e("x^(1/2)"), &env, &pt),
        Err(Skip::Domain(_))
    ));
}

#[test]
fn a_true_identity_never_clearly_differs_even_with_cancellation() {
    let env = GuardEnv::default();
    let pt = at(&[("a", 12345.678), ("b", -12345.677)]);
    assert!(same(
        "(a + b)^4",
        "a^4 + 4 a^3 b + 6 a^2 b^2 + 4 a b^3 + b^4",
        &env,
        &pt
    ));
    assert!(!same("(a + b)^2", "a^2 - 2 a b + b^2", &env, &pt));
}

#[test]
fn what_it_cannot_evaluate_it_skips() {
    let mut env = GuardEnv::default();
    env.time.insert("x".into());
    let pt = at(&[("T", 2.0), ("x", 1.0), ("x''", 3.0)]);
    for s in [
        "int(x'', t, 0, T)",
        "subs(x, t, 2)",
        "int(x^2, x)",
        "zzz + 1",
    ] {
        assert!(
            matches!(eval(&e(s), &env, &pt), Err(Skip::Unsupported(_))),
            "{s}"
        );
    }
    for s in ["1/0", "ln(-1)", "sqrt(-2)", "0^0", "tan(pi/2)"] {
        assert!(eval(&e(s), &env, &pt).is_err(), "{s}");
    }
}

#[test]
fn let_names_and_bound_variables_keep_their_meanings() {
    let mut env = GuardEnv::default();
    env.defs.insert("u".into(), e("x^2"));
    let pt = at(&[("x", 1.5)]);
    // diff(u^2, u) is 2u, read with u = x^2.
    assert!(same("diff(u^2, u)", "2 x^2", &env, &pt));
    // A bound x is fresh: its value comes from the range, not the point.
    assert!(same("int(abs(x), x, -1, 1)", "1", &env, &pt));
    assert!(same("subs(sqrt(x^2), x, -2)", "2", &env, &pt));
}

#[test]
fn deep_trees_run_out_of_budget_without_overflowing() {
    let mut deep = e("x");
    for _ in 0..100_000 {
        deep = Expr::new(
            crate::syntax::ast::ExprKind::Neg(Box::new(deep)),
            crate::syntax::ast::Span::default(),
        );
    }
    let env = GuardEnv::default();
    assert_eq!(eval(&deep, &env, &at(&[("x", 1.0)])), Err(Skip::Limit));
    std::mem::forget(deep);
}

#[test]
fn nested_derivatives_read_let_names_back() {
    let mut env = GuardEnv::default();
    env.defs.insert("u".into(), e("x^2"));
    let pt = at(&[("x", 1.5)]);
    assert!(same("diff(diff(u^2, u), x)", "4 x", &env, &pt));
    assert!(!same("diff(diff(u^2, u), x)", "0", &env, &pt));
}
