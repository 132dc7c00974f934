//! Definitions that outlive their section. A chain whose left side is a lone symbol
//! new to its section (`I_G = \frac{m L^2}{12}`) defines it; later sections may use
//! the symbol without stating it again (`I_O = I_G + m (L/2)^2 = \frac{m L^2}{3}`
//! under the next heading), so the definition is in scope there — unless that section
//! states the symbol again, or one of the symbols the definition is written in (the
//! letter reused). A chain verified with it says so: `using I_G = … from line 8`.

use super::{declare, first_link_names, flat, free, write_statement, Build, Item, Scope};
use crate::syntax::ast::{Chain, ExprKind, RelOp};
use std::collections::HashSet;

/// The symbol a chain's first link states, when its left side is a lone symbol (not a
/// derivative) and the link is `=`.
fn stated_symbol(c: &Chain) -> Option<&str> {
    match (&c.first.kind, c.links.first()) {
        (ExprKind::Sym(n), Some(l)) if l.op == RelOp::Eq && !n.ends_with('\'') => Some(n),
        _ => None,
    }
}

/// Adds to `carried` the definitions `scope` leaves to the sections after it: each
/// chain whose left side is a symbol nothing before it in the scope used, as a chain of
/// its first link. A later definition of the same symbol replaces an earlier one.
pub(super) fn left_by(scope: &Scope, carried: &mut Vec<Chain>) {
    let mut seen: HashSet<String> = scope.names.clone();
    for item in &scope.items {
        match item {
            Item::Directive(_, names) => seen.extend(names.iter().cloned()),
            Item::Chain(c) | Item::Imposed(c) => {
                let fresh = matches!(item, Item::Chain(_))
                    && stated_symbol(c).is_some_and(|n| !seen.contains(n));
                if let (true, Some(n), Some(l)) = (fresh, stated_symbol(c), c.links.first()) {
                    carried.retain(|d| stated_symbol(d) != Some(n));
                    carried.push(Chain {
                        first: c.first.clone(),
                        links: vec![l.clone()],
                    });
                }
                let mut names = Vec::new();
                for e in c.exprs() {
                    free(e, &mut Vec::new(), &mut names);
                }
                seen.extend(names.iter().map(|n| n.trim_end_matches('\'').to_string()));
            }
        }
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
        let names: Vec<String> = first_link_names(c)
            .into_iter()
            .filter(|x| x != n)
            .collect();
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
        declare(names, None, &mut b.deriv, &mut b.declared, (b.time, b.solve));
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
