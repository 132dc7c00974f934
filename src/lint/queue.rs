//! [`lint_all`]: several documents read and their scopes checked from one queue on every
//! core ([`crate::files::staged`]): a worker reads the next document (the longest first)
//! while any is left, then checks the ready scope with the most chains; so no core waits
//! for the others to finish reading, and a long section starts early rather than last.
//! A document's cache of reports is emptied by the worker that checks its last scope.

use super::cache::Checked;
use super::{pieces, reader, ChainReport, DocKind, LintReport, Scope, Verdict};
use crate::check::Options;
use crate::diag::LineIndex;

/// A document to lint: its name, its text and how it is written.
pub struct Document {
    /// The name reports give it (its path).
    pub name: String,
    /// Its text.
    pub text: String,
    /// Markdown or LaTeX.
    pub kind: DocKind,
}

/// A document read into scopes, before they are checked.
struct Read {
    /// The report so far (the chains the reader settled on its own).
    report: LintReport,
    scopes: Vec<Scope>,
    cleaned: String,
    cache: Checked,
}

/// Checks the chains of each document as [`lint`](super::lint) does, the reports in the
/// order given. Scopes share nothing but their document's reports of identical
/// derivations.
pub fn lint_all(docs: &[Document], opts: &Options) -> Vec<LintReport> {
    let done = crate::files::staged(
        docs,
        |d| d.text.len(),
        |d| {
            let r = read_one(d, opts);
            let chains = r.scopes.iter().map(|s| s.items.len()).collect();
            (r, chains)
        },
        |r, k| close(r, k, opts),
        |r| r.cache.clear(),
    );
    done.into_iter()
        .zip(docs)
        .map(|(r, doc)| match r {
            Some((r, outs)) => {
                let mut report = r.report;
                // Each document's scopes in their order, as one document alone is reported.
                report.chains.extend(outs.into_iter().flatten());
                report.chains.sort_by_key(|c| c.span.start);
                report
            }
            None => LintReport {
                path: doc.name.clone(),
                source: doc.text.clone(),
                chains: Vec::new(),
            },
        })
        .collect()
}

/// A document read into its scopes (the chains the reader settles on its own reported).
fn read_one(d: &Document, opts: &Options) -> Read {
    let mut report = LintReport {
        path: d.name.clone(),
        source: d.text.clone(),
        chains: Vec::new(),
    };
    let cache = Checked::default();
    let mut reader = reader::Reader::new(&d.text, opts, &cache);
    for piece in pieces(&d.text, d.kind) {
        reader.piece(piece, &mut report.chains);
    }
    let (scopes, cleaned) = reader.finish();
    Read {
        report,
        scopes,
        cleaned,
        cache,
    }
}

/// The chains of scope `k` of a read document.
fn close(r: &Read, k: usize, opts: &Options) -> Vec<ChainReport> {
    let Some(scope) = r.scopes.get(k) else {
        return Vec::new();
    };
    let lines = LineIndex::new(&r.cleaned);
    let mut out = Vec::new();
    scope.close((&r.report.path, &lines), (opts, &r.cache), &mut out);
    // A condition or value stated in a sentence (`$\mu = 0$`) is not a chain.
    out.retain(|c| !(c.verdict == Verdict::NeedsContext && scope.quiet.contains(&c.span.start)));
    out
}
