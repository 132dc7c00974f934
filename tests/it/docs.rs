//! The documentation runs: every example in `docs/*.md` is checked, and every relative
//! link in `README.md` and `docs/*.md` leads to a file of the repository.
//!
//! The convention for examples (a fenced block's info string):
//!
//! - ```` ```deriv ````: a whole derivation file, checked in-process with
//!   [`rigor::check_source`] and no wall-clock budget. It must verify: every link
//!   verified, no error and no warning.
//! - ```` ```deriv emits=E0301,N0205 ````: checking must produce a diagnostic with each
//!   listed code (any severity); other diagnostics are allowed.
//! - ```` ```deriv file=lib.deriv ````: the block is also the file `lib.deriv` for the
//!   later blocks of the same document (`use … from "lib.deriv"`). Attributes combine.
//! - ```` ```console ````: lines `$ rigor ARGS [# exit N]`, each followed by what it prints
//!   (standard error, then standard output), run with the built binary from the
//!   repository's root.
//! - any other fence is not run.

use crate::readme::{tidy, words};
use pulldown_cmark::{CodeBlockKind, Event, Options as MdOptions, Parser, Tag, TagEnd};
use rigor::diag::Severity;
use rigor::{check_source, MemoryResolver, Options};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// `docs/*.md`, by name, as paths relative to the root.
fn docs() -> Vec<String> {
    let mut out: Vec<String> = std::fs::read_dir(root().join("docs"))
        .expect("docs/ exists")
        .filter_map(|e| {
            let name = e.ok()?.file_name().to_string_lossy().into_owned();
            name.ends_with(".md").then(|| format!("docs/{name}"))
        })
        .collect();
    out.sort();
    out
}

fn read(doc: &str) -> String {
    std::fs::read_to_string(root().join(doc)).unwrap_or_else(|e| panic!("{doc}: {e}"))
}

/// 1-based line of a byte offset.
fn line_of(text: &str, offset: usize) -> usize {
    text[..offset.min(text.len())].matches('\n').count() + 1
}

fn markdown(text: &str) -> Parser<'_> {
    Parser::new_ext(
        text,
        MdOptions::ENABLE_TABLES | MdOptions::ENABLE_HEADING_ATTRIBUTES,
    )
}

/// One fenced code block.
struct Block {
    /// Line of the opening fence.
    line: usize,
    /// The first word of the info string (`deriv`, `console`).
    lang: String,
    /// The other words of the info string.
    attrs: Vec<String>,
    /// Its text.
    body: String,
}

fn blocks(text: &str) -> Vec<Block> {
    let mut out = Vec::new();
    let mut open: Option<Block> = None;
    for (event, range) in markdown(text).into_offset_iter() {
        match event {
            Event::Start(Tag::CodeBlock(CodeBlockKind::Fenced(info))) => {
                let mut words = info.split_whitespace().map(str::to_string);
                open = Some(Block {
                    line: line_of(text, range.start),
                    lang: words.next().unwrap_or_default(),
                    attrs: words.collect(),
                    body: String::new(),
                });
            }
            Event::Text(t) => {
                if let Some(b) = open.as_mut() {
                    b.body.push_str(&t);
                }
            }
            Event::End(TagEnd::CodeBlock) => out.extend(open.take()),
            _ => {}
        }
    }
    out
}

/// Whether a block is one the runner runs.
fn runnable(b: &Block) -> bool {
    b.lang == "deriv" || b.lang == "console"
}

/// Runs every example of one document; each failure names the document and line.
fn run_examples(doc: &str, text: &str) -> Vec<String> {
    let mut failures = Vec::new();
    let mut files = MemoryResolver::new();
    for b in blocks(text) {
        let at = format!("{doc}:{}", b.line);
        match b.lang.as_str() {
            "deriv" => {
                if let Err(e) = run_deriv(&b, &mut files) {
                    failures.push(format!("{at}: deriv example: {e}"));
                }
            }
            "console" => failures.extend(
                run_console(&b)
                    .into_iter()
                    .map(|(k, e)| format!("{doc}:{}: console example: {e}", b.line + 1 + k)),
            ),
            _ => {}
        }
    }
    failures
}

fn run_deriv(b: &Block, files: &mut MemoryResolver) -> Result<(), String> {
    let mut emits: Vec<String> = Vec::new();
    let mut file: Option<String> = None;
    for a in &b.attrs {
        match a.split_once('=') {
            Some(("emits", codes)) => emits.extend(codes.split(',').map(str::to_string)),
            Some(("file", name)) => file = Some(name.to_string()),
            _ => return Err(format!("unknown attribute `{a}` (emits=, file=)")),
        }
    }
    let name = file
        .clone()
        .unwrap_or_else(|| format!("example-{}.deriv", b.line));
    if let Some(f) = &file {
        files.insert(f, &b.body);
    }
    let options = Options {
        clock: None,
        ..Default::default()
    };
    let report = check_source(&name, &b.body, &options, files);
    let shown = || rigor::render::human::report(&report, false);
    if emits.is_empty() {
        let bad = report
            .diagnostics
            .iter()
            .any(|d| matches!(d.severity, Severity::Error | Severity::Warning));
        if !report.ok() || bad {
            return Err(format!(
                "expected to verify with no error or warning, got:\n{}",
                shown()
            ));
        }
    } else {
        let got: BTreeSet<&str> = report.diagnostics.iter().map(|d| d.code.as_str()).collect();
        let missing: Vec<&String> = emits.iter().filter(|c| !got.contains(c.as_str())).collect();
        if !missing.is_empty() {
            return Err(format!(
                "expected a diagnostic {missing:?}, got {got:?}:\n{}",
                shown()
            ));
        }
    }
    Ok(())
}

/// One `$ rigor …` line of a console block and what it should print.
struct ConsoleExample {
    /// Line within the block (0-based).
    line: usize,
    args: Vec<String>,
    code: i32,
    expected: String,
}

fn console_examples(body: &str) -> Result<Vec<ConsoleExample>, (usize, String)> {
    let mut out: Vec<ConsoleExample> = Vec::new();
    for (k, l) in body.lines().enumerate() {
        if let Some(cmd) = l.strip_prefix("$ ") {
            let (cmd, code) = match cmd.split_once("# exit ") {
                Some((c, n)) => match n.trim().parse() {
                    Ok(n) => (c, n),
                    Err(_) => return Err((k, format!("`# exit {n}` is not an exit status"))),
                },
                None => (cmd, 0),
            };
            let mut args = words(cmd);
            if args.first().map(String::as_str) != Some("rigor") {
                return Err((k, format!("a console line runs rigor, not `{cmd}`")));
            }
            args.remove(0);
            out.push(ConsoleExample {
                line: k,
                args,
                code,
                expected: String::new(),
            });
        } else if let Some(e) = out.last_mut() {
            e.expected.push_str(l);
            e.expected.push('\n');
        } else if !l.trim().is_empty() {
            return Err((k, "output before the first `$ rigor` line".to_string()));
        }
    }
    if out.is_empty() {
        return Err((0, "no `$ rigor` line".to_string()));
    }
    Ok(out)
}

/// Failures of a console block, each with its line within the block.
fn run_console(b: &Block) -> Vec<(usize, String)> {
    let examples = match console_examples(&b.body) {
        Ok(e) => e,
        Err(e) => return vec![e],
    };
    let mut failures = Vec::new();
    for e in examples {
        let out = Command::new(env!("CARGO_BIN_EXE_rigor"))
            .args(&e.args)
            .current_dir(root())
            .output()
            .expect("rigor runs");
        let got = format!(
            "{}{}",
            String::from_utf8_lossy(&out.stderr),
            String::from_utf8_lossy(&out.stdout)
        );
        let cmd = format!("rigor {}", e.args.join(" "));
        if tidy(&got) != tidy(&e.expected) {
            failures.push((
                e.line,
                format!(
                    "`{cmd}` printed\n{}\n--- instead of ---\n{}",
                    tidy(&got),
                    tidy(&e.expected)
                ),
            ));
        }
        if out.status.code() != Some(e.code) {
            failures.push((
                e.line,
                format!(
                    "`{cmd}` exited with {:?}, not {}",
                    out.status.code(),
                    e.code
                ),
            ));
        }
    }
    failures
}

/// GitHub's anchor of a heading: lower case, letters, digits, `-` and `_` kept, spaces
/// made `-`, everything else dropped.
fn slug(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
            _ => None,
        })
        .collect()
}

/// The anchors of a Markdown document's headings (duplicates numbered as GitHub does).
fn anchors(text: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    let mut heading: Option<String> = None;
    for event in markdown(text) {
        match event {
            Event::Start(Tag::Heading { id, .. }) => {
                if let Some(id) = id {
                    out.insert(id.to_string());
                }
                heading = Some(String::new());
            }
            Event::Text(t) | Event::Code(t) => {
                if let Some(h) = heading.as_mut() {
                    h.push_str(&t);
                }
            }
            Event::End(TagEnd::Heading(_)) => {
                let s = slug(&heading.take().unwrap_or_default());
                let mut name = s.clone();
                let mut k = 0;
                while out.contains(&name) {
                    k += 1;
                    name = format!("{s}-{k}");
                }
                out.insert(name);
            }
            _ => {}
        }
    }
    out
}

/// Every relative link (and image) of a document that does not lead to a file or
/// folder of the repository, or to a heading of a Markdown file.
fn broken_links(doc: &str, text: &str) -> Vec<String> {
    let root = root().canonicalize().expect("the root");
    let dir = root
        .join(doc)
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or(root.clone());
    let mut failures = Vec::new();
    for (event, range) in markdown(text).into_offset_iter() {
        let dest = match event {
            Event::Start(Tag::Link { dest_url, .. })
            | Event::Start(Tag::Image { dest_url, .. }) => dest_url.to_string(),
            _ => continue,
        };
        let at = format!("{doc}:{}", line_of(text, range.start));
        if dest.contains("://") || dest.starts_with("mailto:") {
            continue;
        }
        let (path, anchor) = match dest.split_once('#') {
            Some((p, a)) => (p, Some(a)),
            None => (dest.as_str(), None),
        };
        let target: PathBuf = if path.is_empty() {
            root.join(doc)
        } else if path.starts_with('/') {
            failures.push(format!("{at}: `{dest}` is an absolute path"));
            continue;
        } else {
            dir.join(path)
        };
        let Ok(target) = target.canonicalize() else {
            failures.push(format!("{at}: `{dest}` leads to no file"));
            continue;
        };
        if !target.starts_with(&root) {
            failures.push(format!("{at}: `{dest}` leads outside the repository"));
            continue;
        }
        if let Some(a) = anchor {
            let ok = target.extension().is_some_and(|e| e == "md")
                && std::fs::read_to_string(&target).is_ok_and(|t| anchors(&t).contains(a));
            if !ok {
                failures.push(format!("{at}: `{dest}`: no heading has the anchor `#{a}`"));
            }
        }
    }
    failures
}

fn fail_with(failures: Vec<String>) {
    assert!(
        failures.is_empty(),
        "{} failing:\n\n{}",
        failures.len(),
        failures.join("\n\n")
    );
}

#[test]
fn every_docs_example_holds() {
    let mut failures = Vec::new();
    for doc in docs() {
        failures.extend(run_examples(&doc, &read(&doc)));
    }
    fail_with(failures);
}

#[test]
fn every_doc_has_a_runnable_example() {
    let docs = docs();
    for needed in ["docs/language.md", "docs/commands.md"] {
        assert!(docs.iter().any(|d| d == needed), "{needed} exists");
    }
    for doc in docs {
        let n = blocks(&read(&doc)).iter().filter(|b| runnable(b)).count();
        assert!(
            n > 0,
            "{doc} has no runnable example (```deriv or ```console)"
        );
    }
}

#[test]
fn every_relative_link_resolves() {
    let mut failures = Vec::new();
    for doc in std::iter::once("README.md".to_string()).chain(docs()) {
        failures.extend(broken_links(&doc, &read(&doc)));
    }
    fail_with(failures);
}

// The runner itself can fail, and says where.

const BROKEN: &str = r#"# A document with one mistake of each kind

Text.

```deriv
symbols m L > 0
claim [IG] m L^2/12 = m L^2/24
```

```deriv emits=E0301
symbols m L > 0
claim [ok] m L^2/12 = m L^2/12
```

```deriv file=lib.deriv
symbols m L > 0
claim [IO] m L^2/3 = m L^2/3
```

```deriv
symbols m L > 0
use [IO] from "lib.deriv"
claim [x] m L^2/3 = m L^2/3
```

```deriv
symbols m L > 0
use [IO] from "missing.deriv"
```

```console
$ rigor equiv "m L^2/12 + m (L/2)^2" "m L^2/3"
not equal
```

```console
$ rigor equiv "x" "x"    # exit 1
equal
```

```text
$ rigor this is not run
```

[a broken link](nowhere.md) and [a good one](../README.md), [a missing
anchor](../README.md#no-such-heading), [outside](../../outside/FORMAT.md).
"#;

#[test]
fn the_runner_reports_each_failing_example_where_it_is() {
    let failures = run_examples("docs/broken.md", BROKEN);
    let lines: Vec<&str> = failures
        .iter()
        .map(|f| f.split(": ").next().unwrap())
        .collect();
    // Line 5: a step that does not hold; 10: the code it should emit is missing; 20
    // (importing lib.deriv) verifies; 26: an import that does not resolve; 32 and 37:
    // wrong output, and a wrong exit status.
    assert_eq!(
        lines,
        [
            "docs/broken.md:5",
            "docs/broken.md:10",
            "docs/broken.md:26",
            "docs/broken.md:32",
            "docs/broken.md:37",
        ],
        "{failures:#?}"
    );
    assert!(failures[0].contains("E0301"), "{}", failures[0]);
    assert!(
        failures[4].contains("exited with Some(0), not 1"),
        "{}",
        failures[4]
    );
}

#[test]
fn the_link_checker_reports_each_broken_link() {
    let failures = broken_links("docs/broken.md", BROKEN);
    assert_eq!(failures.len(), 3, "{failures:#?}");
    assert!(failures[0].starts_with("docs/broken.md:45: `nowhere.md` leads to no file"));
    assert!(failures[1].contains("no heading has the anchor `#no-such-heading`"));
    assert!(failures[2].contains("../../outside/FORMAT.md"));
}

#[test]
fn anchors_are_githubs() {
    let a = anchors("# rigor\n## A tour of the language\n## `check` options\n## Tour\n## Tour\n");
    let want = [
        "rigor",
        "a-tour-of-the-language",
        "check-options",
        "tour",
        "tour-1",
    ];
    assert_eq!(a, want.iter().map(|s| s.to_string()).collect());
}
