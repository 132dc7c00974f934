//! The GitHub Action (`action.yml`) and the pre-commit hook (`.pre-commit-hooks.yaml`)
//! for course repositories: their shell steps run here as GitHub would run them (with
//! rigor already installed where the action installs it; TeX's install and the upload
//! are GitHub's own), so a renamed flag or a broken script is caught.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The `run:` script of the step named `name` in `action.yml` (a one-line value,
/// quoted or not, or a `|` block).
fn step_script(yaml: &str, name: &str) -> String {
    let lines: Vec<&str> = yaml.lines().collect();
    let start = lines
        .iter()
        .position(|l| l.trim() == format!("- name: {name}"))
        .unwrap_or_else(|| panic!("action.yml has no step `{name}`"));
    let indent = |l: &str| l.len() - l.trim_start().len();
    let step_indent = indent(lines[start]);
    let mut i = start + 1;
    while i < lines.len() && indent(lines[i]) > step_indent {
        let t = lines[i].trim_start();
        if let Some(v) = t.strip_prefix("run:") {
            let v = v.trim();
            if v == "|" {
                let body_indent = indent(lines[i + 1]);
                return lines[i + 1..]
                    .iter()
                    .take_while(|l| l.trim().is_empty() || indent(l) >= body_indent)
                    .map(|l| l.get(body_indent..).unwrap_or(""))
                    .collect::<Vec<_>>()
                    .join("\n");
            }
            return v.trim_matches('\'').to_string();
        }
        i += 1;
    }
    panic!("step `{name}` has no run:");
}

/// Runs a step's script with bash, rigor where the action installs it.
fn run_step(script: &str, temp: &Path, env: &[(&str, &str)]) -> std::process::Output {
    let bin = temp.join("rigor/bin");
    std::fs::create_dir_all(&bin).unwrap();
    let _ = std::fs::remove_file(bin.join("rigor"));
    std::os::unix::fs::symlink(env!("CARGO_BIN_EXE_rigor"), bin.join("rigor")).unwrap();
    Command::new("bash")
        .args(["-e", "-c", script])
        .current_dir(root())
        .env("RUNNER_TEMP", temp)
        .envs(env.iter().copied())
        .output()
        .expect("bash runs")
}

#[test]
fn the_action_checks_a_folder_and_typesets_its_book() {
    let yaml = std::fs::read_to_string(root().join("action.yml")).expect("action.yml");
    let temp = std::env::temp_dir().join(format!("rigor-action-{}", std::process::id()));
    let check = step_script(&yaml, "Check the derivations");
    // A folder that verifies: exit 0, no annotation.
    let out = run_step(&check, &temp, &[("RIGOR_PATH", "derivations/")]);
    assert!(out.status.success(), "{out:?}");
    assert!(!String::from_utf8_lossy(&out.stdout).contains("::error"));
    // A failing step fails the job, with an annotation at its line.
    let out = run_step(
        &check,
        &temp,
        &[("RIGOR_PATH", "tests/check/fail/kind_wrong_power.deriv")],
    );
    assert_eq!(out.status.code(), Some(1), "{out:?}");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.starts_with("::error file=tests/check/fail/kind_wrong_power.deriv,line=7,"),
        "{stdout}"
    );
    // The book: its TeX is written (pdflatex runs where TeX is installed).
    let book = step_script(&yaml, "Typeset the worked solutions");
    let out = run_step(
        &book,
        &temp,
        &[("RIGOR_PATH", "tests/data/book"), ("RIGOR_TITLE", "Rods")],
    );
    let tex = std::fs::read_to_string(temp.join("rigor-book/solutions.tex")).unwrap_or_default();
    let pdf = temp.join("rigor-book/solutions.pdf").is_file();
    let _ = std::fs::remove_dir_all(&temp);
    assert!(out.status.success(), "{out:?}");
    assert!(
        tex.contains("\\title{Rods}") && tex.contains("\\tableofcontents"),
        "{tex}"
    );
    assert!(pdf, "no PDF");
}

#[test]
fn the_pre_commit_hook_runs_rigor_check_on_derivation_files() {
    let hooks = std::fs::read_to_string(root().join(".pre-commit-hooks.yaml")).expect("hooks");
    let field = |k: &str| {
        hooks
            .lines()
            .find_map(|l| {
                l.trim()
                    .trim_start_matches("- ")
                    .strip_prefix(&format!("{k}: "))
            })
            .unwrap_or_else(|| panic!("no {k}"))
            .to_string()
    };
    assert_eq!(field("id"), "rigor-check");
    assert_eq!(field("language"), "rust");
    assert_eq!(field("files"), "\\.deriv$");
    // pre-commit runs the entry with the changed files as arguments.
    let entry = field("entry");
    let mut words = entry.split_whitespace();
    assert_eq!(words.next(), Some("rigor"));
    let out = Command::new(env!("CARGO_BIN_EXE_rigor"))
        .args(words)
        .args(["derivations/rod.deriv", "derivations/disk.deriv"])
        .current_dir(root())
        .output()
        .expect("rigor runs");
    assert!(out.status.success(), "{out:?}");
    assert!(String::from_utf8_lossy(&out.stdout).starts_with("files: 2,"));
}
