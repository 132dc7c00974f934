//! The browser playground's one call (`web/`): a request as JSON in, everything the page
//! shows as JSON out. It calls the one checker entry, [`check_source`], with the files
//! the page holds as a [`MemoryResolver`], and renders the report three ways: the
//! verdicts and diagnostics as [`super::json`] writes them, each diagnostic as the
//! terminal shows it, and the worked solution as blocks whose math is the LaTeX that
//! [`super::markdown`] writes.
//!
//! Everything in the answer is data: the page builds its elements from it with text
//! nodes, so nothing from a derivation becomes markup.

use super::solution::{build, rich, Block, Inline, Problem};
use crate::check::{check_source, FileReport, MemoryResolver, Options};
use crate::clock::Clock;
use serde_json::{json, Value};
use std::time::Duration;

/// The longest budget per claim a request may ask for.
const MAX_TIMEOUT_MS: u64 = 10_000;

/// Answers one request:
///
/// ```text
/// request:  {"name": "main.deriv", "source": "…", "files": {"rod.deriv": "…"},
///            "timeout_ms": 3000}
/// answer:   {"summary": "files: 1, claims: …", "ok": bool,
///            "report": <as `check --format json`>, "rendered": ["error[E0301]: …"],
///            "solution": {"title": [part…], "blocks": [block…]}}
///           or {"error": "…"} for a request that is not of that shape.
/// ```
///
/// `files` are what `use … from "…"` resolves against; `timeout_ms` (default 3000, at
/// most 10000) is the budget per claim on `clock` (none without a clock). A part is
/// `{"text"}`, `{"strong"}`, `{"code"}` or `{"math"}` (LaTeX); a block is a `heading`
/// (`level`, `parts`), `paragraph` (`parts`), `display` (`prefix`, `latex`), `claim`
/// (`latex`), `problems` (`items`: `kind`, `line`, `message`, `notes`) or `listing`
/// (`lines`).
pub fn respond(request: &str, clock: Option<Clock>) -> String {
    match answer(request, clock) {
        Ok(v) => v.to_string(),
        Err(e) => json!({ "error": e }).to_string(),
    }
}

fn answer(request: &str, clock: Option<Clock>) -> Result<Value, String> {
    let req: Value =
        serde_json::from_str(request).map_err(|e| format!("a request that is not JSON: {e}"))?;
    let text = |k: &str| req.get(k).and_then(Value::as_str);
    let name = text("name").unwrap_or("main.deriv");
    let source = text("source").ok_or("a request without \"source\"")?;
    let mut files = MemoryResolver::new();
    if let Some(map) = req.get("files").and_then(Value::as_object) {
        for (path, body) in map {
            if let Some(body) = body.as_str() {
                files.insert(path, body);
            }
        }
    }
    let timeout_ms = req
        .get("timeout_ms")
        .and_then(Value::as_u64)
        .unwrap_or(3000)
        .min(MAX_TIMEOUT_MS);
    let opts = Options {
        timeout: Duration::from_millis(timeout_ms),
        clock,
        ..Options::default()
    };
    let report = check_source(name, source, &opts, &files);
    Ok(page(&report))
}

/// Everything the page shows of one checked file.
pub fn page(report: &FileReport) -> Value {
    let idx = crate::diag::LineIndex::new(&report.source);
    let rendered: Vec<String> = report
        .diagnostics
        .iter()
        .map(|d| crate::diag::render_in(&super::human::as_shown(d, report), &report.path, &idx))
        .collect();
    let solution = build(report);
    json!({
        "summary": super::human::summary(std::slice::from_ref(report)).trim_end(),
        "ok": report.ok(),
        "report": super::json::report(report),
        "rendered": rendered,
        "solution": {
            "title": parts(&rich(&solution.title)),
            "blocks": solution.blocks.iter().map(block).collect::<Vec<_>>(),
        },
    })
}

fn parts(inlines: &[Inline]) -> Vec<Value> {
    inlines
        .iter()
        .map(|p| match p {
            Inline::Text(t) => json!({ "text": t }),
            Inline::Strong(t) => json!({ "strong": t }),
            Inline::Code(t) => json!({ "code": t }),
            Inline::Math(m) => json!({ "math": m }),
        })
        .collect()
}

fn block(b: &Block) -> Value {
    let latex = super::markdown::display_latex(b, true);
    match b {
        Block::Heading(level, t) => {
            json!({ "kind": "heading", "level": level, "parts": parts(&rich(t)) })
        }
        Block::Paragraph(ps) => json!({ "kind": "paragraph", "parts": parts(ps) }),
        Block::Display { prefix, .. } => {
            json!({ "kind": "display", "prefix": prefix, "latex": latex })
        }
        Block::Claim { .. } => json!({ "kind": "claim", "latex": latex }),
        Block::Problems(ps) => json!({
            "kind": "problems",
            "items": ps.iter().map(problem).collect::<Vec<_>>(),
        }),
        Block::Listing(lines) => json!({ "kind": "listing", "lines": lines }),
        Block::Working(work) => json!({
            "kind": "working",
            "items": work
                .iter()
                .map(|w| json!({ "parts": parts(&w.lead), "latex": super::markdown::work_latex(w) }))
                .collect::<Vec<_>>(),
        }),
    }
}

/// A problem as the worked solution sets it: its notes typeset by the same pieces as
/// the LaTeX and Markdown ([`super::solution::note_inlines`]), each a list of parts.
fn problem(p: &Problem) -> Value {
    let notes: Vec<Value> = p
        .notes
        .iter()
        .map(|n| Value::from(parts(&super::solution::note_inlines(n))))
        .collect();
    json!({ "kind": p.kind.words(), "line": p.line, "message": p.message, "notes": notes })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ask(req: Value) -> Value {
        serde_json::from_str(&respond(&req.to_string(), None)).expect("JSON")
    }

    #[test]
    fn a_request_is_checked_with_its_files_and_rendered_as_data() {
        let v = ask(json!({
            "name": "main.deriv",
            "source": "# End of a rod\nsymbols m L > 0\nunknowns I_O\nuse [IG] from \"rod.deriv\"\ngiven [PA] I_O = m L^2/12 + m (L/2)^2\nclaim [IO] I_O = m L^2/3 by [PA]\nclaim [bad] I_O = m L^2/4 by [PA]\n",
            "files": { "rod.deriv": "symbols m L > 0\nbody rod: dm = m/L dy, y from -L/2 to L/2\nclaim [IG] int(y^2, rod) = m L^2/12\n" },
        }));
        assert_eq!(
            v["summary"],
            "files: 1, claims: 2, links: 2, verified: 1, failed: 1, undecided: 0, errors: 0"
        );
        assert_eq!(v["ok"], false);
        let links: Vec<(u64, &str)> = v["report"]["claims"]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(|c| c["links"].as_array().unwrap())
            .map(|l| (l["line"].as_u64().unwrap(), l["status"].as_str().unwrap()))
            .collect();
        assert_eq!(links, [(6, "verified"), (7, "failed")]);
        let rendered = v["rendered"].as_array().unwrap();
        assert_eq!(rendered.len(), 1);
        let first = rendered[0].as_str().unwrap();
        assert!(first.starts_with("error[E0301]"), "{first}");
        assert!(first.contains("--> main.deriv:7:"), "{first}");
        // The worked solution: the title typeset as text, the failing claim flagged in
        // its LaTeX and its diagnosis as a problem block.
        assert_eq!(v["solution"]["title"], json!([{ "text": "End of a rod" }]));
        let blocks = v["solution"]["blocks"].as_array().unwrap();
        let claims: Vec<&str> = blocks
            .iter()
            .filter(|b| b["kind"] == "claim")
            .map(|b| b["latex"].as_str().unwrap())
            .collect();
        assert_eq!(claims.len(), 2, "{blocks:?}");
        assert!(claims[0].starts_with("\\begin{aligned}"), "{}", claims[0]);
        assert!(!claims[0].contains("not verified"), "{}", claims[0]);
        assert!(claims[1].contains("[does not hold]"), "{}", claims[1]);
        let problem = blocks.iter().find(|b| b["kind"] == "problems").unwrap();
        assert_eq!(problem["items"][0]["line"], 7);
    }

    #[test]
    fn a_bad_request_is_an_error_not_a_panic() {
        for bad in ["", "not json", "{}", "[1, 2]", "{\"source\": 3}"] {
            let v: Value = serde_json::from_str(&respond(bad, None)).expect("JSON");
            assert!(v["error"].is_string(), "{bad}: {v}");
        }
    }
}
