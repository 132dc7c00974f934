//! `rigor lint` reports: one line per chain (`doc.md:12:5: verified`), the diagnostics of
//! failed chains rustc-style, JSON and GitHub annotations, and the summary line.

use crate::diag::LineIndex;
use crate::lint::{LintReport, Verdict};
use serde_json::json;

fn word(v: &Verdict) -> &'static str {
    match v {
        Verdict::Verified => "verified",
        Verdict::Failed => "failed",
        Verdict::NeedsContext => "needs context",
        Verdict::Defined => "defined",
    }
}

/// How a verified chain's report says what it rests on: ` from lines 12 and 14, using
/// I_G = … from line 8` (empty when it rests on nothing stated).
fn rests_on(from: &[usize], using: &[(String, usize)]) -> String {
    let mut out = String::new();
    if !from.is_empty() {
        let lines: Vec<String> = from.iter().map(usize::to_string).collect();
        let list = match lines.split_last() {
            Some((last, [])) => format!("line {last}"),
            Some((last, rest)) => format!("lines {} and {last}", rest.join(", ")),
            None => String::new(),
        };
        out.push_str(&format!(" from {list}"));
    }
    for (i, (text, line)) in using.iter().enumerate() {
        out.push_str(if i == 0 { ", using " } else { " and " });
        out.push_str(&format!("{text} from line {line}"));
    }
    out
}

/// A `rigor:` statement as a comment of the document's kind: `% rigor: …` in LaTeX,
/// `<!-- rigor: … -->` in Markdown.
fn comment_in(path: &str, k: &str) -> String {
    if path.ends_with(".tex") {
        format!("% {k}")
    } else {
        format!("<!-- {k} -->")
    }
}

/// The human report: (standard output, standard error).
pub fn human(r: &LintReport) -> (String, String) {
    let (mut out, mut err) = (String::new(), String::new());
    let idx = LineIndex::new(&r.source);
    for c in &r.chains {
        // A failed chain is reported where its mistake is (a chain may run over rows).
        let at = match c.verdict {
            Verdict::Failed => c.diagnostics.first().and_then(|d| d.primary.as_ref()),
            _ => None,
        };
        let (line, col) = idx.line_col(at.map_or(c.span.start, |(s, _)| s.start));
        let why = c.diagnostics.first().map_or(String::new(), |d| {
            let m = d.message.as_str();
            format!(": {}", m.strip_prefix("needs context: ").unwrap_or(m))
        });
        match c.verdict {
            // What it rests on, and what the signs do not show, as `check` says it.
            Verdict::Verified => {
                let assuming = if c.assuming.is_empty() {
                    String::new()
                } else {
                    format!(", assuming {}", c.assuming.join(" and "))
                };
                out.push_str(&format!(
                    "{}:{line}:{col}: verified{}{assuming}\n",
                    r.path,
                    rests_on(&c.from, &c.using)
                ))
            }
            // A definition is taken as the notes give it: said, never counted as checked.
            Verdict::Defined => out.push_str(&format!(
                "{}:{line}:{col}: defines {}\n",
                r.path,
                c.defines.as_deref().unwrap_or("a new symbol")
            )),
            Verdict::NeedsContext => {
                // The comment that makes it checkable, as the document writes comments.
                let add = c
                    .comment
                    .as_ref()
                    .filter(|k| !why.contains(k.as_str()))
                    .map_or(String::new(), |k| {
                        format!("; `{}` makes it checkable", comment_in(&r.path, k))
                    });
                out.push_str(&format!(
                    "{}:{line}:{col}: needs context{why}{add}\n",
                    r.path
                ))
            }
            Verdict::Failed => {
                out.push_str(&format!("{}:{line}:{col}: FAILED{why}\n", r.path));
                for d in &c.diagnostics {
                    err.push_str(&crate::diag::render_in(d, &r.path, &idx));
                }
            }
        }
    }
    (out, err)
}

/// `chains: N, verified: V, defined: D, failed: F, needs context: C`.
pub fn summary(reports: &[LintReport]) -> String {
    let n: usize = reports.iter().map(|r| r.chains.len()).sum();
    let c = |v: Verdict| -> usize { reports.iter().map(|r| r.count(&v)).sum() };
    format!(
        "chains: {n}, verified: {}, defined: {}, failed: {}, needs context: {}",
        c(Verdict::Verified),
        c(Verdict::Defined),
        c(Verdict::Failed),
        c(Verdict::NeedsContext)
    )
}

/// One JSON object per document.
pub fn json(r: &LintReport) -> String {
    let idx = LineIndex::new(&r.source);
    let chains: Vec<serde_json::Value> = r
        .chains
        .iter()
        .map(|c| {
            let (line, column) = idx.line_col(c.span.start);
            let diags: Vec<serde_json::Value> = c
                .diagnostics
                .iter()
                .map(|d| {
                    let at = d.primary.as_ref().map(|(s, _)| idx.line_col(s.start));
                    json!({"code": d.code.as_str(), "message": d.message.as_str(), "notes": super::json::notes(d),
                           "line": at.map(|a| a.0), "column": at.map(|a| a.1)})
                })
                .collect();
            json!({"line": line, "column": column, "verdict": word(&c.verdict),
                   "assuming": c.assuming, "defines": c.defines,
                   "reason": c.reason.map(|r| r.as_str()), "comment": c.comment,
                   "from": c.from,
                   "using": c.using.iter().map(|(t, l)| json!({"relation": t, "line": l})).collect::<Vec<_>>(),
                   "diagnostics": diags})
        })
        .collect();
    json!({
        "path": r.path,
        "chains": chains,
        "verified": r.count(&Verdict::Verified),
        "defined": r.count(&Verdict::Defined),
        "failed": r.count(&Verdict::Failed),
        "needs_context": r.count(&Verdict::NeedsContext),
    })
    .to_string()
}

/// GitHub annotations: an error for each diagnostic of a failed chain, a notice for
/// each chain that needs context (its reason, and the `rigor:` comment that would make
/// it checkable where rigor knows it), and a notice for each chain verified from
/// premises, naming them.
pub fn github(r: &LintReport) -> String {
    let idx = LineIndex::new(&r.source);
    let mut out = String::new();
    for c in &r.chains {
        match c.verdict {
            Verdict::Failed => {
                for d in &c.diagnostics {
                    out.push_str(&super::github::command_in(&r.path, &idx, d));
                }
            }
            Verdict::NeedsContext => {
                let Some(first) = c.diagnostics.first() else {
                    continue;
                };
                let mut d = first.clone();
                d.severity = crate::diag::Severity::Note;
                if let Some(reason) = c.reason {
                    d.message = format!("{} [{}]", d.message, reason.as_str()).into();
                }
                if let Some(comment) = &c.comment {
                    d.add_note(format!("to have it checked: {comment}"));
                }
                out.push_str(&super::github::command_in(&r.path, &idx, &d));
            }
            Verdict::Verified if !c.from.is_empty() || !c.using.is_empty() => {
                let (line, col) = idx.line_col(c.span.start);
                let (end_line, end_col) = idx.line_col(c.span.end.max(c.span.start));
                out.push_str(&format!(
                    "::notice file={},line={line},col={col},endLine={end_line},endColumn={end_col},title=verified::{}\n",
                    super::github::escape_property(&r.path),
                    super::github::escape_data(&format!("verified{}", rests_on(&c.from, &c.using)))
                ));
            }
            _ => {}
        }
    }
    out
}
