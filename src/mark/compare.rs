//! The one batched check of a submission against the reference: its facts and its
//! results, written in the reference's terms, appended to the reference as unlabelled
//! claims (so one that fails does not mark the others "not checked"; one that holds adds
//! only a consequence of the reference) and checked through the one checker entry.

use super::Outcome;
use crate::check::{check_source, FileReport, Options, Resolver, Status};
use crate::diag::{Diagnostic, FailureKind};

/// Claims appended to the reference, each remembered by its line.
pub(crate) struct Batch {
    source: String,
    next_line: usize,
}

impl Batch {
    /// The reference's text, nothing appended yet.
    pub(crate) fn new(reference: &FileReport) -> Batch {
        let source = format!("{}\n", reference.source);
        Batch {
            next_line: source.lines().count() + 1,
            source,
        }
    }

    /// Appends `claim TEXT`; its line.
    pub(crate) fn claim(&mut self, text: &str) -> usize {
        // One line each: the text is printed by rigor, never a student's line breaks.
        let text = text.replace(['\n', '\r'], " ");
        self.source.push_str(&format!("claim {text}\n"));
        self.next_line += 1;
        self.next_line - 1
    }

    /// Checks the reference with the claims appended.
    pub(crate) fn run(self, path: &str, opts: &Options, resolver: &dyn Resolver) -> Checked {
        Checked(check_source(path, &self.source, opts, resolver))
    }
}

/// The reference, checked with the claims appended.
pub(crate) struct Checked(FileReport);

impl Checked {
    /// Whether the appended claim on `line` verified.
    pub(crate) fn verified(&self, line: usize) -> bool {
        self.0
            .claims
            .iter()
            .find(|c| c.line == line)
            .is_some_and(|c| !c.links.is_empty() && c.verified())
    }

    /// The outcome of the appended claim on `line`, compared with the reference.
    pub(crate) fn outcome(&self, line: usize) -> Outcome {
        let r = &self.0;
        let Some(c) = r.claims.iter().find(|c| c.line == line) else {
            return Outcome::Undecided(
                "the result could not be read in the reference's terms".into(),
            );
        };
        let inside = |d: &&Diagnostic| {
            d.primary
                .as_ref()
                .is_some_and(|p| p.0.start >= c.span.start && p.0.start <= c.span.end)
        };
        match c.links.first().map(|l| &l.status) {
            Some(Status::Verified { .. }) => Outcome::Right,
            // Shown false: wrong, whatever the diagnostic (a sign, a false inequality, a
            // division by zero, units), as `check` says it. Facts that contradict each
            // other show nothing.
            Some(Status::Failed)
                if !r
                    .diagnostics
                    .iter()
                    .filter(inside)
                    .any(|d| d.failure() == Some(FailureKind::FalseFacts)) =>
            {
                Outcome::Wrong
            }
            Some(Status::Failed) => Outcome::Undecided(
                "the reference's facts contradict each other where it is checked".into(),
            ),
            _ => Outcome::Undecided(
                r.diagnostics
                    .iter()
                    .filter(inside)
                    .map(|d| d.message.clone())
                    .next()
                    .unwrap_or_else(|| "it uses names the reference does not declare".into()),
            ),
        }
    }
}
