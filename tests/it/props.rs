//! Laws of the normal form and of the calculus, checked with proptest on small
//! random expressions. Expressions are generated as strings and parsed, so the
//! parser is exercised too.

use crate::normal::{norm, norm_in};
use proptest::prelude::*;
use rigor::decide::{decide, Verdict};
use rigor::lower::Env;
use rigor::normal::gcd::div_exact;
use rigor::normal::mono::Mono;
use rigor::normal::pack::Packing;
use rigor::normal::print::plain;
use rigor::normal::{Assumptions, AtomId, Poly, Rat, Q};

/// A small rational, written as `n`, `(n/d)` or `(-n/d)`.
fn rational() -> impl Strategy<Value = String> {
    (-6i64..=6, 1i64..=4).prop_map(|(n, d)| match d {
        1 if n < 0 => format!("({n})"),
        1 => n.to_string(),
        _ => format!("({n}/{d})"),
    })
}

/// One term of a polynomial in `x` with rational coefficients and parameters `a`, `b`,
/// in one of several surface syntaxes.
fn term() -> impl Strategy<Value = String> {
    term_with(rational())
}

/// A term with a small integer coefficient.
fn int_term() -> impl Strategy<Value = String> {
    term_with((-2i64..=2).prop_map(|n| format!("({n})")))
}

fn term_with(coefficient: impl Strategy<Value = String>) -> impl Strategy<Value = String> {
    let param = prop_oneof![
        Just(""),
        Just("a"),
        Just("b"),
        Just("a b"),
        Just("a^2"),
        Just("a*b")
    ];
    (coefficient, param, 0u32..=4, 0usize..3).prop_map(|(c, p, k, style)| {
        let xs = match (k, style) {
            (0, _) => String::new(),
            (1, _) => "x".to_string(),
            (k, 0) => format!("x^{k}"),
            (k, 1) => vec!["x"; k as usize].join(" "),
            (k, _) => format!("x^({k})"),
        };
        let mut parts = vec![c];
        if !p.is_empty() {
            parts.push(p.to_string());
        }
        if !xs.is_empty() {
            parts.push(xs);
        }
        if style == 2 {
            parts.join("*")
        } else {
            parts.join(" ")
        }
    })
}

/// A polynomial in `x` with parameters: a sum of one to four terms.
fn poly() -> impl Strategy<Value = String> {
    prop::collection::vec(term(), 1..=4).prop_map(|ts| ts.join(" + "))
}

/// A polynomial in `x` with parameters, of one or two terms.
fn small_poly() -> impl Strategy<Value = String> {
    prop::collection::vec(term(), 1..=2).prop_map(|ts| ts.join(" + "))
}

/// A polynomial with small integer coefficients and one or two terms (sines of
/// sums of integer multiples expand into many terms: keep them small).
fn int_poly() -> impl Strategy<Value = String> {
    prop::collection::vec(int_term(), 1..=2).prop_map(|ts| ts.join(" + "))
}

/// A rational function of `x`, `a`, `b`: sums, differences, products (written and
/// juxtaposed), quotients by constants, by `x^2 + 1` and by any other expression
/// (which may vanish somewhere, or everywhere), powers with negative exponents.
fn expr() -> impl Strategy<Value = String> {
    let leaf = prop_oneof![
        rational(),
        Just("x".to_string()),
        Just("a".to_string()),
        Just("b".to_string()),
        Just("0.5".to_string()),
    ];
    leaf.prop_recursive(3, 24, 3, |inner| {
        prop_oneof![
            (inner.clone(), inner.clone()).prop_map(|(p, q)| format!("{p} + {q}")),
            (inner.clone(), inner.clone()).prop_map(|(p, q)| format!("{p} - ({q})")),
            (inner.clone(), inner.clone()).prop_map(|(p, q)| format!("({p})({q})")),
            (inner.clone(), inner.clone()).prop_map(|(p, q)| format!("({p}) * ({q})")),
            (inner.clone(), 1i64..=5).prop_map(|(p, d)| format!("({p})/{d}")),
            inner.clone().prop_map(|p| format!("({p})/(x^2 + 1)")),
            (inner.clone(), inner.clone()).prop_map(|(p, q)| format!("({p})/({q})")),
            (inner.clone(), poly()).prop_map(|(p, q)| format!("({p})/({q})")),
            (inner.clone(), 0u32..=3).prop_map(|(p, k)| format!("({p})^{k}")),
            (inner.clone(), 1u32..=3).prop_map(|(p, k)| format!("({p})^(-{k})")),
            inner.clone().prop_map(|p| format!("-({p})")),
        ]
    })
}

/// A rational point, as a value for substitution.
fn point() -> impl Strategy<Value = [(i64, i64); 3]> {
    [
        (-9i64..=9, 1i64..=5),
        (-9i64..=9, 1i64..=5),
        (-9i64..=9, 1i64..=5),
    ]
}

fn plain_of(src: &str) -> String {
    plain(&norm(src))
}

/// `src` with `x`, `a`, `b` defined as the values of `pt`; `None` where undefined.
fn value_at(src: &str, pt: &[(i64, i64); 3]) -> Option<Q> {
    let mut env = Env::default();
    for (name, (n, d)) in ["x", "a", "b"].iter().zip(pt) {
        env.defs.insert(
            name.to_string(),
            Rat::constant(Q::new((*n).into(), (*d).into())),
        );
    }
    let r = norm_in(src, &env).ok()?;
    Some(
        r.as_constant()
            .unwrap_or_else(|| panic!("{src} is not a number at {pt:?}")),
    )
}

fn is_equal(a: &str, b: &str) -> bool {
    matches!(
        decide(&norm(a), &norm(b), &Assumptions::new()),
        Verdict::Equal
    )
}

/// The terms of the normal form of `src` (a polynomial), each as plain text.
fn terms_of(src: &str) -> Vec<(String, Q)> {
    let r = norm(src);
    assert!(r.den().is_one(), "{src} is not a polynomial");
    r.num()
        .terms()
        .iter()
        .map(|(m, q)| {
            let unit = Rat::poly(Poly::term(m.clone(), Q::from_integer(1.into()))).unwrap();
            (plain(&unit), q.clone())
        })
        .collect()
}

fn show_terms(ts: &[(String, Q)]) -> String {
    if ts.is_empty() {
        return "0".into();
    }
    ts.iter()
        .map(|(u, q)| format!("({q}) ({u})"))
        .collect::<Vec<_>>()
        .join(" + ")
}

proptest! {
    #![proptest_config(crate::config(256))]

    #[test]
    fn normal_form_is_idempotent(e in expr()) {
        let once = norm_in(&e, &Env::default());
        prop_assume!(once.is_ok());
        let p = plain(&once.unwrap());
        prop_assert_eq!(plain_of(&p), p.clone(), "{} printed as {}", e, p);
    }

    #[test]
    fn normal_form_has_the_same_value(e in expr(), pt in point()) {
        let Ok(r) = norm_in(&e, &Env::default()) else { return Ok(()) };
        let p = plain(&r);
        if let (Some(v1), Some(v2)) = (value_at(&e, &pt), value_at(&p, &pt)) {
            prop_assert_eq!(v1, v2, "{} ⇒ {} at {:?}", e, p, pt);
        }
    }

    #[test]
    fn addition_commutes(p in expr(), q in expr()) {
        let (Ok(_), Ok(_)) = (norm_in(&p, &Env::default()), norm_in(&q, &Env::default())) else {
            return Ok(());
        };
        prop_assert_eq!(plain_of(&format!("({p}) + ({q})")), plain_of(&format!("({q}) + ({p})")));
        prop_assert_eq!(plain_of(&format!("({p}) ({q})")), plain_of(&format!("({q})*({p})")));
    }

    #[test]
    fn multiplication_distributes(p in poly(), q in poly(), r in poly()) {
        prop_assert_eq!(
            plain_of(&format!("({p}) (({q}) + ({r}))")),
            plain_of(&format!("({p}) ({q}) + ({p}) ({r})"))
        );
        prop_assert_eq!(
            plain_of(&format!("(({p}) ({q})) ({r})")),
            plain_of(&format!("({p}) (({q}) ({r}))"))
        );
    }

    #[test]
    fn derivative_of_antiderivative(p in poly()) {
        prop_assert_eq!(plain_of(&format!("diff(int({p}, x), x)")), plain_of(&p));
    }

    #[test]
    fn integrals_add_over_intervals(p in poly(), l in rational(), m in rational(), u in rational()) {
        for (lo, mid, hi) in [(l.as_str(), m.as_str(), u.as_str()), ("c", "d", "e")] {
            prop_assert_eq!(
                plain_of(&format!("int({p}, x, {lo}, {mid}) + int({p}, x, {mid}, {hi})")),
                plain_of(&format!("int({p}, x, {lo}, {hi})"))
            );
        }
    }

    #[test]
    fn swapping_bounds_negates(p in poly(), l in rational(), u in rational()) {
        prop_assert_eq!(
            plain_of(&format!("int({p}, x, {u}, {l})")),
            plain_of(&format!("-int({p}, x, {l}, {u})"))
        );
        prop_assert_eq!(
            plain_of(&format!("int({p}, x, d, c)")),
            plain_of(&format!("-int({p}, x, c, d)"))
        );
    }

    #[test]
    fn integration_is_linear(p in poly(), q in poly(), k in rational()) {
        prop_assert_eq!(
            plain_of(&format!("int({k} ({p}) + ({q}), x, c, d)")),
            plain_of(&format!("{k} int({p}, x, c, d) + int({q}, x, c, d)"))
        );
        prop_assert_eq!(
            plain_of(&format!("int(a ({p}) - ({q}), x)")),
            plain_of(&format!("a int({p}, x) - int({q}, x)"))
        );
    }

    #[test]
    fn definite_is_eval_of_antiderivative(p in poly(), l in rational()) {
        prop_assert_eq!(
            plain_of(&format!("int({p}, x, {l}, c)")),
            plain_of(&format!("eval(int({p}, x), x, {l}, c)"))
        );
    }

    #[test]
    fn root_of_a_square_is_the_absolute_value(p in poly()) {
        prop_assert_eq!(plain_of(&format!("sqrt(({p})^2)")), plain_of(&format!("abs({p})")));
        prop_assert_eq!(plain_of(&format!("abs({p})^2")), plain_of(&format!("({p})^2")));
    }

    #[test]
    fn trigonometric_identities(p in small_poly(), q in small_poly(), k in int_poly()) {
        prop_assert_eq!(plain_of(&format!("sin({p})^2 + cos({p})^2")), "1");
        // Integer multiples of unrelated arguments have the same normal form.
        let px = format!("x ({k})");
        let qy = q.replace('x', "y");
        prop_assert_eq!(
            plain_of(&format!("sin(2 ({px}))")),
            plain_of(&format!("2 sin({px}) cos({px})"))
        );
        prop_assert_eq!(
            plain_of(&format!("cos(({px}) + ({qy}))")),
            plain_of(&format!("cos({px}) cos({qy}) - sin({px}) sin({qy})"))
        );
        // Any arguments: rational coefficients, constant terms, arguments that are
        // half or a shift of one another (`x/2` and `x`). Their normal forms may
        // differ (sines of different multiples of one angle); `decide` rewrites both
        // in the common base angle.
        for (a, b) in [
            (format!("sin(2 ({p}))"), format!("2 sin({p}) cos({p})")),
            (format!("cos(2 ({p}))"), format!("1 - 2 sin({p})^2")),
            (format!("cos(({p}) + ({q}))"), format!("cos({p}) cos({q}) - sin({p}) sin({q})")),
            (format!("sin(({p}) - ({q}))"), format!("sin({p}) cos({q}) - cos({p}) sin({q})")),
            (format!("tan({p}) cos({p})"), format!("sin({p})")),
        ] {
            prop_assert!(is_equal(&a, &b), "{} = {}", a, b);
        }
    }

    #[test]
    fn renaming_matches_general_substitution(p in poly(), q in poly()) {
        // x → w with w fresh takes the renaming shortcut; x → w + 1 then w → w − 1
        // takes the general path to the same place.
        let f = format!("({p})/(({q})^2 + 1)");
        prop_assert_eq!(
            plain_of(&format!("subs({f}, x, w)")),
            plain_of(&format!("subs(subs({f}, x, w + 1), w, w - 1)"))
        );
    }

    #[test]
    fn exponentials_merge(p in poly(), q in poly()) {
        prop_assert_eq!(
            plain_of(&format!("exp({p}) exp({q})")),
            plain_of(&format!("exp(({p}) + ({q}))"))
        );
        prop_assert_eq!(plain_of(&format!("ln(exp({p}))")), plain_of(&p));
    }

    #[test]
    fn derivative_of_product(p in poly(), q in poly()) {
        prop_assert_eq!(
            plain_of(&format!("diff(({p}) ({q}), x)")),
            plain_of(&format!("diff({p}, x) ({q}) + ({p}) diff({q}, x)"))
        );
    }
}

proptest! {
    #![proptest_config(crate::config(2048))]

    /// `(P)(Q)` equals its expansion; changing one coefficient, dropping one term or
    /// flipping one sign of the expansion makes it `not equal`.
    #[test]
    fn perturbed_identities_are_not_equal(p in poly(), q in poly(), which in 0usize..16, how in 0u8..3) {
        let lhs = format!("({p}) ({q})");
        let ts = terms_of(&lhs);
        prop_assume!(!ts.is_empty());
        prop_assert!(is_equal(&lhs, &show_terms(&ts)), "{} vs {}", lhs, show_terms(&ts));
        let i = which % ts.len();
        let mut bad = ts.clone();
        match how {
            0 => bad[i].1 += Q::from_integer(1.into()),
            1 => { bad.remove(i); }
            _ => bad[i].1 = -bad[i].1.clone(),
        }
        let rhs = show_terms(&bad);
        let v = decide(&norm(&lhs), &norm(&rhs), &Assumptions::new());
        let Verdict::NotEqual { exact, .. } = v else {
            return Err(TestCaseError::fail(format!("{lhs} = {rhs}: {v:?}")));
        };
        prop_assert!(exact, "{} vs {}: the difference is a polynomial", lhs, rhs);
    }
}

#[test]
fn value_at_substitutes_exactly() {
    let pt = [(2, 1), (3, 2), (-1, 3)];
    assert_eq!(value_at("x^2 + a b", &pt), Some(Q::new(7.into(), 2.into())));
    assert_eq!(value_at("1/(x - 2)", &pt), None);
}

/// A polynomial with integer coefficients in `atoms` atoms (ids from 0), exponents from
/// `exps`: small ones pack into `u128` bit fields, large ones (2^20 and more) or many
/// atoms do not, and take the general path of multiplication and exact division.
fn raw_poly(atoms: u32, exps: impl Strategy<Value = u32> + Clone) -> impl Strategy<Value = Poly> {
    let term = (
        prop::collection::vec((0..atoms, exps), 0..4),
        (-4i64..=4).prop_filter("nonzero", |c| *c != 0),
    );
    prop::collection::vec(term, 1..5).prop_map(|ts| {
        Poly::from_terms(
            ts.into_iter()
                .filter_map(|(m, c)| {
                    let m = m.into_iter().map(|(a, e)| (AtomId::from_index(a), e));
                    Some((Mono::from_pairs(m.collect())?, Q::from_integer(c.into())))
                })
                .collect(),
        )
    })
}

/// Polynomials of the three kinds: packed, huge exponents, many atoms.
fn any_poly() -> impl Strategy<Value = Poly> {
    prop_oneof![
        raw_poly(4, 0u32..4),
        raw_poly(3, prop_oneof![0u32..4, (1u32 << 20)..(1u32 << 26)]),
        raw_poly(60, 0u32..16),
    ]
}

proptest! {
    #![proptest_config(crate::config(512))]

    /// `(a b) / b = a` and a division with a remainder fails (or is exact), on every
    /// path: packed monomials, and monomials whose fields do not fit in 128 bits.
    #[test]
    fn exact_division_recovers_the_factor_on_every_path(a in any_poly(), b in any_poly(), r in any_poly()) {
        prop_assume!(!b.is_zero());
        let Ok(ab) = a.mul(&b) else { return Ok(()) };
        prop_assert_eq!(div_exact(&ab, &b), Ok(Some(a.clone())), "({:?}) ({:?}) / ({:?})", a, b, b);
        // With a remainder the division is not exact, unless b divides it. (Not with
        // huge exponents: the general path then runs for as many steps as the
        // exponents are large before it finds the remainder.)
        let huge = |p: &Poly| p.terms().iter().any(|(m, _)| m.degree() > 1 << 16);
        if huge(&ab) || huge(&r) {
            return Ok(());
        }
        let abr = ab.add(&r);
        if let Ok(Some(q)) = div_exact(&abr, &b) {
            prop_assert_eq!(q.mul(&b).ok(), Some(abr));
        }
    }
}

#[test]
fn the_exact_division_property_reaches_the_general_path() {
    // Exponents of 2^20 and more in three atoms need more than 128 bits of fields,
    // as do 60 atoms with exponents up to 15.
    let big = |e: u32| {
        Poly::from_terms(vec![
            (
                Mono::from_pairs((0..5).map(|a| (AtomId::from_index(a), e)).collect()).unwrap(),
                Q::from_integer(1.into()),
            ),
            (Mono::one(), Q::from_integer(1.into())),
        ])
    };
    let (a, b) = (big(1 << 25), big(1 << 24));
    assert!(Packing::for_quotient(&a.mul(&b).unwrap(), &b).is_none());
    assert_eq!(div_exact(&a.mul(&b).unwrap(), &b), Ok(Some(a)));
    let wide = Poly::from_terms(
        (0..60)
            .map(|i| {
                (
                    Mono::atom(AtomId::from_index(i), 15),
                    Q::from_integer(1.into()),
                )
            })
            .collect(),
    );
    assert!(Packing::for_quotient(&wide, &wide).is_none());
    assert_eq!(div_exact(&wide, &wide), Ok(Some(Poly::one())));
}
