//! `rigor mark`: a class's submissions against a reference derivation. Each submission is
//! checked as `check` does; its first failing step is classified in a small vocabulary;
//! the reference's results are found in it (by label, else by the quantity on the left)
//! and compared exactly under the reference's declarations, through the one checker
//! entry.

use crate::check::{check_source, FileReport, Options, Resolver, Status};
use crate::diag::{line_col, Diagnostic};
use crate::syntax::ast::{Chain, Item, StmtKind};

/// The kinds of first mistake (README, "rigor mark").
pub const KINDS: [&str; 10] = [
    "sign",
    "factor",
    "power",
    "missing_term",
    "extra_term",
    "missing_fact",
    "undeclared",
    "syntax",
    "units",
    "undecided",
];

/// A result of the reference: its label and the quantity on its left, as written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Expected {
    /// The claim's label.
    pub label: String,
    /// The first expression of the claim, as written (`x''`).
    pub lhs: String,
}

/// What became of one expected result in a submission.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// The submission's result equals the reference's.
    Right,
    /// It differs.
    Wrong,
    /// The submission has no claim for it.
    Missing,
    /// rigor could not compare them; the text says why.
    Undecided(String),
}

/// One submission, marked.
#[derive(Clone, Debug)]
pub struct Row {
    /// The submission's name.
    pub file: String,
    /// Links verified and in all.
    pub steps: (usize, usize),
    /// The first failing step: line, kind, message.
    pub first_failure: Option<(usize, &'static str, String)>,
    /// Each expected result and its outcome.
    pub results: Vec<(Expected, Outcome)>,
    /// Why the submission could not be marked at all, if it could not.
    pub unreadable: Option<String>,
    /// The submission's check report (for feedback).
    pub report: Option<FileReport>,
}

impl Row {
    /// Results right and expected.
    pub fn results_score(&self) -> (usize, usize) {
        let right = self
            .results
            .iter()
            .filter(|r| r.1 == Outcome::Right)
            .count();
        (right, self.results.len())
    }
}

/// The chain of the claim labelled `label` in a checked file.
fn claim_chain<'r>(r: &'r FileReport, label: &str) -> Option<&'r Chain> {
    r.ast.as_ref()?.items.iter().find_map(|i| match i {
        Item::Stmt(s) => match &s.kind {
            StmtKind::Claim {
                label: Some(l),
                chain,
                ..
            } if l.name == label => Some(chain),
            _ => None,
        },
        _ => None,
    })
}

fn text(r: &FileReport, s: crate::syntax::ast::Span) -> String {
    r.source
        .get(s.start..s.end)
        .unwrap_or("")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

/// The reference's results: those `result` names, else every labelled claim.
pub fn expected(reference: &FileReport) -> Vec<Expected> {
    let Some(ast) = &reference.ast else {
        return Vec::new();
    };
    let mut named: Vec<String> = Vec::new();
    let mut labelled: Vec<String> = Vec::new();
    for item in &ast.items {
        if let Item::Stmt(s) = item {
            match &s.kind {
                StmtKind::Result { labels } => named.extend(labels.iter().map(|l| l.name.clone())),
                StmtKind::Claim { label: Some(l), .. } => labelled.push(l.name.clone()),
                _ => {}
            }
        }
    }
    let labels = if named.is_empty() { labelled } else { named };
    labels
        .into_iter()
        .filter_map(|label| {
            let chain = claim_chain(reference, &label)?;
            Some(Expected {
                lhs: text(reference, chain.first.span),
                label,
            })
        })
        .collect()
}

/// The kind of a failing step's diagnosis.
pub fn kind(d: &Diagnostic) -> &'static str {
    let m = format!(
        "{} {}",
        d.message,
        d.primary.as_ref().map_or("", |p| p.1.as_str())
    );
    match d.code {
        "E0001" | "E0002" => return "syntax",
        "E0201" => return "undeclared",
        "E0401" | "E0402" | "E0403" => return "units",
        _ => {}
    }
    if m.contains("wrong sign") || m.contains("opposite signs") {
        "sign"
    } else if m.contains("power") {
        "power"
    } else if m.contains("× what it should be")
        || m.contains("constant factor")
        || m.contains("extra factor")
    {
        "factor"
    } else if m.contains("nothing in scope determines") || m.contains("fact may be missing") {
        "missing_fact"
    } else if m.contains("extra term") || m.contains("should not be there") {
        "extra_term"
    } else if m.contains("missing") || m.contains("differ by") {
        "missing_term"
    } else {
        "undecided"
    }
}

/// The row of a submission that could not be read: every result missing.
pub fn unreadable(name: &str, why: String, expected: &[Expected]) -> Row {
    Row {
        file: name.to_string(),
        steps: (0, 0),
        first_failure: None,
        results: expected
            .iter()
            .map(|e| (e.clone(), Outcome::Missing))
            .collect(),
        unreadable: Some(why),
        report: None,
    }
}

/// Marks one submission (`name`, `text`) against the checked reference.
pub fn mark(
    reference: &FileReport,
    expected: &[Expected],
    (name, text_of): (&str, &str),
    opts: &Options,
    resolvers: (&dyn Resolver, &dyn Resolver),
) -> Row {
    let sub = check_source(name, text_of, opts, resolvers.1);
    let links: Vec<(&crate::check::LinkReport, usize)> = sub
        .claims
        .iter()
        .flat_map(|c| c.links.iter().map(move |l| (l, c.line)))
        .collect();
    let verified = links.iter().filter(|(l, _)| l.status.is_verified()).count();
    let first_failure = first_failure(&sub);
    let results = expected
        .iter()
        .map(|e| (e.clone(), compare(reference, e, &sub, opts, resolvers.0)))
        .collect();
    Row {
        file: name.to_string(),
        steps: (verified, links.len()),
        first_failure,
        results,
        unreadable: None,
        report: Some(sub),
    }
}

/// The first failing step (or input error): its line, kind and message.
fn first_failure(sub: &FileReport) -> Option<(usize, &'static str, String)> {
    let d = sub
        .diagnostics
        .iter()
        .filter(|d| d.severity == crate::diag::Severity::Error)
        .min_by_key(|d| d.primary.as_ref().map_or(0, |p| p.0.start))?;
    let line = d
        .primary
        .as_ref()
        .map_or(0, |p| line_col(&sub.source, p.0.start).0);
    Some((line, kind(d), d.message.clone()))
}

/// One expected result in the submission, compared under the reference's declarations:
/// the submission's `lhs = last expression` checked as a claim at the end of the
/// reference.
fn compare(
    reference: &FileReport,
    e: &Expected,
    sub: &FileReport,
    opts: &Options,
    resolver: &dyn Resolver,
) -> Outcome {
    let chain = claim_chain(sub, &e.label).or_else(|| {
        let ast = sub.ast.as_ref()?;
        ast.items.iter().find_map(|i| match i {
            Item::Stmt(s) => match &s.kind {
                StmtKind::Claim { chain, .. } if text(sub, chain.first.span) == e.lhs => {
                    Some(chain)
                }
                _ => None,
            },
            _ => None,
        })
    });
    let Some(chain) = chain else {
        return Outcome::Missing;
    };
    let last = chain.links.last().map_or(chain.first.span, |l| l.rhs.span);
    let claim = format!(
        "{}\nclaim [rigor_mark_result] {} = {}\n",
        reference.source,
        text(sub, chain.first.span),
        text(sub, last)
    );
    let r = check_source(&reference.path, &claim, opts, resolver);
    let Some(c) = r
        .claims
        .iter()
        .find(|c| c.label.as_deref() == Some("rigor_mark_result"))
    else {
        return Outcome::Undecided("the result could not be read in the reference's terms".into());
    };
    match c.links.first().map(|l| &l.status) {
        Some(Status::Verified { .. }) => Outcome::Right,
        Some(Status::Failed) => {
            let refuted = r.diagnostics.iter().any(|d| {
                d.primary
                    .as_ref()
                    .is_some_and(|p| p.0.start >= reference.source.len())
                    && d.code == "E0301"
            });
            if refuted {
                Outcome::Wrong
            } else {
                Outcome::Undecided("rigor could not decide it".into())
            }
        }
        _ => {
            let why = r
                .diagnostics
                .iter()
                .filter(|d| {
                    d.primary
                        .as_ref()
                        .is_some_and(|p| p.0.start >= reference.source.len())
                })
                .map(|d| d.message.clone())
                .next()
                .unwrap_or_else(|| "it uses names the reference does not declare".into());
            Outcome::Undecided(why)
        }
    }
}
