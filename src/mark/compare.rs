//! The one batched check of a submission against the reference: its facts and its
//! results, written in the reference's terms, appended to the reference as unlabelled
//! claims, each with `by` (so each uses only the facts it names, one that fails does
//! not mark the others "not checked", and one that holds changes nothing for the
//! others), and checked through the one checker entry. A class shares a [`Memo`]: a
//! comparison already settled for a classmate (most copy the problem's givens) is not
//! checked again, and a submission with nothing new is not checked against the
//! reference at all.

use super::Outcome;
use crate::check::{check_source, FileReport, Options, Resolver, Status};
use crate::diag::{Diagnostic, FailureKind};
use std::collections::HashMap;
use std::sync::Mutex;

/// Comparisons settled for a class: the appended claim's text and whether it holds in
/// the reference (only verified or refuted claims, whose outcome does not depend on the
/// batch or on the time left).
#[derive(Debug, Default)]
pub struct Memo {
    settled: Mutex<HashMap<String, Outcome>>,
}

impl Memo {
    fn get(&self, text: &str) -> Option<Outcome> {
        let m = self.settled.lock().unwrap_or_else(|e| e.into_inner());
        m.get(text).cloned()
    }

    fn put(&self, text: String, o: Outcome) {
        let mut m = self.settled.lock().unwrap_or_else(|e| e.into_inner());
        m.insert(text, o);
    }
}

/// A comparison: settled before, or appended on a line.
#[derive(Clone, Debug)]
pub(crate) enum Slot {
    Known(Outcome),
    Line(usize),
}

/// Claims appended to the reference, each remembered by its line.
pub(crate) struct Batch<'m> {
    source: String,
    next_line: usize,
    memo: &'m Memo,
    appended: HashMap<String, usize>,
}

impl<'m> Batch<'m> {
    /// The reference's text with `labels` inserted (at byte offsets: unlabelled facts
    /// named, so that a comparison can cite them), nothing appended yet.
    pub(crate) fn new(
        reference: &FileReport,
        labels: &[(usize, String)],
        memo: &'m Memo,
    ) -> Batch<'m> {
        let mut source = reference.source.clone();
        let mut at: Vec<&(usize, String)> = labels.iter().collect();
        at.sort_by_key(|l| std::cmp::Reverse(l.0));
        for (k, l) in at {
            if source.is_char_boundary(*k) {
                source.insert_str(*k, l);
            }
        }
        source.push('\n');
        Batch {
            next_line: source.lines().count() + 1,
            source,
            memo,
            appended: HashMap::new(),
        }
    }

    /// `claim TEXT`: settled before, appended before in this batch, or appended now.
    pub(crate) fn claim(&mut self, text: &str) -> Slot {
        // One line each: the text is printed by rigor, never a student's line breaks.
        let text = text.replace(['\n', '\r'], " ");
        if let Some(o) = self.memo.get(&text) {
            return Slot::Known(o);
        }
        if let Some(&l) = self.appended.get(&text) {
            return Slot::Line(l);
        }
        self.source.push_str(&format!("claim {text}\n"));
        let line = self.next_line;
        self.next_line += 1;
        self.appended.insert(text, line);
        Slot::Line(line)
    }

    /// Checks the reference with the claims appended (not at all when none was), and
    /// keeps what it settled.
    pub(crate) fn run(self, path: &str, opts: &Options, resolver: &dyn Resolver) -> Checked {
        if self.appended.is_empty() {
            return Checked(None);
        }
        let checked = Checked(Some(check_source(path, &self.source, opts, resolver)));
        for (text, line) in self.appended {
            let o = checked.outcome(&Slot::Line(line));
            if matches!(o, Outcome::Right | Outcome::Wrong) {
                self.memo.put(text, o);
            }
        }
        checked
    }
}

/// The reference, checked with the claims appended.
pub(crate) struct Checked(Option<FileReport>);

impl Checked {
    /// Whether the comparison verified.
    pub(crate) fn verified(&self, slot: &Slot) -> bool {
        self.outcome(slot) == Outcome::Right
    }

    /// The outcome of a comparison.
    pub(crate) fn outcome(&self, slot: &Slot) -> Outcome {
        let line = match slot {
            Slot::Known(o) => return o.clone(),
            Slot::Line(l) => *l,
        };
        let Some(r) = &self.0 else {
            return Outcome::Undecided("it was not compared".into());
        };
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
                    .map(|d| d.message.to_string())
                    .next()
                    .unwrap_or_else(|| "it uses names the reference does not declare".into()),
            ),
        }
    }
}
