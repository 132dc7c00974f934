//! Deciding `A = B`: the pairs of `tests/data/equiv.txt` with their expected
//! verdicts, every counterexample re-checked by substituting its values, and the
//! diagnoses of the unequal pairs as one snapshot.

use crate::normal::{assume_field, data_lines, env_with, norm_in};
use num_traits::Signed;
use rigor::decide::{decide, Counterexample, Verdict};
use rigor::lower::Env;
use rigor::normal::print::plain;
use rigor::normal::Rat;

fn verdict_name(v: &Verdict) -> &'static str {
    match v {
        Verdict::Equal => "equal",
        Verdict::NotEqual { .. } => "not equal",
        Verdict::Undecided { .. } => "undecided",
    }
}

/// Re-evaluates both sides at the counterexample's values, as definitions of the
/// symbols, and asserts that they really differ there.
fn recheck(a: &str, b: &str, env: &Env, c: &Counterexample) -> Result<(), String> {
    let mut env = env.clone();
    for (name, q) in &c.values {
        env.defs.insert(name.clone(), Rat::constant(q.clone()));
    }
    let va = norm_in(a, &env).map_err(|e| format!("{a} at {}: {e}", c.assignment()))?;
    let vb = norm_in(b, &env).map_err(|e| format!("{b} at {}: {e}", c.assignment()))?;
    match decide(&va, &vb, &env.signs) {
        Verdict::NotEqual { .. } => Ok(()),
        v => Err(format!(
            "{a} ;; {b}: at {} the sides are {} and {}, which are {}",
            c.assignment(),
            plain(&va),
            plain(&vb),
            verdict_name(&v)
        )),
    }
}

#[test]
fn equiv_pairs() {
    let cases = data_lines("equiv.txt");
    assert!(cases.len() >= 60, "only {} cases", cases.len());
    let mut wrong = Vec::new();
    let mut diagnoses = String::new();
    for f in &cases {
        let [a, b, expected, ..] = f.as_slice() else {
            panic!("bad line {f:?}")
        };
        let assume = assume_field(f);
        let env = env_with(&assume);
        let (ra, rb) = match (norm_in(a, &env), norm_in(b, &env)) {
            (Ok(x), Ok(y)) => (x, y),
            (x, y) => {
                wrong.push(format!("{a} ;; {b}: does not lower: {x:?} {y:?}"));
                continue;
            }
        };
        let v = decide(&ra, &rb, &env.signs);
        if verdict_name(&v) != expected {
            wrong.push(format!(
                "{a} ;; {b} [{assume}]: expected {expected}, got {v:?}"
            ));
        }
        if let Verdict::NotEqual {
            diagnosis,
            exact,
            counterexample,
            difference,
        } = &v
        {
            // Not equal needs a reason: an exact argument or a counterexample.
            if !exact && counterexample.is_none() {
                wrong.push(format!("{a} ;; {b}: not equal with neither reason"));
            }
            if difference.is_zero() {
                wrong.push(format!("{a} ;; {b}: not equal with a zero difference"));
            }
            if let Some(c) = counterexample {
                if let Err(e) = recheck(a, b, &env, c) {
                    wrong.push(e);
                }
            }
            let mut line = format!("{a} ;; {b}");
            if !assume.is_empty() {
                line.push_str(&format!("  [{assume}]"));
            }
            line.push_str(&format!(
                "\n    {}",
                diagnosis
                    .as_ref()
                    .map_or("(no diagnosis)", |d| d.text.as_str())
            ));
            if *exact {
                line.push_str(&format!(
                    "\n    exact: left − right = {}",
                    plain(difference)
                ));
            }
            if let Some(c) = counterexample {
                line.push_str(&format!(
                    "\n    counterexample: {{{}}}: {} vs {}",
                    c.assignment(),
                    c.lhs,
                    c.rhs
                ));
            }
            diagnoses.push_str(&line);
            diagnoses.push('\n');
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
    insta::assert_snapshot!("diagnoses", diagnoses);
}

/// Asserts the verdict of `a = b` under `assume`.
#[track_caller]
fn check(a: &str, b: &str, assume: &str, expected: &str) {
    let env = env_with(assume);
    let ra = norm_in(a, &env).unwrap_or_else(|e| panic!("{a}: {e}"));
    let rb = norm_in(b, &env).unwrap_or_else(|e| panic!("{b}: {e}"));
    let v = decide(&ra, &rb, &env.signs);
    assert_eq!(verdict_name(&v), expected, "{a} = {b} [{assume}]: {v:?}");
}

#[test]
fn symmetric_verdicts() {
    // Swapping the sides never changes the verdict.
    for f in data_lines("equiv.txt") {
        let env = env_with(&assume_field(&f));
        let a = norm_in(&f[0], &env).unwrap();
        let b = norm_in(&f[1], &env).unwrap();
        assert_eq!(
            verdict_name(&decide(&a, &b, &env.signs)),
            verdict_name(&decide(&b, &a, &env.signs)),
            "{} ;; {}",
            f[0],
            f[1]
        );
    }
}

#[test]
fn counterexamples_respect_signs() {
    let env = env_with("x > 0 ; y >= 0");
    let a = norm_in("x + y", &env).unwrap();
    let b = norm_in("x - y + 1", &env).unwrap();
    let Verdict::NotEqual {
        counterexample: Some(c),
        ..
    } = decide(&a, &b, &env.signs)
    else {
        panic!("x + y = x - y + 1 should be not equal with a counterexample")
    };
    for (n, q) in &c.values {
        match n.as_str() {
            "x" => assert!(q.is_positive(), "x = {q} but x > 0"),
            "y" => assert!(!q.is_negative(), "y = {q} but y >= 0"),
            _ => panic!("unexpected symbol {n}"),
        }
    }
}

#[test]
fn sign_slip_diagnosis() {
    let a = norm_in("m g sin(beta) - F", &Env::default()).unwrap();
    let b = norm_in("F - m g sin(beta)", &Env::default()).unwrap();
    let Verdict::NotEqual { diagnosis, .. } = decide(&a, &b, &Default::default()) else {
        panic!("not equal expected")
    };
    let d = diagnosis.unwrap();
    assert_eq!(d.mistake, rigor::diag::Mistake::Sign);
    assert!(d.text.contains("opposite signs"));
}

#[test]
fn factor_of_two_diagnosis() {
    let a = norm_in("m L^2/6", &Env::default()).unwrap();
    let b = norm_in("m L^2/12", &Env::default()).unwrap();
    let Verdict::NotEqual {
        diagnosis, exact, ..
    } = decide(&a, &b, &Default::default())
    else {
        panic!("not equal expected")
    };
    assert!(exact);
    let d = diagnosis.unwrap();
    assert_eq!(d.mistake, rigor::diag::Mistake::Factor);
    assert!(d.text.contains("2 × the right side"));
}

#[test]
fn radicals_need_signs() {
    check("sqrt(R^2)", "R", "", "not equal");
    check("sqrt(R^2)", "R", "R > 0", "equal");
    check("sqrt(R^2)", "R", "R >= 0", "equal");
    check("sqrt(R^2)", "-R", "R < 0", "equal");
    check("k_G", "R/sqrt(2)", "", "not equal");
}

#[test]
fn nothing_is_equal_by_sampling() {
    // Agree at every sample point but differ as normal forms: never `equal`.
    check("ln(a b)", "ln(a) + ln(b)", "", "undecided");
}

#[test]
fn products_of_large_prime_radicals_are_equal() {
    // 1000000007 · 1000000009 = 1000000016000000063: a true identity.
    check(
        "sqrt(1000000007) sqrt(1000000009)",
        "sqrt(1000000016000000063)",
        "",
        "equal",
    );
}
