//! The guard: an independent evaluator of syntax trees, used as defence in depth. Before
//! a link is reported verified, both sides *as written* are evaluated at points that
//! satisfy the signs and the facts; a clear disagreement makes the link "undecided",
//! never verified and never failed. It shares nothing with the exact engine (`normal/`,
//! `lower.rs`, `calculus/`): its own derivatives, its own quadrature, `f64` balls.

mod ball;
mod deriv;
mod eval;

pub use ball::{Ball, Skip};

use crate::syntax::ast::{BodyDef, Expr};
use std::collections::{HashMap, HashSet};

/// What names mean, as written.
#[derive(Clone, Debug, Default)]
pub struct GuardEnv {
    /// `let` definitions as written (they may use earlier ones).
    pub defs: HashMap<String, Expr>,
    /// Bodies as declared.
    pub bodies: HashMap<String, BodyDef>,
    /// Base names of `time` symbols.
    pub time: HashSet<String>,
}

/// The value of `e` at `point` (symbol name → value; `x`, `x'`, `x''` are separate).
pub fn eval(e: &Expr, env: &GuardEnv, point: &HashMap<String, f64>) -> Result<Ball, Skip> {
    eval::Evaluator::new(env, point, 2_000_000).eval(e)
}

/// The values of two expressions at one point (definitions computed once for both).
pub fn eval_both(
    a: &Expr,
    b: &Expr,
    env: &GuardEnv,
    point: &HashMap<String, f64>,
) -> (Result<Ball, Skip>, Result<Ball, Skip>) {
    let mut ev = eval::Evaluator::new(env, point, 4_000_000);
    let x = ev.eval(a);
    let y = ev.eval(b);
    (x, y)
}

/// The symbols `e` needs a value for: free names, `let` names expanded, bound
/// variables and body coordinates excluded.
pub fn free_symbols(e: &Expr, env: &GuardEnv) -> HashSet<String> {
    let mut budget = 100_000;
    let expanded = deriv::expand(e, &env.defs, &mut Vec::new(), &mut budget);
    let mut out = HashSet::new();
    if let Some(x) = expanded {
        free(&x, env, &mut Vec::new(), &mut out);
    }
    out
}

fn free(e: &Expr, env: &GuardEnv, bound: &mut Vec<String>, out: &mut HashSet<String>) {
    use crate::syntax::ast::{ExprKind, Func};
    match &e.kind {
        ExprKind::Sym(n) if !bound.contains(n) => {
            out.insert(n.clone());
        }
        ExprKind::Sym(_) | ExprKind::Num(_) | ExprKind::Pi => {}
        ExprKind::Neg(a) => free(a, env, bound, out),
        ExprKind::Bin(_, a, b) => {
            free(a, env, bound, out);
            free(b, env, bound, out);
        }
        ExprKind::Call(f, args) => {
            let var = match (f, args.get(1).map(|a| &a.kind)) {
                (Func::Int | Func::Diff | Func::Subs | Func::Eval, Some(ExprKind::Sym(v))) => {
                    Some(v.clone())
                }
                _ => None,
            };
            let mut scoped: Vec<String> = var.iter().cloned().collect();
            if let (Func::Int, 2, Some(v)) = (f, args.len(), &var) {
                let name = if v == "dm" && env.bodies.len() == 1 {
                    env.bodies.keys().next().cloned().unwrap_or_default()
                } else {
                    v.clone()
                };
                if let Some(b) = env.bodies.get(&name) {
                    match b {
                        BodyDef::Concrete { ranges, .. } => {
                            scoped = ranges.iter().map(|r| r.var.name.clone()).collect();
                            for r in ranges {
                                free(&r.from, env, bound, out);
                                free(&r.to, env, bound, out);
                            }
                        }
                        BodyDef::Abstract { coords, .. } => {
                            scoped = coords.iter().map(|c| c.name.clone()).collect();
                        }
                    }
                }
            }
            for (i, a) in args.iter().enumerate() {
                if i == 1 && var.is_some() {
                    continue;
                }
                if i == 0 {
                    let n = scoped.len();
                    bound.extend(scoped.iter().cloned());
                    free(a, env, bound, out);
                    bound.truncate(bound.len() - n);
                } else {
                    free(a, env, bound, out);
                }
            }
            // A derivative is a function of its variable as meant outside: the free
            // symbol, or what a `let` name is defined as.
            if let (Func::Diff, Some(v)) = (f, &var) {
                if !bound.contains(v) {
                    match env.defs.get(v) {
                        Some(d) => out.extend(free_symbols(d, env)),
                        None => {
                            out.insert(v.clone());
                        }
                    }
                }
            }
            if *f == Func::Diff && var.as_deref() == Some("t") {
                // Derivatives over t bring in derivatives of the time symbols.
                let mut more = HashSet::new();
                for n in out.iter() {
                    if env.time.contains(n.trim_end_matches('\'')) {
                        for k in 1..=8 {
                            more.insert(format!("{n}{}", "'".repeat(k)));
                        }
                    }
                }
                out.extend(more);
            }
        }
    }
}

#[cfg(test)]
mod tests;
