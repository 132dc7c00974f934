//! Syntax to normal form: evaluates an expression tree in an environment of
//! definitions, bodies and declared signs, computing `int`, `diff`, `eval` and `subs`.
//! Errors carry the span of the node that caused them.

use crate::calculus::{self, Body, IntError, Wrt};
use crate::normal::atom::{self, Atom, AtomId};
use crate::normal::subst::{depends_on, subst_atom};
use crate::normal::{func, trig, Assumptions, Limit, NormError, Rat, Sign};
use crate::syntax::ast::{BinOp, Expr, ExprKind, Func, Reading, Span};
use foldhash::{HashMap, HashSet};
use num_integer::Integer;
use num_traits::{Signed, ToPrimitive};
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
    /// What went wrong.
    pub kind: LowerErrorKind,
}

/// What went wrong while lowering.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum LowerErrorKind {
    /// A resource limit: a size limit refuses the input (E0901); [`Limit::Time`], the
    /// time budget ran out (the claim is undecided, not bad input).
    Limit(Limit),
    /// The engine refused a value: division by zero, `0^0`, a value outside a
    /// function's domain (never [`NormError::Limit`]: that is [`LowerErrorKind::Limit`]).
    Engine(NormError),
    /// An integral rigor does not compute (never [`IntError::Norm`]).
    Integral(IntError),
    /// Input that means nothing here (an unknown body, a derivative with respect to a
    /// number, …); the text says what, a full sentence fragment.
    Invalid(String),
}

impl LowerError {
    /// The resource limit the lowering ran into, if that is what went wrong.
    pub fn limit(&self) -> Option<Limit> {
        match self.kind {
            LowerErrorKind::Limit(l) => Some(l),
            _ => None,
        }
    }

    /// Whether the time budget ran out (the claim is undecided, not bad input).
    pub fn timed_out(&self) -> bool {
        self.limit() == Some(Limit::Time)
    }
}

impl fmt::Display for LowerError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.kind {
            LowerErrorKind::Limit(l) => NormError::Limit(*l).fmt(f),
            LowerErrorKind::Engine(e) => e.fmt(f),
            LowerErrorKind::Integral(e) => e.fmt(f),
            LowerErrorKind::Invalid(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for LowerError {}

fn err(span: Span, e: NormError) -> LowerError {
    let kind = match e {
        NormError::Limit(l) => LowerErrorKind::Limit(l),
        e => LowerErrorKind::Engine(e),
    };
    LowerError { span, kind }
}

fn int_err(span: Span, e: IntError) -> LowerError {
    match e {
        IntError::Norm(n) => err(span, n),
        e => LowerError {
            span,
            kind: LowerErrorKind::Integral(e),
        },
    }
}

fn msg(span: Span, m: impl Into<String>) -> LowerError {
    LowerError {
        span,
        kind: LowerErrorKind::Invalid(m.into()),
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

/// A condition as data: a value and what it must be.
pub type Condition = (Rat, Need);

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
///
/// A bound variable (of `int`, `diff`, `subs`, `eval`, a body's coordinates) is fresh:
/// while its operand is lowered, it knows only the sign its range gives, whatever a free
/// symbol or a `let` name of the same name means outside.
pub struct Lowerer<'a> {
    env: &'a Env,
    /// The declared signs, with bound variables' signs overridden in their scopes.
    signs: Assumptions,
    bound: Vec<String>,
    /// Every division by a non-constant expression met, in order.
    pub divisors: Vec<Divisor>,
}

/// A bound variable and the declared sign and interval of its name, to restore.
type Bound = (AtomId, Sign, Option<crate::normal::Range>);

/// What happens to the conditions recorded inside a bound variable's scope.
enum Scope<'v> {
    /// `subs(f, x, v)`: each condition at `x = v`.
    At(&'v [Rat]),
    /// A definite integral or a body: the variables range over a region.
    Region,
    /// `diff` or an antiderivative: the result is a function of the free name.
    Free,
}

impl<'a> Lowerer<'a> {
    /// A lowerer over `env`.
    pub fn new(env: &'a Env) -> Lowerer<'a> {
        Lowerer {
            env,
            signs: env.signs.clone(),
            bound: Vec::new(),
            divisors: Vec::new(),
        }
    }

    fn signs(&self) -> &Assumptions {
        &self.signs
    }

    fn note_divisor(&mut self, d: &Rat, span: Span) {
        self.note(d, Need::NonZero, span);
    }

    /// Records a condition the signs do not settle; a constant one is recorded only when
    /// it is false (so the step that needs it fails).
    fn note(&mut self, d: &Rat, need: Need, span: Span) {
        let settled = if let Some(q) = d.as_constant() {
            match need {
                Need::NonZero => !num_traits::Zero::is_zero(&q),
                Need::Positive => q.is_positive(),
                Need::NonNegative => !q.is_negative(),
            }
        } else {
            let s = self.signs().rat(d);
            match need {
                Need::NonZero => s.is_nonzero(),
                Need::Positive => s == Sign::Pos,
                Need::NonNegative => s.is_nonneg(),
            }
        };
        if !settled {
            self.divisors.push(Divisor {
                value: d.clone(),
                need,
                span,
            });
        }
    }

    /// Whether `name` is the time variable and `time` symbols are declared.
    fn is_time_var(&self, name: &str) -> bool {
        name == "t" && !self.env.time.is_empty()
    }

    /// Lowers `e` with `vars` bound, each knowing only its sign; returns the value and
    /// the conditions recorded inside, for the caller to carry out of the scope.
    fn lower_in_scope(
        &mut self,
        e: &Expr,
        vars: &[(String, Sign)],
    ) -> Result<(Rat, Vec<Divisor>), LowerError> {
        let outer = std::mem::take(&mut self.divisors);
        let mut saved = Vec::with_capacity(vars.len());
        for (name, sign) in vars {
            saved.push(self.bind(atom::sym(name), *sign));
            self.bound.push(name.clone());
        }
        let r = self.lower(e);
        for s in saved.into_iter().rev() {
            self.unbind(s);
            self.bound.pop();
        }
        let inner = std::mem::replace(&mut self.divisors, outer);
        Ok((r?, inner))
    }

    /// Makes `x` a fresh variable of sign `sign` (no declared interval); what to restore.
    fn bind(&mut self, x: AtomId, sign: Sign) -> Bound {
        let old = (x, self.signs.declared(x), self.signs.set_range(x, None));
        self.signs.set(x, sign);
        old
    }

    fn unbind(&mut self, (x, sign, range): Bound) {
        self.signs.set(x, sign);
        self.signs.set_range(x, range);
    }

    /// Carries conditions recorded in the scope of `var` out of it.
    fn carry(
        &mut self,
        inner: Vec<Divisor>,
        var: &str,
        scope: Scope<'_>,
        sp: Span,
    ) -> Result<(), LowerError> {
        let x = atom::sym(var);
        for d in inner {
            if !depends_on(&d.value, x) {
                self.note(&d.value, d.need, d.span);
                continue;
            }
            match &scope {
                Scope::At(points) => {
                    for v in points.iter() {
                        let at = self.at(&d.value, var, v).map_err(|e| err(sp, e))?;
                        self.note(&at, d.need, d.span);
                    }
                }
                // A divisor vanishes on a set of measure zero: the integral is unchanged.
                Scope::Region if d.need == Need::NonZero => {}
                Scope::Region => {
                    let op = if d.need == Need::Positive { ">" } else { ">=" };
                    return Err(msg(
                        d.span,
                        format!(
                            "the integrand needs {} {op} 0 for every {var} in the range, which the signs do not show",
                            crate::normal::print::plain(&d.value)
                        ),
                    ));
                }
                Scope::Free => {
                    let v = self.free_meaning(&d.value, var).map_err(|e| err(sp, e))?;
                    self.note(&v, d.need, d.span);
                }
            }
        }
        Ok(())
    }

    /// `r` (a function of the bound `var`) read with `var` meaning what the name means
    /// outside: a `let` name's value, or the free symbol with its declared sign.
    fn free_meaning(&self, r: &Rat, var: &str) -> Result<Rat, NormError> {
        let x = atom::sym(var);
        match self.env.defs.get(var) {
            Some(v) if !self.bound.iter().any(|b| b == var) => subst_atom(r, x, v, self.signs()),
            _ => crate::normal::subst::rebuild_under(r, x, self.signs()),
        }
    }

    /// `r` at `var = v`; over the time variable, `time` symbols are taken at the instant.
    fn at(&self, r: &Rat, var: &str, v: &Rat) -> Result<Rat, NormError> {
        let x = atom::sym(var);
        if self.is_time_var(var) {
            let time = &self.env.time;
            let is_time = |b: &str| time.contains(b);
            return calculus::at_instant(r, x, v, &is_time, self.signs());
        }
        subst_atom(r, x, v, self.signs())
    }

    /// The sign a variable ranging between `a` and `b` (either order) has inside the range.
    pub fn range_sign(&self, a: &Rat, b: &Rat) -> Sign {
        let (sa, sb) = (self.signs().rat(a), self.signs().rat(b));
        let pos = |s: Sign| s == Sign::Pos;
        let neg = |s: Sign| s == Sign::Neg;
        if (pos(sa) && sb.is_nonneg()) || (pos(sb) && sa.is_nonneg()) {
            Sign::Pos
        } else if sa.is_nonneg() && sb.is_nonneg() {
            Sign::NonNeg
        } else if (neg(sa) && sb.is_nonpos()) || (neg(sb) && sa.is_nonpos()) {
            Sign::Neg
        } else if sa.is_nonpos() && sb.is_nonpos() {
            Sign::NonPos
        } else {
            Sign::Unknown
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
            ExprKind::Call(Func::Diff, args) if e.reading == Reading::Leibniz => {
                self.diff(args, sp, true)
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

    fn call(&mut self, f: Func, args: &[Expr], sp: Span) -> Result<Rat, LowerError> {
        match f {
            Func::Sqrt | Func::Sin | Func::Cos | Func::Tan | Func::Exp | Func::Ln | Func::Abs => {
                self.function(f, args, sp)
            }
            Func::Int => self.int(args, sp),
            Func::Diff => self.diff(args, sp, false),
            Func::Eval => {
                let var = self.var_name(self.arg(args, 1, sp)?, "the variable of eval")?;
                let (fv, inner) =
                    self.lower_in_scope(self.arg(args, 0, sp)?, &[(var.clone(), Sign::Unknown)])?;
                let a = self.lower(self.arg(args, 2, sp)?)?;
                let b = self.lower(self.arg(args, 3, sp)?)?;
                self.carry(inner, &var, Scope::At(&[a.clone(), b.clone()]), sp)?;
                let hi = self.at(&fv, &var, &b).map_err(|e| err(sp, e))?;
                let lo = self.at(&fv, &var, &a).map_err(|e| err(sp, e))?;
                hi.sub(&lo).map_err(|e| err(sp, e))
            }
            Func::Subs => {
                let var = self.var_name(self.arg(args, 1, sp)?, "the variable of subs")?;
                let (fv, inner) =
                    self.lower_in_scope(self.arg(args, 0, sp)?, &[(var.clone(), Sign::Unknown)])?;
                let v = self.lower(self.arg(args, 2, sp)?)?;
                self.carry(inner, &var, Scope::At(std::slice::from_ref(&v)), sp)?;
                self.at(&fv, &var, &v).map_err(|e| err(sp, e))
            }
        }
    }

    fn function(&mut self, f: Func, args: &[Expr], sp: Span) -> Result<Rat, LowerError> {
        let a = self.arg(args, 0, sp)?;
        let u = self.lower(a)?;
        match f {
            Func::Sqrt => self.note(&u, Need::NonNegative, a.span),
            Func::Ln => self.note(&u, Need::Positive, a.span),
            _ => {}
        }
        let s = self.signs.clone();
        let r = match f {
            Func::Sqrt => func::sqrt(&u, &s),
            Func::Sin => trig::sin(&u),
            Func::Cos => trig::cos(&u),
            Func::Tan => {
                let c = trig::cos(&u).map_err(|e| err(sp, e))?;
                if c.is_zero() {
                    return Err(msg(sp, "tan is undefined here: the cosine is exactly zero"));
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

    /// `diff(f, x[, n])`. Written in Leibniz notation (`leibniz`), the writer means a
    /// quantity that varies with `x`: an operand that, as declared, does not vary with
    /// it (and is not a number) is refused, never differentiated to zero.
    fn diff(&mut self, args: &[Expr], sp: Span, leibniz: bool) -> Result<Rat, LowerError> {
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
        let (fv, inner) = self.lower_in_scope(body, &[(var.clone(), Sign::Unknown)])?;
        let x = atom::sym(&var);
        let time = &self.env.time;
        let is_time = |b: &str| time.contains(b);
        let wrt = Wrt {
            var: x,
            time: (var == "t").then_some(&is_time as &dyn Fn(&str) -> bool),
        };
        let signs = self.signs_without(x);
        if leibniz {
            let d1 = calculus::diff(&fv, &wrt, &signs).map_err(|e| err(sp, e))?;
            if d1.is_zero() && fv.as_constant().is_none() {
                return Err(msg(sp, constant_operand(body, &var)));
            }
        }
        let d = calculus::diff_n(&fv, &wrt, n, &signs).map_err(|e| err(sp, e))?;
        self.carry(inner, &var, Scope::Free, sp)?;
        self.free_meaning(&d, &var).map_err(|e| err(sp, e))
    }

    /// The signs with `x` of unknown sign (it is a bound variable).
    fn signs_without(&self, x: AtomId) -> Assumptions {
        let mut s = self.signs.clone();
        s.set(x, Sign::Unknown);
        s.set_range(x, None);
        s
    }

    fn int(&mut self, args: &[Expr], sp: Span) -> Result<Rat, LowerError> {
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
                return self.int_body(b, body, sp);
            }
            let (fv, inner) = self.lower_in_scope(body, &[(var.clone(), Sign::Unknown)])?;
            let x = atom::sym(&var);
            let s = self.signs_without(x);
            let r = if self.is_time_var(&var) {
                let time = &self.env.time;
                let is_time = |b: &str| time.contains(b);
                calculus::time_antiderivative(&fv, x, &is_time, &s)
            } else {
                calculus::antiderivative(&fv, x, &s)
            }
            .map_err(|e| int_err(body.span, e))?;
            self.carry(inner, &var, Scope::Free, sp)?;
            return self.free_meaning(&r, &var).map_err(|e| err(sp, e));
        }
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
        let (Some(a), Some(b)) = (bounds.first().cloned(), bounds.get(1).cloned()) else {
            return Err(msg(sp, "missing bounds"));
        };
        let sign = self.range_sign(&a, &b);
        let (fv, inner) = self.lower_in_scope(body, &[(var.clone(), sign)])?;
        self.carry(inner, &var, Scope::Region, sp)?;
        let mut s = self.signs.clone();
        s.set(x, sign);
        s.set_range(x, None);
        if self.is_time_var(&var) {
            let time = &self.env.time;
            let is_time = |b: &str| time.contains(b);
            let big_f = calculus::time_antiderivative(&fv, x, &is_time, &s)
                .map_err(|e| int_err(body.span, e))?;
            let hi = self.at(&big_f, &var, &b).map_err(|e| err(sp, e))?;
            let lo = self.at(&big_f, &var, &a).map_err(|e| err(sp, e))?;
            return hi.sub(&lo).map_err(|e| err(sp, e));
        }
        let big_f = calculus::antiderivative_owned(fv, x, &s).map_err(|e| int_err(body.span, e))?;
        calculus::between_bounds(big_f, x, &a, &b, self.signs()).map_err(|e| err(sp, e))
    }

    /// `int(f, B)`: the coordinates are bound, each with the sign its range gives.
    fn int_body(&mut self, b: &Body, body: &Expr, sp: Span) -> Result<Rat, LowerError> {
        let vars = self.coordinate_signs(b);
        let (fv, inner) = self.lower_in_scope(body, &vars)?;
        // Conditions that mention a coordinate hold almost everywhere or fail (see carry).
        let mut rest = inner;
        for (name, _) in &vars {
            let x = atom::sym(name);
            let (here, other): (Vec<Divisor>, Vec<Divisor>) =
                rest.into_iter().partition(|d| depends_on(&d.value, x));
            self.carry(here, name, Scope::Region, sp)?;
            rest = other;
        }
        for d in rest {
            self.note(&d.value, d.need, d.span);
        }
        let mut s = self.signs.clone();
        for (name, sign) in &vars {
            s.set(atom::sym(name), *sign);
            s.set_range(atom::sym(name), None);
        }
        b.integrate(&fv, &s).map_err(|e| int_err(body.span, e))
    }

    /// Each coordinate of a body with the sign its range gives (abstract bodies: none).
    pub fn coordinate_signs(&mut self, b: &Body) -> Vec<(String, Sign)> {
        let mut out = Vec::new();
        match b {
            Body::Concrete { ranges, .. } => {
                let mut saved = Vec::new();
                for (v, lo, hi) in ranges {
                    let sign = self.range_sign(lo, hi);
                    saved.push(self.bind(*v, sign));
                    if let Some(n) = atom::sym_name(*v) {
                        out.push((n, sign));
                    }
                }
                for s in saved.into_iter().rev() {
                    self.unbind(s);
                }
            }
            Body::Abstract { coords, .. } => {
                out.extend(coords.iter().map(|c| (c.0.clone(), Sign::Unknown)));
            }
        }
        out
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
            // Coordinates are fresh: each knows only the sign its range gives, whatever
            // a declared symbol of the same name means.
            for (i, r) in ranges.iter().enumerate() {
                lw.bound = names[..i].to_vec();
                lw.bound.push(r.var.name.clone());
                let v = atom::sym(&r.var.name);
                lw.signs.set(v, Sign::Unknown);
                lw.signs.set_range(v, None);
                let from = lw.lower(&r.from)?;
                let to = lw.lower(&r.to)?;
                let sign = lw.range_sign(&from, &to);
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
                lw.signs.set(v, sign);
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

/// Why a derivative in Leibniz notation of something that does not vary with `var` is
/// refused: what to declare instead.
fn constant_operand(body: &Expr, var: &str) -> String {
    let mut names = Vec::new();
    symbol_names(body, &mut names);
    names.retain(|n| n != var);
    let what = match names.as_slice() {
        [one] => format!("`{one}`"),
        _ => format!("an expression in {}", names.join(", ")),
    };
    if var == "t" {
        let bases: Vec<&str> = names.iter().map(|n| n.trim_end_matches('\'')).collect();
        format!(
            "a derivative with respect to time of {what}, which as declared does not change with time: declare what changes with `time` (e.g. `time {}`)",
            bases.last().copied().unwrap_or("x")
        )
    } else {
        format!(
            "a derivative with respect to {var} of {what}, which as declared does not depend on {var}: rigor does not know it as a function of {var}"
        )
    }
}

/// The symbol names written in `e`, each once, in order.
fn symbol_names(e: &Expr, out: &mut Vec<String>) {
    match &e.kind {
        ExprKind::Sym(n) => {
            if !out.contains(n) {
                out.push(n.clone());
            }
        }
        ExprKind::Num(_) | ExprKind::Pi => {}
        ExprKind::Neg(a) => symbol_names(a, out),
        ExprKind::Bin(_, a, b) => {
            symbol_names(a, out);
            symbol_names(b, out);
        }
        ExprKind::Call(_, args) => args.iter().for_each(|a| symbol_names(a, out)),
    }
}
