//! `rigor mark` output: per-submission lines, the class summary table, CSV and JSON for a
//! gradebook, and one Markdown feedback file per submission. Submissions are untrusted:
//! their names and text are escaped wherever they appear.

use crate::check::{FileReport, Status};
use crate::diag::Mistake;
use crate::mark::facts::{FactKind, Standing};
use crate::mark::{Outcome, ResultMark, Row, Why};
use serde_json::json;

/// Why a result earns nothing, in words.
fn why(w: &Why) -> String {
    match w {
        Why::OwnAssumption { label, line, kind } => {
            let what = match (label, kind) {
                (Some(l), _) => format!(" [{l}]"),
                (None, FactKind::Let) => " (a `let`)".into(),
                (None, FactKind::Where) => " (a `where` value)".into(),
                (None, _) => String::new(),
            };
            format!("rests on your own assumption{what}, line {line}, which the problem does not give")
        }
        Why::Contradiction { label, line } => {
            let what = label.as_ref().map_or(String::new(), |l| format!(" [{l}]"));
            format!("rests on your fact{what}, line {line}, which contradicts your other facts")
        }
        Why::Import { line } => format!(
            "rests on the `use` on line {line}, which imported nothing (a submission may import only the course library's verified results)"
        ),
        Why::DoesNotFollow { line } => {
            format!("your claim on line {line} does not follow in your own work")
        }
        Why::Unmatched { name } => format!(
            "it is written with `{name}`, which no fact of the problem matches to one of its quantities"
        ),
    }
}

fn outcome(o: &Outcome) -> String {
    match o {
        Outcome::Right => "right".into(),
        Outcome::Wrong => "wrong".into(),
        Outcome::Missing => "missing".into(),
        Outcome::Undecided(w) => format!("undecided ({w})"),
        Outcome::NotCredited(w) => format!("not credited ({})", why(w)),
    }
}

/// `an earlier claim, line 7, says otherwise`, if one does.
fn earlier(r: &ResultMark) -> Option<String> {
    match r.earlier.as_slice() {
        [] => None,
        [l] => Some(format!("an earlier claim, line {l}, says otherwise")),
        ls => Some(format!(
            "earlier claims, lines {}, say otherwise",
            ls.iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        )),
    }
}

/// A fact of the submission that is not the problem's, in words.
fn own_fact(f: &crate::mark::facts::Fact) -> String {
    let what = match (&f.label, f.kind) {
        (Some(l), _) => format!("[{l}], line {}", f.line),
        (None, FactKind::Use) => format!("`use`, line {}", f.line),
        (None, FactKind::Let) => format!("`let`, line {}", f.line),
        (None, FactKind::Where) => format!("`where`, line {}", f.line),
        (None, _) => format!("line {}", f.line),
    };
    let standing = match f.standing {
        Standing::Own => "your own assumption: the problem does not give it",
        Standing::Contradiction => "contradicts your other facts",
        Standing::ImportFailed => {
            "imported nothing: a submission may import only the course library's verified results"
        }
        Standing::Problem => "the problem's",
    };
    format!("{what}: {standing}")
}

/// Control characters and line breaks out of an untrusted name.
fn clean(s: &str) -> String {
    s.chars()
        .map(|c| if c.is_control() { '?' } else { c })
        .collect()
}

/// `s → x, P → −F`: the names a submission declared differently.
fn mapped(r: &Row) -> String {
    r.mapping
        .iter()
        .map(|m| {
            let sign = if m.negated { "−" } else { "" };
            format!("{} → {sign}{}", m.from, m.to)
        })
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
        if let Some(f) = &r.first_failure {
            out.push_str(&format!(
                "  first mistake: line {} ({}): {}\n",
                f.line,
                f.kind,
                clean(&f.diagnostic.message)
            ));
        }
        if !r.mapping.is_empty() {
            out.push_str(&format!("  names matched by role: {}\n", clean(&mapped(r))));
        }
        if !r.unmatched.is_empty() {
            out.push_str(&format!(
                "  names no fact of the problem matches: {}\n",
                clean(&r.unmatched.join(", "))
            ));
        }
        for f in &r.own {
            out.push_str(&format!("  fact {}\n", clean(&own_fact(f))));
        }
        for m in &r.results {
            out.push_str(&format!(
                "  [{}] {}: {}\n",
                m.expected.label,
                clean(&m.expected.lhs),
                clean(&outcome(&m.outcome))
            ));
            if let Some(e) = earlier(m) {
                out.push_str(&format!("    {e}\n"));
            }
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
            (None, Some(f)) => format!("line {} ({})", f.line, f.kind),
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

/// One CSV cell of untrusted text: control characters out, a leading `=`, `+`, `-` or
/// `@` (a spreadsheet formula) behind a `'` (OWASP, CSV injection), quoted when it holds
/// a comma or a quote.
fn csv_cell(s: &str) -> String {
    let mut s = clean(s);
    if s.starts_with(['=', '+', '-', '@']) {
        s.insert(0, '\'');
    }
    if s.contains([',', '"']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s
    }
}

/// The note of a row: why it was not marked, else why results earned nothing and which
/// of its facts are not the problem's.
fn note(r: &Row) -> String {
    if let Some(why) = &r.unreadable {
        return format!("not marked: {why}");
    }
    let mut notes: Vec<String> = Vec::new();
    for m in &r.results {
        let n = match &m.outcome {
            Outcome::NotCredited(w) => format!("[{}] not credited: {}", m.expected.label, why(w)),
            Outcome::Undecided(w) => format!("[{}] undecided: {w}", m.expected.label),
            _ => continue,
        };
        if !notes.contains(&n) {
            notes.push(n);
        }
    }
    if !r.own.is_empty() {
        let facts: Vec<String> = r
            .own
            .iter()
            .map(|f| match (&f.label, f.kind) {
                (Some(l), _) => format!("[{l}] line {}", f.line),
                (None, FactKind::Use) => format!("use line {}", f.line),
                (None, FactKind::Let) => format!("let line {}", f.line),
                (None, FactKind::Where) => format!("where line {}", f.line),
                (None, _) => format!("line {}", f.line),
            })
            .collect();
        notes.push(format!("facts not the problem's: {}", facts.join(", ")));
    }
    notes.join("; ")
}

/// The gradebook CSV.
pub fn csv(rows: &[Row]) -> String {
    let mut out = String::from("file,steps_verified,steps_total,first_failure_line,first_failure_kind,results_correct,results_total,note\n");
    for r in rows {
        let (right, all) = r.results_score();
        let (line, kind) = match &r.first_failure {
            Some(f) => (f.line.to_string(), f.kind),
            None if r.unreadable.is_some() => (String::new(), "not_read"),
            None => (String::new(), ""),
        };
        out.push_str(&format!(
            "{},{},{},{line},{kind},{right},{all},{}\n",
            csv_cell(&r.file),
            r.steps.0,
            r.steps.1,
            csv_cell(&note(r))
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
                .map(|m| {
                    json!({
                        "label": m.expected.label,
                        "quantity": m.expected.lhs,
                        "outcome": outcome(&m.outcome),
                        "line": m.line,
                        "earlier_disagreeing": m.earlier,
                    })
                })
                .collect();
            json!({
                "file": r.file,
                "steps_verified": r.steps.0,
                "steps_total": r.steps.1,
                "first_failure": r.first_failure.as_ref().map(|f| json!({"line": f.line, "kind": f.kind, "message": f.diagnostic.message.to_string()})),
                "results_correct": right,
                "results_total": all,
                "results": results,
                "names_mapped": r.mapping.iter().map(|m| json!({"submission": m.from, "reference": m.to, "negated": m.negated})).collect::<Vec<_>>(),
                "names_unmatched": r.unmatched,
                "facts_not_credited": r.own.iter().map(own_fact).collect::<Vec<_>>(),
                "not_marked": r.unreadable,
            })
            .to_string()
                + "\n"
        })
        .collect()
}

/// The hint for a kind of first mistake, in plain words; `term` is the term the checker
/// points at, as written, when it points at one.
fn hint(kind: &str, term: Option<&str>) -> String {
    match (kind, term) {
        ("sign", Some(t)) => format!(
            "check the direction you took as positive for the term {}",
            code(t)
        ),
        ("sign", None) => {
            "the two sides differ in sign: check the direction you took as positive".into()
        }
        ("factor", _) => "compare the sizes of the two sides: a factor is off".into(),
        ("power", _) => "check the power of each quantity in this step".into(),
        ("missing_term", _) => {
            "a term is missing on one side: compare the terms step by step".into()
        }
        ("extra_term", _) => "a term appears that should not be there".into(),
        ("missing_fact", _) => {
            "this step needs a fact (an equation of motion, a constraint) you have not written"
                .into()
        }
        ("undeclared", _) => "a name is used before it is declared (a typo?)".into(),
        ("syntax", _) => "rigor could not read this line".into(),
        ("import", _) => {
            "a submission may import only the course library its tutor allows".into()
        }
        ("units", _) => "the two sides are not in the same units".into(),
        ("false_fact", _) => {
            "this fact is false (or your facts contradict each other): anything would follow from it, so nothing that rests on it counts".into()
        }
        _ => "rigor could not decide this step".into(),
    }
}

/// Untrusted text as a Markdown code span (a fence longer than any run of backticks in it).
fn code(s: &str) -> String {
    let s = clean(s);
    let mut run = 0;
    let mut longest = 0;
    for c in s.chars() {
        run = if c == '`' { run + 1 } else { 0 };
        longest = longest.max(run);
    }
    let fence = "`".repeat(longest + 1);
    let pad = if s.starts_with('`') || s.ends_with('`') {
        " "
    } else {
        ""
    };
    format!("{fence}{pad}{s}{pad}{fence}")
}

/// A message for Markdown: its `…` spans as code, the rest escaped.
fn inline(msg: &str) -> String {
    let parts: Vec<&str> = msg.split('`').collect();
    if parts.len() % 2 == 0 {
        // An odd number of backticks: no spans to trust.
        return crate::render::text::markdown_text(&clean(msg));
    }
    parts
        .iter()
        .enumerate()
        .map(|(k, p)| {
            if k % 2 == 1 {
                code(p)
            } else {
                crate::render::text::markdown_text(&clean(p))
            }
        })
        .collect()
}

/// Text for a fenced block: control characters out (line breaks kept), and no line that
/// could close the fence.
fn fenced(s: &str) -> String {
    s.chars()
        .map(|c| if c.is_control() && c != '\n' { '?' } else { c })
        .collect::<String>()
        .replace("```", "'''")
}

/// The term a sign mistake is about, as the checker names it under the spot (the first
/// `…` of its label; for display only: the kind was decided from [`Mistake`]).
fn pointed_term(r: &Row) -> Option<String> {
    let f = r.first_failure.as_ref()?;
    if f.diagnostic.mistake != Some(Mistake::Sign) {
        return None;
    }
    let (_, label) = f.diagnostic.primary.as_ref()?;
    let mut parts = label.split('`').skip(1);
    let term = parts.next()?;
    parts.next().map(|_| term.to_string())
}

/// The steps of a submission, one line each.
fn steps(r: &Row) -> String {
    let mut out = String::new();
    if let Some(rep) = &r.report {
        let idx = crate::diag::LineIndex::new(&rep.source);
        for l in rep.claims.iter().flat_map(|c| &c.links) {
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
    if out.is_empty() {
        out.push_str("- none that could be checked\n");
    }
    out
}

/// The first mistake as `check` shows it: the message, the student's line with the spot
/// marked, both sides, the counterexample, the factor, did-you-mean; then a hint.
fn first_mistake(r: &Row) -> String {
    let (Some(f), Some(rep)) = (&r.first_failure, &r.report) else {
        return String::new();
    };
    let d = crate::render::human::as_shown(&f.diagnostic, rep);
    let shown = crate::diag::render(&d, &clean(&r.file), &rep.source);
    format!(
        "\n## First mistake\n\nLine {}: {}.\n\n```text\n{}```\n\nHint: {}.\n",
        f.line,
        inline(&f.diagnostic.message),
        fenced(&shown),
        hint(f.kind, pointed_term(r).as_deref())
    )
}

/// The feedback file for one submission (Markdown). The submission's working is typeset
/// by the renderer of worked solutions ([`crate::render::markdown::section`]), each step
/// that does not follow marked where it stands; the reference's worked solution is shown
/// only with `reveal`.
pub fn feedback(r: &Row, reveal: Option<&FileReport>) -> String {
    let mut out = format!(
        "# Feedback: {}\n\n",
        crate::render::text::markdown_text(&clean(&r.file))
    );
    if let Some(why) = &r.unreadable {
        out.push_str(&format!(
            "Your file could not be marked: {}\n",
            crate::render::text::markdown_text(&clean(why))
        ));
        return out;
    }
    out.push_str(&format!(
        "{} of {} steps verified.\n\n## Steps\n\n{}",
        r.steps.0,
        r.steps.1,
        steps(r)
    ));
    out.push_str(&first_mistake(r));
    if !r.own.is_empty() {
        out.push_str("\n## Your facts\n\n");
        for f in &r.own {
            out.push_str(&format!("- {}\n", inline(&own_fact(f))));
        }
    }
    out.push_str("\n## Results\n\n");
    if !r.mapping.is_empty() {
        out.push_str(&format!(
            "Your names were matched to the reference's by the role they play in your equations: {}.\n\n",
            crate::render::text::markdown_text(&clean(&mapped(r)))
        ));
    }
    if !r.unmatched.is_empty() {
        out.push_str(&format!(
            "No fact of the problem matches these names of yours to its quantities: {}.\n\n",
            r.unmatched
                .iter()
                .map(|n| code(n))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    for m in &r.results {
        let said = match &m.outcome {
            Outcome::Right => "right".to_string(),
            Outcome::Wrong => "not what it should be".to_string(),
            Outcome::Missing => "not found in your work".to_string(),
            Outcome::Undecided(w) => format!("could not be compared: {}", inline(w)),
            Outcome::NotCredited(w) => format!("not credited: {}", inline(&why(w))),
        };
        let at = m.line.map_or(String::new(), |l| format!(" (line {l})"));
        out.push_str(&format!("- {}{at}: {said}\n", code(&m.expected.lhs)));
        if let Some(e) = earlier(m) {
            out.push_str(&format!("  ({e})\n"));
        }
    }
    if let Some(rep) = &r.report {
        out.push_str("\n## Your working\n\n");
        out.push_str(&crate::render::markdown::section(rep));
    }
    if let Some(reference) = reveal {
        out.push_str("\n## Reference\n\n");
        out.push_str(&crate::render::markdown::section(reference));
    }
    out
}
