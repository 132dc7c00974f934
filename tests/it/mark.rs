//! `rigor mark` on a small class (`tests/mark/`): the summary in every format and the
//! feedback files are snapshots; the exit status says whether the class was marked.

use std::path::Path;
use std::process::Command;

/// Runs `rigor mark ARGS`. Unless a test sets them, there is no time budget (`--timeout
/// 0`, `--budget 0`): marks must not depend on how loaded the machine is.
fn mark(args: &[&str]) -> (String, String, i32) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_rigor"));
    if !args.contains(&"--timeout") {
        cmd.args(["--timeout", "0"]);
    }
    cmd.arg("mark");
    if !args.contains(&"--budget") {
        cmd.args(["--budget", "0"]);
    }
    let out = cmd
        .args(args)
        .current_dir(root)
        .output()
        .expect("rigor runs");
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
        out.status.code().unwrap_or(-1),
    )
}

const REF: &str = "tests/mark/reference.deriv";
const CLASS: &str = "tests/mark/class";

#[test]
fn the_class_is_marked_in_every_format() {
    for format in ["human", "csv", "json"] {
        let (out, err, code) = mark(&["--reference", REF, CLASS, "--format", format]);
        assert_eq!(code, 0, "{err}");
        insta::assert_snapshot!(format!("mark_{format}"), out);
    }
    let (out, _, code) = mark(&["--reference", REF, CLASS, "--summary"]);
    assert_eq!(code, 0);
    insta::assert_snapshot!("mark_summary", out);
}

#[test]
fn the_gradebook_has_the_documented_header_and_one_row_per_submission() {
    let (out, _, _) = mark(&["--reference", REF, CLASS, "--format", "csv"]);
    let mut lines = out.lines();
    assert_eq!(
        lines.next(),
        Some("file,steps_verified,steps_total,first_failure_line,first_failure_kind,results_correct,results_total")
    );
    let rows: Vec<&str> = lines.collect();
    assert_eq!(rows.len(), 9);
    assert!(rows[0].ends_with(",2,2,,,2,2"), "{}", rows[0]);
    assert!(rows[2].contains(",10,sign,1,2"), "{}", rows[2]);
    assert!(rows[3].contains(",9,factor,0,2"), "{}", rows[3]);
    assert!(rows[4].contains(",8,missing_fact,1,2"), "{}", rows[4]);
    // Other names for the same quantities: matched by role, both results right.
    assert!(
        rows[8].ends_with("09_other_names.deriv,2,2,,,2,2"),
        "{}",
        rows[8]
    );
}

#[test]
fn names_declared_differently_are_matched_by_role_and_said() {
    let sub = "tests/mark/class/09_other_names.deriv";
    let (out, _, code) = mark(&["--reference", REF, sub]);
    assert_eq!(code, 0);
    assert!(
        out.contains("  names matched by role: Fr → F, s → x, phi → theta\n"),
        "{out}"
    );
    assert!(
        out.contains("[xdd] x'': right") && out.contains("[F] F: right"),
        "{out}"
    );
    let (out, _, _) = mark(&["--reference", REF, sub, "--format", "json"]);
    let v: serde_json::Value = serde_json::from_str(out.trim()).expect("JSON");
    assert_eq!(
        v["names_mapped"][1],
        serde_json::json!({"submission": "s", "reference": "x"})
    );
    // A name in the same place but with other derivatives (the acceleration written `a`
    // where the reference has x'') is not mapped onto x: never called wrong for it.
    let (out, _, _) = mark(&[
        "--reference",
        REF,
        "tests/mark/other/acceleration_named_a.deriv",
    ]);
    assert!(!out.contains("names matched"), "{out}");
    assert!(
        out.contains("[xdd] x'': undecided (undeclared symbol `a`)"),
        "{out}"
    );
    // A submission that uses the reference's names needs no mapping.
    let (out, _, _) = mark(&["--reference", REF, "tests/mark/class/01_correct.deriv"]);
    assert!(!out.contains("names matched"), "{out}");
}

#[test]
fn feedback_names_the_first_mistake_without_revealing_the_reference() {
    let dir = std::env::temp_dir().join(format!("rigor-feedback-{}", std::process::id()));
    let d = dir.display().to_string();
    let (_, err, code) = mark(&["--reference", REF, CLASS, "--feedback", &d]);
    assert_eq!(code, 0, "{err}");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .expect("feedback folder")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .collect();
    files.sort();
    assert_eq!(files.len(), 9);
    for k in [0usize, 2, 4, 8] {
        let text = std::fs::read_to_string(&files[k]).expect("feedback");
        assert!(
            !text.contains("-2/3 g sin(beta) by"),
            "the reference is not revealed:\n{text}"
        );
        insta::assert_snapshot!(format!("feedback_{k}"), text);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_reference_that_does_not_verify_is_refused() {
    let (_, err, code) = mark(&["--reference", "tests/mark/class/04_factor.deriv", CLASS]);
    assert_eq!(code, 2);
    assert!(err.contains("does not verify"), "{err}");
}

#[test]
fn a_submission_that_spends_its_budget_is_a_row_with_the_reason_and_the_class_goes_on() {
    // Each `int((u - k)^6000, u, 0, 1) = …` needs far more than the 0.3 s budget; the
    // correct submission beside it is marked as usual.
    let (out, err, code) = mark(&[
        "--reference",
        "tests/mark/reference.deriv",
        "tests/mark/slow/slow.deriv",
        "tests/mark/class/01_correct.deriv",
        "--format",
        "csv",
        "--budget",
        "0.3",
    ]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(
        out.contains("tests/mark/slow/slow.deriv,2,5,"),
        "the two ordinary steps verified, the three slow ones not:\n{out}"
    );
    assert!(out.contains(",undecided,2,2"), "{out}");
    assert!(
        out.contains("tests/mark/class/01_correct.deriv,2,2,,,2,2"),
        "{out}"
    );
}

#[test]
fn the_file_budget_stops_the_remaining_claims_once_and_says_so() {
    use rigor::check::{check_source, MemoryResolver, Options};
    use std::sync::atomic::{AtomicU64, Ordering};
    use std::time::Duration;
    // A clock that moves on by 1 µs each time it is read.
    static NOW: AtomicU64 = AtomicU64::new(0);
    fn ticking() -> Duration {
        Duration::from_micros(NOW.fetch_add(1, Ordering::SeqCst))
    }
    let text = "symbols a b\nclaim [one] (a + b)^2 = a^2 + 2 a b + b^2\nclaim [two] a + b = b + a\nclaim [three] a = a\n";
    let with = |budget| Options {
        file_budget: budget,
        clock: Some(ticking as fn() -> Duration),
        ..Options::default()
    };
    let free = check_source("f.deriv", text, &with(None), &MemoryResolver::new());
    assert!(free.ok(), "{:?}", free.diagnostics);
    let spent = check_source(
        "f.deriv",
        text,
        &with(Some(Duration::ZERO)),
        &MemoryResolver::new(),
    );
    assert!(!spent.ok());
    assert_eq!(spent.verified(), 0);
    assert_eq!(spent.undecided(), 3);
    let budget: Vec<_> = spent
        .diagnostics
        .iter()
        .filter(|d| d.message.contains("time budget for this file"))
        .collect();
    assert_eq!(budget.len(), 1, "said once: {:?}", spent.diagnostics);
}

/// The second problem: the handout's trapdoor, marked against `derivations/trapdoor.deriv`.
const TRAPDOOR: &str = "derivations/trapdoor.deriv";
const TRAPDOOR_CLASS: &str = "tests/mark/trapdoor";

#[test]
fn a_second_problem_is_marked_in_every_format() {
    let (out, err, code) = mark(&["--reference", TRAPDOOR, TRAPDOOR_CLASS, "--format", "csv"]);
    assert_eq!(code, 0, "{err}");
    let rows: Vec<&str> = out.lines().skip(1).collect();
    assert_eq!(rows.len(), 5, "{out}");
    // Two correct submissions, in other orders and labels.
    assert!(
        rows[0].ends_with("01_correct.deriv,4,4,,,2,2"),
        "{}",
        rows[0]
    );
    assert!(rows[1].ends_with(",3,3,,,2,2"), "{}", rows[1]);
    // A sign slip in a step (the results as written are right: still counted right).
    assert!(rows[2].contains(",6,sign,2,2"), "{}", rows[2]);
    // Every step follows from a wrong moment of inertia: only the results are wrong.
    assert!(rows[3].ends_with(",4,4,,,0,2"), "{}", rows[3]);
    // The centre's acceleration never related to theta'': a missing fact.
    assert!(rows[4].contains(",8,missing_fact,2,2"), "{}", rows[4]);
    insta::assert_snapshot!("trapdoor_csv", out);
    for format in ["human", "json"] {
        let (out, _, code) = mark(&["--reference", TRAPDOOR, TRAPDOOR_CLASS, "--format", format]);
        assert_eq!(code, 0);
        insta::assert_snapshot!(format!("trapdoor_{format}"), out);
    }
    let (out, _, code) = mark(&["--reference", TRAPDOOR, TRAPDOOR_CLASS, "--summary"]);
    assert_eq!(code, 0);
    insta::assert_snapshot!("trapdoor_summary", out);
}
