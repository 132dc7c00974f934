//! Derivatives of syntax trees, by the textbook rules, independent of the normal form's
//! calculus: `let` names are expanded first, and with respect to `t` a `time` symbol
//! `x'` differentiates to `x''`.

use super::ball::Skip;
use crate::syntax::ast::{BinOp, Expr, ExprKind, Func, Span};
use foldhash::{HashMap, HashSet, HashSetExt};

fn node(kind: ExprKind) -> Expr {
    Expr::new(kind, Span::default())
}

fn num(n: i64) -> Expr {
    node(ExprKind::Num(num_rational::BigRational::from_integer(
        n.into(),
    )))
}

fn bin(op: BinOp, a: Expr, b: Expr) -> Expr {
    node(ExprKind::Bin(op, Box::new(a), Box::new(b)))
}

fn call(f: Func, a: Expr) -> Expr {
    node(ExprKind::Call(f, vec![a]))
}

/// `e` with every `let` name (not bound inside) replaced by its definition, itself
/// expanded; `None` when the expansion grows past `budget` nodes.
pub fn expand(
    e: &Expr,
    defs: &HashMap<String, Expr>,
    bound: &mut Vec<String>,
    budget: &mut usize,
) -> Option<Expr> {
    *budget = budget.checked_sub(1)?;
    Some(match &e.kind {
        ExprKind::Sym(n) if !bound.contains(n) => match defs.get(n) {
            Some(d) => {
                let mut none = Vec::new();
                expand(d, defs, &mut none, budget)?
            }
            None => e.clone(),
        },
        ExprKind::Num(_) | ExprKind::Pi | ExprKind::Sym(_) => e.clone(),
        ExprKind::Neg(a) => node(ExprKind::Neg(Box::new(expand(a, defs, bound, budget)?))),
        ExprKind::Bin(op, a, b) => bin(
            *op,
            expand(a, defs, bound, budget)?,
            expand(b, defs, bound, budget)?,
        ),
        ExprKind::Call(f, args) => {
            let var = match (f, args.get(1).map(|a| &a.kind)) {
                (Func::Int | Func::Diff | Func::Subs | Func::Eval, Some(ExprKind::Sym(v))) => {
                    Some(v.clone())
                }
                _ => None,
            };
            let mut out = Vec::with_capacity(args.len());
            for (i, a) in args.iter().enumerate() {
                // The operand is in the bound variable's scope; the variable itself and
                // the bounds or values are not.
                let scoped = i == 0 && var.is_some();
                if scoped {
                    bound.extend(var.clone());
                }
                let r = if i == 1 && var.is_some() {
                    Some(a.clone())
                } else {
                    expand(a, defs, bound, budget)
                };
                if scoped {
                    bound.pop();
                }
                out.push(r?);
            }
            node(ExprKind::Call(*f, out))
        }
    })
}

/// Every symbol name in `e`, bound or free.
pub fn names(e: &Expr, out: &mut HashSet<String>) {
    match &e.kind {
        ExprKind::Sym(n) => {
            out.insert(n.clone());
        }
        ExprKind::Num(_) | ExprKind::Pi => {}
        ExprKind::Neg(a) => names(a, out),
        ExprKind::Bin(_, a, b) => {
            names(a, out);
            names(b, out);
        }
        ExprKind::Call(_, args) => args.iter().for_each(|a| names(a, out)),
    }
}

/// What a derivative is taken with respect to.
pub struct Wrt<'a> {
    /// The variable's name.
    pub var: &'a str,
    /// With respect to `t`: the `time` symbols' base names.
    pub time: Option<&'a HashSet<String>>,
    /// `let` definitions: a derivative in a `let` name is read with the name meaning
    /// its definition again.
    pub defs: &'a HashMap<String, Expr>,
}

impl Wrt<'_> {
    fn moves(&self, name: &str) -> bool {
        name == self.var
            || self
                .time
                .is_some_and(|t| t.contains(name.trim_end_matches('\'')))
    }

    fn depends(&self, e: &Expr) -> bool {
        let mut n = HashSet::new();
        names(e, &mut n);
        n.iter().any(|x| self.moves(x))
    }
}

/// The derivative of an expanded tree.
pub fn deriv(e: &Expr, w: &Wrt<'_>, budget: &mut usize) -> Result<Expr, Skip> {
    *budget = budget.checked_sub(1).ok_or(Skip::Limit)?;
    let d = |x: &Expr, b: &mut usize| deriv(x, w, b);
    Ok(match &e.kind {
        ExprKind::Num(_) | ExprKind::Pi => num(0),
        ExprKind::Sym(n) if n == w.var => num(1),
        ExprKind::Sym(n) if w.moves(n) => node(ExprKind::Sym(format!("{n}'"))),
        ExprKind::Sym(_) => num(0),
        ExprKind::Neg(a) => node(ExprKind::Neg(Box::new(d(a, budget)?))),
        ExprKind::Bin(op, a, b) => {
            let (da, db) = (d(a, budget)?, d(b, budget)?);
            let (a, b) = ((**a).clone(), (**b).clone());
            match op {
                BinOp::Add | BinOp::Sub => bin(*op, da, db),
                BinOp::Mul => bin(BinOp::Add, bin(BinOp::Mul, da, b), bin(BinOp::Mul, a, db)),
                BinOp::Div => bin(
                    BinOp::Div,
                    bin(
                        BinOp::Sub,
                        bin(BinOp::Mul, da, b.clone()),
                        bin(BinOp::Mul, a, db),
                    ),
                    bin(BinOp::Pow, b, num(2)),
                ),
                BinOp::Pow if !w.depends(&b) => bin(
                    BinOp::Mul,
                    bin(
                        BinOp::Mul,
                        b.clone(),
                        bin(BinOp::Pow, a, bin(BinOp::Sub, b, num(1))),
                    ),
                    da,
                ),
                BinOp::Pow => bin(
                    BinOp::Mul,
                    bin(BinOp::Pow, a.clone(), b.clone()),
                    bin(
                        BinOp::Add,
                        bin(BinOp::Mul, db, call(Func::Ln, a.clone())),
                        bin(BinOp::Div, bin(BinOp::Mul, b, da), a),
                    ),
                ),
            }
        }
        ExprKind::Call(f, args) => deriv_call(*f, args, w, budget)?,
    })
}

fn deriv_call(f: Func, args: &[Expr], w: &Wrt<'_>, budget: &mut usize) -> Result<Expr, Skip> {
    let u = args.first().ok_or(Skip::Limit)?.clone();
    let chain = |outer: Expr, budget: &mut usize| -> Result<Expr, Skip> {
        Ok(bin(BinOp::Mul, outer, deriv(&u, w, budget)?))
    };
    match f {
        Func::Sqrt => chain(
            bin(
                BinOp::Div,
                num(1),
                bin(BinOp::Mul, num(2), call(Func::Sqrt, u.clone())),
            ),
            budget,
        ),
        Func::Sin => chain(call(Func::Cos, u.clone()), budget),
        Func::Cos => chain(
            node(ExprKind::Neg(Box::new(call(Func::Sin, u.clone())))),
            budget,
        ),
        Func::Tan => chain(
            bin(
                BinOp::Div,
                num(1),
                bin(BinOp::Pow, call(Func::Cos, u.clone()), num(2)),
            ),
            budget,
        ),
        Func::Exp => chain(call(Func::Exp, u.clone()), budget),
        Func::Ln => chain(bin(BinOp::Div, num(1), u.clone()), budget),
        Func::Abs => chain(
            bin(BinOp::Div, u.clone(), call(Func::Abs, u.clone())),
            budget,
        ),
        Func::Diff => {
            let inner = diff_node(args, w.time, w.defs, budget)?;
            deriv(&inner, w, budget)
        }
        Func::Int | Func::Subs | Func::Eval => {
            let whole = node(ExprKind::Call(f, args.to_vec()));
            if w.depends(&whole) {
                Err(Skip::Unsupported(
                    "a derivative of an integral or substitution".into(),
                ))
            } else {
                Ok(num(0))
            }
        }
    }
}

/// The tree of `diff(f, x, n)` with the derivative taken.
pub fn diff_node(
    args: &[Expr],
    time: Option<&HashSet<String>>,
    defs: &HashMap<String, Expr>,
    budget: &mut usize,
) -> Result<Expr, Skip> {
    let (Some(f), Some(ExprKind::Sym(var))) = (args.first(), args.get(1).map(|a| &a.kind)) else {
        return Err(Skip::Unsupported("diff of a non-symbol".into()));
    };
    let n = match args.get(2).map(|a| &a.kind) {
        None => 1,
        Some(ExprKind::Num(q)) if q.is_integer() => num_traits::ToPrimitive::to_u32(q.numer())
            .filter(|n| *n <= 6)
            .ok_or(Skip::Limit)?,
        _ => return Err(Skip::Unsupported("a derivative of symbolic order".into())),
    };
    let w = Wrt {
        var,
        time: if var == "t" { time } else { None },
        defs,
    };
    let mut cur = f.clone();
    for _ in 0..n {
        cur = deriv(&cur, &w, budget)?;
    }
    // The result is a function of the name as it is meant outside: a `let` name's
    // definition.
    match defs.get(var) {
        Some(d) => replace(&cur, var, d, budget).ok_or(Skip::Limit),
        None => Ok(cur),
    }
}

/// `e` with the free symbol `name` replaced by `by`.
fn replace(e: &Expr, name: &str, by: &Expr, budget: &mut usize) -> Option<Expr> {
    *budget = budget.checked_sub(1)?;
    Some(match &e.kind {
        ExprKind::Sym(n) if n == name => by.clone(),
        ExprKind::Num(_) | ExprKind::Pi | ExprKind::Sym(_) => e.clone(),
        ExprKind::Neg(a) => node(ExprKind::Neg(Box::new(replace(a, name, by, budget)?))),
        ExprKind::Bin(op, a, b) => bin(
            *op,
            replace(a, name, by, budget)?,
            replace(b, name, by, budget)?,
        ),
        ExprKind::Call(f, args) => {
            let shadows = matches!(args.get(1).map(|a| &a.kind), Some(ExprKind::Sym(v)) if v == name)
                && matches!(f, Func::Int | Func::Diff | Func::Subs | Func::Eval);
            let mut out = Vec::with_capacity(args.len());
            for (i, a) in args.iter().enumerate() {
                out.push(if (i == 0 || i == 1) && shadows {
                    a.clone()
                } else {
                    replace(a, name, by, budget)?
                });
            }
            node(ExprKind::Call(*f, out))
        }
    })
}
