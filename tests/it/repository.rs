//! The repository is the whole product: a clone with nothing beside it builds, tests and
//! documents itself. Nothing in it may read, include or link a folder beside it.

use std::path::{Path, PathBuf};

/// Folders that are built or downloaded, never written by hand (and never committed).
const GENERATED: &[&str] = &[
    ".git",
    "target",
    "node_modules",
    "dist",
    ".venv",
    "corpus",
    "artifacts",
];

/// Every file of the repository, generated folders left out.
fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        let name = entry.file_name();
        let Ok(kind) = entry.file_type() else {
            continue;
        };
        if kind.is_dir() {
            if !GENERATED.iter().any(|g| name == *g) {
                files(&path, out);
            }
        } else if kind.is_file() {
            out.push(path);
        }
    }
}

/// The places in the repository's text files that name the folder beside it.
fn outside_references(root: &Path, needle: &str) -> Vec<String> {
    let mut all = Vec::new();
    files(root, &mut all);
    all.sort();
    let mut found = Vec::new();
    for path in all {
        let Ok(text) = std::fs::read_to_string(&path) else {
            continue; // binary
        };
        for (k, line) in text.lines().enumerate() {
            if line.contains(needle) {
                let rel = path.strip_prefix(root).unwrap_or(&path);
                found.push(format!("{}:{}: {}", rel.display(), k + 1, line.trim()));
            }
        }
    }
    found
}

/// The team's private folder beside the repository, spelt so that this file does not
/// name it itself.
fn team_folder() -> String {
    ["..", "shared"].join("/")
}

#[test]
fn nothing_in_the_repository_names_the_folder_beside_it() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let found = outside_references(root, &team_folder());
    assert!(
        found.is_empty(),
        "users get the repository alone; these lines name a folder outside it:\n{}",
        found.join("\n")
    );
}

#[test]
fn the_search_finds_a_reference_where_there_is_one() {
    // The check above must be able to fail: a planted reference is found.
    let dir = std::env::temp_dir().join(format!("rigor-repo-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("docs")).expect("a temporary folder");
    std::fs::create_dir_all(dir.join("target")).expect("a temporary folder");
    let needle = team_folder();
    std::fs::write(
        dir.join("docs/notes.md"),
        format!("see [the format]({needle}/FORMAT.md)\n"),
    )
    .expect("written");
    std::fs::write(dir.join("target/built.txt"), &needle).expect("written");
    let found = outside_references(&dir, &needle);
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(found[0].starts_with("docs/notes.md:1:"), "{found:?}");
}
