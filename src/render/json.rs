//! `rigor check --format json`: one JSON object per file with every link's verdict
//! and every diagnostic, positions as 1-based lines and columns (in characters).

use crate::check::report::{FileReport, Justification, LinkReport, Status};
use crate::diag::{Diagnostic, LineIndex};
use crate::syntax::ast::Span;
use serde_json::{json, Value};

/// The report of one file:
///
/// ```text
/// {"path", "ok", "input_error",
///  "claims": [{"label", "line", "links": [{"line", "column", "end_line", "end_column",
///      "op", "lhs", "rhs", "status", "justification", "side_conditions"}]}],
///  "diagnostics": [{"severity", "code", "message", "line", "column", "end_line",
///      "end_column", "label", "notes"}]}
/// ```
///
/// `status` is `verified`, `failed`, `undecided`, `not_checked` (it cites a step that
/// did not hold; a note says which) or `error`; `justification` is
/// `{"kind": "identity"}`, `{"kind": "facts", "facts": [...]}`,
/// `{"kind": "signs", "facts": [...]}`, `{"kind": "approx"}`, or `null` when not
/// verified. `lhs`, `rhs`, positions and labels are `null` when unknown. A
/// diagnostic's `label` is the hint written under the caret ("the left side is 2 × the
/// right side", "a sign error?"); its `notes` hold both sides and the checked
/// counterexample (`"counterexample: at …"`).
pub fn report(r: &FileReport) -> Value {
    let idx = LineIndex::new(&r.source);
    let claims: Vec<Value> = r
        .claims
        .iter()
        .map(|c| {
            let links: Vec<Value> = c.links.iter().map(|l| link(&idx, l)).collect();
            json!({ "label": c.label, "line": c.line, "links": links })
        })
        .collect();
    let diagnostics: Vec<Value> = r.diagnostics.iter().map(|d| diagnostic(&idx, d)).collect();
    json!({
        "path": r.path,
        "ok": r.ok(),
        "input_error": r.input_error,
        "claims": claims,
        "diagnostics": diagnostics,
    })
}

/// The four position fields of a span, merged into `obj`.
fn position(idx: &LineIndex<'_>, span: Option<Span>, obj: &mut serde_json::Map<String, Value>) {
    let (a, b) = match span {
        Some(s) => {
            let (l, c) = idx.line_col(s.start);
            let (l2, c2) = idx.line_col(s.end.max(s.start));
            (Some((l, c)), Some((l2, c2)))
        }
        None => (None, None),
    };
    obj.insert("line".into(), json!(a.map(|p| p.0)));
    obj.insert("column".into(), json!(a.map(|p| p.1)));
    obj.insert("end_line".into(), json!(b.map(|p| p.0)));
    obj.insert("end_column".into(), json!(b.map(|p| p.1)));
}

fn link(idx: &LineIndex<'_>, l: &LinkReport) -> Value {
    let (status, how, side): (&str, Value, &[String]) = match &l.status {
        Status::Verified {
            how,
            side_conditions,
        } => ("verified", justification(how), side_conditions),
        Status::Failed => ("failed", Value::Null, &[]),
        Status::Undecided => ("undecided", Value::Null, &[]),
        Status::Error => ("error", Value::Null, &[]),
        Status::NotChecked => ("not_checked", Value::Null, &[]),
    };
    let mut obj = serde_json::Map::new();
    position(idx, Some(l.span), &mut obj);
    obj.insert("op".into(), json!(l.op.as_str()));
    obj.insert("lhs".into(), json!(l.lhs));
    obj.insert("rhs".into(), json!(l.rhs));
    obj.insert("status".into(), json!(status));
    if let Some(u) = &l.units {
        obj.insert("units".into(), json!(u));
    }
    obj.insert("justification".into(), how);
    obj.insert("side_conditions".into(), json!(side));
    Value::Object(obj)
}

fn justification(how: &Justification) -> Value {
    match how {
        Justification::Identity => json!({ "kind": "identity" }),
        Justification::Facts(fs) => json!({ "kind": "facts", "facts": keys(fs) }),
        Justification::Signs(fs) => json!({ "kind": "signs", "facts": keys(fs) }),
        Justification::Approx => json!({ "kind": "approx" }),
        Justification::Small { order, of } => {
            json!({ "kind": "small", "order": order, "small": of })
        }
    }
}

fn diagnostic(idx: &LineIndex<'_>, d: &Diagnostic) -> Value {
    let mut obj = serde_json::Map::new();
    obj.insert("severity".into(), json!(d.severity.as_str()));
    obj.insert("code".into(), json!(d.code.as_str()));
    obj.insert("message".into(), json!(d.message.as_str()));
    position(idx, d.primary.as_ref().map(|(s, _)| *s), &mut obj);
    obj.insert("label".into(), json!(d.primary.as_ref().map(|(_, l)| l)));
    obj.insert("notes".into(), json!(notes(d)));
    Value::Object(obj)
}

/// Facts by the names JSON gives them (`Fx`, `line 12`).
fn keys(fs: &[crate::diag::FactRef]) -> Vec<String> {
    fs.iter().map(crate::diag::FactRef::key).collect()
}

/// A diagnostic's notes, in words.
pub(crate) fn notes(d: &Diagnostic) -> Vec<String> {
    d.notes.iter().map(ToString::to_string).collect()
}
