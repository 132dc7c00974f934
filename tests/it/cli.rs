//! Command line: the built `rigor` binary, its exit statuses (FORMAT.md §4) and the
//! key lines of its output. Every run has a wall-clock guard.

use sha2::{Digest, Sha256};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus, Stdio};
use std::time::{Duration, Instant};

/// What one run of the binary did.
pub(crate) struct Run {
    /// The exit status.
    pub status: ExitStatus,
    /// Standard output, lossily decoded.
    pub stdout: String,
    /// Standard error, lossily decoded.
    pub stderr: String,
    /// Wall-clock time of the run.
    pub elapsed: Duration,
}

impl Run {
    /// The exit code; fails the test if the process died of a signal.
    pub fn code(&self) -> i32 {
        match self.status.code() {
            Some(c) => c,
            None => panic!(
                "rigor was killed by a signal ({:?})\nstderr:\n{}",
                self.status,
                head(&self.stderr)
            ),
        }
    }
}

/// The first few kilobytes of `s`, for failure messages.
pub(crate) fn head(s: &str) -> String {
    let mut end = s.len().min(4000);
    while !s.is_char_boundary(end) {
        end -= 1;
    }
    s[..end].to_string()
}

/// The crate's folder: runs start there so that relative paths such as `derivations/` work.
pub(crate) fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A fresh, empty scratch folder for one test.
pub(crate) fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("rigor-it")
        .join(format!("{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create a scratch folder");
    dir
}

/// Runs `rigor ARGS` in the crate's folder; kills it and fails after `limit`.
/// Output is collected by threads so that a chatty run cannot fill a pipe and stall.
pub(crate) fn run_with_limit(args: &[&str], limit: Duration) -> Run {
    let start = Instant::now();
    let mut child = Command::new(env!("CARGO_BIN_EXE_rigor"))
        .args(args)
        .current_dir(root())
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn rigor");
    let mut out = child.stdout.take().expect("stdout");
    let mut err = child.stderr.take().expect("stderr");
    let t_out = std::thread::spawn(move || {
        let mut v = Vec::new();
        let _ = std::io::Read::read_to_end(&mut out, &mut v);
        v
    });
    let t_err = std::thread::spawn(move || {
        let mut v = Vec::new();
        let _ = std::io::Read::read_to_end(&mut err, &mut v);
        v
    });
    let status = loop {
        match child.try_wait().expect("wait for rigor") {
            Some(s) => break s,
            None if start.elapsed() > limit => {
                let _ = child.kill();
                let _ = child.wait();
                panic!(
                    "rigor {} did not finish within {limit:?}: killed",
                    shorten(&args.join(" "))
                );
            }
            None => std::thread::sleep(Duration::from_millis(10)),
        }
    };
    let elapsed = start.elapsed();
    let stdout = String::from_utf8_lossy(&t_out.join().unwrap_or_default()).into_owned();
    let stderr = String::from_utf8_lossy(&t_err.join().unwrap_or_default()).into_owned();
    Run {
        status,
        stdout,
        stderr,
        elapsed,
    }
}

/// The command line, cut short for messages.
fn shorten(s: &str) -> String {
    if s.chars().count() > 200 {
        format!("{}…", s.chars().take(200).collect::<String>())
    } else {
        s.to_string()
    }
}

/// Runs `rigor ARGS` with a 60-second guard.
pub(crate) fn run(args: &[&str]) -> Run {
    run_with_limit(args, Duration::from_secs(60))
}

/// Fails unless the run exited with `code`, showing its output.
#[track_caller]
fn expect_code(r: &Run, code: i32, what: &str) {
    assert_eq!(
        r.code(),
        code,
        "{what}: exit status\nstdout:\n{}\nstderr:\n{}",
        head(&r.stdout),
        head(&r.stderr)
    );
}

/// The `files: …` summary line of human output.
fn summary(r: &Run) -> BTreeMap<String, usize> {
    let line = r
        .stdout
        .lines()
        .find(|l| l.starts_with("files: "))
        .unwrap_or_else(|| panic!("no summary line in:\n{}", head(&r.stdout)));
    line.split(", ")
        .map(|kv| {
            let (k, v) = kv.split_once(": ").expect("key: value");
            (k.to_string(), v.trim().parse().expect("a count"))
        })
        .collect()
}

/// The number of derivation files in `derivations/`.
fn handout_files() -> usize {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("derivations");
    std::fs::read_dir(dir)
        .expect("derivations/")
        .filter(|e| {
            e.as_ref()
                .is_ok_and(|e| e.path().extension().is_some_and(|x| x == "deriv"))
        })
        .count()
}

#[test]
fn check_derivations_verifies_everything() {
    let r = run(&["check", "derivations/"]);
    expect_code(&r, 0, "check derivations/");
    let s = summary(&r);
    assert_eq!(s["files"], handout_files(), "{s:?}");
    assert!(s["claims"] > 0 && s["links"] >= s["claims"], "{s:?}");
    assert_eq!(s["verified"], s["links"], "{s:?}");
    assert_eq!(s["failed"], 0, "{s:?}");
    assert_eq!(s["undecided"], 0, "{s:?}");
    assert_eq!(s["errors"], 0, "{s:?}");
    assert!(
        r.stderr.is_empty(),
        "nothing on stderr: {}",
        head(&r.stderr)
    );
}

#[test]
fn check_without_paths_reads_derivations() {
    let r = run(&["check"]);
    expect_code(&r, 0, "check");
    assert_eq!(summary(&r)["files"], handout_files());
}

#[test]
fn check_failing_fixture_exits_1() {
    let r = run(&["check", "tests/check/fail/disk_wrong_power.deriv"]);
    expect_code(&r, 1, "a failing step");
    assert!(r.stderr.contains("error[E0301]"), "{}", head(&r.stderr));
    assert!(
        r.stderr
            .contains("tests/check/fail/disk_wrong_power.deriv:50:3"),
        "the diagnostic points at the line: {}",
        head(&r.stderr)
    );
    assert!(r.stderr.contains("counterexample"), "{}", head(&r.stderr));
    let s = summary(&r);
    assert!(s["failed"] > 0 && s["errors"] == 0, "{s:?}");
}

#[test]
fn check_syntax_error_exits_2() {
    let r = run(&["check", "tests/check/fail/kind_syntax_statement.deriv"]);
    expect_code(&r, 2, "a syntax error");
    assert!(
        r.stderr.contains("error[E0001]: syntax error"),
        "{}",
        head(&r.stderr)
    );
    assert!(
        r.stderr.contains("kind_syntax_statement.deriv:5:10"),
        "{}",
        head(&r.stderr)
    );
    assert_eq!(summary(&r)["errors"], 1);
}

#[test]
fn check_missing_path_exits_2_naming_path_and_os_error() {
    let missing = "no/such/folder/missing.deriv";
    let r = run(&["check", missing]);
    expect_code(&r, 2, "a missing path");
    assert!(r.stderr.contains(missing), "names the path: {}", r.stderr);
    assert!(
        r.stderr.contains("No such file or directory") && r.stderr.contains("os error"),
        "gives the OS error: {}",
        r.stderr
    );
}

#[test]
fn check_mixes_statuses_worst_wins() {
    // A verified file with a failing one: 1; with bad input as well: 2.
    let r = run(&[
        "check",
        "derivations/rod.deriv",
        "tests/check/fail/disk_wrong_power.deriv",
    ]);
    expect_code(&r, 1, "verified + failing");
    let r = run(&[
        "check",
        "derivations/rod.deriv",
        "tests/check/fail/disk_wrong_power.deriv",
        "no-such-file.deriv",
    ]);
    expect_code(&r, 2, "verified + failing + missing");
}

#[test]
fn check_json_is_one_object_per_line() {
    let r = run(&["check", "--format", "json", "derivations/"]);
    expect_code(&r, 0, "json");
    let lines: Vec<&str> = r.stdout.lines().collect();
    assert_eq!(
        lines.len(),
        handout_files(),
        "one line per file:\n{}",
        head(&r.stdout)
    );
    for l in lines {
        let v: serde_json::Value = serde_json::from_str(l).expect("each line is JSON");
        assert!(v["path"].as_str().is_some_and(|p| p.ends_with(".deriv")));
        assert_eq!(v["ok"], serde_json::Value::Bool(true), "{l}");
        let claims = v["claims"].as_array().expect("claims");
        assert!(!claims.is_empty());
        for c in claims {
            for link in c["links"].as_array().expect("links") {
                assert_eq!(link["status"], "verified", "{link}");
                assert!(link["line"].as_u64().is_some());
            }
        }
        assert!(v["diagnostics"].as_array().expect("diagnostics").is_empty());
    }

    let r = run(&[
        "check",
        "--format",
        "json",
        "tests/check/fail/disk_wrong_power.deriv",
    ]);
    expect_code(&r, 1, "json, failing");
    let v: serde_json::Value = serde_json::from_str(r.stdout.trim()).expect("JSON");
    assert_eq!(v["ok"], serde_json::Value::Bool(false));
    let diags = v["diagnostics"].as_array().expect("diagnostics");
    assert!(!diags.is_empty());
    assert_eq!(diags[0]["code"], "E0301");
    assert_eq!(diags[0]["line"], 50);
    // The hint (the words under the caret) and the counterexample are in the JSON too.
    assert_eq!(
        diags[0]["label"],
        "the left side is 3 R/4 × the right side (a wrong power?)"
    );
    let notes = diags[0]["notes"].as_array().expect("notes");
    assert!(
        notes.iter().any(|n| n
            .as_str()
            .is_some_and(|n| n.starts_with("counterexample: at R = "))),
        "{notes:?}"
    );
    let failed = v["claims"]
        .as_array()
        .expect("claims")
        .iter()
        .flat_map(|c| c["links"].as_array().cloned().unwrap_or_default())
        .map(|l| l["status"].as_str().unwrap_or_default().to_string())
        .filter(|s| s != "verified")
        .collect::<Vec<_>>();
    // One mistake, one error: the next line, which follows only from the right
    // version of line 50, is not checked (a note), not a second failure.
    assert_eq!(failed, ["failed", "not_checked"]);

    // Unreadable input is still one JSON object.
    let r = run(&["check", "--format", "json", "missing.deriv"]);
    expect_code(&r, 2, "json, missing");
    let v: serde_json::Value = serde_json::from_str(r.stdout.trim()).expect("JSON");
    assert_eq!(v["ok"], serde_json::Value::Bool(false));
    assert!(!v["diagnostics"].as_array().expect("diagnostics").is_empty());
}

#[test]
fn check_github_annotations() {
    let r = run(&[
        "check",
        "--format",
        "github",
        "tests/check/fail/disk_wrong_power.deriv",
    ]);
    expect_code(&r, 1, "github");
    let errors: Vec<&str> = r
        .stdout
        .lines()
        .filter(|l| l.starts_with("::error "))
        .collect();
    assert_eq!(errors.len(), 1, "{}", r.stdout);
    assert!(
        errors[0].starts_with("::error file=tests/check/fail/disk_wrong_power.deriv,line=50,"),
        "{}",
        errors[0]
    );
    // A workflow command is one line: newlines in messages are escaped.
    assert!(errors[0].contains("%0A"), "{}", errors[0]);
    // The hint under the caret and the checked counterexample travel with it.
    assert!(
        errors[0].contains("%0Athe left side is 3 R/4 × the right side (a wrong power?)%0A"),
        "{}",
        errors[0]
    );
    assert!(
        errors[0].contains("%0Acounterexample: at R = "),
        "{}",
        errors[0]
    );

    let r = run(&["check", "--format", "github", "derivations/"]);
    expect_code(&r, 0, "github, verified");
    assert!(!r.stdout.contains("::error"), "{}", r.stdout);
}

#[test]
fn check_verbose_tells_how_links_were_justified() {
    let quiet = run(&["check", "derivations/rod.deriv"]);
    expect_code(&quiet, 0, "rod");
    assert!(!quiet.stdout.contains("verified ("), "{}", quiet.stdout);
    for flag in ["--verbose", "-v"] {
        let r = run(&["check", flag, "derivations/rod.deriv"]);
        expect_code(&r, 0, "rod, verbose");
        let n = r
            .stdout
            .lines()
            .filter(|l| l.starts_with("derivations/rod.deriv:") && l.contains(": verified ("))
            .count();
        assert_eq!(n, summary(&r)["links"], "one line per link:\n{}", r.stdout);
        assert!(r.stdout.contains("verified (identity)"), "{}", r.stdout);
    }
}

#[test]
fn simplify_exit_statuses() {
    let r = run(&["simplify", "sqrt(R^2/2)", "--assume", "R > 0"]);
    expect_code(&r, 0, "simplify");
    assert_eq!(r.stdout.trim(), "sqrt(2) R/2");
    let r = run(&["simplify", "m L^2/12 + m (L/2)^2"]);
    expect_code(&r, 0, "simplify");
    // The normal form parses back to itself.
    let again = run(&["simplify", r.stdout.trim()]);
    expect_code(&again, 0, "simplify its own output");
    assert_eq!(again.stdout, r.stdout);
    let r = run(&["simplify", "-x^2"]);
    expect_code(&r, 0, "a leading minus is an expression, not a flag");
    for bad in ["x +", "f(x)", "1/(x-x)", "0^0", "((x)", ""] {
        let r = run(&["simplify", bad]);
        expect_code(&r, 2, bad);
        assert!(r.stderr.contains("error"), "{bad}: {}", r.stderr);
    }
    let r = run(&["simplify", "x", "--assume", "x >"]);
    expect_code(&r, 2, "bad --assume");
}

#[test]
fn equiv_exit_statuses() {
    let r = run(&["equiv", "m L^2/12 + m (L/2)^2", "m L^2/3"]);
    expect_code(&r, 0, "equal");
    assert_eq!(r.stdout.lines().next(), Some("equal"));
    let r = run(&["equiv", "sin(2 theta)", "2 sin(theta)"]);
    expect_code(&r, 1, "not equal");
    assert_eq!(r.stdout.lines().next(), Some("not equal"));
    assert!(r.stdout.contains("counterexample"), "{}", r.stdout);
    let r = run(&["equiv", "x +", "1"]);
    expect_code(&r, 2, "bad input");
    let r = run(&["equiv", "sqrt(x)^2", "abs(x)"]);
    expect_code(&r, 3, "undecided");
    assert_eq!(r.stdout.lines().next(), Some("undecided"));
    let r = run(&["equiv", "sqrt(R^2)", "R", "--assume", "R > 0"]);
    expect_code(&r, 0, "equal under an assumption");
}

/// The names in `dir`.
fn listing(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .expect("read_dir")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn latex_writes_its_output_atomically() {
    let dir = scratch("latex");
    let out = dir.join("rod.tex");
    let out_s = out.to_str().expect("utf-8 path");
    let r = run(&["latex", "derivations/rod.deriv", "-o", out_s]);
    expect_code(&r, 0, "latex of a verified file");
    assert!(r.stdout.is_empty(), "the document goes to -o, not stdout");
    let text = std::fs::read_to_string(&out).expect("OUT written");
    assert!(text.starts_with("\\documentclass"), "{}", head(&text));
    assert!(text.trim_end().ends_with("\\end{document}"));
    assert_eq!(listing(&dir), ["rod.tex"], "no temporary file left behind");

    // Overwrites an existing OUT; a failing file still renders, exit 1.
    let r = run(&[
        "latex",
        "tests/check/fail/disk_wrong_power.deriv",
        "-o",
        out_s,
    ]);
    expect_code(&r, 1, "latex of a failing file");
    let text = std::fs::read_to_string(&out).expect("OUT written");
    assert!(text.starts_with("\\documentclass"));
    assert!(text.contains("\\end{document}"));
    assert!(
        r.stderr.contains("E0301"),
        "failures are reported: {}",
        r.stderr
    );
    assert_eq!(listing(&dir), ["rod.tex"], "no temporary file left behind");

    // Bad input: exit 2, OUT not written.
    let bad = dir.join("bad.tex");
    let r = run(&[
        "latex",
        "tests/check/fail/kind_syntax_statement.deriv",
        "-o",
        bad.to_str().expect("utf-8"),
    ]);
    expect_code(&r, 2, "latex of a syntax error");
    assert!(!bad.exists());
    assert_eq!(listing(&dir), ["rod.tex"]);

    // Without -o the document goes to stdout.
    let r = run(&["latex", "derivations/rod.deriv"]);
    expect_code(&r, 0, "latex to stdout");
    assert!(r.stdout.starts_with("\\documentclass"));

    // An OUT in a folder that does not exist: exit 2, nothing written.
    let r = run(&[
        "latex",
        "derivations/rod.deriv",
        "-o",
        dir.join("no/such/dir/x.tex").to_str().expect("utf-8"),
    ]);
    expect_code(&r, 2, "unwritable OUT");
    assert!(r.stderr.contains("cannot write"), "{}", r.stderr);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn markdown_renders() {
    let r = run(&["markdown", "derivations/rod.deriv"]);
    expect_code(&r, 0, "markdown");
    assert!(r.stdout.starts_with("# "), "{}", head(&r.stdout));
    assert!(r.stdout.contains("$$"), "display math");
    let dir = scratch("markdown");
    let out = dir.join("disk.md");
    let r = run(&[
        "markdown",
        "tests/check/fail/disk_wrong_power.deriv",
        "-o",
        out.to_str().expect("utf-8"),
    ]);
    expect_code(&r, 1, "markdown of a failing file");
    assert!(std::fs::read_to_string(&out)
        .expect("written")
        .contains("$$"));
    assert_eq!(listing(&dir), ["disk.md"]);
    let r = run(&["markdown", "tests/check/fail/kind_syntax_statement.deriv"]);
    expect_code(&r, 2, "markdown of a syntax error");
    let r = run(&["markdown", "missing.deriv"]);
    expect_code(&r, 2, "markdown of a missing file");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn steps_fill_in_the_work() {
    let bracket = "\\Big[\\frac{m\\,y^{3}}{3 L}\\Big]_{y=-\\frac{L}{2}}^{y=\\frac{L}{2}}";
    for format in ["latex", "markdown"] {
        let plain = run(&[format, "derivations/rod.deriv"]);
        expect_code(&plain, 0, format);
        let steps = run(&[format, "derivations/rod.deriv", "--steps"]);
        expect_code(&steps, 0, "--steps");
        assert!(steps.stdout.contains(bracket), "{}", steps.stdout);
        assert!(steps.stdout.contains("Working."), "{}", steps.stdout);
        assert!(!plain.stdout.contains(bracket) && !plain.stdout.contains("Working."));
    }
    let r = run(&["latex", "derivations", "--steps", "--title", "Handout"]);
    expect_code(&r, 0, "a book with --steps");
    assert!(r.stdout.contains("\\tableofcontents") && r.stdout.contains("Working."));
    let r = run(&[
        "markdown",
        "tests/check/fail/rod_factor_two.deriv",
        "--steps",
    ]);
    expect_code(&r, 1, "--steps of a failing file");
    assert!(r.stdout.contains("**does not hold**") && r.stdout.contains("*Working.*"));
}

/// SHA-256 of every file under `dir`, by path.
fn hashes(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).expect("read_dir") {
            let p = e.expect("entry").path();
            if p.is_dir() {
                stack.push(p);
            } else {
                let bytes = std::fs::read(&p).expect("read");
                out.insert(p, Sha256::digest(&bytes).to_vec());
            }
        }
    }
    out
}

#[test]
fn check_never_modifies_its_input() {
    // A copy of the handouts and the failing fixtures (imports included), checked in
    // every format: the folder holds the same files with the same bytes afterwards.
    let dir = scratch("readonly");
    for (from, to) in [("derivations", "derivations"), ("tests/check/fail", "fail")] {
        let src = root().join(from);
        let mut stack = vec![(src.clone(), dir.join(to))];
        while let Some((s, d)) = stack.pop() {
            std::fs::create_dir_all(&d).expect("mkdir");
            for e in std::fs::read_dir(&s).expect("read_dir") {
                let p = e.expect("entry").path();
                let name = p.file_name().expect("name").to_owned();
                if p.is_dir() {
                    stack.push((p, d.join(name)));
                } else if p.extension().is_some_and(|x| x == "deriv") {
                    std::fs::copy(&p, d.join(name)).expect("copy");
                }
            }
        }
    }
    let before = hashes(&dir);
    assert!(before.len() > 20, "copied the fixtures");
    let d = dir.to_str().expect("utf-8");
    for format in ["human", "json", "github"] {
        let r = run(&["check", "--format", format, "--verbose", d]);
        assert_eq!(r.code(), 2, "the fixtures include bad input ({format})");
    }
    let r = run(&["latex", &format!("{d}/derivations/rod.deriv")]);
    expect_code(&r, 0, "latex to stdout");
    assert_eq!(hashes(&dir), before, "check changed or created files");

    // The repository's own handouts, too.
    let before = hashes(&root().join("derivations"));
    expect_code(&run(&["check", "derivations"]), 0, "check derivations");
    assert_eq!(hashes(&root().join("derivations")), before);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn usage_errors_exit_2_and_help_exits_0() {
    let r = run(&[]);
    expect_code(&r, 2, "no command");
    let r = run(&["frobnicate"]);
    expect_code(&r, 2, "unknown command");
    let r = run(&["check", "--format", "xml"]);
    expect_code(&r, 2, "unknown format");
    let r = run(&["--help"]);
    expect_code(&r, 0, "--help");
    assert!(r.stdout.contains("check"));
    let r = run(&["--version"]);
    expect_code(&r, 0, "--version");
    assert!(r.stdout.starts_with("rigor "));
}

#[test]
fn check_on_a_folder_without_derivations_is_an_error_naming_it() {
    let dir = std::env::temp_dir().join(format!("rigor-empty-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    let path = dir.display().to_string();
    let r = run(&["check", &path]);
    expect_code(&r, 2, "check on an empty folder");
    assert!(
        r.stderr.contains(&path) && r.stderr.contains("no `.deriv` file"),
        "{}",
        r.stderr
    );
    let _ = std::fs::remove_dir(&dir);
}

#[test]
fn json_gives_each_link_its_units_when_units_are_declared() {
    let r = run(&["check", "--format", "json", "derivations/rod.deriv"]);
    expect_code(&r, 0, "json with units");
    let v: serde_json::Value = serde_json::from_str(r.stdout.trim()).expect("JSON");
    let units: Vec<String> = v["claims"]
        .as_array()
        .expect("claims")
        .iter()
        .flat_map(|c| c["links"].as_array().cloned().unwrap_or_default())
        .filter_map(|l| l["units"].as_str().map(str::to_string))
        .collect();
    assert!(units.iter().any(|u| u == "kg·m²"), "{units:?}");
}

#[test]
fn a_folder_becomes_one_book() {
    let r = run(&["latex", "tests/data/book", "--title", "Rods"]);
    expect_code(&r, 0, "latex book");
    assert!(r.stdout.contains("\\title{Rods}"), "{}", r.stdout);
    assert!(r.stdout.contains("\\tableofcontents"), "{}", r.stdout);
    assert_eq!(r.stdout.matches("\\section{").count(), 3, "{}", r.stdout);
    let r = run(&["markdown", "tests/data/book"]);
    expect_code(&r, 0, "markdown book");
    assert!(
        r.stdout.starts_with("# Worked solutions\n\n1. "),
        "{}",
        r.stdout
    );
    // An ORDER that names a file the folder does not have is bad input.
    let dir = std::env::temp_dir().join(format!("rigor-book-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("a.deriv"), "symbols a > 0\nclaim a = a\n").unwrap();
    std::fs::write(dir.join("ORDER"), "a.deriv\nmissing.deriv\n").unwrap();
    let r = run(&["latex", dir.to_str().unwrap()]);
    let _ = std::fs::remove_dir_all(&dir);
    expect_code(&r, 2, "latex book, bad ORDER");
    assert!(
        r.stderr
            .contains("ORDER:2: `missing.deriv` is not a `.deriv` file of the folder"),
        "{}",
        r.stderr
    );
}
