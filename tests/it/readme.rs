//! Every command example in the README runs, with the output and exit status shown: a
//! `sh` block line `$ rigor …` (optionally ending in `# exit N`, else 0) is followed by
//! what it prints (standard error, then standard output), up to the next `$` line.

use std::path::Path;
use std::process::Command;

/// Splits a command line into words, with double quotes (shared with `docs.rs`).
pub(crate) fn words(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut cur = String::new();
    let mut quoted = false;
    let mut any = false;
    for c in line.chars() {
        match c {
            '"' => {
                quoted = !quoted;
                any = true;
            }
            c if c.is_whitespace() && !quoted => {
                if any {
                    out.push(std::mem::take(&mut cur));
                    any = false;
                }
            }
            c => {
                cur.push(c);
                any = true;
            }
        }
    }
    if any {
        out.push(cur);
    }
    out
}

struct Example {
    line: usize,
    args: Vec<String>,
    code: i32,
    expected: String,
}

fn examples(readme: &str) -> Vec<Example> {
    let mut out: Vec<Example> = Vec::new();
    let mut in_sh = false;
    // Output lines belong to a command of the same block.
    let mut open = false;
    for (k, l) in readme.lines().enumerate() {
        if l.starts_with("```") {
            in_sh = !in_sh && l.trim() == "```sh";
            open = false;
            continue;
        }
        if !in_sh {
            continue;
        }
        if let Some(cmd) = l.strip_prefix("$ ") {
            let (cmd, code) = match cmd.split_once("# exit ") {
                Some((c, n)) => (c, n.trim().parse().expect("an exit status")),
                None => (cmd, 0),
            };
            let mut args = words(cmd);
            assert_eq!(
                args.first().map(String::as_str),
                Some("rigor"),
                "line {}",
                k + 1
            );
            args.remove(0);
            open = true;
            out.push(Example {
                line: k + 1,
                args,
                code,
                expected: String::new(),
            });
        } else if let Some(e) = out.last_mut().filter(|_| open) {
            e.expected.push_str(l);
            e.expected.push('\n');
        }
    }
    out
}

/// Output as compared: trailing spaces and blank lines around it dropped.
pub(crate) fn tidy(s: &str) -> String {
    s.lines()
        .map(str::trim_end)
        .collect::<Vec<_>>()
        .join("\n")
        .trim()
        .to_string()
}

#[test]
fn every_readme_example_prints_what_the_readme_says() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("README.md")).expect("README.md");
    let all = examples(&readme);
    assert!(
        all.len() >= 6,
        "the README's examples are found ({})",
        all.len()
    );
    for e in all {
        let out = Command::new(env!("CARGO_BIN_EXE_rigor"))
            .args(&e.args)
            .current_dir(root)
            .output()
            .expect("rigor runs");
        let got = format!(
            "{}{}",
            String::from_utf8_lossy(&out.stderr),
            String::from_utf8_lossy(&out.stdout)
        );
        assert_eq!(
            tidy(&got),
            tidy(&e.expected),
            "README line {}: rigor {}",
            e.line,
            e.args.join(" ")
        );
        assert_eq!(
            out.status.code(),
            Some(e.code),
            "README line {}: exit status",
            e.line
        );
    }
}

#[test]
fn words_keep_quoted_arguments_whole() {
    assert_eq!(
        words(r#"equiv "m L^2/12" "m L^2/3" --assume "m > 0""#),
        ["equiv", "m L^2/12", "m L^2/3", "--assume", "m > 0"]
    );
}
