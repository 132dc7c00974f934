//! Terminal output of `rigor check --format human`: rustc-style diagnostics, with
//! `--verbose` one line per verified link, and the one-line summary.

use crate::check::report::{FileReport, Status};

/// The diagnostics of one file, rendered by [`crate::diag::render`] in their order,
/// separated by blank lines. With `verbose`, each verified link also gets a line
/// `path:line:col: verified (identity)` (or `(from [Fx], [MG])`, `(signs)`,
/// `(approx)`), followed by `, assuming …` when it has side conditions; these lines
/// are merged into the diagnostics by source position.
pub fn report(r: &FileReport, verbose: bool) -> String {
    let mut verified: Vec<(usize, String)> = Vec::new();
    let idx = crate::diag::LineIndex::new(&r.source);
    if verbose {
        for link in r.claims.iter().flat_map(|c| &c.links) {
            if let Status::Verified {
                how,
                side_conditions,
            } = &link.status
            {
                let (line, col) = idx.line_col(link.span.start);
                let mut s = format!("{}:{line}:{col}: verified ({how})", r.path);
                if !side_conditions.is_empty() {
                    s.push_str(&format!(", assuming {}", side_conditions.join(", ")));
                }
                s.push('\n');
                verified.push((link.span.start, s));
            }
        }
        verified.sort_by_key(|(at, _)| *at);
    }
    let mut out = String::new();
    let mut pending = verified.into_iter().peekable();
    let mut previous_was_diagnostic = false;
    for d in &r.diagnostics {
        if let Some((at, _)) = &d.primary {
            while let Some((_, s)) = pending.next_if(|(v, _)| *v <= at.start) {
                out.push_str(&s);
                previous_was_diagnostic = false;
            }
        }
        if previous_was_diagnostic {
            out.push('\n');
        }
        out.push_str(&crate::diag::render_in(&as_shown(d, r), &r.path, &idx));
        previous_was_diagnostic = true;
    }
    for (_, s) in pending {
        out.push_str(&s);
    }
    out
}

/// A diagnostic of `r` as every view shows it: the sides in its notes with their square
/// roots as a person writes them (`sqrt(2 g h)`, see [`super::pieces::as_written`]).
pub(crate) fn as_shown(d: &crate::diag::Diagnostic, r: &FileReport) -> crate::diag::Diagnostic {
    let mut shown = d.clone();
    shown.notes = (d.notes.iter())
        .map(|n| n.map_values(|v| super::pieces::as_written(v, &r.env)))
        .collect();
    shown
}

/// One line `files: N, claims: C, links: L, verified: V, failed: F, undecided: U,
/// errors: E` (with a newline), and `, not checked: K` after it when K > 0.
///
/// - `files`: the reports given;
/// - `claims`: the claims (a chain `a = b = c` is one claim of 2 links);
/// - `links`: the links checked;
/// - `verified`, `failed`, `undecided`: links verified, shown false, and neither;
/// - `errors`: problems that are not a failed link: every error-severity diagnostic
///   whose primary span does not lie inside a claim with a failed or undecided link
///   (syntax errors, undeclared symbols, missing files, contradictory facts…), and
///   one for each file with `input_error` that has no such diagnostic;
/// - `not checked`: links that cite a step that did not hold (counted once there).
pub fn summary(reports: &[FileReport]) -> String {
    let sum = |f: fn(&FileReport) -> usize| -> usize { reports.iter().map(f).sum() };
    let claims = sum(|r| r.claims.len());
    let (links, verified) = (sum(FileReport::links), sum(FileReport::verified));
    let (failed, undecided) = (sum(FileReport::failed), sum(FileReport::undecided));
    let errors = sum(errors);
    let not_checked = sum(FileReport::not_checked);
    let tail = if not_checked > 0 {
        format!(", not checked: {not_checked}")
    } else {
        String::new()
    };
    format!(
        "files: {}, claims: {claims}, links: {links}, verified: {verified}, failed: {failed}, undecided: {undecided}, errors: {errors}{tail}\n",
        reports.len()
    )
}

/// The errors of one file, as defined in [`summary`].
pub(crate) fn errors(r: &FileReport) -> usize {
    let failing: Vec<_> = r
        .claims
        .iter()
        .filter(|c| {
            c.links
                .iter()
                .any(|l| matches!(l.status, Status::Failed | Status::Undecided))
        })
        .map(|c| c.span)
        .collect();
    let n = r
        .diagnostics
        .iter()
        .filter(|d| d.severity == crate::diag::Severity::Error)
        .filter(|d| match &d.primary {
            Some((s, _)) => !failing
                .iter()
                .any(|c| s.start >= c.start && s.start < c.end.max(c.start + 1)),
            None => true,
        })
        .count();
    if r.input_error && n == 0 {
        1
    } else {
        n
    }
}
