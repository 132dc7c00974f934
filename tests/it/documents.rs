//! Worked solutions as documents: the LaTeX and Markdown of every handout file, with
//! and without the filled-in work of `--steps`, and of two failing fixtures, as
//! reviewed snapshots. (`src/render/tests.rs` compiles the LaTeX with pdflatex.)

use rigor::files::check_paths;
use rigor::render::{latex, markdown, Detail};
use std::path::{Path, PathBuf};

/// The four documents of one file, each as a snapshot named after the file; whether
/// `--steps` filled anything in.
fn snapshot_documents(path: &Path) -> bool {
    let mut reports = check_paths(&[path.to_path_buf()], &crate::no_budget());
    assert_eq!(reports.len(), 1, "{}", path.display());
    let mut r = reports.remove(0);
    // The path as the snapshot shows it does not depend on where the repository is.
    r.path = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let name = path
        .file_stem()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let written = latex::document_with(&r, Detail::Written);
    let steps = latex::document_with(&r, Detail::Steps);
    let filled = steps.contains("\\textit{Working.}");
    assert_eq!(filled, steps.len() > written.len(), "{name}");
    insta::assert_snapshot!(format!("{name}.tex"), written);
    insta::assert_snapshot!(format!("{name}.steps.tex"), steps);
    insta::assert_snapshot!(
        format!("{name}.md"),
        markdown::document_with(&r, Detail::Written)
    );
    insta::assert_snapshot!(
        format!("{name}.steps.md"),
        markdown::document_with(&r, Detail::Steps)
    );
    filled
}

#[test]
fn handout_documents() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("derivations");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("derivations/")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "deriv"))
        .collect();
    files.sort();
    assert!(files.len() >= 11);
    let mut nothing_to_fill = Vec::new();
    for path in files {
        if !snapshot_documents(&path) {
            nothing_to_fill.extend(path.file_name().map(|n| n.to_string_lossy().into_owned()));
        }
    }
    // Its steps are identities of definitions: no integral, no fact.
    assert_eq!(nothing_to_fill, ["radius_of_gyration.deriv"]);
}

#[test]
fn failing_documents() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/check/fail");
    for name in ["rod_factor_two.deriv", "rolling_cylinder_wrong_sign.deriv"] {
        assert!(snapshot_documents(&dir.join(name)), "{name}");
    }
}
