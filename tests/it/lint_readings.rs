//! `rigor lint` reads LaTeX as a physicist means it (issue 27, item 4): Leibniz notation
//! is a derivative, `\Delta x` one symbol, a declared `e` that symbol, `\cos\omega t`
//! the cosine of a product, `\times` between quantities a cross product. Each note in
//! `tests/lint/readings_*.md` has one chain per reading; each chain's verdict is
//! asserted at its line. `tests/lint/zero_divisors.md`: divisors that the stated
//! relations force to zero through an identity (issue 27, item 1). `readings_given_value.md`:
//! a value the notes give, used before a law that would otherwise divide by zero.

use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

/// Each chain's line and verdict (`verified`, `FAILED`, `needs context`, `defines`), and
/// the exit status of `rigor lint` on the note.
fn verdicts(note: &str) -> (BTreeMap<usize, String>, i32, String) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = Command::new(env!("CARGO_BIN_EXE_rigor"))
        .args(["lint", note])
        .current_dir(root)
        .output()
        .expect("rigor runs");
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    let mut map = BTreeMap::new();
    for line in text.lines() {
        let Some(rest) = line.strip_prefix(note).and_then(|r| r.strip_prefix(':')) else {
            continue;
        };
        let mut parts = rest.splitn(3, ':');
        let (Some(l), Some(_col), Some(verdict)) = (parts.next(), parts.next(), parts.next())
        else {
            continue;
        };
        let verdict = verdict.trim_start();
        let kind = ["verified", "FAILED", "needs context", "defines"]
            .into_iter()
            .find(|k| verdict.starts_with(k))
            .unwrap_or("?");
        if let Ok(l) = l.parse() {
            map.insert(l, kind.to_string());
        }
    }
    (map, out.status.code().unwrap_or(-1), text)
}

fn expect(note: &str, want: &[(usize, &str)], code: i32) {
    let (got, status, text) = verdicts(note);
    for (line, verdict) in want {
        assert_eq!(
            got.get(line).map(String::as_str),
            Some(*verdict),
            "{note}:{line} should be {verdict}:\n{text}"
        );
    }
    assert_eq!(got.len(), want.len(), "one verdict per chain:\n{text}");
    assert_eq!(status, code, "{text}");
}

#[test]
fn leibniz_notation_is_a_derivative_never_a_product() {
    expect(
        "tests/lint/readings_leibniz.md",
        &[
            // F = m dv/dt defines F; F t = m v does not follow (d does not cancel).
            (5, "defines"),
            (7, "needs context"),
            // dx/dt = x/t and the \mathrm{d} form: a velocity is not x/t.
            (11, "needs context"),
            (15, "needs context"),
            // \Delta s/\Delta\tau is a ratio of increments, not s/tau.
            (19, "needs context"),
            // The true one: theta-dot is d theta/dt.
            (23, "verified"),
            // m under d/dt is taken as changing: m u-dot alone is not shown.
            (30, "needs context"),
            (34, "needs context"),
            // dq/dp of an unknown function of p: never q/p.
            (38, "needs context"),
        ],
        0,
    );
}

#[test]
fn a_declared_e_is_that_symbol() {
    expect(
        "tests/lint/readings_euler_e.md",
        &[(5, "verified"), (7, "FAILED"), (9, "verified")],
        1,
    );
}

#[test]
fn a_function_takes_the_factors_juxtaposed_after_it() {
    expect(
        "tests/lint/readings_functions.md",
        &[
            (5, "FAILED"),
            (9, "verified"),
            (13, "verified"),
            (17, "verified"),
        ],
        1,
    );
}

#[test]
fn times_between_quantities_is_a_cross_product_and_needs_context() {
    expect(
        "tests/lint/readings_cross.md",
        &[(5, "needs context"), (9, "verified"), (11, "defines")],
        0,
    );
}

#[test]
fn a_divisor_the_stated_relations_force_to_zero_is_never_assumed_nonzero() {
    // sin(theta) = 1 makes cos(theta) zero (sin^2 + cos^2 = 1), and u^2 + v^2 = 0 makes
    // u zero: dividing the moment balance by either proves nothing about R_A. Before
    // issue 27 both were "verified, assuming … != 0".
    let note = "tests/lint/zero_divisors.md";
    let all: Vec<(usize, &str)> = [7, 11, 15, 21, 23, 25]
        .into_iter()
        .map(|l| (l, "needs context"))
        .collect();
    expect(note, &all, 0);
    let (_, _, text) = verdicts(note);
    for line in [15, 25] {
        let at = format!("{note}:{line}:3: needs context: not verified: solving the facts");
        assert!(text.contains(&at), "{at}\n{text}");
        assert!(text.contains("which the facts make zero"), "{text}");
    }
}

#[test]
fn a_value_the_notes_give_is_used_before_a_law_that_would_divide_by_zero_without_it() {
    // `F = I_G x''/R^2 = m x''/2` holds x'' times I_G/R^2 - m/2, which the stated
    // `I_G = m R^2/2` makes zero: solving that for x'' first left lines 17 and 19
    // "needs context" and hid the wrong factor on line 28. The value is now substituted
    // first when the first way divides by zero; and solving that way no longer counts
    // as the facts determining g (g = 0), which made lint take g for an unknown and left
    // line 24 "needs context".
    expect(
        "tests/lint/readings_given_value.md",
        &[
            (6, "needs context"),
            (8, "needs context"),
            (13, "verified"),
            (17, "verified"),
            (19, "verified"),
            (21, "defines"),
            (24, "verified"),
            (28, "FAILED"),
        ],
        1,
    );
}
