//! Finding things in a parsed derivation: the facts its labels name, the labels it
//! cites (`by [..]`, `use [..]`, `result [..]`), the names it declares, what is under
//! the cursor, the imported file a `use` reads, and the outline (headings, claims,
//! givens, constraints, bodies, definitions).

use super::text::Lines;
use super::world::{key, Open};
use crate::syntax::ast::{By, Chain, File, Item, Label, Name, Stmt, StmtKind};
use lsp_types::{DocumentSymbol, SymbolKind};
use std::path::{Path, PathBuf};

/// Every statement of a file, in order.
pub fn statements(file: &File) -> impl Iterator<Item = &Stmt> {
    file.items.iter().filter_map(|i| match i {
        Item::Stmt(s) => Some(s),
        _ => None,
    })
}

/// The label and chain of a `given`, `constraint` or `claim`.
pub fn fact(stmt: &Stmt) -> Option<(Option<&Label>, &Chain)> {
    match &stmt.kind {
        StmtKind::Given { label, chain }
        | StmtKind::Constraint { label, chain }
        | StmtKind::Claim { label, chain, .. } => Some((label.as_ref(), chain)),
        _ => None,
    }
}

/// The statement that carries the label `name`, if the file has one.
pub fn labelled<'f>(file: &'f File, name: &str) -> Option<(&'f Label, &'f Stmt)> {
    statements(file).find_map(|s| match fact(s) {
        Some((Some(l), _)) if l.name == name => Some((l, s)),
        _ => None,
    })
}

/// A label cited, with the path of the file it comes from when a `use` names it.
pub struct Cited<'f> {
    /// The label as written.
    pub label: &'f Label,
    /// The `use` path, for a label of a `use`.
    pub from: Option<&'f str>,
}

/// Every label the file cites: in `by [..]`, `use [..]` and `result [..]`.
pub fn cited(file: &File) -> Vec<Cited<'_>> {
    let mut out = Vec::new();
    for s in statements(file) {
        match &s.kind {
            StmtKind::Use { labels, path, .. } => out.extend(labels.iter().map(|label| Cited {
                label,
                from: Some(path.as_str()),
            })),
            StmtKind::Result { labels } => {
                out.extend(labels.iter().map(|label| Cited { label, from: None }))
            }
            _ => {}
        }
        if let Some((_, chain)) = fact(s) {
            for link in &chain.links {
                if let Some((By::Labels(ls), _)) = &link.by {
                    out.extend(ls.iter().map(|label| Cited { label, from: None }));
                }
            }
        }
    }
    out
}

/// The `use` path a label of this file comes from, if a `use` imports it.
pub fn imported_from<'f>(file: &'f File, name: &str) -> Option<&'f str> {
    statements(file).find_map(|s| match &s.kind {
        StmtKind::Use { labels, path, .. } if labels.iter().any(|l| l.name == name) => {
            Some(path.as_str())
        }
        _ => None,
    })
}

/// Every name the file declares, with the statement that declares it.
pub fn declared(file: &File) -> Vec<(&Name, &Stmt)> {
    let mut out = Vec::new();
    for s in statements(file) {
        match &s.kind {
            StmtKind::Symbols { names, .. }
            | StmtKind::Time { names }
            | StmtKind::Unknowns { names }
            | StmtKind::Range { names, .. } => out.extend(names.iter().map(|n| (n, s))),
            StmtKind::Let { name, .. } | StmtKind::Body { name, .. } => out.push((name, s)),
            _ => {}
        }
    }
    out
}

/// The first declaration of `name` (primes taken off: `theta''` is `theta`'s).
pub fn declaration<'f>(file: &'f File, name: &str) -> Option<(&'f Name, &'f Stmt)> {
    let base = name.trim_end_matches('\'');
    declared(file).into_iter().find(|(n, _)| n.name == base)
}

/// What the cursor is on.
pub enum Target<'f> {
    /// A label, where it is defined or cited.
    Label(Cited<'f>),
    /// A name (with any primes), where it is written.
    Name(String),
}

/// What is at byte offset `at` of `text` (parsed as `file`): a label, else the word.
pub fn target_at<'f>(file: &'f File, text: &str, at: usize) -> Option<Target<'f>> {
    let inside = |l: &Label| l.span.start <= at && at < l.span.end.max(l.span.start + 1);
    if let Some(c) = cited(file).into_iter().find(|c| inside(c.label)) {
        return Some(Target::Label(c));
    }
    let own = statements(file).find_map(|s| fact(s).and_then(|(l, _)| l).filter(|l| inside(l)));
    if let Some(label) = own {
        return Some(Target::Label(Cited { label, from: None }));
    }
    word_at(text, at).map(|(w, _)| Target::Name(w))
}

/// The name (letters, digits, `_`, primes) at byte offset `at`, with its byte range.
pub fn word_at(text: &str, at: usize) -> Option<(String, (usize, usize))> {
    let part = |c: char| c.is_alphanumeric() || c == '_' || c == '\'';
    let at = at.min(text.len());
    let start = text[..at]
        .char_indices()
        .rev()
        .take_while(|(_, c)| part(*c))
        .last()
        .map_or(at, |(i, _)| i);
    let end = text[at..]
        .char_indices()
        .find(|(_, c)| !part(*c))
        .map_or(text.len(), |(i, _)| at + i);
    let word = text.get(start..end)?;
    let word = word.trim_start_matches('\'');
    word.chars()
        .next()
        .filter(|c| c.is_alphabetic() || *c == '_')
        .map(|_| (word.to_string(), (end - word.len(), end)))
}

/// An imported file: its path, text and parse (`None` if it does not parse).
pub struct Imported {
    /// Where it is.
    pub path: PathBuf,
    /// Its text.
    pub text: String,
    /// Its syntax tree.
    pub file: Option<File>,
}

/// The file `use_path`, written in the document at `doc`: the open document, else the
/// file on disk.
pub fn import(doc: &Path, use_path: &str, open: &Open) -> Option<Imported> {
    if Path::new(use_path).is_absolute() {
        return None;
    }
    let path = key(&doc.parent()?.join(use_path));
    let text = match open.get(&path) {
        Some(t) => t.to_string(),
        None => crate::files::read(&path, 10_000_000).ok()?,
    };
    let file = crate::syntax::parse_file(&text, &Default::default()).ok();
    Some(Imported { path, text, file })
}

/// The statement's first line, as written: how the outline and hovers name it.
pub fn first_line(text: &str, stmt: &Stmt) -> String {
    let s = text.get(stmt.span.start..stmt.span.end).unwrap_or("");
    s.lines().next().unwrap_or("").trim().to_string()
}

/// The outline: headings (nested by level), and under each its claims, givens,
/// constraints, bodies and definitions.
pub fn outline(file: &File, text: &str, lines: &Lines<'_>) -> Vec<DocumentSymbol> {
    // Open headings: (level, symbol), innermost last.
    let mut stack: Vec<(usize, DocumentSymbol)> = Vec::new();
    let mut top: Vec<DocumentSymbol> = Vec::new();
    fn close(stack: &mut Vec<(usize, DocumentSymbol)>, top: &mut Vec<DocumentSymbol>) {
        if let Some((_, done)) = stack.pop() {
            match stack.last_mut() {
                Some((_, parent)) => {
                    parent.range.end = parent.range.end.max(done.range.end);
                    parent.children.get_or_insert_with(Vec::new).push(done)
                }
                None => top.push(done),
            }
        }
    }
    for item in &file.items {
        let sym = match item {
            Item::Heading {
                level,
                text: t,
                span,
            } => {
                while stack.last().is_some_and(|(l, _)| *l >= *level) {
                    close(&mut stack, &mut top);
                }
                let mut h = symbol(t.trim(), SymbolKind::NAMESPACE, lines.range(*span));
                // A heading's range runs to the end of its section: widened as it closes.
                h.children = Some(Vec::new());
                stack.push((*level, h));
                continue;
            }
            Item::Prose { .. } => continue,
            Item::Stmt(s) => match stmt_symbol(s, text, lines) {
                Some(sym) => sym,
                None => continue,
            },
        };
        match stack.last_mut() {
            Some((_, h)) => {
                h.range.end = sym.range.end;
                h.children.get_or_insert_with(Vec::new).push(sym);
            }
            None => top.push(sym),
        }
    }
    while !stack.is_empty() {
        close(&mut stack, &mut top);
    }
    top
}

fn stmt_symbol(s: &Stmt, text: &str, lines: &Lines<'_>) -> Option<DocumentSymbol> {
    let (what, kind) = match &s.kind {
        StmtKind::Claim { .. } => ("claim", SymbolKind::FUNCTION),
        StmtKind::Given { .. } => ("given", SymbolKind::CONSTANT),
        StmtKind::Constraint { .. } => ("constraint", SymbolKind::CONSTANT),
        StmtKind::Body { name, .. } => {
            let mut b = symbol(&name.name, SymbolKind::STRUCT, lines.range(s.span));
            b.detail = Some("body".into());
            b.selection_range = lines.range(name.span);
            return Some(b);
        }
        StmtKind::Let { name, .. } => {
            let mut b = symbol(&name.name, SymbolKind::VARIABLE, lines.range(s.span));
            b.detail = Some("let".into());
            b.selection_range = lines.range(name.span);
            return Some(b);
        }
        _ => return None,
    };
    let (label, _) = fact(s)?;
    let line = first_line(text, s);
    let name = match label {
        Some(l) => format!("[{}]", l.name),
        None => line.clone(),
    };
    let mut sym = symbol(&name, kind, lines.range(s.span));
    sym.detail = Some(if label.is_some() {
        format!(
            "{what}: {}",
            line.strip_prefix(what).unwrap_or(&line).trim()
        )
    } else {
        what.to_string()
    });
    if let Some(l) = label {
        sym.selection_range = lines.range(l.span);
    }
    Some(sym)
}

#[allow(deprecated)] // `deprecated` is a field the protocol still requires.
fn symbol(name: &str, kind: SymbolKind, range: lsp_types::Range) -> DocumentSymbol {
    DocumentSymbol {
        name: if name.is_empty() {
            "?".into()
        } else {
            name.into()
        },
        detail: None,
        kind,
        tags: None,
        deprecated: None,
        range,
        selection_range: range,
        children: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_word_under_the_cursor_keeps_its_primes() {
        let text = "claim theta'' = -(g/L) sin(theta)";
        let at = text.find("ta''").unwrap();
        assert_eq!(word_at(text, at), Some(("theta''".into(), (6, 13))));
        // At the end of a word, and on a function name.
        assert_eq!(word_at(text, 13).map(|w| w.0).as_deref(), Some("theta''"));
        let at = text.find("sin").unwrap() + 1;
        assert_eq!(word_at(text, at).map(|w| w.0).as_deref(), Some("sin"));
        // Not a name: a number, an operator.
        assert_eq!(word_at("x = 12", 5), None);
        assert_eq!(word_at("x = 12", 2), None);
    }

    #[test]
    fn the_outline_nests_statements_under_their_headings() {
        let text = "# Title\nsymbols m > 0\n## One\ngiven [a] m = m\nclaim [b] m = m\n## Two\nclaim m + m = 2 m\nbody rod: mass m, coordinates y\n";
        let file = crate::syntax::parse_file(text, &Default::default()).unwrap();
        let out = outline(&file, text, &Lines::new(text));
        assert_eq!(out.len(), 1);
        let names = |s: &DocumentSymbol| -> Vec<String> {
            s.children
                .iter()
                .flatten()
                .map(|c| c.name.clone())
                .collect()
        };
        assert_eq!(out[0].name, "Title");
        assert_eq!(names(&out[0]), ["One", "Two"]);
        let sections = out[0].children.as_ref().unwrap();
        assert_eq!(names(&sections[0]), ["[a]", "[b]"]);
        assert_eq!(names(&sections[1]), ["claim m + m = 2 m", "rod"]);
        // A heading's range runs to the end of its last statement.
        assert_eq!(sections[0].range.end.line, 4);
        assert_eq!(out[0].range.end.line, 7);
    }
}
