//! The error index, `docs/errors.md`: one section `## CODE: title` for every diagnostic
//! code rigor can emit and for no other, each with an example that produces its code.
//!
//! The codes rigor can emit are found by [`codes_in_source`]; the sections' examples follow
//! the convention of the documentation runner (`tests/it/docs.rs`): ```` ```deriv
//! emits=E0301 ```` (checked in-process, must produce each listed code), ```` ```deriv
//! file=lib.deriv ```` (a file for later blocks' `use`), plain ```` ```deriv ```` (must
//! verify cleanly) and ```` ```console ```` (`$ rigor ARGS [# exit N]` lines).

use pulldown_cmark::{CodeBlockKind, Event, HeadingLevel, Parser, Tag, TagEnd};
use rigor::diag::Severity;
use rigor::{check_source, MemoryResolver, Options};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
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

/// Every diagnostic code that rigor's source can emit: the string literals of
/// `src/**/*.rs` that are a code (`"E0301"`), leaving out comments and test code (the
/// files of `#[cfg(test)] mod name;` declarations, such as `src/render/tests.rs`, and
/// the bodies of inline `#[cfg(test)] mod name { … }`).
///
/// The one place that knows how codes are written in the source: when they become a
/// `diag::Code` enum, this function lists its variants instead.
pub fn codes_in_source() -> BTreeSet<String> {
    let mut files = Vec::new();
    rust_files(&root().join("src"), &mut files);
    files.sort();
    let scans: Vec<(PathBuf, Scan)> = files
        .into_iter()
        .map(|f| {
            let text = std::fs::read_to_string(&f).unwrap_or_else(|e| panic!("{f:?}: {e}"));
            let scan = scan(&text);
            (f, scan)
        })
        .collect();
    // `#[cfg(test)] mod name;` in `dir/mod.rs` is `dir/name.rs` or `dir/name/`.
    let mut test_paths: Vec<PathBuf> = Vec::new();
    for (f, s) in &scans {
        let dir = module_dir(f);
        for name in &s.test_mods {
            test_paths.push(dir.join(format!("{name}.rs")));
            test_paths.push(dir.join(name));
        }
    }
    scans
        .into_iter()
        .filter(|(f, _)| !test_paths.iter().any(|t| f.starts_with(t)))
        .flat_map(|(_, s)| s.literals)
        .filter(|l| is_code(l))
        .collect()
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let entries = std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{dir:?}: {e}"));
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The folder holding the submodules of the module in file `f`.
fn module_dir(f: &Path) -> PathBuf {
    let parent = f.parent().unwrap_or(Path::new(""));
    match f.file_name().and_then(|n| n.to_str()) {
        Some("mod.rs" | "lib.rs" | "main.rs") => parent.to_path_buf(),
        _ => parent.join(f.file_stem().unwrap_or_default()),
    }
}

/// What [`scan`] finds in one Rust file.
#[derive(Debug, Default, PartialEq)]
struct Scan {
    /// The contents of its string literals, outside inline test modules.
    literals: Vec<String>,
    /// The names of its `#[cfg(test)] mod name;` declarations.
    test_mods: Vec<String>,
}

/// A small lexer, enough for this purpose: string, raw string and character literals,
/// lifetimes, comments, braces, and `#[cfg(test)]` before a `mod`.
fn scan(src: &str) -> Scan {
    let b = src.as_bytes();
    let mut out = Scan::default();
    let mut depth = 0usize;
    // The depth outside the inline test module being skipped.
    let mut skipping: Option<usize> = None;
    let mut i = 0;
    while i < b.len() {
        let rest = &src[i..];
        if rest.starts_with("//") {
            i += rest.find('\n').unwrap_or(rest.len());
        } else if rest.starts_with("/*") {
            i += rest.find("*/").map_or(rest.len(), |k| k + 2);
        } else if let Some((len, text)) = raw_string(rest) {
            if skipping.is_none() {
                out.literals.push(text);
            }
            i += len;
        } else if b[i] == b'"' {
            let (len, text) = string(rest);
            if skipping.is_none() {
                out.literals.push(text);
            }
            i += len;
        } else if b[i] == b'\'' {
            i += char_or_lifetime(rest);
        } else if rest.starts_with("#[cfg(test)]") && skipping.is_none() {
            let after = i + "#[cfg(test)]".len();
            match test_mod(&src[after..]) {
                Some((name, true)) => {
                    out.test_mods.push(name);
                    i = after;
                }
                Some((_, false)) => {
                    // Skip to its `{`; the brace handling below does the rest.
                    i = after + src[after..].find('{').unwrap_or(0);
                    skipping = Some(depth);
                }
                None => i = after,
            }
        } else {
            match b[i] {
                b'{' => depth += 1,
                b'}' => {
                    depth = depth.saturating_sub(1);
                    if skipping == Some(depth) {
                        skipping = None;
                    }
                }
                _ => {}
            }
            i += 1;
        }
    }
    out
}

/// After `#[cfg(test)]`: `mod name;` (`(name, true)`) or `mod name {` (`(name, false)`),
/// possibly after other attributes and a visibility.
fn test_mod(rest: &str) -> Option<(String, bool)> {
    let mut s = rest.trim_start();
    while s.starts_with("#[") {
        s = s[s.find(']')? + 1..].trim_start();
    }
    if let Some(r) = s.strip_prefix("pub") {
        s = r.trim_start();
        if s.starts_with('(') {
            s = s[s.find(')')? + 1..].trim_start();
        }
    }
    let s = s.strip_prefix("mod")?;
    if !s.starts_with(char::is_whitespace) {
        return None;
    }
    let s = s.trim_start();
    let end = s.find(|c: char| !(c.is_alphanumeric() || c == '_'))?;
    let (name, after) = s.split_at(end);
    match after.trim_start().chars().next()? {
        ';' => Some((name.to_string(), true)),
        '{' => Some((name.to_string(), false)),
        _ => None,
    }
}

/// A raw string at the start of `s` (`r"…"`, `r#"…"#`, `br"…"`): its length and text.
fn raw_string(s: &str) -> Option<(usize, String)> {
    let start = if s.starts_with("br") {
        2
    } else if s.starts_with('r') {
        1
    } else {
        return None;
    };
    let hashes = s[start..].bytes().take_while(|&c| c == b'#').count();
    let open = start + hashes;
    if s.as_bytes().get(open) != Some(&b'"') {
        return None;
    }
    let close = format!("\"{}", "#".repeat(hashes));
    let body = &s[open + 1..];
    let end = body.find(&close).unwrap_or(body.len());
    Some((open + 1 + end + close.len(), body[..end].to_string()))
}

/// A string literal at the start of `s` (at its `"`): its length and text, escapes kept
/// as written.
fn string(s: &str) -> (usize, String) {
    let b = s.as_bytes();
    let mut k = 1;
    while k < b.len() && b[k] != b'"' {
        k += if b[k] == b'\\' { 2 } else { 1 };
    }
    let end = k.min(b.len());
    (end + 1, s[1..end].to_string())
}

/// The length of a character literal (`'x'`, `'\n'`, `'\u{2c6}'`) or lifetime (`'a`)
/// at the start of `s`.
fn char_or_lifetime(s: &str) -> usize {
    let mut chars = s.char_indices().skip(1);
    match chars.next() {
        Some((_, '\\')) => s[2..].find('\'').map_or(s.len(), |k| k + 3),
        Some((_, c)) => {
            let after = 1 + c.len_utf8();
            if s[after..].starts_with('\'') {
                after + 1
            } else {
                1
            }
        }
        None => 1,
    }
}

#[test]
fn the_scan_sees_literals_outside_tests_and_comments() {
    let src = r##"
fn emit() -> &'static str { let c = '{'; let q = '\''; if x { "E0101" } else { "E0102" } }
// "E0103" in a comment
/* "E0104" in a block comment */
const RAW: &str = r#"E0105"#;
#[cfg(test)]
mod tests { fn t() { assert_eq!(code(), "E0106"); let s = "}"; } }
#[cfg(test)]
mod more;
fn after() -> &'static str { "W0107" }
const NOT_A_CODE: &str = "E01080";
"##;
    let s = scan(src);
    let codes: Vec<&str> = s
        .literals
        .iter()
        .map(String::as_str)
        .filter(|l| is_code(l))
        .collect();
    assert_eq!(codes, ["E0101", "E0102", "E0105", "W0107"]);
    assert_eq!(s.test_mods, ["more"]);
    assert_eq!(
        module_dir(Path::new("src/render/mod.rs")),
        Path::new("src/render")
    );
    assert_eq!(
        module_dir(Path::new("src/check/walk.rs")),
        Path::new("src/check/walk")
    );
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
        "the scan of src/ found too few codes: {source:?}"
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
                    let got: BTreeSet<&str> = report.diagnostics.iter().map(|d| d.code).collect();
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
