//! Tidy (in the manner of rust-analyzer's `tidy.rs`): the rules the source keeps about
//! itself, checked on every file under `src/`.
//!
//! - **Boundaries.** Nothing under `src/normal/` names `syntax` (the normal form knows no
//!   spans); nothing under `src/guard/` names `normal`, `lower` or `calculus` (the guard
//!   is independent of the engine it checks). A module is "named" by any path in code,
//!   `use` or not, that resolves to it: `crate::syntax`, `super::super::syntax` from a
//!   file two levels down, an item of a group `crate::{lower, syntax}`. Comments and
//!   string literals are not code.
//! - **Effects.** Files, threads, processes and clocks (`std::fs`, `std::thread`,
//!   `std::process::Command`, `std::net`, `Instant`, `SystemTime`, `File::open`,
//!   `rayon`) appear only in `src/files.rs`, `src/clock.rs`, `src/cli/`, `src/lsp/`
//!   (the language server, a front end like the command line) and `src/main.rs`. The one exception is test-only code, found mechanically: an inline
//!   `#[cfg(test)] mod NAME { … }` (to its closing brace), and a file its parent declares
//!   with `#[cfg(test)] mod NAME;` (with every file below it). Today that exempts the
//!   thread test of the atom interner (`normal/atom.rs`) and the renderers' tests that
//!   read fixtures, write temporary documents and run pdflatex (`render/tests.rs`).
//! - **Headers.** Every source file's first non-blank line is a `//!` comment.
//! - **The code map.** Every file under `src/` is named in ARCHITECTURE.md's code map.
//!   The rule: a row of the map whose first cell names `src/PATH` in backticks names that
//!   file; a row whose first cell names a folder `src/DIR/` names `src/DIR/REST` when the
//!   row holds `REST` in backticks (the path relative to that folder: `lex.rs`,
//!   `latex/tokens.rs`), and names the folder's own `mod.rs`; `REST` written `SUB/` also
//!   names `SUB/mod.rs`. Conversely, every path in a first cell exists, and every
//!   backticked `….rs` in a row exists relative to one of that row's folders, to `src/`
//!   or to the repository's root, so the map does not name a file that has moved.
//!
//! Each checker is a function of text, tested below on planted violations.

use std::collections::BTreeSet;
use std::path::Path;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Every `.rs` file under `src/`: its path relative to `src/` (with `/`) and its text.
fn sources() -> Vec<(String, String)> {
    fn walk(dir: &Path, base: &Path, out: &mut Vec<(String, String)>) {
        for entry in std::fs::read_dir(dir).expect("src/ is readable").flatten() {
            let path = entry.path();
            if path.is_dir() {
                walk(&path, base, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let rel = path.strip_prefix(base).expect("under src/");
                let rel = rel
                    .components()
                    .map(|c| c.as_os_str().to_string_lossy().into_owned())
                    .collect::<Vec<_>>()
                    .join("/");
                let text = std::fs::read_to_string(&path).expect("readable source");
                out.push((rel, text));
            }
        }
    }
    let src = root().join("src");
    let mut out = Vec::new();
    walk(&src, &src, &mut out);
    out.sort();
    assert!(out.len() > 50, "the sources are found ({})", out.len());
    out
}

// ------------------------------------------------------------------ reading code

/// `text` with comments, string literals and character literals blanked out (newlines
/// and byte positions kept), so that only code is left.
fn code_only(text: &str) -> Vec<char> {
    let s: Vec<char> = text.chars().collect();
    let mut out = s.clone();
    let blank = |out: &mut Vec<char>, from: usize, to: usize| {
        for c in out.iter_mut().take(to).skip(from) {
            if *c != '\n' {
                *c = ' ';
            }
        }
    };
    let mut i = 0;
    while i < s.len() {
        let at = |k: usize| s.get(k).copied().unwrap_or('\0');
        if at(i) == '/' && at(i + 1) == '/' {
            let end = (i..s.len()).find(|&k| s[k] == '\n').unwrap_or(s.len());
            blank(&mut out, i, end);
            i = end;
        } else if at(i) == '/' && at(i + 1) == '*' {
            let mut depth = 0;
            let mut k = i;
            while k < s.len() {
                if at(k) == '/' && at(k + 1) == '*' {
                    depth += 1;
                    k += 2;
                } else if at(k) == '*' && at(k + 1) == '/' {
                    depth -= 1;
                    k += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    k += 1;
                }
            }
            blank(&mut out, i, k);
            i = k;
        } else if at(i) == 'r'
            && (at(i + 1) == '"' || at(i + 1) == '#')
            && !(i > 0 && is_ident(at(i - 1)))
        {
            // A raw string r"…", r#"…"#.
            let hashes = (i + 1..s.len()).take_while(|&k| s[k] == '#').count();
            if at(i + 1 + hashes) != '"' {
                i += 1;
                continue;
            }
            let mut k = i + 2 + hashes;
            while k < s.len() && !(s[k] == '"' && (1..=hashes).all(|h| at(k + h) == '#')) {
                k += 1;
            }
            let end = (k + 1 + hashes).min(s.len());
            blank(&mut out, i, end);
            i = end;
        } else if at(i) == '"' {
            let mut k = i + 1;
            while k < s.len() && s[k] != '"' {
                k += if s[k] == '\\' { 2 } else { 1 };
            }
            let end = (k + 1).min(s.len());
            blank(&mut out, i, end);
            i = end;
        } else if at(i) == '\'' && at(i + 1) == '\\' {
            let end = (i + 2..s.len())
                .find(|&k| s[k] == '\'')
                .map_or(s.len(), |k| k + 1);
            blank(&mut out, i, end);
            i = end;
        } else if at(i) == '\'' && at(i + 2) == '\'' {
            blank(&mut out, i, i + 3);
            i += 3;
        } else {
            i += 1;
        }
    }
    out
}

fn is_ident(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// The paths of a use tree or path starting at `s[*i]`, groups expanded:
/// `std::{fs, thread::scope}` is `std::fs` and `std::thread::scope`.
fn path_tree(s: &[char], i: &mut usize) -> Vec<String> {
    let skip_ws = |i: &mut usize| {
        while *i < s.len() && s[*i].is_whitespace() {
            *i += 1;
        }
    };
    skip_ws(i);
    match s.get(*i) {
        Some('{') => {
            *i += 1;
            let mut out = Vec::new();
            loop {
                skip_ws(i);
                match s.get(*i) {
                    None => return out,
                    Some('}') => {
                        *i += 1;
                        return out;
                    }
                    Some(',') => *i += 1,
                    Some(_) => {
                        let before = *i;
                        out.extend(path_tree(s, i));
                        if *i == before {
                            *i += 1; // not a path: step over it
                        }
                    }
                }
            }
        }
        Some('*') => {
            *i += 1;
            vec!["*".to_string()]
        }
        _ => {
            let start = *i;
            while *i < s.len() && is_ident(s[*i]) {
                *i += 1;
            }
            if *i == start {
                return Vec::new();
            }
            let ident: String = s[start..*i].iter().collect();
            if s.get(*i) == Some(&':') && s.get(*i + 1) == Some(&':') {
                *i += 2;
                let rest = path_tree(s, i);
                if rest.is_empty() {
                    return vec![ident];
                }
                return rest.into_iter().map(|r| format!("{ident}::{r}")).collect();
            }
            vec![ident]
        }
    }
}

/// Every path of two segments or more in `code`, groups expanded.
fn paths(code: &[char]) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < code.len() {
        let c = code[i];
        let starts = is_ident(c)
            && !c.is_ascii_digit()
            && (i == 0 || !(is_ident(code[i - 1]) || code[i - 1] == ':'));
        if !starts {
            i += 1;
            continue;
        }
        let start = i;
        let found = path_tree(code, &mut i);
        if i == start {
            i += 1;
        }
        for p in found {
            if p.contains("::") {
                out.push((start, p));
            }
        }
    }
    out
}

/// The line (from 1) of byte-free position `at` in `code`.
fn line_of(code: &[char], at: usize) -> usize {
    code[..at].iter().filter(|&&c| c == '\n').count() + 1
}

/// The module path of the file `rel` (relative to `src/`): `guard/ball.rs` is
/// `[guard, ball]`, `guard/mod.rs` is `[guard]`, `lib.rs` and `main.rs` the root.
fn module_of(rel: &str) -> Vec<String> {
    let mut parts: Vec<String> = rel.split('/').map(str::to_string).collect();
    let last = parts.pop().unwrap_or_default();
    if !(last == "mod.rs" || (parts.is_empty() && (last == "lib.rs" || last == "main.rs"))) {
        parts.push(last.trim_end_matches(".rs").to_string());
    }
    parts
}

/// The crate's top-level modules that the file `rel` names in code, each with the line
/// of the path (or `use` tree) that names it, once per line.
fn crate_modules_named(rel: &str, text: &str) -> BTreeSet<(usize, String)> {
    let code = code_only(text);
    let module = module_of(rel);
    let mut out = BTreeSet::new();
    for (at, p) in paths(&code) {
        let segs: Vec<&str> = p.split("::").collect();
        let (mut depth, mut k) = match segs[0] {
            "crate" => (0usize, 1usize),
            "super" => (module.len().saturating_sub(1), 1),
            _ => continue,
        };
        while segs.get(k) == Some(&"super") {
            depth = depth.saturating_sub(1);
            k += 1;
        }
        let top = if depth == 0 {
            segs.get(k).map(|s| s.to_string())
        } else {
            module.first().cloned()
        };
        if let Some(top) = top {
            out.insert((line_of(&code, at), top));
        }
    }
    out
}

// ------------------------------------------------------------------ the checks

/// Which modules each folder may not name.
const BOUNDARIES: &[(&str, &[&str])] = &[
    ("normal/", &["syntax"]),
    ("guard/", &["normal", "lower", "calculus"]),
];

/// The file `rel`'s crossings of [`BOUNDARIES`].
fn boundary_violations(rel: &str, text: &str) -> Vec<String> {
    let mut out = Vec::new();
    for (folder, forbidden) in BOUNDARIES {
        if !rel.starts_with(folder) {
            continue;
        }
        for (line, top) in crate_modules_named(rel, text) {
            if forbidden.contains(&top.as_str()) {
                out.push(format!("src/{rel}:{line}: {folder} names `{top}`"));
            }
        }
    }
    out
}

/// Where files, threads, processes and clocks may be used.
const EFFECT_PLACES: &[&str] = &["files.rs", "clock.rs", "main.rs", "cli/", "lsp/"];

/// Paths (prefixes of an expanded path) that are effects.
const EFFECT_PATHS: &[&str] = &[
    "std::fs",
    "std::thread",
    "std::process::Command",
    "std::net",
    "std::time::Instant",
    "std::time::SystemTime",
    "rayon",
];

/// Names that are effects wherever they come from (an imported `Instant::now()`).
const EFFECT_NAMES: &[&str] = &["Instant::now", "SystemTime::", "File::open", "File::create"];

/// The byte-free ranges of `code` that are test-only: inline `#[cfg(test)] mod NAME {…}`.
fn inline_test_modules(code: &[char]) -> Vec<(usize, usize)> {
    let text: String = code.iter().collect();
    let chars: Vec<(usize, char)> = text.char_indices().collect();
    let to_char = |byte: usize| chars.partition_point(|&(b, _)| b < byte);
    let mut out = Vec::new();
    let mut from = 0;
    while let Some(k) = text[from..].find("#[cfg(test)]") {
        let at = from + k;
        from = at + 1;
        let rest = text[at + "#[cfg(test)]".len()..].trim_start();
        let Some(after_mod) = rest.strip_prefix("mod ") else {
            continue;
        };
        let name_len = after_mod.chars().take_while(|&c| is_ident(c)).count();
        if !after_mod[name_len..].trim_start().starts_with('{') {
            continue; // `mod tests;`: a file of its own
        }
        let open = to_char(at)
            + (text[at..]
                .find('{')
                .map_or(0, |b| text[at..at + b].chars().count()));
        let mut depth = 0;
        let mut end = code.len();
        for (k, &c) in code.iter().enumerate().skip(open) {
            if c == '{' {
                depth += 1;
            } else if c == '}' {
                depth -= 1;
                if depth == 0 {
                    end = k + 1;
                    break;
                }
            }
        }
        out.push((to_char(at), end));
    }
    out
}

/// The files (relative to `src/`) that are test-only: declared `#[cfg(test)] mod NAME;`
/// by their parent, or below such a file.
fn test_only_files(files: &[(String, String)]) -> BTreeSet<String> {
    let declares_for_test = |parent: &str, name: &str| {
        files.iter().any(|(rel, text)| {
            rel == parent && {
                let t: String = code_only(text).iter().collect();
                let lines: Vec<&str> = t.lines().map(str::trim).collect();
                lines
                    .windows(2)
                    .any(|w| w[0] == "#[cfg(test)]" && w[1] == format!("mod {name};"))
            }
        })
    };
    let mut out = BTreeSet::new();
    for (rel, _) in files {
        // Walk up: `a/b/c.rs` is declared by `a/b.rs` or `a/b/mod.rs`, which is declared by
        // `a.rs` or `a/mod.rs`, up to `lib.rs` or `main.rs`.
        let module = module_of(rel);
        for depth in (1..=module.len()).rev() {
            let name = &module[depth - 1];
            let parent = &module[..depth - 1];
            let candidates: Vec<String> = if parent.is_empty() {
                vec!["lib.rs".into(), "main.rs".into()]
            } else {
                let p = parent.join("/");
                vec![format!("{p}.rs"), format!("{p}/mod.rs")]
            };
            if candidates.iter().any(|c| declares_for_test(c, name)) {
                out.insert(rel.clone());
                break;
            }
        }
    }
    out
}

/// The file `rel`'s effects outside test-only code; `test_only` when the whole file is.
fn effect_violations(rel: &str, text: &str, test_only: bool) -> Vec<String> {
    if test_only {
        return Vec::new();
    }
    effects(rel, text, true)
}

/// The file `rel`'s effects outside the edges; in inline test modules too unless
/// `skip_tests`.
fn effects(rel: &str, text: &str, skip_tests: bool) -> Vec<String> {
    let at_an_edge = EFFECT_PLACES
        .iter()
        .any(|p| rel == *p || (p.ends_with('/') && rel.starts_with(p)));
    if at_an_edge {
        return Vec::new();
    }
    let code = code_only(text);
    let exempt = if skip_tests {
        inline_test_modules(&code)
    } else {
        Vec::new()
    };
    let in_test = |at: usize| exempt.iter().any(|&(a, b)| a <= at && at < b);
    let mut out = Vec::new();
    for (at, p) in paths(&code) {
        if in_test(at) {
            continue;
        }
        let hit = EFFECT_PATHS.iter().chain(EFFECT_NAMES).find(|e| {
            p == **e || p.starts_with(&format!("{e}::")) || (e.ends_with("::") && p.starts_with(*e))
        });
        if let Some(e) = hit {
            out.push(format!("src/{rel}:{}: `{p}` ({e})", line_of(&code, at)));
        }
    }
    out
}

/// Whether the file's first non-blank line is a `//!` comment.
fn has_header(text: &str) -> bool {
    text.lines()
        .find(|l| !l.trim().is_empty())
        .is_some_and(|l| l.starts_with("//!"))
}

/// The rows of the code map in `architecture`: the backticked names of each row's first
/// cell, and of the whole row.
fn code_map(architecture: &str) -> Vec<(Vec<String>, BTreeSet<String>)> {
    let ticks = |s: &str| -> Vec<String> {
        s.split('`')
            .skip(1)
            .step_by(2)
            .map(str::to_string)
            .collect()
    };
    let section = architecture
        .split("\n## ")
        .find(|s| s.starts_with("Code map"))
        .unwrap_or("");
    let mut rows = Vec::new();
    for line in section.lines() {
        let Some(rest) = line.strip_prefix('|') else {
            continue;
        };
        let Some((first, _)) = rest.split_once('|') else {
            continue;
        };
        let roots = ticks(first);
        if roots.is_empty() {
            continue; // the header and the rule
        }
        rows.push((roots, ticks(line).into_iter().collect()));
    }
    rows
}

/// Files under `src/` (relative to it) the map does not name, and names in the map that
/// are not there (`exists` answers for a path relative to the repository's root).
fn code_map_problems(
    architecture: &str,
    files: &[String],
    exists: &dyn Fn(&str) -> bool,
) -> Vec<String> {
    let rows = code_map(architecture);
    let mut out = Vec::new();
    if rows.is_empty() {
        out.push("ARCHITECTURE.md has no `## Code map` table".to_string());
    }
    for rel in files {
        let full = format!("src/{rel}");
        let named = rows.iter().any(|(roots, names)| {
            roots.iter().any(|r| {
                if *r == full {
                    return true;
                }
                let Some(rest) = r
                    .ends_with('/')
                    .then(|| full.strip_prefix(r.as_str()))
                    .flatten()
                else {
                    return false;
                };
                rest == "mod.rs"
                    || names.contains(rest)
                    || rest
                        .strip_suffix("mod.rs")
                        .is_some_and(|dir| dir.ends_with('/') && names.contains(dir))
            })
        });
        if !named {
            out.push(format!("{full} is not named in ARCHITECTURE.md's code map"));
        }
    }
    for (roots, names) in &rows {
        for r in roots {
            if !exists(r) {
                out.push(format!("the code map's `{r}` does not exist"));
            }
        }
        for n in names
            .iter()
            .filter(|n| n.ends_with(".rs") && !n.contains([' ', ':']))
        {
            let mut bases: Vec<&str> = roots
                .iter()
                .filter(|r| r.ends_with('/'))
                .map(String::as_str)
                .collect();
            bases.extend(["src/", ""]);
            if !bases.iter().any(|b| exists(&format!("{b}{n}"))) {
                out.push(format!(
                    "the code map's `{n}` (row of `{}`) does not exist",
                    roots.join("`, `")
                ));
            }
        }
    }
    out
}

// ------------------------------------------------------------------ the repository

#[test]
fn normal_knows_no_syntax_and_the_guard_shares_nothing_with_the_engine() {
    let found: Vec<String> = sources()
        .iter()
        .flat_map(|(rel, text)| boundary_violations(rel, text))
        .collect();
    assert!(
        found.is_empty(),
        "boundaries crossed:\n{}",
        found.join("\n")
    );
}

#[test]
fn only_the_edges_touch_files_threads_and_clocks() {
    let files = sources();
    let tests = test_only_files(&files);
    for expected in [
        "render/tests.rs",
        "guard/tests.rs",
        "syntax/tests/expr_tests.rs",
    ] {
        assert!(
            tests.contains(expected),
            "{expected} is test-only: {tests:?}"
        );
    }
    let found: Vec<String> = files
        .iter()
        .flat_map(|(rel, text)| effect_violations(rel, text, tests.contains(rel)))
        .collect();
    assert!(
        found.is_empty(),
        "effects outside files.rs, clock.rs, cli/, lsp/, main.rs:\n{}",
        found.join("\n")
    );
    // The exemption is narrow and explicit: these are the only files whose effects it
    // excuses, all in test-only code. A new one is a deliberate edit here.
    let excused: BTreeSet<&str> = files
        .iter()
        .filter(|(rel, text)| !effects(rel, text, false).is_empty())
        .map(|(rel, _)| rel.as_str())
        .collect();
    assert_eq!(
        excused,
        BTreeSet::from(["normal/atom.rs", "render/tests.rs"]),
        "files with effects in test-only code"
    );
    // The edges themselves are seen: the check reads what it means to.
    let clock = files
        .iter()
        .find(|(r, _)| r == "clock.rs")
        .expect("src/clock.rs");
    assert!(!effect_violations("normal/clock.rs", &clock.1, false).is_empty());
}

#[test]
fn every_source_file_has_a_header() {
    let missing: Vec<String> = sources()
        .into_iter()
        .filter(|(_, text)| !has_header(text))
        .map(|(rel, _)| format!("src/{rel}"))
        .collect();
    assert!(
        missing.is_empty(),
        "no `//!` header:\n{}",
        missing.join("\n")
    );
}

#[test]
fn the_code_map_names_every_source_file_and_nothing_that_is_gone() {
    let architecture =
        std::fs::read_to_string(root().join("ARCHITECTURE.md")).expect("ARCHITECTURE.md");
    let files: Vec<String> = sources().into_iter().map(|(rel, _)| rel).collect();
    let problems = code_map_problems(&architecture, &files, &|p| root().join(p).exists());
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

// ------------------------------------------------------------------ the checks can fail

#[test]
fn a_boundary_crossing_is_found_however_it_is_written() {
    let crossing = [
        ("normal/rat.rs", "use crate::syntax::ast::Expr;\n"),
        ("normal/rat.rs", "use crate::{lower, syntax};\n"),
        (
            "normal/rat.rs",
            "use crate::{\n    interval::Prec,\n    syntax::{ast, lex},\n};\n",
        ),
        (
            "normal/rat.rs",
            "fn f(e: &super::super::syntax::ast::Expr) {}\n",
        ),
        ("normal/mod.rs", "use super::syntax;\n"),
        ("guard/eval.rs", "use super::super::normal::Rat;\n"),
        ("guard/mod.rs", "pub(crate) use crate::calculus::diff;\n"),
        ("guard/tests.rs", "use crate::lower::Lowerer;\n"),
    ];
    for (rel, text) in crossing {
        assert_eq!(boundary_violations(rel, text).len(), 1, "{rel}: {text}");
    }
    let fine = [
        (
            "normal/rat.rs",
            "//! Unlike crate::syntax, no spans.\nuse super::poly::Poly;\n",
        ),
        ("normal/rat.rs", "const S: &str = \"crate::syntax\";\n"),
        ("normal/sub/x.rs", "use super::super::poly::Poly;\n"),
        (
            "guard/eval.rs",
            "use crate::syntax::ast::Expr;\nuse super::ball::Ball;\n",
        ),
        (
            "check/step.rs",
            "use crate::normal::Rat;\nuse crate::syntax::ast;\n",
        ),
    ];
    for (rel, text) in fine {
        assert_eq!(
            boundary_violations(rel, text),
            Vec::<String>::new(),
            "{rel}: {text}"
        );
    }
}

#[test]
fn an_effect_is_found_outside_the_edges_and_in_no_test() {
    let effects = [
        "fn f() { let _ = std::fs::read_to_string(\"x\"); }\n",
        "use std::{collections::HashMap, fs};\n",
        "use std::thread;\n",
        "fn f() { std::thread::scope(|_| {}); }\n",
        "use std::time::{Duration, Instant};\n",
        "fn f() { let t = Instant::now(); }\n",
        "fn f() { let t = SystemTime::now(); }\n",
        "fn f() { let f = File::open(\"x\"); }\n",
        "use rayon::prelude::*;\n",
        "fn f() { std::process::Command::new(\"sh\"); }\n",
    ];
    for text in effects {
        assert_eq!(
            effect_violations("normal/rat.rs", text, false).len(),
            1,
            "{text}"
        );
        for place in [
            "files.rs",
            "clock.rs",
            "main.rs",
            "cli/mod.rs",
            "lsp/mod.rs",
        ] {
            assert!(
                effect_violations(place, text, false).is_empty(),
                "{place}: {text}"
            );
        }
        assert!(effect_violations("render/tests.rs", text, true).is_empty());
    }
    // An inline test module is exempt up to its closing brace, and only it.
    let text = "fn f() {}\n#[cfg(test)]\nmod tests {\n    #[test]\n    fn t() { std::thread::scope(|s| { s.spawn(|| {}); }); }\n}\nfn g() { std::fs::write(\"x\", \"\"); }\n";
    let found = effect_violations("normal/atom.rs", text, false);
    assert_eq!(
        found,
        vec!["src/normal/atom.rs:7: `std::fs::write` (std::fs)".to_string()]
    );
    // Comments, strings and names that merely contain a word are not effects.
    let fine = "// std::fs is for files.rs\nconst S: &str = \"std::thread\";\nfn instant_now() {}\nuse std::time::Duration;\n";
    assert!(effect_violations("normal/rat.rs", fine, false).is_empty());
    // Files declared `#[cfg(test)] mod NAME;` are test-only, and so is what they declare.
    let files = vec![
        ("lib.rs".to_string(), "pub mod a;\n".to_string()),
        (
            "a/mod.rs".to_string(),
            "mod b;\n#[cfg(test)]\nmod tests;\n".to_string(),
        ),
        ("a/b.rs".to_string(), String::new()),
        ("a/tests.rs".to_string(), "mod deep;\n".to_string()),
        ("a/tests/deep.rs".to_string(), String::new()),
    ];
    let tests = test_only_files(&files);
    assert_eq!(
        tests,
        BTreeSet::from(["a/tests.rs".to_string(), "a/tests/deep.rs".to_string()])
    );
}

#[test]
fn a_file_without_a_header_is_found() {
    assert!(has_header("//! What this is.\n\nuse x;\n"));
    assert!(has_header("\n//! What this is.\n"));
    assert!(!has_header("use super::*;\n"));
    assert!(!has_header("/// An item's doc.\nfn f() {}\n"));
    assert!(!has_header(""));
}

#[test]
fn a_file_the_map_does_not_name_and_a_name_that_is_gone_are_found() {
    let map = "# A\n\n## Code map\n\n| where | what |\n|---|---|\n\
        | `src/syntax/` | `lex.rs` tokens; `latex/` LaTeX (`latex/tokens.rs`); `old.rs` |\n\
        | `src/lower.rs` | lowering |\n| `src/gone/` | nothing |\n\n## Invariants\n\n| `src/x.rs` | y |\n";
    let files: Vec<String> = [
        "syntax/mod.rs",
        "syntax/lex.rs",
        "syntax/latex/mod.rs",
        "syntax/latex/tokens.rs",
        "syntax/latex/physics.rs",
        "syntax/prec.rs",
        "lower.rs",
        "x.rs",
    ]
    .map(String::from)
    .to_vec();
    let exists = |p: &str| {
        p == "src/syntax/" || p == "src/lower.rs" || files.iter().any(|f| format!("src/{f}") == p)
    };
    assert_eq!(
        code_map_problems(map, &files, &exists),
        vec![
            "src/syntax/latex/physics.rs is not named in ARCHITECTURE.md's code map".to_string(),
            "src/syntax/prec.rs is not named in ARCHITECTURE.md's code map".to_string(),
            "src/x.rs is not named in ARCHITECTURE.md's code map".to_string(),
            "the code map's `old.rs` (row of `src/syntax/`) does not exist".to_string(),
            "the code map's `src/gone/` does not exist".to_string(),
        ]
    );
    assert_eq!(
        code_map_problems("# A\n", &[], &exists).len(),
        1,
        "no map is a problem"
    );
}
