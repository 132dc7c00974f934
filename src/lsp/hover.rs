//! What a hover shows, as Markdown: on a label, the fact it names (in this file or the
//! one a `use` imports it from); on a name, its declaration, its sign or range and its
//! unit; on a link, its verdict, the side conditions it assumes, both sides' normal
//! forms and their unit. Read from the last report; nothing is decided here.

use super::nav::{self, Target};
use super::world::Open;
use crate::check::{FileReport, LinkReport, Status};
use crate::syntax::ast::{SignDecl, StmtKind};
use std::path::Path;

/// The hover at byte offset `at` of the report's text, if there is something to say.
pub fn hover(r: &FileReport, at: usize, doc: Option<&Path>, open: &Open) -> Option<String> {
    let file = r.ast.as_ref()?;
    let text = &r.source;
    let mut parts = Vec::new();
    match nav::target_at(file, text, at) {
        Some(Target::Label(c)) => {
            if let Some(l) = label(r, &c, doc, open) {
                parts.push(l);
            }
        }
        Some(Target::Name(name)) => {
            if let Some(s) = symbol(r, &name) {
                parts.push(s);
            }
        }
        None => {}
    }
    if let Some(l) = link_at(r, at) {
        parts.push(link(l));
    }
    (!parts.is_empty()).then(|| parts.join("\n\n---\n\n"))
}

/// The innermost link whose span holds `at`.
fn link_at(r: &FileReport, at: usize) -> Option<&LinkReport> {
    r.claims
        .iter()
        .flat_map(|c| &c.links)
        .filter(|l| l.span.start <= at && at <= l.span.end)
        .min_by_key(|l| l.span.end - l.span.start)
}

fn code(s: &str) -> String {
    format!("```rigor\n{s}\n```")
}

fn label(r: &FileReport, c: &nav::Cited<'_>, doc: Option<&Path>, open: &Open) -> Option<String> {
    let name = &c.label.name;
    let file = r.ast.as_ref()?;
    let from = c.from.or_else(|| nav::imported_from(file, name));
    if let Some(path) = from {
        let imported = nav::import(doc?, path, open)?;
        let (_, s) = nav::labelled(imported.file.as_ref()?, name)?;
        let stated = imported.text.get(s.span.start..s.span.end)?;
        return Some(format!(
            "**[{name}]**, from \"{path}\"\n\n{}",
            code(stated.trim_end())
        ));
    }
    let (_, s) = nav::labelled(file, name)?;
    let line = crate::diag::line_col(&r.source, s.span.start).0;
    let stated = r.source.get(s.span.start..s.span.end)?;
    Some(format!(
        "**[{name}]**, line {line}\n\n{}",
        code(stated.trim_end())
    ))
}

fn symbol(r: &FileReport, name: &str) -> Option<String> {
    let file = r.ast.as_ref()?;
    let (n, s) = nav::declaration(file, name)?;
    let text = &r.source;
    let mut out = format!("**{name}**\n\n{}", code(&nav::first_line(text, s)));
    let what = match &s.kind {
        StmtKind::Symbols { sign, .. } => match sign {
            SignDecl::Any => "a symbol of any sign".to_string(),
            SignDecl::Positive => format!("a symbol, `{} > 0`", n.name),
            SignDecl::Nonnegative => format!("a symbol, `{} >= 0`", n.name),
            SignDecl::Nonzero => format!("a symbol, `{} != 0`", n.name),
        },
        StmtKind::Range {
            lo,
            lo_strict,
            hi,
            hi_strict,
            ..
        } => {
            let rel = |strict: bool| if strict { "<" } else { "<=" };
            let src =
                |e: &crate::syntax::ast::Expr| text.get(e.span.start..e.span.end).unwrap_or("?");
            format!(
                "a symbol in a range, `{} {} {} {} {}`",
                src(lo),
                rel(*lo_strict),
                n.name,
                rel(*hi_strict),
                src(hi)
            )
        }
        StmtKind::Time { .. } => "a function of time (its primes are its derivatives)".into(),
        StmtKind::Unknowns { .. } => "an unknown, which the facts determine".into(),
        StmtKind::Let { value, .. } => format!(
            "a definition, `{} = {}`",
            n.name,
            text.get(value.span.start..value.span.end).unwrap_or("?")
        ),
        StmtKind::Body { .. } => "a body".into(),
        _ => String::new(),
    };
    if !what.is_empty() {
        out.push_str(&format!("\n\n{what}"));
    }
    if let Some(unit) = unit_of(r, &n.name) {
        out.push_str(&format!("\n\nunit: `{unit}`"));
    }
    Some(out)
}

/// The unit a `units` statement gives `name`.
fn unit_of(r: &FileReport, name: &str) -> Option<String> {
    nav::statements(r.ast.as_ref()?).find_map(|s| match &s.kind {
        StmtKind::Units { decls } => decls
            .iter()
            .find(|d| d.name.name == name)
            .map(|d| d.unit.trim().to_string()),
        _ => None,
    })
}

fn link(l: &LinkReport) -> String {
    let verdict = match &l.status {
        Status::Verified { how, .. } => format!("verified ({how})"),
        Status::Failed => "false".into(),
        Status::Undecided => "not verified".into(),
        Status::Error => "not checked: the statement could not be read".into(),
        Status::NotChecked => "not checked: it cites a fact that did not hold".into(),
    };
    let mut out = format!("**`{}` link: {verdict}**", l.op);
    if let Status::Verified {
        side_conditions, ..
    } = &l.status
    {
        if !side_conditions.is_empty() {
            out.push_str(&format!("\n\nassuming `{}`", side_conditions.join("`, `")));
        }
    }
    if let (Some(a), Some(b)) = (&l.lhs, &l.rhs) {
        out.push_str(&format!(
            "\n\nleft side:\n{}\n\nright side:\n{}",
            code(a),
            code(b)
        ));
    }
    if let Some(u) = &l.units {
        out.push_str(&format!("\n\nunit: `{u}`"));
    }
    out
}
