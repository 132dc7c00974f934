//! Values the prose gives (`where $r = A$`, `for $h = 2$`): a section's inline
//! relations that give a lone symbol a value are not premises of its displays when they
//! come after them or give a number (a case the sentence sets), so a chain that needs
//! one is suggested the exact `rigor:` comment that gives it (`rigor: let r = A`) —
//! only after the scope, checked again with that comment, no longer needs context. A
//! `let` or `given` comment declares the symbols it uses that nothing declared, as
//! `small` does.

use super::{free, verdict, Build, ChainReport, Checked, Reason, Scope, Verdict};
use crate::check::Options;
use crate::syntax::{parse_expr, ParseOptions};
use foldhash::HashSet;

/// A `let` or `given` comment in rigor's own syntax, with the symbols it uses that
/// `names` does not hold declared first (`symbols A` before `let r = A`); `None` when
/// it needs nothing declared or is not such a comment.
pub(super) fn declaring(text: &str, names: &HashSet<String>) -> Option<String> {
    let (kw, rest) = text.split_once(' ')?;
    if kw != "let" && kw != "given" {
        return None;
    }
    let used = used_names(rest)?;
    let lhs = rest.trim().trim_start_matches("$$").split('=').next()?;
    let defined = (kw == "let").then(|| lhs.trim());
    let new: Vec<String> = used
        .into_iter()
        .filter(|n| !names.contains(n) && Some(n.as_str()) != defined && !n.ends_with('\''))
        .collect();
    (!new.is_empty()).then(|| format!("symbols {}\n{text}", new.join(" ")))
}

/// The names a relation in rigor's syntax or between `$$` uses, left side first.
fn used_names(relation: &str) -> Option<Vec<String>> {
    let latex = relation.trim().starts_with("$$");
    let relation = relation
        .trim()
        .trim_start_matches("$$")
        .trim_end_matches("$$");
    let (lhs, rhs) = relation.split_once('=')?;
    let mut used = Vec::new();
    for side in [lhs, rhs] {
        let e = if latex {
            crate::syntax::latex::parse_latex_expr(side.trim(), 0, &ParseOptions::default()).ok()?
        } else {
            parse_expr(side.trim(), &ParseOptions::default()).ok()?
        };
        free(&e, &mut Vec::new(), &mut used);
    }
    Some(used)
}

/// The needs-context reasons a value from the prose may settle.
fn settles(r: Option<Reason>) -> bool {
    matches!(
        r,
        Some(Reason::NewSymbol | Reason::Stated | Reason::Undetermined) | None
    )
}

/// For each chain of the scope that needs context and uses a symbol the section's prose
/// gives a value, the `rigor: let …` comment that makes it checkable, when checking the
/// scope again with it shows that it does.
pub(super) fn suggest(
    scope: &Scope,
    (b, sets): (&Build<'_>, super::Sets<'_>),
    (name, doc): (&str, &str),
    (opts, cache): (&Options, &Checked),
    out: &mut [ChainReport],
) {
    if scope.values.is_empty() {
        return;
    }
    // A chain's report, when a value may settle it.
    let unsettled = |r: &ChainReport, p: &super::Placed| {
        r.span.end == p.span.end
            && r.verdict == Verdict::NeedsContext
            && r.comment.is_none()
            && settles(r.reason)
    };
    // The chains a value may settle: only their claims are checked again.
    let open: HashSet<usize> = b
        .placed
        .iter()
        .filter(|p| out.iter().any(|r| unsettled(r, p)))
        .map(|p| p.span.start)
        .collect();
    if open.is_empty() {
        return;
    }
    for (i, p) in b.placed.iter().enumerate() {
        let Some(r) = out.iter_mut().find(|r| unsettled(r, p)) else {
            continue;
        };
        // Its own symbols, or those of the chains before it (`h` in `v = \sqrt{2 g h}`,
        // then `v^2 = 4 g`).
        let uses = |n: &str| {
            b.placed[..=i]
                .iter()
                .flat_map(|q| q.symbols.iter())
                .any(|s| s.trim_end_matches('\'') == n)
        };
        let candidates = scope
            .values
            .iter()
            .filter(|(n, _)| uses(n) && !scope.names.contains(n))
            .take(3);
        for (_, v) in candidates {
            let stmt = format!("let {v}");
            let text = declaring(&stmt, &scope.names).unwrap_or_else(|| stmt.clone());
            if !cache.parses(&text) {
                continue;
            }
            let extra = (text, used_names(v).unwrap_or_default());
            let again = scope.build_with(doc, sets, (cache, b.carry), (Some(&extra), Some(&open)));
            let Some(q) = again.placed.get(i) else {
                continue;
            };
            let checked = cache.report(name, &again.deriv, opts);
            if verdict(&checked, q).verdict != Verdict::NeedsContext {
                r.comment = Some(format!("rigor: {stmt}"));
                break;
            }
        }
    }
}
