//! What one run of `rigor lint` has checked and read: the reports of the derivations
//! made from the document's scopes, by their text, and whether each generated
//! statement reads. A check that stops at a quantity the facts determine is kept apart
//! from a whole check.

use super::Options;
use crate::check::{check_source, FileReport, MemoryResolver};
use crate::syntax::ParseOptions;
use foldhash::HashMap;
use std::sync::{Arc, Mutex};

/// The reports of the derivations checked so far in one run, by their text, and
/// whether each statement generated so far reads. Notes repeat themselves (the same
/// worked example under several headings, boilerplate relations): a derivation
/// identical to one already checked, with the same options, has the same report, so it
/// is checked once (and a statement read once). The cache lives for one call of
/// [`lint`](super::lint).
#[derive(Default)]
pub(crate) struct Checked {
    reports: Mutex<Reports>,
    parsed: Mutex<HashMap<String, bool>>,
}

/// Reports by the name they were checked under, whether the check stopped at a
/// determined quantity and whether it gave verdicts only, then by the derivation's text.
type Reports = HashMap<(String, bool, bool), HashMap<String, Arc<FileReport>>>;

impl Checked {
    /// The report of `deriv` checked as `name`, checked now unless it was before.
    pub(crate) fn report(&self, name: &str, deriv: &str, opts: &Options) -> Arc<FileReport> {
        let key = (
            name.to_string(),
            opts.stop_at_determined_given,
            opts.verdicts_only,
        );
        let known = lock(&self.reports)
            .get(&key)
            .and_then(|m| m.get(deriv))
            .cloned();
        if let Some(r) = known {
            return r;
        }
        let r = Arc::new(check_source(name, deriv, opts, &MemoryResolver::new()));
        let mut reports = lock(&self.reports);
        if key.1 && !r.names_determined_given() {
            // It did not stop: it is the whole check.
            reports
                .entry((name.to_string(), false, key.2))
                .or_default()
                .insert(deriv.to_string(), r.clone());
        }
        reports
            .entry(key)
            .or_default()
            .insert(deriv.to_string(), r.clone());
        r
    }

    /// Forgets everything (once the document's last scope is checked: the memory is
    /// given back by the thread that checked it, not all at the end by one thread).
    pub(crate) fn clear(&self) {
        let reports = std::mem::take(&mut *lock(&self.reports));
        let parsed = std::mem::take(&mut *lock(&self.parsed));
        drop((reports, parsed));
    }

    /// Whether a generated statement reads on its own (one bad statement must not stop
    /// the rest of the document from being checked).
    pub(crate) fn parses(&self, stmt: &str) -> bool {
        let known = lock(&self.parsed).get(stmt).copied();
        if let Some(ok) = known {
            return ok;
        }
        let ok = crate::syntax::parse_file(stmt, &ParseOptions::default()).is_ok();
        lock(&self.parsed).insert(stmt.to_string(), ok);
        ok
    }
}

fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}
