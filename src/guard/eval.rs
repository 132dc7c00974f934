//! Evaluating a syntax tree at a point, in ball arithmetic: integrals by adaptive
//! Gauss–Legendre quadrature (exact for polynomials up to rounding), bodies by iterated
//! quadrature, derivatives through `deriv.rs`.

use super::ball::{Ball, Skip};
use super::deriv::{diff_node, names};
use super::GuardEnv;
use crate::syntax::ast::{BinOp, BodyDef, Expr, ExprKind, Func};
use foldhash::{HashMap, HashMapExt};
use num_rational::BigRational;
use num_traits::{ToPrimitive, Zero};
use std::sync::OnceLock;

/// Gauss–Legendre nodes and weights on [−1, 1] for `n` points (Newton on Pₙ).
fn gauss(n: usize) -> Vec<(f64, f64)> {
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let k = k as f64;
                let p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
            let dx = p1 / dp;
            x -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
        out.push((x, 2.0 / ((1.0 - x * x) * dp * dp)));
    }
    out
}

/// The rules used: 4, 6, 8, 10, 12 and 20 points.
const SIZES: [usize; 6] = [4, 6, 8, 10, 12, 20];

fn rule(n: usize) -> &'static [(f64, f64)] {
    static RULES: OnceLock<Vec<Vec<(f64, f64)>>> = OnceLock::new();
    let all = RULES.get_or_init(|| SIZES.iter().map(|n| gauss(*n)).collect());
    let i = SIZES
        .iter()
        .position(|s| *s == n)
        .unwrap_or(SIZES.len() - 1);
    all.get(i).map_or(&[], Vec::as_slice)
}

/// The evaluator: bound variables in scope, a work budget.
pub struct Evaluator<'a> {
    env: &'a GuardEnv,
    point: &'a HashMap<String, f64>,
    bound: Vec<(String, Ball)>,
    budget: usize,
    depth: usize,
    /// Values of `let` definitions at this point.
    defs: HashMap<String, Result<Ball, Skip>>,
}

impl<'a> Evaluator<'a> {
    /// An evaluator at `point` with a budget of node evaluations.
    pub fn new(env: &'a GuardEnv, point: &'a HashMap<String, f64>, budget: usize) -> Self {
        Evaluator {
            env,
            point,
            bound: Vec::new(),
            budget,
            depth: 0,
            defs: HashMap::new(),
        }
    }

    /// The value of `e`.
    pub fn eval(&mut self, e: &Expr) -> Result<Ball, Skip> {
        self.budget = self.budget.checked_sub(1).ok_or(Skip::Limit)?;
        if self.depth > 400 {
            return Err(Skip::Limit);
        }
        self.depth += 1;
        let r = self.eval_node(e);
        self.depth -= 1;
        r
    }

    fn eval_node(&mut self, e: &Expr) -> Result<Ball, Skip> {
        match &e.kind {
            ExprKind::Num(q) => {
                let x = q.to_f64().ok_or(Skip::Limit)?;
                Ok(if q.is_integer() && x.abs() < 9e15 {
                    Ball::exact(x)
                } else {
                    Ball::rounded(x)
                })
            }
            ExprKind::Pi => Ok(Ball::rounded(std::f64::consts::PI)),
            ExprKind::Sym(n) => self.symbol(n),
            ExprKind::Neg(a) => Ok(self.eval(a)?.negate()),
            ExprKind::Bin(op, a, b) => {
                if *op == BinOp::Pow {
                    return self.power(a, b);
                }
                let (x, y) = (self.eval(a)?, self.eval(b)?);
                match op {
                    BinOp::Add => x.plus(y),
                    BinOp::Sub => x.minus(y),
                    BinOp::Mul => x.times(y),
                    _ => x.over(y),
                }
            }
            ExprKind::Call(f, args) => self.call(*f, args),
        }
    }

    fn symbol(&mut self, n: &str) -> Result<Ball, Skip> {
        if let Some((_, v)) = self.bound.iter().rev().find(|(b, _)| b == n) {
            return Ok(*v);
        }
        if let Some(d) = self.env.defs.get(n) {
            if let Some(v) = self.defs.get(n) {
                return v.clone();
            }
            // A definition is evaluated as written, outside any binding inside this tree;
            // its value depends on the point only, so it is computed once.
            let saved = std::mem::take(&mut self.bound);
            let r = self.eval(d);
            self.bound = saved;
            self.defs.insert(n.to_string(), r.clone());
            return r;
        }
        self.point
            .get(n)
            .map(|x| Ball::exact(*x))
            .ok_or_else(|| Skip::Unsupported(format!("no value for {n}")))
    }

    fn power(&mut self, a: &Expr, b: &Expr) -> Result<Ball, Skip> {
        let base = self.eval(a)?;
        let may_be_zero = base.lo() <= 0.0 && base.hi() >= 0.0;
        if let Some(q) = constant(b, 0) {
            if may_be_zero && q <= BigRational::from_integer(0.into()) {
                return Err(Skip::Domain("0 to a power that is not positive".into()));
            }
            if q.is_integer() {
                return base.powi(q.to_integer().to_i64().ok_or(Skip::Limit)?);
            }
            if let (Some(p), Some(d)) = (q.numer().to_i64(), q.denom().to_u32()) {
                if d <= 64 && p.abs() <= 4096 {
                    return base.root(d)?.powi(p);
                }
            }
            return Err(Skip::Limit);
        }
        let e = self.eval(b)?;
        if base.lo() <= 0.0 {
            return Err(Skip::Domain(
                "a symbolic power of a value that may not be positive".into(),
            ));
        }
        e.times(base.ln()?)?.exp()
    }

    fn call(&mut self, f: Func, args: &[Expr]) -> Result<Ball, Skip> {
        let arg = |i: usize| args.get(i).ok_or(Skip::Limit);
        match f {
            Func::Sqrt => self.eval(arg(0)?)?.sqrt(),
            Func::Sin => self.eval(arg(0)?)?.sin(),
            Func::Cos => self.eval(arg(0)?)?.cos(),
            Func::Tan => {
                let u = self.eval(arg(0)?)?;
                u.sin()?.over(u.cos()?)
            }
            Func::Exp => self.eval(arg(0)?)?.exp(),
            Func::Ln => self.eval(arg(0)?)?.ln(),
            Func::Abs => Ok(self.eval(arg(0)?)?.abs()),
            Func::Diff => {
                let mut budget = 20_000;
                let d = diff_node(args, Some(&self.env.time), &self.env.defs, &mut budget)?;
                self.eval(&d)
            }
            Func::Subs | Func::Eval => {
                let var = self.var(arg(1)?)?;
                self.refuse_time(&var, arg(0)?)?;
                if f == Func::Subs {
                    let v = self.eval(arg(2)?)?;
                    return self.with(&var, v, arg(0)?);
                }
                let (a, b) = (self.eval(arg(2)?)?, self.eval(arg(3)?)?);
                self.with(&var, b, arg(0)?)?
                    .minus(self.with(&var, a, arg(0)?)?)
            }
            Func::Int => self.int(args),
        }
    }

    fn var(&self, e: &Expr) -> Result<String, Skip> {
        match &e.kind {
            ExprKind::Sym(n) => Ok(n.clone()),
            _ => Err(Skip::Unsupported(
                "a bound variable that is not a symbol".into(),
            )),
        }
    }

    /// Over `t`, a `time` symbol at another instant has no value at this point.
    fn refuse_time(&self, var: &str, body: &Expr) -> Result<(), Skip> {
        if var != "t" {
            return Ok(());
        }
        let mut n = foldhash::HashSet::default();
        names(body, &mut n);
        let mut todo: Vec<String> = n.into_iter().collect();
        let mut seen = foldhash::HashSet::default();
        while let Some(x) = todo.pop() {
            if !seen.insert(x.clone()) {
                continue;
            }
            if self.env.time.contains(x.trim_end_matches('\'')) {
                return Err(Skip::Unsupported("a time symbol at another instant".into()));
            }
            if let Some(d) = self.env.defs.get(&x) {
                let mut m = foldhash::HashSet::default();
                names(d, &mut m);
                todo.extend(m);
            }
        }
        Ok(())
    }

    fn with(&mut self, var: &str, v: Ball, body: &Expr) -> Result<Ball, Skip> {
        self.bound.push((var.to_string(), v));
        let r = self.eval(body);
        self.bound.pop();
        r
    }

    fn int(&mut self, args: &[Expr]) -> Result<Ball, Skip> {
        let (Some(body), Some(second)) = (args.first(), args.get(1)) else {
            return Err(Skip::Limit);
        };
        let var = self.var(second)?;
        if args.len() == 2 {
            let name =
                if var == "dm" && !self.env.bodies.contains_key("dm") && self.env.bodies.len() == 1
                {
                    self.env.bodies.keys().next().cloned().unwrap_or_default()
                } else {
                    var
                };
            return match self.env.bodies.get(&name) {
                Some(BodyDef::Concrete { dm, ranges }) => {
                    let ranges: Vec<(String, &Expr, &Expr)> = ranges
                        .iter()
                        .map(|r| (r.var.name.clone(), &r.from, &r.to))
                        .collect();
                    // The density is the mass element with every differential set to 1.
                    for (c, _, _) in &ranges {
                        self.bound.push((format!("d{c}"), Ball::exact(1.0)));
                    }
                    // Cheap rules first (exact for the polynomial densities of textbook
                    // bodies), finer ones only where two rules disagree.
                    let mut result = Err(Skip::Limit);
                    for (fine, coarse) in [(6, 4), (12, 8), (20, 10)] {
                        let f = self.body(body, dm, &ranges, fine);
                        let c = self.body(body, dm, &ranges, coarse);
                        let (Ok(f), Ok(c)) = (f, c) else {
                            break;
                        };
                        result = widen(f, c);
                        if close(&f, &c) {
                            break;
                        }
                    }
                    self.bound.truncate(self.bound.len() - ranges.len());
                    result
                }
                _ => Err(Skip::Unsupported(
                    "an antiderivative or an abstract body".into(),
                )),
            };
        }
        self.refuse_time(&var, body)?;
        let (a, b) = (
            self.eval(args.get(2).ok_or(Skip::Limit)?)?,
            self.eval(args.get(3).ok_or(Skip::Limit)?)?,
        );
        self.quad(body, &var, a, b, 0)
    }

    /// `∫ f` over `[a, b]`: 20-point Gauss–Legendre, checked against 10 points; where they
    /// disagree the interval is halved.
    fn quad(&mut self, f: &Expr, var: &str, a: Ball, b: Ball, depth: u32) -> Result<Ball, Skip> {
        let mut fine = self.gl(f, var, a.mid, b.mid, 6)?;
        let mut coarse = self.gl(f, var, a.mid, b.mid, 4)?;
        if !close(&fine, &coarse) {
            fine = self.gl(f, var, a.mid, b.mid, 20)?;
            coarse = self.gl(f, var, a.mid, b.mid, 10)?;
        }
        if !close(&fine, &coarse) && depth < 8 {
            let m = Ball::exact((a.mid + b.mid) / 2.0);
            let left = self.quad(f, var, Ball::exact(a.mid), m, depth + 1)?;
            let right = self.quad(f, var, m, Ball::exact(b.mid), depth + 1)?;
            return left.plus(right);
        }
        let mut r = widen(fine, coarse)?;
        // The ends' own uncertainty, times a bound on |f| there.
        if a.rad > 0.0 || b.rad > 0.0 {
            let fa = self.with(var, a, f)?.abs().hi();
            let fb = self.with(var, b, f)?.abs().hi();
            r.rad += a.rad * fa + b.rad * fb;
        }
        Ok(r)
    }

    fn gl(&mut self, f: &Expr, var: &str, a: f64, b: f64, n: usize) -> Result<Ball, Skip> {
        let (h, c) = ((b - a) / 2.0, (a + b) / 2.0);
        let mut total = Ball::exact(0.0);
        for (x, w) in rule(n) {
            let v = self.with(var, Ball::rounded(c + h * x), f)?;
            total = total.plus(v.times(Ball::rounded(*w))?)?;
        }
        total.times(Ball::rounded(h))
    }

    /// `∫ f dm` over a concrete body: iterated `n`-point rules, outermost coordinate first.
    fn body(
        &mut self,
        f: &Expr,
        dm: &Expr,
        ranges: &[(String, &Expr, &Expr)],
        n: usize,
    ) -> Result<Ball, Skip> {
        let Some(((var, from, to), rest)) = ranges.split_first() else {
            return self.eval(dm)?.times(self.eval(f)?);
        };
        let (a, b) = (self.eval(from)?.mid, self.eval(to)?.mid);
        let (h, c) = ((b - a) / 2.0, (a + b) / 2.0);
        let mut total = Ball::exact(0.0);
        for (x, w) in rule(n) {
            self.bound.push((var.clone(), Ball::rounded(c + h * x)));
            let v = self.body(f, dm, rest, n);
            self.bound.pop();
            total = total.plus(v?.times(Ball::rounded(*w))?)?;
        }
        total.times(Ball::rounded(h))
    }
}

/// Whether two quadratures agree: relative to the value, or (for an integral near 0)
/// to its terms' size, which the balls' rounding radii measure.
fn close(f: &Ball, c: &Ball) -> bool {
    (f.mid - c.mid).abs() <= 1e-12 * f.mid.abs() + 1e4 * (f.rad + c.rad) + 1e-300
}

/// Two quadratures of one integral: the finer value, with their difference (times a
/// safety factor) as its error.
fn widen(fine: Ball, coarse: Ball) -> Result<Ball, Skip> {
    let err = (fine.mid - coarse.mid).abs();
    Ok(Ball {
        mid: fine.mid,
        rad: fine.rad + coarse.rad + 10.0 * err + 1e-14 * fine.mid.abs(),
    })
}

/// The exact value of a tree of numbers and `+ − · /` (an exponent as written: `1/3`).
fn constant(e: &Expr, depth: u32) -> Option<BigRational> {
    if depth > 32 {
        return None;
    }
    match &e.kind {
        ExprKind::Num(q) => Some(q.clone()),
        ExprKind::Neg(a) => Some(-constant(a, depth + 1)?),
        ExprKind::Bin(op, a, b) => {
            let (x, y) = (constant(a, depth + 1)?, constant(b, depth + 1)?);
            match op {
                BinOp::Add => Some(x + y),
                BinOp::Sub => Some(x - y),
                BinOp::Mul => Some(x * y),
                BinOp::Div if !y.is_zero() => Some(x / y),
                _ => None,
            }
        }
        _ => None,
    }
}
