//! `rigor lint` on lecture notes: the handout as it is, and two documents of our own with
//! deliberate mistakes; the full report of each is a snapshot.

use std::path::Path;
use std::process::Command;

fn lint(paths: &[&str]) -> (String, String, i32) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = Command::new(env!("CARGO_BIN_EXE_rigor"))
        .arg("lint")
        .args(paths)
        .current_dir(root)
        .output()
        .expect("rigor runs");
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
        out.status.code().unwrap_or(-1),
    )
}

#[test]
fn notes_with_mistakes_fail_at_the_mistakes_only() {
    let (out, err, code) = lint(&["tests/lint/rod_notes.md", "tests/lint/incline_notes.tex"]);
    assert_eq!(code, 1, "{out}{err}");
    assert!(
        out.ends_with("chains: 8, verified: 5, failed: 2, needs context: 1\n"),
        "{out}"
    );
    assert!(
        out.contains("tests/lint/rod_notes.md:15:3: FAILED"),
        "{out}"
    );
    assert!(
        out.contains("tests/lint/incline_notes.tex:12:1: FAILED"),
        "{out}"
    );
    // Code blocks and inline code are never math.
    assert!(
        !out.contains("rod_notes.md:19") && !out.contains("rod_notes.md:18"),
        "{out}"
    );
    insta::assert_snapshot!(format!("{out}\n{err}"));
}

#[test]
fn the_handout_as_it_is_never_fails_and_verifies_what_holds_on_its_own() {
    let seed =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/seeds/000_4a418897358df19b.txt");
    let Ok(text) = std::fs::read_to_string(&seed) else {
        panic!("the handout is at {}", seed.display());
    };
    let dir = std::env::temp_dir().join(format!("rigor-lint-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    let doc = dir.join("handout.md");
    std::fs::write(&doc, text).expect("written");
    let (out, err, code) = lint(&[&doc.display().to_string()]);
    assert_eq!(code, 0, "no chain of the handout is false:\n{out}{err}");
    let summary = out.lines().last().unwrap_or_default().to_string();
    assert!(
        summary.starts_with("chains: 49, verified: 9, failed: 0"),
        "{summary}"
    );
    let report = out.replace(&doc.display().to_string(), "handout.md");
    insta::assert_snapshot!(report);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_missing_document_is_bad_input() {
    let (_, err, code) = lint(&["tests/lint/no_such_notes.md"]);
    assert_eq!(code, 2);
    assert!(err.contains("no_such_notes.md"), "{err}");
}
