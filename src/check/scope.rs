//! Scope: which names are declared, which are bound, and suggestions for typos.

use crate::syntax::ast::{Expr, ExprKind, Func, Span};
use foldhash::{HashMap, HashSet};

/// What a declared name is.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Decl {
    /// A symbol from `symbols`.
    Symbol,
    /// A function of time from `time`.
    Time,
    /// The time variable `t`.
    TimeVar,
    /// An unknown from `unknowns`.
    Unknown,
    /// A `let` definition.
    Def,
    /// A body.
    Body,
}

/// The names declared so far in a file.
#[derive(Clone, Debug, Default)]
pub struct Scope {
    /// Name → what it is.
    pub names: HashMap<String, Decl>,
    /// Names declared in `unknowns` (some are also `symbols`).
    pub unknowns: HashSet<String>,
}

impl Scope {
    /// Whether `name` (possibly with primes) may be used in an expression.
    pub fn is_declared(&self, name: &str) -> bool {
        if self.names.contains_key(name) {
            return true;
        }
        let base = name.trim_end_matches('\'');
        base.len() < name.len() && self.names.get(base) == Some(&Decl::Time)
    }

    /// Whether a symbol is an unknown to eliminate (unknowns, time symbols and their derivatives).
    pub fn is_unknown(&self, name: &str) -> bool {
        if self.unknowns.contains(name) {
            return true;
        }
        // Derivatives of unknowns (from a differentiated constraint) are unknowns too.
        let base = name.trim_end_matches('\'');
        self.names.get(base) == Some(&Decl::Time) || self.unknowns.contains(base)
    }

    /// What to say under an undeclared name: a derivative of a constant (`theta''` with
    /// `symbols theta`), names glued together (`mg` for `m g`), a near miss, or how
    /// to declare it.
    pub fn undeclared_hint(&self, name: &str) -> String {
        let base = name.trim_end_matches('\'');
        if base.len() < name.len() {
            let what = match self.names.get(base) {
                Some(Decl::Symbol) => Some("`symbols`"),
                Some(Decl::Unknown) => Some("`unknowns`"),
                _ => None,
            };
            if let Some(what) = what {
                return format!(
                    "`{base}` is declared with {what}, so it has no time derivative: declare it with `time {base}`"
                );
            }
        }
        if let Some(parts) = self.split_glued(name) {
            return format!(
                "did you mean `{}`? (a product needs a space between its factors)",
                parts.join(" ")
            );
        }
        if base.len() < name.len() && !base.is_empty() && !self.names.contains_key(base) {
            return format!(
                "a derivative with respect to time: declare `{base}` with `time {base}`"
            );
        }
        match self.suggest(name) {
            Some(s) => format!("did you mean `{s}`?"),
            None => "declare it with `symbols`, `time` or `unknowns`".into(),
        }
    }

    /// `name` as two or more declared names written together (`mgd` → m, g, d), the
    /// fewest pieces first, each piece a symbol, time symbol (with primes), unknown or
    /// definition; `None` if there is no such reading.
    fn split_glued(&self, name: &str) -> Option<Vec<String>> {
        let n = name.len();
        if n > 64 {
            return None;
        }
        // best[i]: the fewest pieces that spell name[..i].
        let mut best: Vec<Option<Vec<String>>> = vec![None; n + 1];
        best[0] = Some(Vec::new());
        for i in 0..n {
            let Some(prefix) = best[i].clone() else {
                continue;
            };
            for (j, slot) in best.iter_mut().enumerate().skip(i + 1) {
                let Some(piece) = name.get(i..j) else {
                    continue;
                };
                let usable =
                    self.is_declared(piece) && !matches!(self.names.get(piece), Some(Decl::Body));
                if !usable || piece == name {
                    continue;
                }
                let mut cand = prefix.clone();
                cand.push(piece.to_string());
                if slot.as_ref().is_none_or(|b| cand.len() < b.len()) {
                    *slot = Some(cand);
                }
            }
        }
        best[n].take().filter(|p| p.len() >= 2)
    }

    /// The declared name closest to `name`, if reasonably close.
    pub fn suggest(&self, name: &str) -> Option<String> {
        let mut best: Option<(usize, String)> = None;
        for cand in self.names.keys() {
            let d = crate::diag::distance(&name.to_lowercase(), &cand.to_lowercase())
                + usize::from(name.to_lowercase() != cand.to_lowercase() || name != cand);
            let limit = 1 + name.len() / 3;
            if d <= limit + 1
                && best
                    .as_ref()
                    .is_none_or(|b| d < b.0 || d == b.0 && *cand < b.1)
            {
                best = Some((d, cand.clone()));
            }
        }
        best.map(|b| b.1)
    }
}

/// Every use of an undeclared name in `e`, with its span, honouring bound variables.
pub fn undeclared(
    e: &Expr,
    scope: &Scope,
    body_coords: &dyn Fn(&str) -> Option<Vec<String>>,
) -> Vec<(String, Span)> {
    let mut out = Vec::new();
    let mut bound = Vec::new();
    walk(e, scope, body_coords, &mut bound, &mut out);
    out
}

fn walk(
    e: &Expr,
    scope: &Scope,
    coords: &dyn Fn(&str) -> Option<Vec<String>>,
    bound: &mut Vec<String>,
    out: &mut Vec<(String, Span)>,
) {
    match &e.kind {
        ExprKind::Num(_) | ExprKind::Pi => {}
        ExprKind::Sym(n) => {
            if !bound.iter().any(|b| b == n) && !scope.is_declared(n) {
                out.push((n.clone(), e.span));
            }
        }
        ExprKind::Neg(a) => walk(a, scope, coords, bound, out),
        ExprKind::Bin(_, a, b) => {
            walk(a, scope, coords, bound, out);
            walk(b, scope, coords, bound, out);
        }
        ExprKind::Call(f, args) => {
            let var = args.get(1).and_then(|a| match &a.kind {
                ExprKind::Sym(n) => Some(n.clone()),
                _ => None,
            });
            match f {
                Func::Int | Func::Diff | Func::Eval | Func::Subs => {
                    // The integrand/body: with the variable (or the body's coordinates) bound.
                    let mut local: Vec<String> = Vec::new();
                    if let Some(v) = &var {
                        let is_body = *f == Func::Int && args.len() == 2;
                        match (is_body, coords(v)) {
                            (true, Some(cs)) => local.extend(cs),
                            (true, None) if v == "dm" => {
                                if let Some(cs) = coords("dm") {
                                    local.extend(cs)
                                }
                            }
                            _ => local.push(v.clone()),
                        }
                    }
                    let n = local.len();
                    bound.extend(local);
                    if let Some(a) = args.first() {
                        walk(a, scope, coords, bound, out);
                    }
                    bound.truncate(bound.len() - n);
                    // The variable itself is not a use; a non-symbol there is the lowerer's error.
                    for a in args.iter().skip(2) {
                        walk(a, scope, coords, bound, out);
                    }
                }
                _ => {
                    for a in args {
                        walk(a, scope, coords, bound, out);
                    }
                }
            }
        }
    }
}
