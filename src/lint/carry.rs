//! Results that outlive their section. A relation whose left side is a lone symbol
//! (`I_G = \frac{m L^2}{12}`, or the prose's `v_G = \omega R`) states what the symbol
//! stands for; later sections may use the symbol without stating it again (`I_O = I_G + m (L/2)^2 = \frac{m L^2}{3}`
//! under the next heading), so the definition is in scope there — unless that section
//! states the symbol again, or one of the symbols the definition is written in (the
//! letter reused). A chain verified with it says so: `using I_G = … from line 8`.

use super::{
    declare, first_link_names, flat, free, write_statement, Build, ChainReport, Item, Scope,
    Verdict,
};
use crate::syntax::ast::{Chain, ExprKind, RelOp};
use foldhash::{HashSet, HashSetExt};

/// The symbol a chain's first link states, when its left side is a lone symbol (not a
/// derivative) and the link is `=`.
fn stated_symbol(c: &Chain) -> Option<&str> {
    match (&c.first.kind, c.links.first()) {
        (ExprKind::Sym(n), Some(l)) if l.op == RelOp::Eq && !n.ends_with('\'') => Some(n),
        _ => None,
    }
}

/// Adds to `carried` the results `scope` leaves to the sections after it: each chain
/// whose left side is a lone symbol its first link's right side does not use, as a
/// chain of that link. A later section's relation for the same symbol replaces an
/// earlier section's.
pub(super) fn left_by(scope: &Scope, carried: &mut Vec<Chain>) {
    // Within a section, the first relation for a symbol is what it stands for (`I_G =
    // \frac12 m R^2`, then `I_G = m k^2` defines `k`).
    let mut stated = HashSet::new();
    for item in &scope.items {
        let Item::Chain(c) = item else {
            continue;
        };
        let (Some(n), Some(l)) = (stated_symbol(c), c.links.first()) else {
            continue;
        };
        let mut rhs = Vec::new();
        free(&l.rhs, &mut Vec::new(), &mut rhs);
        if rhs.iter().any(|r| r.trim_end_matches('\'') == n) || !stated.insert(n.to_string()) {
            continue;
        }
        carried.retain(|d| stated_symbol(d) != Some(n));
        carried.push(Chain {
            first: c.first.clone(),
            links: vec![l.clone()],
        });
    }
}

/// Writes into the derivation, as `let`s, the definitions of earlier sections the scope
/// uses and does not state again.
pub(super) fn place_carried(scope: &Scope, doc: &str, b: &mut Build<'_>) {
    if scope.carried.is_empty() {
        return;
    }
    let mut restated = HashSet::new();
    let mut mentioned = Vec::new();
    for item in &scope.items {
        // A symbol the section declares in a comment is that section's own.
        if let Item::Directive(_, names) = item {
            restated.extend(names.iter().cloned());
        }
        if let Item::Chain(c) | Item::Imposed(c) = item {
            restated.extend(stated_symbol(c).map(String::from));
            for e in c.exprs() {
                free(e, &mut Vec::new(), &mut mentioned);
            }
        }
    }
    let mentioned: HashSet<&str> = mentioned.iter().map(|n| n.trim_end_matches('\'')).collect();
    for c in &scope.carried {
        let (Some(n), Some(link)) = (stated_symbol(c), c.links.first()) else {
            continue;
        };
        let names: Vec<String> = first_link_names(c).into_iter().filter(|x| x != n).collect();
        let reused = names
            .iter()
            .any(|x| restated.contains(x.trim_end_matches('\'')));
        if reused
            || restated.contains(n)
            || !mentioned.contains(n)
            || b.declared.contains(n)
            || b.time.contains(n)
        {
            continue;
        }
        // The symbols it is written in are the scope's from here on, as if a chain had
        // used them (a step that brings in `m` and `L` with `I_O` brings in nothing new).
        b.seen
            .extend(names.iter().map(|x| x.trim_end_matches('\'').to_string()));
        declare(
            names,
            None,
            &mut b.deriv,
            &mut b.declared,
            (b.time, b.solve),
        );
        let pieces = [c.first.span, link.span];
        if write_statement("let", &pieces, (doc, b.cache), &mut b.deriv).is_some() {
            b.declared.insert(n.to_string());
            b.known.insert(n.to_string());
            let text = flat(doc, c.first.span.to(link.span));
            b.carried
                .push((n.to_string(), text.trim().to_string(), c.first.span.start));
        }
    }
}

/// The verdicts of a section's chains: each as checked without the results of earlier
/// sections (`base`), unless it was not verified and is verified with them (`with`), or
/// needed context and fails with them.
pub(super) fn settle(base: Vec<ChainReport>, with: &[ChainReport], out: &mut Vec<ChainReport>) {
    for r in base {
        let open = matches!(r.verdict, Verdict::NeedsContext | Verdict::Failed);
        let settled = with.iter().find(|w| {
            open && w.span == r.span
                && (w.verdict == Verdict::Verified
                    || (w.verdict == Verdict::Failed && r.verdict == Verdict::NeedsContext))
        });
        out.push(settled.cloned().unwrap_or(r));
    }
}
