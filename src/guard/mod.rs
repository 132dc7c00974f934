//! The guard: an independent evaluator of syntax trees, used as defence in depth. Before
//! a link is reported verified, both sides *as written* are evaluated at points that
//! satisfy the signs and the facts; a clear disagreement makes the link "undecided",
//! never verified and never failed. It shares nothing with the exact engine (`normal/`,
//! `lower.rs`, `calculus/`): its own derivatives, its own quadrature, `f64` balls.

mod ball;
mod deriv;
mod eval;

pub use ball::{Ball, Skip};

use crate::syntax::ast::{BodyDef, Expr, SignDecl};
use foldhash::{HashMap, HashSet, HashSetExt};

/// What names mean, as written.
#[derive(Clone, Debug, Default)]
pub struct GuardEnv {
    /// `let` definitions as written (they may use earlier ones).
    pub defs: HashMap<String, Expr>,
    /// Bodies as declared.
    pub bodies: HashMap<String, BodyDef>,
    /// Base names of `time` symbols.
    pub time: HashSet<String>,
    /// What the declarations say of each symbol's value, as written, in order.
    pub domains: Vec<(String, Domain)>,
}

/// What a declaration says of a symbol's value, as written.
#[derive(Clone, Debug, PartialEq)]
pub enum Domain {
    /// `symbols m > 0` (and `>= 0`, `!= 0`, or no sign).
    Sign(SignDecl),
    /// `symbols lo < x < hi`, each bound excluded or not.
    Range {
        /// The lower bound, as written.
        lo: Expr,
        /// Whether it is excluded.
        lo_strict: bool,
        /// The upper bound, as written.
        hi: Expr,
        /// Whether it is excluded.
        hi_strict: bool,
    },
}

/// Whether `point` clearly satisfies every declaration of `env.domains` about the
/// symbols it gives values (a range's bounds evaluated as written at the point, with
/// their rounding counted against it); the error names the first declaration it does
/// not clearly satisfy. A counterexample is printed only when this holds.
pub fn respects(env: &GuardEnv, point: &HashMap<String, f64>) -> Result<(), String> {
    for (name, domain) in &env.domains {
        let Some(&v) = point.get(name) else {
            continue;
        };
        let x = Ball::rounded(v);
        let ok = match domain {
            Domain::Sign(SignDecl::Any) => true,
            Domain::Sign(SignDecl::Positive) => x.lo() > 0.0,
            Domain::Sign(SignDecl::Nonnegative) => x.lo() >= 0.0 || v == 0.0,
            Domain::Sign(SignDecl::Nonzero) => x.lo() > 0.0 || x.hi() < 0.0,
            Domain::Range {
                lo,
                lo_strict,
                hi,
                hi_strict,
            } => {
                let (Ok(l), Ok(h)) = (eval(lo, env, point), eval(hi, env, point)) else {
                    return Err(format!(
                        "the bounds of `{name}` could not be evaluated there"
                    ));
                };
                let above = if *lo_strict {
                    x.lo() > l.hi()
                } else {
                    x.lo() >= l.hi()
                };
                let below = if *hi_strict {
                    x.hi() < h.lo()
                } else {
                    x.hi() <= h.lo()
                };
                above && below
            }
        };
        if !ok {
            let what = match domain {
                Domain::Sign(SignDecl::Positive) => format!("{name} > 0"),
                Domain::Sign(SignDecl::Nonnegative) => format!("{name} >= 0"),
                Domain::Sign(SignDecl::Nonzero) => format!("{name} != 0"),
                Domain::Sign(SignDecl::Any) => name.clone(),
                Domain::Range {
                    lo,
                    lo_strict,
                    hi,
                    hi_strict,
                } => format!(
                    "{} {} {name} {} {}",
                    crate::syntax::print::source(lo),
                    if *lo_strict { "<" } else { "<=" },
                    if *hi_strict { "<" } else { "<=" },
                    crate::syntax::print::source(hi)
                ),
            };
            return Err(format!("{name} = {v} does not satisfy {what}"));
        }
    }
    Ok(())
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

/// Whether a counterexample stands: `point` clearly satisfies every declaration
/// ([`respects`]), and the two sides as written, evaluated there, are not equal (their
/// enclosures tight and overlapping). A side the guard cannot evaluate leaves the exact
/// engine's word. The error says why it does not stand.
pub fn counterexample_stands(
    (a, b): (&Expr, &Expr),
    env: &GuardEnv,
    point: &HashMap<String, f64>,
) -> Result<(), String> {
    respects(env, point)?;
    if let (Ok(x), Ok(y)) = eval_both(a, b, env, point) {
        let scale = x.mid.abs().max(y.mid.abs());
        let equal_there = (x.mid - y.mid).abs() <= x.rad + y.rad && x.rad + y.rad <= 1e-10 * scale;
        if equal_there {
            return Err(format!(
                "evaluated as written there, both sides are ≈ {:.9}",
                x.mid
            ));
        }
    }
    Ok(())
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

/// One step of splitmix64, the small deterministic generator behind the points the guard
/// is tried at (`check/confirm.rs`) and the differential test's random pairs: the same
/// sequence on every platform and in every run. The one generator in the repository
/// (`normal/gcd.rs` mixes its evaluation points with the same finaliser, a hash there:
/// the guard shares no code with the engine it checks).
pub fn splitmix64(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

#[cfg(test)]
mod tests;
