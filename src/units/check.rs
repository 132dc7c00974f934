//! Dimensions through expressions as written: time derivatives divide by s, `diff`
//! divides and `int` multiplies by the variable's unit, bodies' coordinates take the
//! units of their bounds, roots divide exponents, and `sin`, `cos`, `tan`, `exp`, `ln`
//! need dimensionless arguments. A literal 0 has every dimension.

use super::Dim;
use crate::syntax::ast::{BinOp, BodyDef, Expr, ExprKind, Func, Span};
use foldhash::{HashMap, HashSet};
use num_rational::BigRational;
use num_traits::{One, Zero};

/// The dimension of a value: a literal zero goes with anything.
// `Any` is the rare case; boxing the common one would cost an allocation per node.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum DimV {
    /// 0, which has every dimension.
    Any,
    /// A dimension.
    D(Dim),
}

impl DimV {
    fn map(self, f: impl FnOnce(Dim) -> Dim) -> DimV {
        match self {
            DimV::Any => DimV::Any,
            DimV::D(d) => DimV::D(f(d)),
        }
    }

    /// Whether the two can be equal (or added).
    pub fn agrees(&self, o: &DimV) -> bool {
        match (self, o) {
            (DimV::D(a), DimV::D(b)) => a.same(b),
            _ => true,
        }
    }
}

/// What the units of a file say.
pub struct UnitEnv<'a> {
    /// Declared units of symbols.
    pub units: &'a HashMap<String, Dim>,
    /// `let` definitions as written.
    pub defs: &'a HashMap<String, Expr>,
    /// Bodies as declared.
    pub bodies: &'a HashMap<String, BodyDef>,
    /// Base names of `time` symbols.
    pub time: &'a HashSet<String>,
}

/// A unit inconsistency, at a span.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnitProblem {
    /// Where.
    pub span: Span,
    /// What (a sentence naming both units).
    pub message: String,
    /// A hint, if one factor explains the difference.
    pub note: Option<String>,
}

/// The dimension of `e`. `Err` for an inconsistency inside it; symbols without a
/// unit are collected in `missing` (their dimension taken as 1).
pub fn dim_of(e: &Expr, env: &UnitEnv<'_>, missing: &mut Vec<String>) -> Result<DimV, UnitProblem> {
    dim_and_scales(e, env, missing, &mut Vec::new())
}

/// [`dim_of`], also collecting sums of one dimension in different scales (`L` in mm
/// added to `R` in m): consistent, but a likely slip.
pub fn dim_and_scales(
    e: &Expr,
    env: &UnitEnv<'_>,
    missing: &mut Vec<String>,
    mixed: &mut Vec<UnitProblem>,
) -> Result<DimV, UnitProblem> {
    let mut w = Walk {
        env,
        bound: Vec::new(),
        missing,
        mixed,
        depth: 0,
    };
    w.dim(e)
}

/// What a quantity of this dimension usually is.
pub fn describe(d: &Dim) -> Option<&'static str> {
    let s = d.si().to_string();
    Some(match s.as_str() {
        "m" => "a length",
        "s" => "a time",
        "kg" => "a mass",
        "m/s" => "a speed",
        "m/s²" => "an acceleration",
        "kg·m/s²" => "a force",
        "kg·m²" => "a moment of inertia",
        "1/s" => "an angular speed",
        "1/s²" => "an angular acceleration",
        "m²" => "an area",
        "kg·m²/s²" => "an energy or a moment",
        _ => return None,
    })
}

/// Two sides that should agree: the message and, where one factor explains it, a hint.
pub fn mismatch(span: Span, what: &str, a: &Dim, b: &Dim) -> UnitProblem {
    let ratio = a.div(b).si();
    let nonzero = ratio.exp.iter().filter(|e| !e.is_zero()).count();
    let note = (nonzero == 1).then(|| {
        let kind = describe(&ratio).map_or_else(String::new, |k| format!(": {k}?"));
        format!("the left side has an extra factor with unit {ratio}{kind}")
    });
    UnitProblem {
        span,
        message: format!(
            "{what}: the left side is in {a}, the right side in {b}",
            a = a.si(),
            b = b.si()
        ),
        note,
    }
}

struct Walk<'a, 'm> {
    env: &'a UnitEnv<'a>,
    bound: Vec<(String, DimV)>,
    missing: &'m mut Vec<String>,
    mixed: &'m mut Vec<UnitProblem>,
    depth: usize,
}

fn seconds() -> Dim {
    Dim::base(2)
}

impl Walk<'_, '_> {
    fn symbol(&mut self, name: &str) -> Result<DimV, UnitProblem> {
        if let Some((_, d)) = self.bound.iter().rev().find(|(n, _)| n == name) {
            return Ok(d.clone());
        }
        if let Some(def) = self.env.defs.get(name) {
            let saved = std::mem::take(&mut self.bound);
            let r = self.dim(def);
            self.bound = saved;
            return r;
        }
        if name == "t" {
            return Ok(DimV::D(seconds()));
        }
        let base = name.trim_end_matches('\'');
        let primes = name.len() - base.len();
        if let Some(d) = self.env.units.get(base) {
            let per = seconds().pow(&BigRational::from_integer((primes as i64).into()));
            return Ok(DimV::D(d.div(&per)));
        }
        if !self.missing.iter().any(|m| m == base) {
            self.missing.push(base.to_string());
        }
        Ok(DimV::D(Dim::one()))
    }

    fn dim(&mut self, e: &Expr) -> Result<DimV, UnitProblem> {
        self.depth += 1;
        if self.depth > 500 {
            return Ok(DimV::Any);
        }
        let r = self.dim_node(e);
        self.depth -= 1;
        r
    }

    fn dim_node(&mut self, e: &Expr) -> Result<DimV, UnitProblem> {
        match &e.kind {
            ExprKind::Num(q) if q.is_zero() => Ok(DimV::Any),
            ExprKind::Num(_) | ExprKind::Pi => Ok(DimV::D(Dim::one())),
            ExprKind::Sym(n) => self.symbol(n),
            ExprKind::Neg(a) => self.dim(a),
            ExprKind::Bin(op, a, b) => self.binary(*op, a, b, e.span),
            ExprKind::Call(f, args) => self.call(*f, args, e.span),
        }
    }

    fn binary(&mut self, op: BinOp, a: &Expr, b: &Expr, span: Span) -> Result<DimV, UnitProblem> {
        if op == BinOp::Pow {
            return self.power(a, b);
        }
        let (x, y) = (self.dim(a)?, self.dim(b)?);
        Ok(match op {
            BinOp::Add | BinOp::Sub => match (&x, &y) {
                (DimV::D(p), DimV::D(q)) if !p.same(q) => {
                    let what = if op == BinOp::Add {
                        "a sum"
                    } else {
                        "a difference"
                    };
                    return Err(UnitProblem {
                        span,
                        message: format!(
                            "{what} of quantities in different units: {} and {}",
                            p.si(),
                            q.si()
                        ),
                        note: None,
                    });
                }
                (DimV::D(p), DimV::D(q)) if p.scale != q.scale => {
                    self.mixed.push(UnitProblem {
                        span,
                        message: format!(
                            "a sum of the same kind of quantity in different scales: {} and {} times {}",
                            p.scale,
                            q.scale,
                            p.si()
                        ),
                        note: Some("convert one of them (mm to m is a factor 1/1000)".into()),
                    });
                    x
                }
                (DimV::Any, _) => y,
                _ => x,
            },
            BinOp::Mul => match (x, y) {
                (DimV::D(p), DimV::D(q)) => DimV::D(p.mul(&q)),
                _ => DimV::Any,
            },
            _ => match (x, y) {
                (DimV::D(p), DimV::D(q)) => DimV::D(p.div(&q)),
                _ => DimV::Any,
            },
        })
    }

    fn power(&mut self, a: &Expr, b: &Expr) -> Result<DimV, UnitProblem> {
        let base = self.dim(a)?;
        if let Some(p) = constant(b) {
            return Ok(base.map(|d| d.pow(&p)));
        }
        let exp = self.dim(b)?;
        self.dimensionless(&exp, b.span, "an exponent")?;
        self.dimensionless(&base, a.span, "the base of a symbolic power")?;
        Ok(DimV::D(Dim::one()))
    }

    fn dimensionless(&self, d: &DimV, span: Span, what: &str) -> Result<(), UnitProblem> {
        match d {
            DimV::D(x) if !x.is_one() => Err(UnitProblem {
                span,
                message: format!("{what} must be dimensionless, but it is in {}", x.si()),
                note: describe(x).map(|k| format!("it is {k}")),
            }),
            _ => Ok(()),
        }
    }

    fn call(&mut self, f: Func, args: &[Expr], span: Span) -> Result<DimV, UnitProblem> {
        let arg = |i: usize| {
            args.get(i).ok_or(UnitProblem {
                span,
                message: "a missing argument".into(),
                note: None,
            })
        };
        match f {
            Func::Sqrt => Ok(self
                .dim(arg(0)?)?
                .map(|d| d.pow(&BigRational::new(1.into(), 2.into())))),
            Func::Abs => self.dim(arg(0)?),
            Func::Sin | Func::Cos | Func::Tan | Func::Exp | Func::Ln => {
                let a = arg(0)?;
                let d = self.dim(a)?;
                self.dimensionless(&d, a.span, &format!("the argument of {}", f.name()))?;
                Ok(DimV::D(Dim::one()))
            }
            Func::Int => self.int(args, span),
            Func::Diff => {
                let var = var_name(arg(1)?);
                let unit = self.var_unit(&var, None)?;
                let n = args
                    .get(2)
                    .and_then(constant)
                    .unwrap_or_else(BigRational::one);
                let fd = self.bind(&var, unit.clone(), arg(0)?)?;
                Ok(match (fd, unit) {
                    (DimV::D(a), DimV::D(u)) => DimV::D(a.div(&u.pow(&n))),
                    _ => DimV::Any,
                })
            }
            Func::Subs | Func::Eval => {
                let var = var_name(arg(1)?);
                let mut v = self.dim(arg(2)?)?;
                if f == Func::Eval {
                    let w = self.dim(arg(3)?)?;
                    self.same_bounds(&v, &w, span)?;
                    if v == DimV::Any {
                        v = w;
                    }
                }
                // A variable set to 0 has whatever unit it needs.
                let unit = match v {
                    DimV::Any => DimV::Any,
                    v => self.var_unit(&var, Some(v))?,
                };
                self.bind(&var, unit, arg(0)?)
            }
        }
    }

    fn same_bounds(&self, a: &DimV, b: &DimV, span: Span) -> Result<(), UnitProblem> {
        match (a, b) {
            (DimV::D(x), DimV::D(y)) if !x.same(y) => Err(UnitProblem {
                span,
                message: format!(
                    "the two limits are in different units: {} and {}",
                    x.si(),
                    y.si()
                ),
                note: None,
            }),
            _ => Ok(()),
        }
    }

    /// The unit of a bound variable: from a value it takes, else the declared symbol's.
    fn var_unit(&mut self, var: &str, from: Option<DimV>) -> Result<DimV, UnitProblem> {
        match from {
            Some(DimV::D(d)) => Ok(DimV::D(d)),
            _ => self.symbol(var),
        }
    }

    fn bind(&mut self, var: &str, d: DimV, body: &Expr) -> Result<DimV, UnitProblem> {
        self.bound.push((var.to_string(), d));
        let r = self.dim(body);
        self.bound.pop();
        r
    }

    fn int(&mut self, args: &[Expr], span: Span) -> Result<DimV, UnitProblem> {
        let (Some(body), Some(second)) = (args.first(), args.get(1)) else {
            return Ok(DimV::Any);
        };
        let var = var_name(second);
        if args.len() == 2 {
            let name =
                if var == "dm" && !self.env.bodies.contains_key("dm") && self.env.bodies.len() == 1
                {
                    self.env.bodies.keys().next().cloned().unwrap_or_default()
                } else {
                    var.clone()
                };
            if let Some(b) = self.env.bodies.get(&name).cloned() {
                return self.body(&b, body);
            }
            let unit = self.symbol(&var)?;
            let f = self.bind(&var, unit.clone(), body)?;
            return Ok(times(f, unit));
        }
        let (lo, hi) = match (args.get(2), args.get(3)) {
            (Some(a), Some(b)) => (self.dim(a)?, self.dim(b)?),
            _ => return Ok(DimV::Any),
        };
        self.same_bounds(&lo, &hi, span)?;
        let known = if lo == DimV::Any { hi } else { lo };
        let unit = self.var_unit(&var, Some(known))?;
        let f = self.bind(&var, unit.clone(), body)?;
        Ok(times(f, unit))
    }

    /// `int(f, B)`: coordinates in the units of their bounds, times the mass element.
    fn body(&mut self, b: &BodyDef, f: &Expr) -> Result<DimV, UnitProblem> {
        let n = self.bound.len();
        let r = (|| match b {
            BodyDef::Concrete { dm, ranges } => {
                for r in ranges {
                    let (lo, hi) = (self.dim(&r.from)?, self.dim(&r.to)?);
                    self.same_bounds(&lo, &hi, r.from.span.to(r.to.span))?;
                    let u = if lo == DimV::Any { hi } else { lo };
                    let u = self.var_unit(&r.var.name, Some(u))?;
                    self.bound.push((format!("d{}", r.var.name), u.clone()));
                    self.bound.push((r.var.name.clone(), u));
                }
                let mass = self.dim(dm)?;
                Ok(times(self.dim(f)?, mass))
            }
            BodyDef::Abstract { mass, coords, .. } => {
                for c in coords {
                    self.bound.push((c.name.clone(), DimV::D(Dim::base(1))));
                }
                let m = self.dim(mass)?;
                Ok(times(self.dim(f)?, m))
            }
        })();
        self.bound.truncate(n);
        r
    }
}

fn times(a: DimV, b: DimV) -> DimV {
    match (a, b) {
        (DimV::D(x), DimV::D(y)) => DimV::D(x.mul(&y)),
        _ => DimV::Any,
    }
}

fn var_name(e: &Expr) -> String {
    match &e.kind {
        ExprKind::Sym(n) => n.clone(),
        _ => String::new(),
    }
}

/// The exact value of a tree of numbers and `+ − · /` (an exponent as written).
fn constant(e: &Expr) -> Option<BigRational> {
    match &e.kind {
        ExprKind::Num(q) => Some(q.clone()),
        ExprKind::Neg(a) => Some(-constant(a)?),
        ExprKind::Bin(op, a, b) => {
            let (x, y) = (constant(a)?, constant(b)?);
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
