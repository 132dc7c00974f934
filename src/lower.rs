//! Syntax to normal form: evaluates an expression tree in an environment of
//! definitions, bodies and declared signs, computing `int`, `diff`, `eval` and `subs`.
//! Errors carry the span of the node that caused them.

use crate::calculus::{self, Body, IntError, Wrt};
use crate::normal::atom::{self, Atom};
use crate::normal::subst::{depends_on, subst_atom};
use crate::normal::{func, trig, Assumptions, NormError, Rat, Sign};
use crate::syntax::ast::{BinOp, Expr, ExprKind, Func, Span};
use num_integer::Integer;
use num_traits::{Signed, ToPrimitive};
use std::collections::{HashMap, HashSet};
use std::fmt;

/// What names mean while lowering.
#[derive(Clone, Debug, Default)]
pub struct Env {
    /// Declared signs.
    pub signs: Assumptions,
    /// `let` definitions, already lowered.
    pub defs: HashMap<String, Rat>,
    /// Bodies by name.
    pub bodies: HashMap<String, Body>,
    /// Base names of `time` symbols.
    pub time: HashSet<String>,
}

/// An error while lowering, at a span.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LowerError {
    /// Where.
    pub span: Span,
    /// What went wrong (a full sentence fragment, e.g. "division by …").
    pub message: String,
    /// Whether this is a resource limit (rather than bad input).
    pub limit: bool,
    /// Whether the time budget ran out (the claim is undecided, not bad input).
    pub timeout: bool,
}

impl fmt::Display for LowerError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for LowerError {}

fn err(span: Span, e: NormError) -> LowerError {
    LowerError {
        span,
        limit: matches!(e, NormError::Limit(_)),
        timeout: e == NormError::Limit(crate::normal::Limit::Time),
        message: e.to_string(),
    }
}

fn int_err(span: Span, e: IntError) -> LowerError {
    match e {
        IntError::Norm(n) => err(span, n),
        e => LowerError {
            span,
            message: e.to_string(),
            limit: false,
            timeout: false,
        },
    }
}

fn msg(span: Span, m: impl Into<String>) -> LowerError {
    LowerError {
        span,
        message: m.into(),
        limit: false,
        timeout: false,
    }
}

/// What a recorded condition requires of its value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Need {
    /// A divisor: `!= 0`.
    NonZero,
    /// The argument of `ln`: `> 0`.
    Positive,
    /// The argument of a square (even) root: `>= 0`.
    NonNegative,
}

/// A condition for an expression to be defined (a divisor, the argument of `ln` or of
/// a square root) that the declared signs do not settle, recorded for side conditions.
#[derive(Clone, Debug)]
pub struct Divisor {
    /// The value the condition is about.
    pub value: Rat,
    /// What it must be.
    pub need: Need,
    /// Where it was written.
    pub span: Span,
}

/// Lowers expressions in an environment, recording divisions.
pub struct Lowerer<'a> {
    env: &'a Env,
    bound: Vec<String>,
    /// Every division by a non-constant expression met, in order.
    pub divisors: Vec<Divisor>,
}

impl<'a> Lowerer<'a> {
    /// A lowerer over `env`.
    pub fn new(env: &'a Env) -> Lowerer<'a> {
        Lowerer {
            env,
            bound: Vec::new(),
            divisors: Vec::new(),
        }
    }

    fn signs(&self) -> &Assumptions {
        &self.env.signs
    }

    fn note_divisor(&mut self, d: &Rat, span: Span) {
        self.note(d, Need::NonZero, span);
    }

    fn note(&mut self, d: &Rat, need: Need, span: Span) {
        if d.as_constant().is_some() {
            return;
        }
        let s = self.signs().rat(d);
        let settled = match need {
            Need::NonZero => s.is_nonzero(),
            Need::Positive => s == Sign::Pos,
            Need::NonNegative => s.is_nonneg(),
        };
        if !settled {
            self.divisors.push(Divisor {
                value: d.clone(),
                need,
                span,
            });
        }
    }

    /// The normal form of `e`.
    pub fn lower(&mut self, e: &Expr) -> Result<Rat, LowerError> {
        let sp = e.span;
        match &e.kind {
            ExprKind::Num(q) => Ok(Rat::constant(q.clone())),
            ExprKind::Pi => Ok(Rat::atom(atom::intern(Atom::Pi))),
            ExprKind::Sym(name) => {
                if !self.bound.iter().any(|b| b == name) {
                    if let Some(v) = self.env.defs.get(name) {
                        return Ok(v.clone());
                    }
                }
                Ok(Rat::atom(atom::sym(name)))
            }
            ExprKind::Neg(a) => Ok(self.lower(a)?.neg()),
            ExprKind::Bin(op, a, b) => {
                let x = self.lower(a)?;
                let y = self.lower(b)?;
                let r = match op {
                    BinOp::Add => x.add(&y),
                    BinOp::Sub => x.sub(&y),
                    BinOp::Mul => x.mul(&y),
                    BinOp::Div => {
                        if y.is_zero() {
                            return Err(msg(
                                b.span,
                                "division by an expression that is exactly zero",
                            ));
                        }
                        self.note_divisor(&y, b.span);
                        x.div(&y)
                    }
                    BinOp::Pow => {
                        if x.is_zero() && y.as_constant().is_some_and(|q| !q.is_positive()) {
                            let m = if y.is_zero() {
                                "0^0 is undefined"
                            } else {
                                "division by zero: 0 to a negative power"
                            };
                            return Err(msg(sp, m));
                        }
                        if y.as_constant().is_some_and(|q| q.is_negative()) {
                            self.note_divisor(&x, a.span);
                        }
                        if y.as_constant()
                            .is_some_and(|q| !q.is_integer() && q.denom().is_even())
                        {
                            self.note(&x, Need::NonNegative, a.span);
                        }
                        func::pow(&x, &y, self.signs())
                    }
                };
                r.map_err(|e| err(sp, e))
            }
            ExprKind::Call(f, args) => self.call(*f, args, sp),
        }
    }

    fn arg<'e>(&self, args: &'e [Expr], i: usize, sp: Span) -> Result<&'e Expr, LowerError> {
        args.get(i).ok_or_else(|| msg(sp, "missing argument"))
    }

    fn var_name(&self, e: &Expr, what: &str) -> Result<String, LowerError> {
        match &e.kind {
            ExprKind::Sym(n) => Ok(n.clone()),
            ExprKind::Num(_) => Err(msg(
                e.span,
                format!("{what} must be a symbol, not a number"),
            )),
            _ => Err(msg(e.span, format!("{what} must be a symbol"))),
        }
    }

    fn lower_bound(&mut self, e: &Expr, var: &str) -> Result<Rat, LowerError> {
        self.bound.push(var.to_string());
        let r = self.lower(e);
        self.bound.pop();
        r
    }

    fn call(&mut self, f: Func, args: &[Expr], sp: Span) -> Result<Rat, LowerError> {
        let s = self.env.signs.clone();
        match f {
            Func::Sqrt | Func::Sin | Func::Cos | Func::Tan | Func::Exp | Func::Ln | Func::Abs => {
                let a = self.arg(args, 0, sp)?;
                let u = self.lower(a)?;
                match f {
                    Func::Sqrt => self.note(&u, Need::NonNegative, a.span),
                    Func::Ln => self.note(&u, Need::Positive, a.span),
                    _ => {}
                }
                let r = match f {
                    Func::Sqrt => func::sqrt(&u, &s),
                    Func::Sin => trig::sin(&u),
                    Func::Cos => trig::cos(&u),
                    Func::Tan => {
                        let c = trig::cos(&u).map_err(|e| err(sp, e))?;
                        if c.is_zero() {
                            return Err(msg(
                                sp,
                                "tan is undefined here: the cosine is exactly zero",
                            ));
                        }
                        self.note_divisor(&c, sp);
                        trig::tan(&u)
                    }
                    Func::Exp => func::exp(&u),
                    Func::Ln => func::ln(&u, &s),
                    _ => func::abs(&u, &s),
                };
                r.map_err(|e| err(sp, e))
            }
            Func::Int => self.int(args, sp),
            Func::Diff => {
                let var = self.var_name(self.arg(args, 1, sp)?, "the variable of diff")?;
                let n = match args.get(2) {
                    None => 1,
                    Some(ne) => {
                        let nv = self.lower(ne)?;
                        nv.as_constant()
                            .filter(|q| q.is_integer() && !q.is_negative())
                            .and_then(|q| q.to_integer().to_u32())
                            .filter(|n| *n <= 1000)
                            .ok_or_else(|| {
                                msg(
                                    ne.span,
                                    "the order of diff must be a whole number from 0 to 1000",
                                )
                            })?
                    }
                };
                let body = self.arg(args, 0, sp)?;
                self.bound.push(var.clone());
                let fv = self.lower(body);
                self.bound.pop();
                let fv = fv?;
                let x = atom::sym(&var);
                let time = &self.env.time;
                let is_time = |b: &str| time.contains(b);
                let wrt = Wrt {
                    var: x,
                    time: (var == "t").then_some(&is_time as &dyn Fn(&str) -> bool),
                };
                calculus::diff_n(&fv, &wrt, n, &s).map_err(|e| err(sp, e))
            }
            Func::Eval => {
                let var = self.var_name(self.arg(args, 1, sp)?, "the variable of eval")?;
                let body = self.arg(args, 0, sp)?;
                let fv = self.lower_bound(body, &var)?;
                let a = self.lower(self.arg(args, 2, sp)?)?;
                let b = self.lower(self.arg(args, 3, sp)?)?;
                let x = atom::sym(&var);
                let hi = subst_atom(&fv, x, &b, &s).map_err(|e| err(sp, e))?;
                let lo = subst_atom(&fv, x, &a, &s).map_err(|e| err(sp, e))?;
                hi.sub(&lo).map_err(|e| err(sp, e))
            }
            Func::Subs => {
                let var = self.var_name(self.arg(args, 1, sp)?, "the variable of subs")?;
                let body = self.arg(args, 0, sp)?;
                let fv = self.lower_bound(body, &var)?;
                let v = self.lower(self.arg(args, 2, sp)?)?;
                subst_atom(&fv, atom::sym(&var), &v, &s).map_err(|e| err(sp, e))
            }
        }
    }

    fn int(&mut self, args: &[Expr], sp: Span) -> Result<Rat, LowerError> {
        let s = self.env.signs.clone();
        let second = self.arg(args, 1, sp)?;
        let var = self.var_name(second, "the variable of integration")?;
        let body = self.arg(args, 0, sp)?;
        if args.len() == 2 {
            let body_def = if var == "dm" && !self.env.bodies.contains_key("dm") {
                if self.env.bodies.len() == 1 {
                    self.env.bodies.values().next()
                } else {
                    return Err(msg(
                        second.span,
                        format!(
                            "int(f, dm) needs exactly one declared body, but {} are declared; name the body",
                            self.env.bodies.len()
                        ),
                    ));
                }
            } else {
                self.env.bodies.get(&var)
            };
            if let Some(b) = body_def {
                let coords: Vec<String> = b
                    .coords()
                    .iter()
                    .filter_map(|c| atom::sym_name(*c))
                    .collect();
                let n = coords.len();
                self.bound.extend(coords);
                let fv = self.lower(body);
                self.bound.truncate(self.bound.len() - n);
                let fv = fv?;
                return b.integrate(&fv, &s).map_err(|e| int_err(body.span, e));
            }
            let fv = self.lower_bound(body, &var)?;
            return calculus::antiderivative(&fv, atom::sym(&var), &s)
                .map_err(|e| int_err(body.span, e));
        }
        let fv = self.lower_bound(body, &var)?;
        let x = atom::sym(&var);
        let mut bounds = Vec::new();
        for i in [2, 3] {
            let be = self.arg(args, i, sp)?;
            let bv = self.lower(be)?;
            if depends_on(&bv, x) {
                return Err(msg(
                    be.span,
                    format!("a bound of the integral mentions the integration variable {var}"),
                ));
            }
            bounds.push(bv);
        }
        let (Some(a), Some(b)) = (bounds.first(), bounds.get(1)) else {
            return Err(msg(sp, "missing bounds"));
        };
        calculus::definite(&fv, x, a, b, &s).map_err(|e| int_err(body.span, e))
    }
}

/// Lowers one expression with no recording.
pub fn lower(e: &Expr, env: &Env) -> Result<Rat, LowerError> {
    Lowerer::new(env).lower(e)
}

/// The sign a `symbols` declaration gives.
pub fn sign_of_decl(d: crate::syntax::ast::SignDecl) -> Sign {
    use crate::syntax::ast::SignDecl;
    match d {
        SignDecl::Any => Sign::Unknown,
        SignDecl::Positive => Sign::Pos,
        SignDecl::Nonnegative => Sign::NonNeg,
        SignDecl::Nonzero => Sign::NonZero,
    }
}

/// Builds a body from its declaration, lowering the mass element and the bounds.
pub fn build_body(
    name: &str,
    def: &crate::syntax::ast::BodyDef,
    env: &Env,
) -> Result<Body, LowerError> {
    use crate::syntax::ast::BodyDef;
    let mut lw = Lowerer::new(env);
    match def {
        BodyDef::Concrete { dm, ranges } => {
            let names: Vec<String> = ranges.iter().map(|r| r.var.name.clone()).collect();
            let mut out_ranges = Vec::new();
            for (i, r) in ranges.iter().enumerate() {
                lw.bound = names[..i].to_vec();
                lw.bound.push(r.var.name.clone());
                let from = lw.lower(&r.from)?;
                let to = lw.lower(&r.to)?;
                let v = atom::sym(&r.var.name);
                for (e, val) in [(&r.from, &from), (&r.to, &to)] {
                    if depends_on(val, v) {
                        return Err(msg(
                            e.span,
                            format!("the bound of {} mentions {} itself", r.var.name, r.var.name),
                        ));
                    }
                    for later in &names[i + 1..] {
                        if depends_on(val, atom::sym(later)) {
                            return Err(msg(
                                e.span,
                                format!(
                                    "the bound of {} mentions {later}, which is listed after it; list coordinates outermost first",
                                    r.var.name
                                ),
                            ));
                        }
                    }
                }
                out_ranges.push((v, from, to));
            }
            lw.bound = names.clone();
            let mut density = lw.lower(dm)?;
            for n in &names {
                let d = atom::sym(&format!("d{n}"));
                let deg = density.num().degree_in(d);
                if deg != 1 || density.den().contains(d) {
                    return Err(msg(
                        dm.span,
                        format!("the mass element must be a density times d{n} (once) for each coordinate"),
                    ));
                }
                density = density.div(&Rat::atom(d)).map_err(|e| err(dm.span, e))?;
            }
            Ok(Body::Concrete {
                density,
                ranges: out_ranges,
            })
        }
        BodyDef::Abstract {
            mass,
            coords,
            centred,
        } => {
            let mass = lw.lower(mass)?;
            Ok(Body::Abstract {
                name: name.to_string(),
                mass,
                coords: coords
                    .iter()
                    .map(|c| (c.name.clone(), atom::sym(&c.name)))
                    .collect(),
                centred: *centred,
            })
        }
    }
}
