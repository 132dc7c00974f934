//! `rigor mark` output: per-submission lines, the class summary table, CSV and JSON for a
//! gradebook, and one Markdown feedback file per submission. Submissions are untrusted:
//! their names and text are escaped wherever they appear.

use crate::check::Status;
use crate::mark::{Outcome, Row};
use serde_json::json;

fn outcome(o: &Outcome) -> String {
    match o {
        Outcome::Right => "right".into(),
        Outcome::Wrong => "wrong".into(),
        Outcome::Missing => "missing".into(),
        Outcome::Undecided(why) => format!("undecided ({why})"),
        Outcome::NotCredited(why) => format!("not credited ({why})"),
    }
}

/// Control characters and line breaks out of an untrusted name.
fn clean(s: &str) -> String {
    s.chars()
        .map(|c| if c.is_control() { '?' } else { c })
        .collect()
}

/// `s → x, Fr → F`: the names a submission declared differently.
fn mapped(r: &Row) -> String {
    r.mapping
        .iter()
        .map(|(a, b)| format!("{a} → {b}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A few lines per submission.
pub fn human(rows: &[Row]) -> String {
    let mut out = String::new();
    for r in rows {
        out.push_str(&format!("{}: ", clean(&r.file)));
        if let Some(why) = &r.unreadable {
            out.push_str(&format!("not marked: {}\n", clean(why)));
            continue;
        }
        let (right, all) = r.results_score();
        out.push_str(&format!(
            "steps {}/{} verified, results {right}/{all} right\n",
            r.steps.0, r.steps.1
        ));
        if let Some((line, kind, msg)) = &r.first_failure {
            out.push_str(&format!(
                "  first mistake: line {line} ({kind}): {}\n",
                clean(msg)
            ));
        }
        if !r.mapping.is_empty() {
            out.push_str(&format!("  names matched by role: {}\n", clean(&mapped(r))));
        }
        for (e, o) in &r.results {
            out.push_str(&format!(
                "  [{}] {}: {}\n",
                e.label,
                clean(&e.lhs),
                outcome(o)
            ));
        }
    }
    out
}

/// Untrusted text for a cell of a Markdown table: no `<tag>`, link, code span or entity
/// in it stays live, and no `|` splits the cell (`_` and `*` are left as written).
fn cell(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in clean(s).chars() {
        if matches!(c, '\\' | '<' | '>' | '|' | '[' | ']' | '`' | '&') {
            out.push('\\');
        }
        out.push(c);
    }
    out
}

/// The class summary table (Markdown): file names and reasons are untrusted text,
/// escaped as table cells (`cell`).
pub fn summary(rows: &[Row]) -> String {
    let mut out =
        String::from("| file | steps verified | first failure | results |\n|---|---|---|---|\n");
    for r in rows {
        let (right, all) = r.results_score();
        let first = match (&r.unreadable, &r.first_failure) {
            (Some(why), _) => format!("not marked: {}", cell(why)),
            (None, Some((line, kind, _))) => format!("line {line} ({kind})"),
            (None, None) => "none".into(),
        };
        out.push_str(&format!(
            "| {} | {}/{} | {first} | {right}/{all} |\n",
            cell(&r.file),
            r.steps.0,
            r.steps.1
        ));
    }
    out
}

fn csv_cell(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// The gradebook CSV.
pub fn csv(rows: &[Row]) -> String {
    let mut out = String::from("file,steps_verified,steps_total,first_failure_line,first_failure_kind,results_correct,results_total\n");
    for r in rows {
        let (right, all) = r.results_score();
        let (line, kind) = match &r.first_failure {
            Some((l, k, _)) => (l.to_string(), k.to_string()),
            None if r.unreadable.is_some() => (String::new(), "syntax".into()),
            None => (String::new(), String::new()),
        };
        out.push_str(&format!(
            "{},{},{},{line},{kind},{right},{all}\n",
            csv_cell(&r.file),
            r.steps.0,
            r.steps.1
        ));
    }
    out
}

/// One JSON object per submission, one per line.
pub fn json(rows: &[Row]) -> String {
    rows.iter()
        .map(|r| {
            let (right, all) = r.results_score();
            let results: Vec<serde_json::Value> = r
                .results
                .iter()
                .map(|(e, o)| json!({"label": e.label, "quantity": e.lhs, "outcome": outcome(o)}))
                .collect();
            json!({
                "file": r.file,
                "steps_verified": r.steps.0,
                "steps_total": r.steps.1,
                "first_failure": r.first_failure.as_ref().map(|(l, k, m)| json!({"line": l, "kind": k, "message": m})),
                "results_correct": right,
                "results_total": all,
                "results": results,
                "names_mapped": r.mapping.iter().map(|(a, b)| json!({"submission": a, "reference": b})).collect::<Vec<_>>(),
                "not_marked": r.unreadable,
            })
            .to_string()
                + "\n"
        })
        .collect()
}

/// The hint for a kind of first mistake, in plain words.
fn hint(kind: &str) -> &'static str {
    match kind {
        "sign" => "check the direction you took as positive for this term",
        "factor" => "compare the sizes of the two sides: a factor is off",
        "power" => "check the power of each quantity in this step",
        "missing_term" => "a term is missing on one side: compare the terms step by step",
        "extra_term" => "a term appears that should not be there",
        "missing_fact" => {
            "this step needs a fact (an equation of motion, a constraint) you have not written"
        }
        "undeclared" => "a name is used before it is declared (a typo?)",
        "syntax" => "rigor could not read this line",
        "units" => "the two sides are not in the same units",
        "false_fact" => {
            "this fact is false (or your facts contradict each other): anything would follow from it, so nothing that rests on it counts"
        }
        _ => "rigor could not decide this step",
    }
}

/// The feedback file for one submission (Markdown). The reference's working is shown
/// only with `reveal`.
pub fn feedback(r: &Row, reveal: Option<&str>) -> String {
    let mut out = format!(
        "# Feedback: {}\n\n",
        crate::render::text::markdown_text(&clean(&r.file))
    );
    if let Some(why) = &r.unreadable {
        out.push_str(&format!(
            "Your file could not be marked: {}\n",
            crate::render::text::markdown_text(why)
        ));
        return out;
    }
    out.push_str(&format!(
        "{} of {} steps verified.\n\n## Steps\n\n",
        r.steps.0, r.steps.1
    ));
    if let Some(rep) = &r.report {
        let idx = crate::diag::LineIndex::new(&rep.source);
        for c in &rep.claims {
            for l in &c.links {
                let v = match l.status {
                    Status::Verified { .. } => "verified",
                    Status::Failed => "does not follow",
                    Status::Undecided => "not shown to follow",
                    Status::Error => "not read",
                    Status::NotChecked => "not checked (it cites a step that does not follow)",
                };
                let line = idx.line_col(l.span.start).0;
                out.push_str(&format!("- line {line}: {v}\n"));
            }
        }
    }
    if let Some((line, kind, msg)) = &r.first_failure {
        out.push_str(&format!(
            "\n## First mistake\n\nLine {line}: {}.\n\nHint: {}.\n",
            crate::render::text::markdown_text(msg),
            hint(kind)
        ));
    }
    out.push_str("\n## Results\n\n");
    if !r.mapping.is_empty() {
        out.push_str(&format!(
            "Your names were matched to the reference's by the role they play in your equations: {}.\n\n",
            crate::render::text::markdown_text(&clean(&mapped(r)))
        ));
    }
    for (e, o) in &r.results {
        let said = match o {
            Outcome::Right => "right".to_string(),
            Outcome::Wrong => "not what it should be".to_string(),
            Outcome::Missing => "not found in your work".to_string(),
            Outcome::Undecided(_) => "could not be compared".to_string(),
            Outcome::NotCredited(_) => {
                "not credited: your work reaches it only through facts that are false or contradict each other".to_string()
            }
        };
        out.push_str(&format!("- `{}`: {said}\n", e.lhs.replace('`', "'")));
    }
    if let Some(text) = reveal {
        out.push_str(&format!("\n## Reference\n\n```text\n{text}\n```\n"));
    }
    out
}
