//! One fact, one verdict, in every view: `equiv` and `simplify` read a range in
//! `--assume` as a `symbols` line of a file reads it, and print only counterexamples
//! inside it; `mark` reports a contradictory given as `check` does.

use crate::cli::run;
use num_rational::BigRational;
use std::str::FromStr;

/// The exit code, with the output in the failure message.
fn code(r: &crate::cli::Run) -> i32 {
    r.code()
}

fn show(r: &crate::cli::Run) -> String {
    format!(
        "exit {}\nstdout:\n{}\nstderr:\n{}",
        code(r),
        r.stdout,
        r.stderr
    )
}

/// The value of `name` in the printed counterexample (`at beta = 37/20 the left …`).
fn counterexample_value(out: &str, name: &str) -> BigRational {
    let line = out
        .lines()
        .find(|l| l.contains("counterexample: at "))
        .unwrap_or_else(|| panic!("no counterexample in:\n{out}"));
    let rest = line.split("counterexample: at ").nth(1).unwrap_or("");
    let values = rest.split(" the left side").next().unwrap_or("");
    let value = values
        .split(", ")
        .find_map(|v| v.strip_prefix(&format!("{name} = ")))
        .unwrap_or_else(|| panic!("no value of {name} in: {line}"));
    BigRational::from_str(value.trim()).unwrap_or_else(|e| panic!("{value}: {e}"))
}

/// `p/q` as a rational (π's enclosure below and above, to 10⁻¹²).
fn q(s: &str) -> BigRational {
    BigRational::from_str(s).expect("a rational")
}
const PI_LO: &str = "3141592653589/1000000000000";
const PI_HI: &str = "3141592653590/1000000000000";

#[test]
fn a_range_in_assume_fixes_signs_as_it_does_in_a_file() {
    // abs(beta) is beta there, sqrt(sin^2) is sin, and in the second quadrant
    // sqrt(cos^2) is -cos: equal, where rigor answered "not equal" with beta = -3/5.
    for (a, b, range) in [
        ("abs(beta)", "beta", "0 < beta < pi/2"),
        ("sqrt(sin(beta)^2)", "sin(beta)", "0 < beta < pi/2"),
        ("sqrt(cos(beta)^2)", "cos(beta)", "0 < beta < pi/2"),
        ("sqrt(cos(beta)^2)", "-cos(beta)", "pi/2 < beta < pi"),
        ("sqrt(sin(beta)^2)", "-sin(beta)", "pi < beta < 3 pi/2"),
        ("abs(tan(beta))", "tan(beta)", "0 <= beta < pi/2"),
    ] {
        let r = run(&["equiv", a, b, "--assume", range]);
        assert_eq!(code(&r), 0, "{a} = {b} for {range}: {}", show(&r));
        assert_eq!(r.stdout.lines().next(), Some("equal"), "{}", show(&r));
    }
    // The same in a file, for comparison: the view agrees with `check`.
    let r = run(&[
        "simplify",
        "sqrt(cos(beta)^2)",
        "--assume",
        "pi/2 < beta < pi",
    ]);
    assert_eq!(code(&r), 0, "{}", show(&r));
    assert_eq!(r.stdout.trim(), "-cos(beta)", "{}", show(&r));
    let r = run(&[
        "simplify",
        "abs(beta) + sqrt(sin(beta)^2)",
        "--assume",
        "0 < beta < pi/2",
    ]);
    assert_eq!(code(&r), 0, "{}", show(&r));
    assert_eq!(r.stdout.trim(), "beta + sin(beta)", "{}", show(&r));
}

#[test]
fn a_counterexample_printed_by_equiv_lies_inside_the_range() {
    // Not equal in the second quadrant; the counterexample must be there.
    let r = run(&[
        "equiv",
        "sqrt(cos(beta)^2)",
        "cos(beta)",
        "--assume",
        "pi/2 < beta < pi",
    ]);
    assert_eq!(code(&r), 1, "{}", show(&r));
    let beta = counterexample_value(&r.stdout, "beta");
    assert!(
        beta > q(PI_HI) / q("2") && beta < q(PI_LO),
        "beta = {beta} is outside (pi/2, pi): {}",
        show(&r)
    );
    // A range of numbers: the counterexample is inside it too.
    let r = run(&["equiv", "x^2", "x", "--assume", "2 < x <= 5"]);
    assert_eq!(code(&r), 1, "{}", show(&r));
    let x = counterexample_value(&r.stdout, "x");
    assert!(x > q("2") && x <= q("5"), "x = {x}: {}", show(&r));
}

#[test]
fn no_counterexample_inside_the_range_is_undecided_never_one_outside() {
    // |x - 1| = x - 1 holds for 1 < x < 2, but rigor's signs do not show x - 1 > 0
    // there: it cannot prove it, finds no counterexample inside, and says so. Before,
    // it printed "not equal" at x = -3/5.
    let r = run(&["equiv", "abs(x - 1)", "x - 1", "--assume", "1 < x < 2"]);
    assert_eq!(code(&r), 3, "{}", show(&r));
    assert_eq!(r.stdout.lines().next(), Some("undecided"), "{}", show(&r));
    assert!(!r.stdout.contains("counterexample: at"), "{}", show(&r));
    // An interval of one point: x - 1 is not a nonzero function there.
    let r = run(&["equiv", "x", "1", "--assume", "1 <= x <= 1"]);
    assert_eq!(code(&r), 3, "{}", show(&r));
    assert!(!r.stdout.contains("not equal"), "{}", show(&r));
    // The same in a file: check and equiv agree.
    let dir = crate::cli::scratch("views-point");
    let f = dir.join("point.deriv");
    std::fs::write(&f, "symbols 1 <= x <= 1\nclaim x = 1\n").expect("write");
    let r = run(&["check", f.to_str().expect("path")]);
    assert_eq!(code(&r), 1, "{}", show(&r));
    assert!(
        r.stderr.contains("E0302") && !r.stderr.contains("E0301"),
        "{}",
        show(&r)
    );
}

#[test]
fn a_range_that_is_empty_or_circular_is_bad_input() {
    for assume in [
        &["0 < x < 0"][..],
        &["2 < x < 1"],
        &["0 < a < b", "0 < b < a"],
        &["0 < x < x"],
    ] {
        let mut args = vec!["equiv", "x", "1"];
        for a in assume {
            args.extend(["--assume", a]);
        }
        let r = run(&args);
        assert_eq!(code(&r), 2, "{assume:?}: {}", show(&r));
        assert!(r.stdout.is_empty(), "{assume:?}: {}", show(&r));
        let r = run(&["simplify", "abs(x)", "--assume", assume[0]]);
        if assume.len() == 1 {
            assert_eq!(code(&r), 2, "{assume:?}: {}", show(&r));
        }
    }
    // A bound that uses a symbol assumed before it is fine.
    let r = run(&[
        "equiv",
        "abs(x)",
        "x",
        "--assume",
        "L > 0",
        "--assume",
        "0 < x < L",
    ]);
    assert_eq!(code(&r), 0, "{}", show(&r));
}

#[test]
fn the_guard_drops_a_counterexample_outside_the_declarations() {
    use rigor::decide::{guarded, Counterexample, Verdict};
    use rigor::guard::{self, Domain, GuardEnv};
    use rigor::syntax::{parse_expr, ParseOptions};
    let opts = ParseOptions::default();
    let mut env = GuardEnv::default();
    env.domains.push((
        "beta".into(),
        Domain::Range {
            lo: parse_expr("0", &opts).expect("0"),
            lo_strict: true,
            hi: parse_expr("pi/2", &opts).expect("pi/2"),
            hi_strict: true,
        },
    ));
    let (a, b) = (
        parse_expr("abs(beta)", &opts).expect("a"),
        parse_expr("beta", &opts).expect("b"),
    );
    let at = |v: &str| Verdict::NotEqual {
        difference: rigor::normal::Rat::zero(),
        exact: false,
        counterexample: Some(Counterexample {
            values: vec![("beta".into(), q(v))],
            lhs: "?".into(),
            rhs: "?".into(),
        }),
        diagnosis: None,
    };
    let stands =
        |p: &foldhash::HashMap<String, f64>| guard::counterexample_stands((&a, &b), &env, p);
    // Outside the interval: dropped, and with no exact argument the answer is undecided.
    assert!(matches!(
        guarded(at("-3/5"), stands),
        Verdict::Undecided { .. }
    ));
    assert!(matches!(
        guarded(at("2"), stands),
        Verdict::Undecided { .. }
    ));
    // Inside, where the sides as written are equal: dropped too.
    assert!(matches!(
        guarded(at("3/5"), stands),
        Verdict::Undecided { .. }
    ));
    // A sign declaration as written.
    let mut signs = GuardEnv::default();
    signs.domains.push((
        "m".into(),
        Domain::Sign(rigor::syntax::ast::SignDecl::Positive),
    ));
    let point =
        |v: f64| -> foldhash::HashMap<String, f64> { [("m".to_string(), v)].into_iter().collect() };
    assert!(guard::respects(&signs, &point(2.0)).is_ok());
    assert!(guard::respects(&signs, &point(-2.0)).is_err());
    assert!(guard::respects(&signs, &point(0.0)).is_err());
}

/// `rigor mark ARGS` against the class's reference, with no time budget.
fn mark(args: &[&str]) -> crate::cli::Run {
    let mut all = vec!["--timeout", "0", "mark", "--budget", "0"];
    all.extend(["--reference", "tests/mark/reference.deriv"]);
    all.extend(args);
    run(&all)
}

#[test]
fn a_false_given_is_the_same_mistake_in_check_and_in_mark() {
    let dir = crate::cli::scratch("views-false-given");
    let sub = dir.join("false_given.deriv");
    // The reference's derivation with a false given; [xdd] rests on it, [F] does not.
    std::fs::write(
        &sub,
        "symbols m g R > 0\nsymbols beta\ntime x theta\nunknowns F\n\
         given [bad] 0 = 1\n\
         given [Fx] F - m g sin(beta) = m x''\n\
         given [MG] F R = -(m R^2/2) theta''\n\
         constraint [roll] x = R theta\n\
         claim [xdd] x'' = -2/3 g sin(beta) by [bad]\n\
         claim [F] F = m g sin(beta)/3 by [Fx], [MG], [roll]\n",
    )
    .expect("write");
    let path = sub.to_str().expect("path");
    // check: bad input, E0306.
    let r = run(&["check", path]);
    assert_eq!(code(&r), 2, "{}", show(&r));
    assert!(
        r.stderr.contains("error[E0306]: this fact is false"),
        "{}",
        show(&r)
    );
    // mark: the same mistake by name, never "undecided"; the result that rests on it
    // earns nothing, the one that does not still counts.
    let r = mark(&[path]);
    assert_eq!(code(&r), 0, "{}", show(&r));
    assert!(
        r.stdout
            .contains("first mistake: line 5 (false_fact): this fact is false"),
        "{}",
        show(&r)
    );
    assert!(!r.stdout.contains("undecided"), "{}", show(&r));
    assert!(
        r.stdout.contains("[xdd] x'': not credited ("),
        "{}",
        show(&r)
    );
    assert!(r.stdout.contains("[F] F: right"), "{}", show(&r));
    assert!(r.stdout.contains("results 1/2 right"), "{}", show(&r));
    let r = mark(&[path, "--format", "csv"]);
    assert!(r.stdout.contains(",5,false_fact,1,2,"), "{}", show(&r));
    let r = mark(&[path, "--format", "json"]);
    let v: serde_json::Value = serde_json::from_str(r.stdout.trim()).expect("JSON");
    assert_eq!(v["first_failure"]["kind"], "false_fact", "{v}");
    assert_eq!(v["results_correct"], 1, "{v}");
    // The feedback says what it is, not "could not decide".
    let fb = dir.join("feedback");
    let r = mark(&[path, "--feedback", fb.to_str().expect("path")]);
    assert_eq!(code(&r), 0, "{}", show(&r));
    let text = std::fs::read_to_string(fb.join("000-false_given.md")).expect("feedback");
    assert!(text.contains("Hint: this fact is false"), "{text}");
    assert!(!text.contains("could not decide"), "{text}");
    assert!(text.contains("`x''` (line 9): not credited"), "{text}");
}

#[test]
fn the_class_summary_keeps_a_hostile_file_name_as_text() {
    let dir = crate::cli::scratch("views-hostile-name");
    let sub = dir.join("<img src=x onerror=alert(1)> [a](b) `c` |d|.deriv");
    std::fs::write(&sub, "symbols m > 0\nclaim m = m\n").expect("write");
    let r = mark(&[dir.to_str().expect("path"), "--summary"]);
    assert_eq!(code(&r), 0, "{}", show(&r));
    let row = r
        .stdout
        .lines()
        .find(|l| l.contains("onerror"))
        .unwrap_or_else(|| panic!("{}", show(&r)));
    assert!(
        row.contains("\\<img src=x onerror=alert(1)\\> \\[a\\](b) \\`c\\` \\|d\\|.deriv |"),
        "{row}"
    );
    assert_eq!(
        row.matches(" | ").count() - row.matches("\\| ").count(),
        3,
        "{row}"
    );
}

/// A side with square roots reads as a person writes it in every view that shows it:
/// the terminal, the worked solution, the playground. The value is the same; only the
/// normal form's split roots (`sqrt(2) sqrt(g) sqrt(h)`) are merged.
#[test]
fn square_roots_read_as_written_in_every_view() {
    let file = "tests/check/fail/kind_root_of_unsigned_unknown.deriv";
    let human = run(&["check", file]);
    assert!(
        human.stderr.contains("= right side: sqrt(2 g h)"),
        "{}",
        show(&human)
    );
    assert!(
        !human.stderr.contains("sqrt(2) sqrt(g)"),
        "{}",
        show(&human)
    );
    let md = run(&["markdown", file]);
    assert!(
        md.stdout
            .contains(r"right side: $\displaystyle \sqrt{2 g\,h}$"),
        "{}",
        show(&md)
    );
    // The playground's problem notes are typeset by the same pieces: text and math parts.
    let text = std::fs::read_to_string(file).expect("fixture");
    let request = serde_json::json!({ "name": "f.deriv", "source": text }).to_string();
    let page: serde_json::Value =
        serde_json::from_str(&rigor::render::web::respond(&request, None)).expect("JSON");
    let blocks = page["solution"]["blocks"].as_array().expect("blocks");
    let problem = blocks
        .iter()
        .find(|b| b["kind"] == "problems")
        .expect("a problem");
    let notes = problem["items"][0]["notes"].as_array().expect("notes");
    assert!(
        notes.iter().any(|n| n
            == &serde_json::json!([{ "text": "right side: " }, { "math": r"\displaystyle \sqrt{2 g\,h}" }])),
        "{notes:?}"
    );
    let rendered = page["rendered"][0].as_str().unwrap_or("");
    assert!(rendered.contains("= right side: sqrt(2 g h)"), "{rendered}");
}
