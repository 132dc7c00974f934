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
        Some("file,steps_verified,steps_total,first_failure_line,first_failure_kind,results_correct,results_total,note")
    );
    let rows: Vec<&str> = lines.collect();
    assert_eq!(rows.len(), 9);
    assert!(rows[0].ends_with(",2,2,,,2,2,"), "{}", rows[0]);
    assert!(rows[2].contains(",10,sign,1,2,"), "{}", rows[2]);
    assert!(rows[3].contains(",9,factor,0,2,"), "{}", rows[3]);
    // The answer stated where the facts written do not give it: not credited.
    assert!(
        rows[4].ends_with(
            ",8,missing_fact,0,2,[xdd] not credited: your claim on line 8 does not follow in your own work"
        ),
        "{}",
        rows[4]
    );
    // A binary file: the row says why it was not read.
    assert!(
        rows[7].ends_with(
            ",0,0,,not_read,0,2,not marked: the file is not valid UTF-8 (invalid byte at offset 8)"
        ),
        "{}",
        rows[7]
    );
    // Other names for the same quantities: matched by role, both results right.
    assert!(
        rows[8].ends_with("09_other_names.deriv,2,2,,,2,2,"),
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
        serde_json::json!({"submission": "s", "reference": "x", "negated": false})
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
        out.contains("[xdd] x'': undecided (your [xdd] does not state x'' on one side)"),
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
        out.contains("tests/mark/class/01_correct.deriv,2,2,,,2,2,"),
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
        rows[0].ends_with("01_correct.deriv,4,4,,,2,2,"),
        "{}",
        rows[0]
    );
    assert!(rows[1].ends_with(",3,3,,,2,2,"), "{}", rows[1]);
    // A sign slip in the moment equation, and the reference's answers written anyway:
    // they do not follow from the student's own equation, so they earn nothing.
    assert!(rows[2].contains(",6,sign,0,2,"), "{}", rows[2]);
    // Every step follows from a wrong moment of inertia: the results are wrong.
    assert!(rows[3].contains(",4,4,,,0,2,"), "{}", rows[3]);
    // The centre's acceleration never related to theta'': a missing fact; theta'' is
    // right, R (which needs that fact) earns nothing.
    assert!(rows[4].contains(",8,missing_fact,1,2,"), "{}", rows[4]);
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

/// The CSV rows (no header) of `rigor mark` on `paths` against the rolling cylinder.
fn rows(paths: &[&str], extra: &[&str]) -> Vec<String> {
    let mut args = vec!["--reference", REF];
    args.extend_from_slice(paths);
    args.extend_from_slice(&["--format", "csv"]);
    args.extend_from_slice(extra);
    let (out, err, code) = mark(&args);
    assert_eq!(code, 0, "{err}");
    out.lines().skip(1).map(str::to_string).collect()
}

/// The human lines of `rigor mark` on one submission against the rolling cylinder.
fn human(path: &str, extra: &[&str]) -> String {
    let mut args = vec!["--reference", REF, path];
    args.extend_from_slice(extra);
    let (out, err, code) = mark(&args);
    assert_eq!(code, 0, "{err}");
    out
}

#[test]
fn results_resting_on_the_students_own_givens_earn_nothing_and_say_why() {
    let r = rows(&["tests/mark/gaming"], &[]);
    assert_eq!(r.len(), 12, "{r:?}");
    // The results stated as givens; the answer added as a given; a wrong moment of
    // inertia rescued by `g sin(beta) = 0`; the unknown defined as the answer: every
    // step verifies, and not one result is credited.
    for k in [0, 1, 2, 8] {
        assert!(r[k].contains(",2,2,,,0,2,"), "{}", r[k]);
    }
    let out = human("tests/mark/gaming/02_rescued_inertia.deriv", &[]);
    assert!(
        out.contains("[xdd] x'': not credited (rests on your own assumption [h], line 7, which the problem does not give)"),
        "{out}"
    );
    assert!(
        out.contains("  fact [h], line 7: your own assumption: the problem does not give it\n"),
        "{out}"
    );
    // The wrong moment equation is named too.
    assert!(
        out.contains("  fact [MG], line 8: your own assumption"),
        "{out}"
    );
    let out = human("tests/mark/gaming/03_answer_as_given.deriv", &[]);
    assert!(
        out.contains("rests on your own assumption [ans], line 9"),
        "{out}"
    );
    // The problem's own givens, written as the reference writes them, are not named.
    assert!(!out.contains("fact [Fx]"), "{out}");
    let out = human("tests/mark/gaming/09_let_of_the_answer.deriv", &[]);
    assert!(
        out.contains("[F] F: not credited (rests on your own assumption (a `let`), line 5, which the problem does not give)"),
        "{out}"
    );
}

#[test]
fn contradictory_facts_are_reported_and_nothing_resting_on_them_counts() {
    let out = human(
        "tests/mark/gaming/04_contradictory.deriv",
        &["--format", "csv"],
    );
    assert!(out.contains(",0,2,8,false_fact,0,2,"), "{out}");
    let out = human("tests/mark/gaming/04_contradictory.deriv", &[]);
    assert!(
        out.contains("  fact [h2], line 8: contradicts your other facts\n"),
        "{out}"
    );
    assert!(out.contains("results 0/2 right"), "{out}");
}

#[test]
fn a_use_reaches_only_the_course_library_the_tutor_allows() {
    let r = rows(
        &[
            "tests/mark/gaming/05_import_classmate.deriv",
            "tests/mark/gaming/06_import_reference.deriv",
            "tests/mark/allowed/01_library.deriv",
        ],
        &[],
    );
    // A classmate's file, the reference: reported at the `use`, nothing credited.
    assert!(
        r[0].contains("05_import_classmate.deriv,0,0,2,import,0,2,"),
        "{}",
        r[0]
    );
    assert!(
        r[1].contains("06_import_reference.deriv,0,2,2,import,0,2,"),
        "{}",
        r[1]
    );
    assert!(
        r[1].contains("rests on the `use` on line 2, which imported nothing"),
        "{}",
        r[1]
    );
    // Without --allow-use, even the course library is not reachable.
    assert!(r[2].contains(",6,import,0,2,"), "{}", r[2]);
    let out = human("tests/mark/gaming/05_import_classmate.deriv", &[]);
    assert!(
        out.contains("first mistake: line 2 (import): \"../class/01_correct.deriv\" may not be imported here"),
        "{out}"
    );
    let lib = ["--allow-use", "tests/mark/library"];
    let r = rows(
        &[
            "tests/mark/allowed/01_library.deriv",
            "tests/mark/gaming/05_import_classmate.deriv",
        ],
        &lib,
    );
    assert!(r[0].ends_with("01_library.deriv,2,2,,,2,2,"), "{}", r[0]);
    // The library allowed does not open the rest of the class.
    assert!(r[1].contains(",2,import,0,2,"), "{}", r[1]);
}

#[test]
fn links_the_reference_and_files_met_twice_are_rows_that_say_why() {
    let dir = std::env::temp_dir().join(format!("rigor-mark-links-{}", std::process::id()));
    let class = dir.join("class");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&class).expect("a temporary folder");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    std::fs::copy(root.join(REF), dir.join("reference.deriv")).expect("copy");
    std::fs::copy(
        root.join("tests/mark/class/01_correct.deriv"),
        class.join("a.deriv"),
    )
    .expect("copy");
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink("../reference.deriv", class.join("ref.deriv")).expect("link");
        std::os::unix::fs::symlink("..", class.join("loop")).expect("link");
    }
    let reference = dir.join("reference.deriv").display().to_string();
    let c = class.display().to_string();
    let a = class.join("a.deriv").display().to_string();
    let (out, err, code) = mark(&[
        "--reference",
        &reference,
        &c,
        &a,
        &reference,
        "--format",
        "csv",
    ]);
    assert_eq!(code, 0, "{err}");
    let rows: Vec<&str> = out.lines().skip(1).collect();
    let credited: Vec<&&str> = rows.iter().filter(|r| r.contains(",2,2,,,2,2,")).collect();
    // One submission, marked once; everything else says why it was not.
    assert_eq!(credited.len(), 1, "{out}");
    assert!(out.contains("it is the same file as"), "{out}");
    assert!(
        out.contains("it is the reference, which is never marked"),
        "{out}"
    );
    #[cfg(unix)]
    {
        assert!(out.contains("/class/loop,0,0,,not_read,0,2,\"not marked: it is a symbolic link, and marking does not follow links\""), "{out}");
        assert!(
            out.contains("/class/ref.deriv,0,0,,not_read,0,2,\"not marked: it is a symbolic link"),
            "{out}"
        );
        // The link `loop -> ..` adds one row, not a copy of the class.
        assert_eq!(rows.len(), 5, "{out}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_result_false_in_the_students_own_model_is_not_right() {
    // Here x is the angle: `x'' = -2/3 g sin(beta)` reads like the reference's text but
    // is about θ, and is false in the student's own equations.
    let out = human("tests/mark/gaming/07_false_in_own_model.deriv", &[]);
    assert!(
        out.contains("names matched by role: s → x, x → theta"),
        "{out}"
    );
    assert!(
        out.contains("[xdd] x'': undecided (your [xdd] does not state x'' on one side)"),
        "{out}"
    );
    assert!(out.contains("[F] F: right"), "{out}");
    assert!(out.contains("results 1/2 right"), "{out}");
    // Results that say nothing (`x'' = x''`, F still in terms of x'') are no answers.
    let out = human("tests/mark/gaming/10_identity.deriv", &[]);
    assert!(out.contains("results 0/2 right"), "{out}");
    assert!(
        out.contains(
            "[xdd] x'': undecided (it is not yet written in the problem's given quantities alone)"
        ),
        "{out}"
    );
}

#[test]
fn the_last_claim_about_a_result_is_marked_and_earlier_ones_that_disagree_are_said() {
    let out = human("tests/mark/gaming/08_wrong_last.deriv", &[]);
    assert!(out.contains("results 0/2 right"), "{out}");
    assert!(
        out.contains("  [xdd] x'': wrong\n    an earlier claim, line 9, says otherwise\n"),
        "{out}"
    );
    let out = human("tests/mark/fair/05_corrected.deriv", &[]);
    assert!(out.contains("results 2/2 right"), "{out}");
    assert!(
        out.contains("  [xdd] x'': right\n    an earlier claim, line 9, says otherwise\n"),
        "{out}"
    );
}

#[test]
fn correct_work_in_fair_forms_is_credited() {
    let r = rows(&["tests/mark/fair"], &[]);
    assert_eq!(r.len(), 10, "{r:?}");
    for (k, row) in r.iter().enumerate() {
        if k == 4 {
            assert!(
                row.ends_with("05_corrected.deriv,2,3,9,factor,2,2,"),
                "{row}"
            );
        } else if k == 9 {
            // Credited, and the note names the fact that is not the problem's.
            assert!(
                row.ends_with(",2,2,,,2,2,facts not the problem's: [N] line 6"),
                "{row}"
            );
        } else {
            assert!(row.ends_with(",2,2,,,2,2,"), "{row}");
        }
    }
    // Positions measured down the slope: two signs turned at once.
    let out = human("tests/mark/fair/07_down_the_slope.deriv", &[]);
    assert!(
        out.contains("names matched by role: P → F, s → −x, phi → −theta\n"),
        "{out}"
    );
    // A fact of the student's own that no result rests on: named, and harmless.
    let out = human("tests/mark/fair/10_extra_fact.deriv", &[]);
    assert!(
        out.contains("  fact [N], line 6: your own assumption"),
        "{out}"
    );
    assert!(out.contains("results 2/2 right"), "{out}");
    // Friction drawn the other way under the reference's own name.
    let out = human("tests/mark/fair/08_same_name_other_way.deriv", &[]);
    assert!(out.contains("names matched by role: F → −F\n"), "{out}");
    assert!(out.contains("results 2/2 right"), "{out}");
    // Partial renaming, the moment equation first, labels of the student's own.
    let out = human("tests/mark/fair/03_partial_renaming.deriv", &[]);
    assert!(
        out.contains("names matched by role: Fr → F, x → theta, s → x\n"),
        "{out}"
    );
    // Friction drawn the other way: the sign is part of the mapping.
    let out = human("tests/mark/fair/04_friction_other_way.deriv", &[]);
    assert!(out.contains("names matched by role: P → −F\n"), "{out}");
    assert!(out.contains("[F] F: right"), "{out}");
    let (out, _, _) = mark(&[
        "--reference",
        REF,
        "tests/mark/fair/04_friction_other_way.deriv",
        "--format",
        "json",
    ]);
    let v: serde_json::Value = serde_json::from_str(out.trim()).expect("JSON");
    assert_eq!(
        v["names_mapped"][0],
        serde_json::json!({"submission": "P", "reference": "F", "negated": true})
    );
}

#[test]
fn gradebook_cells_never_start_a_formula_or_carry_control_characters() {
    let dir = std::env::temp_dir().join(format!("rigor-mark-csv-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let src = root.join("tests/mark/class/01_correct.deriv");
    for name in [
        "=HYPERLINK(1).deriv",
        "+1.deriv",
        "-1.deriv",
        "@SUM(1).deriv",
        "tab\there.deriv",
    ] {
        std::fs::copy(&src, dir.join(name)).expect("copy");
    }
    let out = Command::new(env!("CARGO_BIN_EXE_rigor"))
        .args(["--timeout", "0", "mark", "--budget", "0", "--reference"])
        .arg(root.join(REF))
        .args(["--format", "csv", "--"])
        .args([
            "=HYPERLINK(1).deriv",
            "+1.deriv",
            "-1.deriv",
            "@SUM(1).deriv",
            "tab\there.deriv",
        ])
        .current_dir(&dir)
        .output()
        .expect("rigor runs");
    let out = String::from_utf8_lossy(&out.stdout).into_owned();
    let rows: Vec<&str> = out.lines().skip(1).collect();
    assert_eq!(
        rows,
        [
            "'=HYPERLINK(1).deriv,2,2,,,2,2,",
            "'+1.deriv,2,2,,,2,2,",
            "'-1.deriv,2,2,,,2,2,",
            "'@SUM(1).deriv,2,2,,,2,2,",
            "tab?here.deriv,2,2,,,2,2,",
        ],
        "{out}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn feedback_says_as_much_as_check() {
    let dir = std::env::temp_dir().join(format!("rigor-feedback-full-{}", std::process::id()));
    let d = dir.display().to_string();
    let (_, err, code) = mark(&[
        "--reference",
        REF,
        "tests/mark/class/04_factor.deriv",
        "tests/mark/class/06_typo.deriv",
        "tests/mark/other/sign_of_a_term.deriv",
        "tests/mark/gaming/02_rescued_inertia.deriv",
        "--feedback",
        &d,
    ]);
    assert_eq!(code, 0, "{err}");
    let read = |k: usize, stem: &str| {
        std::fs::read_to_string(dir.join(format!("{k:03}-{stem}.md"))).expect("feedback")
    };
    let factor = read(0, "04_factor");
    // The student's own line, both sides, the counterexample, the factor.
    for words in [
        "9 | claim [xdd] x'' = -1/3 g sin(beta) by [Fx], [MG], [roll]",
        "the left side is 2 × the right side",
        "= left side:  x''",
        "= right side: -g sin(beta)/3",
        "= counterexample: at beta = 2",
    ] {
        assert!(factor.contains(words), "{words}:\n{factor}");
    }
    let typo = read(1, "06_typo");
    assert!(typo.contains("did you mean `R`?"), "{typo}");
    // A name in the message is code, not an escaped backtick.
    assert!(typo.contains("Line 7: undeclared symbol `Rr`."), "{typo}");
    assert!(!typo.contains("\\`"), "{typo}");
    let sign = read(2, "sign_of_a_term");
    assert!(
        sign.contains(
            "Hint: check the direction you took as positive for the term `m g sin(beta)`."
        ),
        "{sign}"
    );
    let own = read(3, "02_rescued_inertia");
    assert!(
        own.contains("- \\[h\\], line 7: your own assumption: the problem does not give it"),
        "{own}"
    );
    assert!(
        own.contains("- `x''` (line 10): not credited: rests on your own assumption \\[h\\], line 7, which the problem does not give"),
        "{own}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_reference_whose_facts_are_unlabelled_still_tells_the_problems_facts_from_the_students() {
    let (out, err, code) = mark(&[
        "--reference",
        "tests/mark/reference_unlabelled.deriv",
        "tests/mark/class/01_correct.deriv",
        "tests/mark/fair/06_facts_rearranged.deriv",
        "tests/mark/gaming/03_answer_as_given.deriv",
        "--format",
        "csv",
    ]);
    assert_eq!(code, 0, "{err}");
    let rows: Vec<&str> = out.lines().skip(1).collect();
    assert!(rows[0].ends_with(",2,2,,,2,2,"), "{out}");
    assert!(rows[1].ends_with(",2,2,,,2,2,"), "{out}");
    assert!(
        rows[2].contains(
            ",2,2,,,0,2,\"[xdd] not credited: rests on your own assumption [ans], line 9"
        ),
        "{out}"
    );
}

#[test]
fn a_role_no_fact_of_the_problem_justifies_is_said_not_claimed() {
    let out = human("tests/mark/gaming/11_unjustified_name.deriv", &[]);
    assert!(!out.contains("names matched by role"), "{out}");
    assert!(
        out.contains("  names no fact of the problem matches: phi\n"),
        "{out}"
    );
}

#[test]
fn a_false_given_that_nothing_marked_rests_on_is_named_in_the_row() {
    let r = rows(&["tests/mark/gaming/12_false_given_unused.deriv"], &[]);
    assert!(
        r[0].ends_with(",2,2,,,2,2,facts not the problem's: [c1] line 9"),
        "{}",
        r[0]
    );
}
