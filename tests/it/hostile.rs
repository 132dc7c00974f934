//! Hostile inputs (`tests/hostile/`, plus large files generated here): `rigor check`
//! exits 1 or 2 with a diagnostic on stderr, never 0 by accident, never panics
//! (exit 101), never dies of a signal, and never runs past a wall-clock guard.

use crate::cli::{head, root, run_with_limit, scratch, Run};
use std::path::Path;
use std::time::Duration;

/// The guard of one run.
const GUARD: Duration = Duration::from_secs(30);

/// Runs `rigor ARGS` and checks the common promises: a normal exit with `code`, not a
/// panic, and `needle` in the diagnostic on stderr (a nonzero code) or in the report
/// on stdout (code 0).
#[track_caller]
fn expect(args: &[&str], code: i32, needle: &str, guard: Duration) -> Run {
    let r = run_with_limit(args, guard);
    let got = r.code();
    assert_ne!(
        got,
        101,
        "rigor {} panicked:\n{}",
        args.join(" "),
        head(&r.stderr)
    );
    assert!(
        !r.stderr.contains("panicked at"),
        "rigor {} panicked:\n{}",
        args.join(" "),
        head(&r.stderr)
    );
    assert_eq!(
        got,
        code,
        "rigor {}: exit status\nstdout:\n{}\nstderr:\n{}",
        args.join(" "),
        head(&r.stdout),
        head(&r.stderr)
    );
    if code != 0 {
        assert!(
            !r.stderr.trim().is_empty(),
            "rigor {}: no diagnostic on stderr",
            args.join(" ")
        );
        assert!(
            r.stderr.contains(needle),
            "rigor {}: stderr lacks {needle:?}:\n{}",
            args.join(" "),
            head(&r.stderr)
        );
    } else {
        assert!(
            r.stdout.contains(needle),
            "rigor {}: stdout lacks {needle:?}:\n{}",
            args.join(" "),
            head(&r.stdout)
        );
    }
    r
}

/// `rigor check tests/hostile/NAME` must exit `code` with `needle` in its diagnostic.
#[track_caller]
fn hostile(name: &str, code: i32, needle: &str) -> Run {
    let path = format!("tests/hostile/{name}");
    assert!(root().join(&path).exists(), "{path} is in the corpus");
    expect(&["check", &path], code, needle, GUARD)
}

#[test]
fn empty_file_has_nothing_to_check() {
    // Intended: an empty file has no claims, so nothing fails (exit 0, `claims: 0`).
    let r = hostile("empty.deriv", 0, "claims: 0");
    assert!(
        r.stdout.contains("files: 1, claims: 0"),
        "{}",
        head(&r.stdout)
    );
}

#[test]
fn binary_garbage_is_unreadable() {
    hostile("binary_garbage.deriv", 2, "not valid UTF-8");
}

#[test]
fn invalid_utf8_names_the_offset() {
    hostile("invalid_utf8.deriv", 2, "invalid byte at offset 67");
}

#[test]
fn odd_characters_are_syntax_errors() {
    hostile("odd_characters.deriv", 2, "syntax error");
}

#[test]
fn huge_numbers_are_exact_or_refused() {
    // 10^100000 has 100,001 digits: within the limit, computed exactly, and not 1.
    hostile("huge_power_of_ten.deriv", 1, "does not hold");
    hostile("huge_power_of_two.deriv", 2, "refused");
    hostile("huge_exponent.deriv", 2, "refused: an exponent exceeds");
    // (a+b)^100000 stays one power: refuted at once, not expanded.
    let r = hostile("huge_binomial.deriv", 1, "does not hold");
    assert!(r.elapsed < Duration::from_secs(10), "{:?}", r.elapsed);
}

#[test]
fn undefined_values_are_bad_input() {
    hostile(
        "division_by_zero.deriv",
        2,
        "division by an expression that is exactly zero",
    );
    hostile("zero_to_zero.deriv", 2, "0^0 is undefined");
    hostile("sqrt_negative.deriv", 2, "square root of a negative");
    hostile("unknown_function.deriv", 2, "unknown function f");
}

#[test]
fn labels_must_be_defined_before_use() {
    hostile("label_before_definition.deriv", 2, "unknown label [b]");
}

#[test]
fn labels_must_be_defined_before_use_even_on_identities() {
    hostile(
        "label_before_definition_identity.deriv",
        2,
        "unknown label [b]",
    );
    hostile("label_self_reference.deriv", 2, "unknown label [a]");
}

#[test]
fn imports_are_confined_and_acyclic() {
    hostile("cycle/a.deriv", 2, "import cycle");
    hostile(
        "escape/escapes.deriv",
        2,
        "outside the folder being checked",
    );
    hostile("absolute_use.deriv", 2, "not the absolute path");
    // The imported file itself is fine.
    hostile("outside.deriv", 0, "verified: 1, failed: 0");
}

#[test]
fn a_short_timeout_makes_a_pathological_claim_undecided() {
    let r = expect(
        &[
            "--timeout",
            "0.5",
            "check",
            "tests/hostile/pathological_timeout.deriv",
        ],
        1,
        "time budget",
        GUARD,
    );
    assert!(
        r.stdout.contains("verified: 0, failed: 0, undecided: 1"),
        "{}",
        r.stdout
    );
    // In JSON the diagnostic is part of the object on stdout.
    let r = run_with_limit(
        &[
            "--timeout",
            "0.5",
            "check",
            "--format",
            "json",
            "tests/hostile/pathological_timeout.deriv",
        ],
        GUARD,
    );
    assert_eq!(r.code(), 1, "{}", head(&r.stdout));
    let v: serde_json::Value = serde_json::from_str(r.stdout.trim()).expect("JSON");
    assert_eq!(v["claims"][0]["links"][0]["status"], "undecided", "{v}");
    assert_eq!(v["diagnostics"][0]["code"], "E0902", "{v}");
}

/// Writes `text` to `dir/name` and returns the path as a string.
fn write(dir: &Path, name: &str, text: &[u8]) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).expect("write");
    p.to_str().expect("utf-8").to_string()
}

#[test]
fn a_50_mb_file_is_refused_by_size() {
    let dir = scratch("hostile-50mb");
    let mut text = b"symbols x\nclaim x = x\n".to_vec();
    text.resize(50 * 1024 * 1024, b'x');
    let p = write(&dir, "big.deriv", &text);
    let r = expect(&["check", &p], 2, "see --max-file-size", GUARD);
    assert!(r.stderr.contains("52428800 bytes"), "{}", r.stderr);
    assert!(r.elapsed < Duration::from_secs(5), "{:?}", r.elapsed);
    // The limit is a flag: a small limit refuses a small file too.
    expect(
        &["check", "--max-file-size", "10", "derivations/rod.deriv"],
        2,
        "more than the limit of 10",
        GUARD,
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_100k_line_file_finishes() {
    let dir = scratch("hostile-100k");
    let mut text = String::from("# 100,000 lines\nsymbols x y > 0\n");
    for i in 0..99_997 {
        text.push_str(&match i % 4 {
            0 => "% a comment line\n".to_string(),
            1 => format!("claim x + {i} y = {i} y + x\n"),
            2 => "> prose with $x + y$\n".to_string(),
            _ => "claim (x + y)^2 = x^2 + 2 x y + y^2\n".to_string(),
        });
    }
    // The last line is wrong: the diagnostic must point at line 100,000.
    text.push_str("claim x + y = x - y\n");
    assert_eq!(text.lines().count(), 100_000);
    let p = write(&dir, "lines.deriv", text.as_bytes());
    let r = expect(
        &["check", &p],
        1,
        "lines.deriv:100000:7",
        Duration::from_secs(60),
    );
    assert!(
        r.stdout.contains("failed: 1, undecided: 0, errors: 0"),
        "{}",
        r.stdout
    );
    // Its speed is measured by the benchmarks, not asserted here (a timed test would
    // fail on a busy machine and prove nothing on a fast one).
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_million_nested_parentheses_are_refused() {
    let dir = scratch("hostile-nest");
    let n = 1_000_000;
    let text = format!("symbols x\nclaim {}x{} = x\n", "(".repeat(n), ")".repeat(n));
    let p = write(&dir, "nest.deriv", text.as_bytes());
    expect(&["check", &p], 2, "nested deeper than 200 levels", GUARD);
    // In a `let`, a `given` and an import line too.
    let text = format!(
        "symbols x\nlet a = {}x{}\ngiven {}x = 1\n",
        "(".repeat(n),
        ")".repeat(n),
        "-".repeat(n)
    );
    let p = write(&dir, "nest2.deriv", text.as_bytes());
    expect(&["check", &p], 2, "syntax error", GUARD);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn hostile_command_line_expressions() {
    let deep = format!("{}x{}", "(".repeat(50_000), ")".repeat(50_000));
    for (args, code, needle) in [
        (vec!["simplify", deep.as_str()], 2, "nested deeper"),
        (vec!["equiv", deep.as_str(), "x"], 2, "nested deeper"),
        (vec!["simplify", "2^(10^9)"], 2, "refused"),
        (vec!["simplify", "x^(10^12)"], 2, "refused"),
        (vec!["simplify", "1/(x-x)"], 2, "division"),
        (vec!["simplify", "0^0"], 2, "0^0"),
        (
            vec!["simplify", "sqrt(-a)", "--assume", "a > 0"],
            2,
            "negative",
        ),
        (vec!["equiv", "f(x)", "x"], 2, "unknown function"),
        (vec!["equiv", "(a+b)^100000", "1"], 1, "not equal"),
        (vec!["simplify", "\u{feff}x"], 2, "syntax error"),
    ] {
        let r = run_with_limit(&args, GUARD);
        assert_eq!(
            r.code(),
            code,
            "rigor {}: {}",
            args.join(" ").chars().take(80).collect::<String>(),
            head(&r.stderr)
        );
        assert!(
            r.stderr.contains(needle) || r.stdout.contains(needle),
            "{needle:?} in {}",
            head(&r.stderr)
        );
    }
}

#[test]
fn timeout_is_honoured_for_huge_numbers() {
    for args in [
        vec!["--timeout", "1", "simplify", "10^1000000"],
        vec!["--timeout", "1", "equiv", "10^1000000", "1"],
        vec!["--timeout", "1", "simplify", "0.11^411111"],
        vec!["--timeout", "1", "simplify", "x 0.11^411111"],
        // Found by `cargo fuzz run expr`.
        vec!["--timeout", "1", "simplify", "x'*III111.11^411111I"],
    ] {
        let r = run_with_limit(&args, GUARD);
        // Each of these is refused (the number would be too large), with exit 2 and
        // the reason: never a result, never a wait.
        assert_eq!(r.code(), 2, "{}", head(&r.stderr));
        assert!(r.stderr.contains("refused"), "{}", head(&r.stderr));
        assert!(
            r.elapsed < Duration::from_secs(5),
            "rigor {}: {:?} with a 1 s budget",
            args.join(" "),
            r.elapsed
        );
    }
    let dir = scratch("hostile-bignum");
    let p = write(&dir, "big.deriv", b"symbols x\nclaim 10^1000000 = 1\n");
    // Refused by the digit limit before any work: bad input, exit 2.
    let r = expect(&["--timeout", "1", "check", &p], 2, "digits", GUARD);
    assert!(r.elapsed < Duration::from_secs(5), "{:?}", r.elapsed);
    assert!(
        r.stderr.len() < 100_000,
        "{} bytes of diagnostic",
        r.stderr.len()
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_whole_corpus_as_one_folder() {
    // Checked together, in parallel: bad input wins (exit 2), nothing panics.
    let r = expect(
        &["--timeout", "2", "check", "tests/hostile"],
        2,
        "import cycle",
        Duration::from_secs(60),
    );
    assert!(r.stdout.contains("files: 21,"), "{}", r.stdout);
}

#[test]
fn the_term_limit_flag_reaches_simplify_equiv_and_the_checking_threads() {
    let product = "(a + b + c + d + e + f) (p + q + r + s + u + v)";
    expect(&["simplify", product], 0, "a p", GUARD);
    expect(
        &["simplify", "--max-terms", "20", product],
        2,
        "refused: the result would have more than the limit of 20 terms (see --max-terms)",
        GUARD,
    );
    expect(
        &["equiv", "--max-terms", "20", product, product],
        2,
        "more than the limit of 20 terms (see --max-terms)",
        GUARD,
    );
    let dir = scratch("hostile-max-terms");
    let p = write(
        &dir,
        "product.deriv",
        format!("symbols a b c d e f p q r s u v > 0\nclaim [x] {product} = {product}\n")
            .as_bytes(),
    );
    expect(&["check", &p], 0, "verified", GUARD);
    // `check` runs its files on threads of their own: the limit goes with the options.
    expect(
        &["check", "--max-terms", "20", &p],
        2,
        "refused: the result would have more than the limit of 20 terms (see --max-terms)",
        GUARD,
    );
    let _ = std::fs::remove_dir_all(&dir);
}
