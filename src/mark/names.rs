//! A submission's names against the reference's: the role mapping (each declared symbol
//! onto the reference's symbol in the same place of the matching fact, `s → x`, and with
//! its sign where the student drew a force the other way, `P → −F`), and a submission's
//! expressions rewritten in the reference's terms (names mapped, the submission's own
//! `let`s written out), printed in rigor's syntax for the one checker entry.

use crate::check::FileReport;
use crate::syntax::ast::{Expr, ExprKind, Item, StmtKind};
use crate::syntax::print;
use std::collections::HashMap;

/// One name of the submission matched by role onto the reference's.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Mapped {
    /// The submission's name (`P`).
    pub from: String,
    /// The reference's name (`F`).
    pub to: String,
    /// Whether it is the reference's quantity with the other sign (`P = −F`).
    pub negated: bool,
}

/// Symbols by first appearance, each with the derivative orders it is used with.
type Syms = Vec<(String, Vec<usize>)>;

/// Symbols of an expression in order of first appearance (primes dropped), each with
/// the derivative orders it is used with (`x''` and `x` → x, {0, 2}).
fn symbols_in_order(e: &Expr, out: &mut Syms) {
    match &e.kind {
        ExprKind::Sym(n) => {
            let base = n.trim_end_matches('\'').to_string();
            let order = n.len() - base.len();
            match out.iter_mut().find(|(b, _)| *b == base) {
                Some((_, orders)) if !orders.contains(&order) => {
                    orders.push(order);
                    orders.sort_unstable();
                }
                Some(_) => {}
                None => out.push((base, vec![order])),
            }
        }
        ExprKind::Neg(x) => symbols_in_order(x, out),
        ExprKind::Bin(_, a, b) => {
            symbols_in_order(a, out);
            symbols_in_order(b, out);
        }
        ExprKind::Call(_, args) => args.iter().for_each(|a| symbols_in_order(a, out)),
        ExprKind::Num(_) | ExprKind::Pi => {}
    }
}

/// The symbol names (primes dropped) an expression uses.
pub(crate) fn names_in(e: &Expr) -> Vec<String> {
    let mut syms = Vec::new();
    symbols_in_order(e, &mut syms);
    syms.into_iter().map(|s| s.0).collect()
}

/// The names a file declares (`symbols`, ranges, `time`, `unknowns`) and defines (`let`).
pub(crate) fn declared(r: &FileReport) -> Vec<String> {
    let mut out = Vec::new();
    for item in r.ast.iter().flat_map(|a| &a.items) {
        if let Item::Stmt(st) = item {
            match &st.kind {
                StmtKind::Symbols { names, .. }
                | StmtKind::Range { names, .. }
                | StmtKind::Time { names }
                | StmtKind::Unknowns { names } => {
                    out.extend(names.iter().map(|n| n.name.clone()));
                }
                StmtKind::Let { name, .. } => out.push(name.name.clone()),
                _ => {}
            }
        }
    }
    out
}

/// The givens and constraints of a file, in order: label and symbols by first appearance.
fn facts_of(r: &FileReport) -> Vec<(Option<String>, Syms)> {
    let mut out = Vec::new();
    for item in r.ast.iter().flat_map(|a| &a.items) {
        if let Item::Stmt(st) = item {
            if let StmtKind::Given { label, chain } | StmtKind::Constraint { label, chain } =
                &st.kind
            {
                let mut syms = Vec::new();
                for e in chain.exprs() {
                    symbols_in_order(e, &mut syms);
                }
                out.push((label.as_ref().map(|l| l.name.clone()), syms));
            }
        }
    }
    out
}

/// Whether two facts have the same shape: as many symbols, each used with the same
/// derivatives (`a` for `x''` is not `x`).
fn same_shape(a: &Syms, b: &Syms) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.1 == y.1)
}

/// Names of the submission matched by role onto the reference's, signs not yet known:
/// the symbol at the same position (order of first appearance) of the matching given or
/// constraint. Facts are paired by label, else each with the reference's fact of the
/// same shape that shares the most names in the same places (so the moment equation
/// may come first). Names may be exchanged (`s` for x and `x` for θ); each is mapped
/// at most once, and a name in its own place keeps it. These are candidates: marking
/// keeps only those its facts justify (`facts.rs`).
pub fn role_pairs(reference: &FileReport, sub: &FileReport) -> Vec<Mapped> {
    let (ref_names, sub_names) = (declared(reference), declared(sub));
    let (ref_facts, sub_facts) = (facts_of(reference), facts_of(sub));
    let mut used = vec![false; ref_facts.len()];
    let mut pairs: Vec<(&Syms, &Syms)> = Vec::new();
    let mut rest = Vec::new();
    for (l, syms) in &sub_facts {
        let by_label = ref_facts
            .iter()
            .position(|o| l.is_some() && &o.0 == l && same_shape(syms, &o.1));
        match by_label {
            Some(k) if !used[k] => {
                used[k] = true;
                pairs.push((syms, &ref_facts[k].1));
            }
            _ => rest.push(syms),
        }
    }
    for syms in rest {
        let score = |r: &Syms| syms.iter().zip(r).filter(|(a, b)| a.0 == b.0).count();
        let best = (0..ref_facts.len())
            .filter(|&k| !used[k] && same_shape(syms, &ref_facts[k].1))
            .max_by_key(|&k| (score(&ref_facts[k].1), std::cmp::Reverse(k)));
        if let Some(k) = best {
            used[k] = true;
            pairs.push((syms, &ref_facts[k].1));
        }
    }
    let mut fixed: Vec<(String, String)> = Vec::new();
    for (s_syms, r_syms) in pairs {
        for ((s, _), (r, _)) in s_syms.iter().zip(r_syms) {
            let candidate = sub_names.contains(s) && ref_names.contains(r);
            let fresh = !fixed.iter().any(|(a, b)| a == s || b == r);
            if candidate && fresh {
                fixed.push((s.clone(), r.clone()));
            }
        }
    }
    // A name in its own place needs no mapping; it only kept others off its place.
    fixed
        .into_iter()
        .filter(|(s, r)| s != r)
        .map(|(from, to)| Mapped {
            from,
            to,
            negated: false,
        })
        .collect()
}

/// How a submission's expressions read in the reference's terms.
pub(crate) struct Terms {
    map: Vec<Mapped>,
    /// The submission's `let`s, each already in the reference's terms.
    lets: HashMap<String, Expr>,
}

impl Terms {
    /// The submission's names under `map`, its `let`s written out.
    pub(crate) fn new(sub: &FileReport, map: &[Mapped]) -> Terms {
        let mut t = Terms {
            map: map.to_vec(),
            lets: HashMap::new(),
        };
        for item in sub.ast.iter().flat_map(|a| &a.items) {
            if let Item::Stmt(st) = item {
                if let StmtKind::Let { name, value } = &st.kind {
                    let v = t.expr(value);
                    t.lets.insert(name.name.clone(), v);
                }
            }
        }
        t
    }

    /// The mapping.
    pub(crate) fn map(&self) -> &[Mapped] {
        &self.map
    }

    /// `e` with names mapped and the submission's `let`s written out.
    pub(crate) fn expr(&self, e: &Expr) -> Expr {
        self.rewrite(e, true)
    }

    /// `e` with names mapped, `let`s kept: how the student names a quantity.
    pub(crate) fn named(&self, e: &Expr) -> Expr {
        self.rewrite(e, false)
    }

    fn rewrite(&self, e: &Expr, lets: bool) -> Expr {
        let kind = match &e.kind {
            ExprKind::Sym(n) => {
                let base = n.trim_end_matches('\'');
                let primes = &n[base.len()..];
                if lets && primes.is_empty() {
                    if let Some(v) = self.lets.get(base) {
                        return v.clone();
                    }
                }
                match self.map.iter().find(|m| m.from == base) {
                    Some(m) => {
                        let sym = Expr::new(ExprKind::Sym(format!("{}{primes}", m.to)), e.span);
                        if m.negated {
                            ExprKind::Neg(Box::new(sym))
                        } else {
                            return sym;
                        }
                    }
                    None => return e.clone(),
                }
            }
            ExprKind::Neg(x) => ExprKind::Neg(Box::new(self.rewrite(x, lets))),
            ExprKind::Bin(op, a, b) => ExprKind::Bin(
                *op,
                Box::new(self.rewrite(a, lets)),
                Box::new(self.rewrite(b, lets)),
            ),
            ExprKind::Call(f, args) => {
                ExprKind::Call(*f, args.iter().map(|a| self.rewrite(a, lets)).collect())
            }
            ExprKind::Num(_) | ExprKind::Pi => return e.clone(),
        };
        Expr::new(kind, e.span)
    }

    /// Whether `e`, with names mapped, is the reference's `quantity` (printed), and with
    /// which sign: `Some(false)` for `F`, `Some(true)` for `P` when `P → −F`.
    pub(crate) fn names_quantity(&self, e: &Expr, quantity: &str) -> Option<bool> {
        let n = self.named(e);
        if print::source(&n) == quantity {
            return Some(false);
        }
        match &n.kind {
            ExprKind::Neg(x) if print::source(x) == quantity => Some(true),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::{check_source, MemoryResolver, Options};

    fn report(text: &str) -> FileReport {
        check_source("f.deriv", text, &Options::default(), &MemoryResolver::new())
    }

    #[test]
    fn names_may_be_exchanged_and_carry_a_sign() {
        let r = report("time x theta\nunknowns F\nsymbols m R > 0\ngiven [a] F = m x''\nconstraint [b] x = R theta\n");
        let s = report(
            "time s x\nunknowns P\nsymbols m R > 0\ngiven [n] P = m s''\nconstraint [c] s = R x\n",
        );
        let pairs: Vec<(String, String)> = role_pairs(&r, &s)
            .into_iter()
            .map(|m| (m.from, m.to))
            .collect();
        let want = [("P", "F"), ("s", "x"), ("x", "theta")];
        assert_eq!(
            pairs,
            want.map(|(a, b)| (a.to_string(), b.to_string())).to_vec()
        );
        let map = [Mapped {
            from: "P".into(),
            to: "F".into(),
            negated: true,
        }];
        let t = Terms::new(&s, &map);
        let Some(crate::syntax::ast::Item::Stmt(st)) = s.ast.as_ref().map(|a| &a.items[3]) else {
            panic!("a statement");
        };
        let StmtKind::Given { chain, .. } = &st.kind else {
            panic!("a given");
        };
        assert_eq!(print::source(&t.expr(&chain.first)), "(-(F))");
        assert_eq!(t.names_quantity(&chain.first, "F"), Some(true));
    }
}
