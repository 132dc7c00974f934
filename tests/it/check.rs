//! Checker fixtures: `tests/check/pass` must verify, every `tests/check/fail` file must
//! fail with the diagnostic in its snapshot, and every handout derivation must verify.

use rigor::check::{check_paths, FileReport, Options, Status};
use std::path::{Path, PathBuf};

fn check_one(path: &Path) -> FileReport {
    let mut reports = check_paths(&[path.to_path_buf()], &Options::default());
    assert_eq!(reports.len(), 1, "one report per file");
    reports.remove(0)
}

/// The diagnostics as the terminal shows them, with the file name only.
fn rendered(r: &FileReport, path: &Path) -> String {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    r.diagnostics
        .iter()
        .map(|d| rigor::diag::render(d, &name, &r.source))
        .collect()
}

#[test]
fn passing_fixtures_verify() {
    insta::glob!("..", "check/pass/*.deriv", |path| {
        let r = check_one(path);
        assert!(
            r.ok(),
            "{} should verify:\n{}",
            path.display(),
            rendered(&r, path)
        );
        assert!(r.links() > 0 || r.claims.is_empty(), "claims are checked");
    });
}

#[test]
fn failing_fixtures_fail_with_their_diagnostic() {
    insta::glob!("..", "check/fail/*.deriv", |path| {
        let r = check_one(path);
        assert!(!r.ok(), "{} should not verify", path.display());
        let text = rendered(&r, path);
        assert!(!text.is_empty(), "a failure comes with a diagnostic");
        // The first line of the fixture says what the mistake is and where.
        let first = r.source.lines().next().unwrap_or_default().to_string();
        insta::assert_snapshot!(format!("{first}\n\n{text}"));
    });
}

fn justification(s: &Status) -> String {
    match s {
        Status::Verified {
            how,
            side_conditions,
        } => {
            let how = how.to_string();
            if side_conditions.is_empty() {
                how
            } else {
                format!("{how}; assuming {}", side_conditions.join(", "))
            }
        }
        Status::Failed => "FAILED".into(),
        Status::Undecided => "UNDECIDED".into(),
        Status::Error => "ERROR".into(),
    }
}

#[test]
fn handout_derivations_verify() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("derivations");
    insta::glob!("../..", "derivations/*.deriv", |path| {
        let r = check_one(path);
        assert!(
            r.ok(),
            "{} must verify:\n{}",
            dir.display(),
            rendered(&r, path)
        );
        let mut out = String::new();
        for c in &r.claims {
            let label = c
                .label
                .clone()
                .map_or_else(|| "(unlabelled)".into(), |l| format!("[{l}]"));
            out.push_str(&format!("{label} line {}\n", c.line));
            for l in &c.links {
                out.push_str(&format!(
                    "    {} {} {}    -- {}\n",
                    l.lhs.as_deref().unwrap_or("?"),
                    l.op,
                    l.rhs.as_deref().unwrap_or("?"),
                    justification(&l.status)
                ));
            }
        }
        insta::assert_snapshot!(out);
    });
}

#[test]
fn results_come_in_a_stable_order() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("derivations");
    let a: Vec<String> = check_paths(std::slice::from_ref(&dir), &Options::default())
        .into_iter()
        .map(|r| r.path)
        .collect();
    let mut sorted = a.clone();
    sorted.sort();
    assert_eq!(a, sorted);
    assert!(a.len() >= 9);
}
