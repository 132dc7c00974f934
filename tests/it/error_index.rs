//! The error index, `docs/errors.md`: one section `## CODE: title` for every diagnostic
//! code rigor can emit and for no other, each with an example that produces its code.
//!
//! The codes rigor can emit are the variants of `rigor::diag::Code` ([`codes_in_source`]); the sections' examples follow
//! the convention of the documentation runner (`tests/it/docs.rs`): ```` ```deriv
//! emits=E0301 ```` (checked in-process, must produce each listed code), ```` ```deriv
//! file=lib.deriv ```` (a file for later blocks' `use`), plain ```` ```deriv ```` (must
//! verify cleanly) and ```` ```console ```` (`$ rigor ARGS [# exit N]` lines).

use pulldown_cmark::{CodeBlockKind, Event, HeadingLevel, Parser, Tag, TagEnd};
use rigor::diag::{Code, Severity};
use rigor::{check_source, MemoryResolver, Options};
use std::collections::BTreeSet;
use std::path::Path;
use std::process::Command;

const INDEX: &str = "docs/errors.md";

/// The line a section gives instead of an example when its code cannot be produced by a
/// small input.
const NOT_REPRODUCIBLE: &str = "Not reproducible by a small example:";

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn read(rel: &str) -> String {
    std::fs::read_to_string(root().join(rel)).unwrap_or_else(|e| panic!("{rel}: {e}"))
}

/// `E0301`, `W0101`, `N0205`: a letter E, W or N and four digits.
fn is_code(s: &str) -> bool {
    let b = s.as_bytes();
    b.len() == 5 && matches!(b[0], b'E' | b'W' | b'N') && b[1..].iter().all(u8::is_ascii_digit)
}

// ---------------------------------------------------------------------------------------
// The codes in the source

/// Every diagnostic code that rigor can emit: the variants of `rigor::diag::Code`, the
/// one table of codes, as printed.
pub fn codes_in_source() -> BTreeSet<String> {
    Code::ALL.iter().map(|c| c.as_str().to_string()).collect()
}

#[test]
fn the_table_of_codes_prints_each_code_once() {
    let printed = codes_in_source();
    assert_eq!(printed.len(), Code::ALL.len(), "two variants print alike");
    assert!(printed.iter().all(|c| is_code(c)), "{printed:?}");
}

// ---------------------------------------------------------------------------------------
// The index

/// One fenced block of the index.
struct Block {
    line: usize,
    lang: String,
    attrs: Vec<String>,
    body: String,
}

/// One `## CODE: title` section.
struct Section {
    code: String,
    line: usize,
    /// Its Markdown, heading included: up to the next level-1 or level-2 heading.
    text: String,
    blocks: Vec<Block>,
}

fn line_of(text: &str, at: usize) -> usize {
    text[..at.min(text.len())].matches('\n').count() + 1
}

/// The sections of the index whose heading starts with a code, in order, and the fenced
/// blocks outside them.
fn sections(text: &str) -> (Vec<Section>, Vec<Block>) {
    let mut out: Vec<Section> = Vec::new();
    let mut stray: Vec<Block> = Vec::new();
    // The current level-2 heading (its text so far, its start) and code block.
    let mut heading: Option<(String, usize)> = None;
    let mut block: Option<Block> = None;
    // Where the open section starts, if one is open.
    let mut open: Option<usize> = None;
    for (event, range) in Parser::new(text).into_offset_iter() {
        match event {
            Event::Start(Tag::Heading { level, .. }) if level <= HeadingLevel::H2 => {
                if let (Some(start), Some(s)) = (open.take(), out.last_mut()) {
                    s.text = text[start..range.start].to_string();
                }
                heading = (level == HeadingLevel::H2).then(|| (String::new(), range.start));
            }
            Event::Text(t) | Event::Code(t) if heading.is_some() => {
                if let Some((h, _)) = heading.as_mut() {
                    h.push_str(&t);
                }
            }
            Event::End(TagEnd::Heading(_)) => {
                if let Some((h, start)) = heading.take() {
                    let code = h.split(':').next().unwrap_or("").trim();
                    if is_code(code) && h.contains(':') {
                        // Until a later heading closes it, the section runs to the end.
                        out.push(Section {
                            code: code.to_string(),
                            line: line_of(text, start),
                            text: text[start..].to_string(),
                            blocks: Vec::new(),
                        });
                        open = Some(start);
                    }
                }
            }
            Event::Start(Tag::CodeBlock(CodeBlockKind::Fenced(info))) => {
                let mut words = info.split_whitespace().map(str::to_string);
                block = Some(Block {
                    line: line_of(text, range.start),
                    lang: words.next().unwrap_or_default(),
                    attrs: words.collect(),
                    body: String::new(),
                });
            }
            Event::Text(t) => {
                if let Some(b) = block.as_mut() {
                    b.body.push_str(&t);
                }
            }
            Event::End(TagEnd::CodeBlock) => {
                if let Some(b) = block.take() {
                    match out.last_mut() {
                        Some(s) if open.is_some() => s.blocks.push(b),
                        _ => stray.push(b),
                    }
                }
            }
            _ => {}
        }
    }
    (out, stray)
}

/// The `emits=` codes and `file=` name of a `deriv` block.
fn deriv_attrs(b: &Block) -> Result<(Vec<String>, Option<String>), String> {
    let mut emits = Vec::new();
    let mut file = None;
    for a in &b.attrs {
        match a.split_once('=') {
            Some(("emits", codes)) => emits.extend(codes.split(',').map(str::to_string)),
            Some(("file", name)) => file = Some(name.to_string()),
            _ => return Err(format!("unknown attribute `{a}`")),
        }
    }
    Ok((emits, file))
}

#[test]
fn index_has_a_section_for_each_code_the_source_emits_and_no_other() {
    let source = codes_in_source();
    assert!(
        source.len() >= 20 && source.contains("E0301"),
        "the table of codes has too few: {source:?}"
    );
    let (sections, _) = sections(&read(INDEX));
    let mut index = BTreeSet::new();
    for s in &sections {
        assert!(
            index.insert(s.code.clone()),
            "{INDEX}:{}: a second section for {}",
            s.line,
            s.code
        );
    }
    let undocumented: Vec<&String> = source.difference(&index).collect();
    let unknown: Vec<&String> = index.difference(&source).collect();
    assert!(
        undocumented.is_empty() && unknown.is_empty(),
        "codes rigor can emit with no section in {INDEX}: {undocumented:?}\n\
         sections in {INDEX} for codes nothing in src/ emits: {unknown:?}"
    );
}

#[test]
fn each_section_has_an_example_that_emits_its_code() {
    let text = read(INDEX);
    let (sections, stray) = sections(&text);
    assert!(
        !sections.is_empty(),
        "{INDEX} has no `## CODE: title` section"
    );
    let mut failures = Vec::new();
    for b in stray
        .iter()
        .filter(|b| b.lang == "deriv" || b.lang == "console")
    {
        failures.push(format!(
            "{INDEX}:{}: an example outside any code's section",
            b.line
        ));
    }
    let options = Options {
        clock: None,
        ..Default::default()
    };
    let mut files = MemoryResolver::new();
    for s in &sections {
        let mut shown = false;
        for b in &s.blocks {
            let at = format!("{INDEX}:{} ({})", b.line, s.code);
            match b.lang.as_str() {
                "deriv" => {
                    let (emits, file) = match deriv_attrs(b) {
                        Ok(a) => a,
                        Err(e) => {
                            failures.push(format!("{at}: {e}"));
                            continue;
                        }
                    };
                    if let Some(f) = &file {
                        files.insert(f, &b.body);
                    }
                    let name = file.unwrap_or_else(|| format!("example-{}.deriv", b.line));
                    let report = check_source(&name, &b.body, &options, &files);
                    let got: BTreeSet<&str> =
                        report.diagnostics.iter().map(|d| d.code.as_str()).collect();
                    let render = || rigor::render::human::report(&report, false);
                    if emits.is_empty() {
                        let loud = report
                            .diagnostics
                            .iter()
                            .any(|d| matches!(d.severity, Severity::Error | Severity::Warning));
                        if !report.ok() || loud {
                            failures.push(format!(
                                "{at}: a plain deriv block must verify cleanly:\n{}",
                                render()
                            ));
                        }
                        continue;
                    }
                    let missing: Vec<&String> =
                        emits.iter().filter(|c| !got.contains(c.as_str())).collect();
                    if !missing.is_empty() {
                        failures.push(format!(
                            "{at}: expected {missing:?}, got {got:?}:\n{}",
                            render()
                        ));
                    } else if emits.contains(&s.code) {
                        shown = true;
                    }
                }
                "console" => match console_output(&b.body) {
                    Ok(out) => {
                        if out.contains(&format!("[{}]", s.code))
                            || out.contains(&format!("\"code\":\"{}\"", s.code))
                        {
                            shown = true;
                        }
                    }
                    Err(e) => failures.push(format!("{at}: {e}")),
                },
                _ => {}
            }
        }
        if !shown {
            let explained = s.text.lines().any(|l| l.starts_with(NOT_REPRODUCIBLE))
                && s.blocks
                    .iter()
                    .any(|b| b.lang == "text" && b.body.contains(&format!("[{}]", s.code)));
            if !explained {
                failures.push(format!(
                    "{INDEX}:{}: the section of {} has no example that emits it \
                     (a ```deriv emits={} block or a ```console block that prints it), \
                     nor a line `{NOT_REPRODUCIBLE} …` and a ```text block of its message",
                    s.line, s.code, s.code
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

/// What the `$ rigor …` lines of a console block print (standard error and output) when
/// run from the repository's root.
fn console_output(body: &str) -> Result<String, String> {
    let mut all = String::new();
    for l in body.lines() {
        let Some(cmd) = l.strip_prefix("$ ") else {
            continue;
        };
        let cmd = cmd.split("# exit ").next().unwrap_or(cmd);
        let mut args = cmd.split_whitespace();
        if args.next() != Some("rigor") {
            return Err(format!("a console line runs rigor, not `{cmd}`"));
        }
        let out = Command::new(env!("CARGO_BIN_EXE_rigor"))
            .args(args)
            .current_dir(root())
            .output()
            .map_err(|e| format!("rigor does not run: {e}"))?;
        all.push_str(&String::from_utf8_lossy(&out.stderr));
        all.push_str(&String::from_utf8_lossy(&out.stdout));
    }
    if all.is_empty() {
        return Err("a console block with no `$ rigor` line, or one that prints nothing".into());
    }
    Ok(all)
}
