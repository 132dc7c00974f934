//! Differential test (issue #14, item 7): random pairs of expressions, true by
//! construction (a random expression and a known rewrite of it: expanding, factoring,
//! combining fractions, radicals under the declared signs and ranges, trigonometric,
//! exponential and logarithmic identities, absolute values, small-quantity series) or
//! made false by one perturbation (a sign flipped, a factor changed, a term dropped).
//! Each pair is checked by `rigor::check_source` as a one-claim derivation, and the
//! verdict is compared with an independent evaluation: the guard's ball arithmetic
//! (`rigor::guard`, straight from the syntax tree, nothing of the normal forms) at
//! random points inside the declared signs and ranges, cross-checked against this
//! file's own `f64` evaluation of the generator's tree (so a printing slip cannot pass
//! for a wrong verdict).
//!
//! A wrong verdict (a true pair refuted, a pair that clearly differs at a valid point
//! verified) fails the test with the derivation that reproduces it. The counts are
//! printed (`cargo test --test it differential -- --nocapture`); the pairs are
//! deterministic (`DIFFERENTIAL_SEED` changes the seed, `PROPTEST_CASES` the number).

use foldhash::{HashMap, HashMapExt};
use rigor::check::{check_source, MemoryResolver, Options, Status};
use rigor::guard::{self, GuardEnv};
use rigor::syntax::ast::Expr;
use rigor::syntax::{parse_expr, ParseOptions};
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::time::Duration;

// ---------------------------------------------------------------- random numbers

/// splitmix64: small, fast, and the same sequence on every platform.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        rigor::guard::splitmix64(&mut self.0)
    }

    /// A whole number in `0..n`.
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    /// A whole number in `lo..=hi`.
    fn int(&mut self, lo: i64, hi: i64) -> i64 {
        lo + (self.next() % (hi - lo + 1) as u64) as i64
    }

    fn chance(&mut self, p: f64) -> bool {
        self.unit() < p
    }

    /// A float in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }

    fn pick<T: Copy>(&mut self, xs: &[T]) -> T {
        xs[self.below(xs.len())]
    }
}

// ---------------------------------------------------------------- symbols and signs

/// What a `symbols` line says about a symbol.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Decl {
    Pos,
    NonNeg,
    NonZero,
    Any,
    /// `lo < s < hi`, with the bounds as written.
    Range(f64, f64, &'static str, &'static str),
}

/// Ranges for plain symbols: wholly negative, wholly positive.
const RANGES: &[Decl] = &[
    Decl::Range(-3.0, -0.5, "-3", "-1/2"),
    Decl::Range(1.0, 3.0, "1", "3"),
];

const HALF_PI: f64 = std::f64::consts::FRAC_PI_2;
const PI: f64 = std::f64::consts::PI;

/// Ranges for angles, each fixing the signs of some of sin, cos and tan.
const ANGLE_RANGES: &[Decl] = &[
    Decl::Range(0.0, HALF_PI, "0", "pi/2"),
    Decl::Range(HALF_PI, PI, "pi/2", "pi"),
    Decl::Range(-HALF_PI, 0.0, "-pi/2", "0"),
    Decl::Range(0.0, PI, "0", "pi"),
    Decl::Range(-PI, 0.0, "-pi", "0"),
    Decl::Range(-HALF_PI, HALF_PI, "-pi/2", "pi/2"),
];

/// The symbols of one pair, with their declarations, and the small quantity if any.
#[derive(Clone, Debug)]
struct Scope {
    syms: Vec<(&'static str, Decl)>,
    small: Option<u32>,
}

const GENERIC: &[&str] = &["a", "b", "c", "x", "y"];
const ANGLES: &[&str] = &["beta", "gamma"];
const THETA: &str = "theta";

impl Scope {
    fn random(rng: &mut Rng) -> Scope {
        let mut syms = Vec::new();
        for (i, n) in GENERIC.iter().enumerate() {
            // `a` is always positive and `x` always free, so that every kind of
            // identity has a symbol to work with; the others take random signs.
            let d = match (i, rng.below(7)) {
                (0, _) => Decl::Pos,
                (3, _) => Decl::Any,
                (_, 0 | 1) => Decl::Pos,
                (_, 2) => Decl::NonNeg,
                (_, 3) => Decl::NonZero,
                (_, 4) => Decl::Any,
                _ => rng.pick(RANGES),
            };
            syms.push((*n, d));
        }
        for n in ANGLES {
            let d = if rng.chance(0.3) {
                Decl::Any
            } else {
                rng.pick(ANGLE_RANGES)
            };
            syms.push((*n, d));
        }
        Scope { syms, small: None }
    }

    fn decl(&self, n: &str) -> Decl {
        self.syms
            .iter()
            .find(|(m, _)| *m == n)
            .map_or(Decl::Any, |(_, d)| *d)
    }

    /// Names with a declaration that `ok` accepts.
    fn names(&self, ok: impl Fn(Decl) -> bool) -> Vec<&'static str> {
        self.syms
            .iter()
            .filter(|(_, d)| ok(*d))
            .map(|(n, _)| *n)
            .collect()
    }

    /// The declarations, one `symbols` line each.
    fn header(&self) -> String {
        let mut s = String::new();
        for (n, d) in &self.syms {
            let line = match d {
                Decl::Pos => format!("symbols {n} > 0"),
                Decl::NonNeg => format!("symbols {n} >= 0"),
                Decl::NonZero => format!("symbols {n} != 0"),
                Decl::Any => format!("symbols {n}"),
                Decl::Range(_, _, lo, hi) => format!("symbols {lo} < {n} < {hi}"),
            };
            s.push_str(&line);
            s.push('\n');
        }
        if let Some(order) = self.small {
            s.push_str("symbols theta\n");
            if order == 1 {
                s.push_str("small theta\n");
            } else {
                let _ = writeln!(s, "small theta to order {order}");
            }
        }
        s
    }

    /// A random point inside the declarations (`theta` is set by the caller).
    fn point(&self, rng: &mut Rng) -> HashMap<String, f64> {
        let mut p = HashMap::new();
        for (n, d) in &self.syms {
            let mag = 0.3 + 3.7 * rng.unit();
            let v = match d {
                Decl::Pos => mag,
                Decl::NonNeg if rng.chance(0.1) => 0.0,
                Decl::NonNeg => mag,
                Decl::NonZero if rng.chance(0.5) => -mag,
                Decl::NonZero => mag,
                Decl::Any => 8.0 * rng.unit() - 4.0,
                Decl::Range(lo, hi, _, _) => lo + (hi - lo) * (0.02 + 0.96 * rng.unit()),
            };
            p.insert(n.to_string(), v);
        }
        p
    }
}

/// What this file's generator knows about the sign of an expression.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Sg {
    Pos,
    NonNeg,
    Neg,
    NonZero,
    Any,
}

impl Sg {
    fn nonneg(self) -> bool {
        matches!(self, Sg::Pos | Sg::NonNeg)
    }
    fn nonzero(self) -> bool {
        matches!(self, Sg::Pos | Sg::Neg | Sg::NonZero)
    }
    fn neg(self) -> Sg {
        match self {
            Sg::Pos => Sg::Neg,
            Sg::Neg => Sg::Pos,
            Sg::NonZero => Sg::NonZero,
            _ => Sg::Any,
        }
    }
}

fn decl_sign(d: Decl) -> Sg {
    match d {
        Decl::Pos => Sg::Pos,
        Decl::NonNeg => Sg::NonNeg,
        Decl::NonZero => Sg::NonZero,
        Decl::Any => Sg::Any,
        Decl::Range(lo, _, _, _) if lo >= 0.0 => Sg::Pos,
        Decl::Range(_, hi, _, _) if hi <= 0.0 => Sg::Neg,
        Decl::Range(..) => Sg::Any,
    }
}

// ---------------------------------------------------------------- the expression tree

#[derive(Clone, Copy, Debug, PartialEq)]
enum Fun {
    Sqrt,
    Sin,
    Cos,
    Tan,
    Exp,
    Ln,
    Abs,
}

impl Fun {
    fn name(self) -> &'static str {
        match self {
            Fun::Sqrt => "sqrt",
            Fun::Sin => "sin",
            Fun::Cos => "cos",
            Fun::Tan => "tan",
            Fun::Exp => "exp",
            Fun::Ln => "ln",
            Fun::Abs => "abs",
        }
    }
}

/// The generator's own expressions: printed for rigor, evaluated here in `f64`.
#[derive(Clone, Debug, PartialEq)]
enum E {
    /// `n/d`, `d > 0`.
    Num(i64, i64),
    Pi,
    Sym(&'static str),
    Neg(Box<E>),
    Add(Box<E>, Box<E>),
    Sub(Box<E>, Box<E>),
    Mul(Box<E>, Box<E>),
    Div(Box<E>, Box<E>),
    /// `base^(p/q)`, `q > 0`.
    Pow(Box<E>, i64, i64),
    F(Fun, Box<E>),
}

fn n(k: i64) -> E {
    E::Num(k, 1)
}
fn q(a: i64, b: i64) -> E {
    E::Num(a, b)
}
fn s(name: &'static str) -> E {
    E::Sym(name)
}
fn neg(a: E) -> E {
    E::Neg(Box::new(a))
}
fn add(a: E, b: E) -> E {
    E::Add(Box::new(a), Box::new(b))
}
fn sub(a: E, b: E) -> E {
    E::Sub(Box::new(a), Box::new(b))
}
fn mul(a: E, b: E) -> E {
    E::Mul(Box::new(a), Box::new(b))
}
fn div(a: E, b: E) -> E {
    E::Div(Box::new(a), Box::new(b))
}
fn pow(a: E, k: i64) -> E {
    E::Pow(Box::new(a), k, 1)
}
fn powq(a: E, p: i64, r: i64) -> E {
    E::Pow(Box::new(a), p, r)
}
fn f(g: Fun, a: E) -> E {
    E::F(g, Box::new(a))
}
fn sqrt(a: E) -> E {
    f(Fun::Sqrt, a)
}
fn sin(a: E) -> E {
    f(Fun::Sin, a)
}
fn cos(a: E) -> E {
    f(Fun::Cos, a)
}
fn tan(a: E) -> E {
    f(Fun::Tan, a)
}
fn exp(a: E) -> E {
    f(Fun::Exp, a)
}
fn ln(a: E) -> E {
    f(Fun::Ln, a)
}
fn abs(a: E) -> E {
    f(Fun::Abs, a)
}
fn sum(terms: Vec<E>) -> E {
    let mut it = terms.into_iter();
    let first = it.next().unwrap_or(n(0));
    it.fold(first, |acc, t| match t {
        E::Neg(x) => E::Sub(Box::new(acc), x),
        t => add(acc, t),
    })
}
fn product(factors: Vec<E>) -> E {
    let mut it = factors.into_iter();
    let first = it.next().unwrap_or(n(1));
    it.fold(first, mul)
}

impl E {
    /// Binding strength for printing: sums 1, products 2, powers and atoms 4.
    fn prec(&self) -> u8 {
        match self {
            E::Add(..) | E::Sub(..) => 1,
            E::Mul(..) | E::Div(..) => 2,
            E::Neg(_) => 3,
            E::Num(k, d) if *k < 0 || *d != 1 => 3,
            _ => 4,
        }
    }

    fn print(&self) -> String {
        let wrap = |e: &E, min: u8| {
            if e.prec() < min {
                format!("({})", e.print())
            } else {
                e.print()
            }
        };
        let base = |e: &E| {
            if e.prec() < 4 || matches!(e, E::Pow(..)) {
                format!("({})", e.print())
            } else {
                e.print()
            }
        };
        match self {
            E::Num(k, 1) if *k >= 0 => k.to_string(),
            E::Num(k, 1) => format!("({k})"),
            E::Num(k, d) => format!("({k}/{d})"),
            E::Pi => "pi".into(),
            E::Sym(s) => (*s).into(),
            E::Neg(a) => format!("-{}", wrap(a, 4)),
            E::Add(a, b) => format!("{} + {}", wrap(a, 1), wrap(b, 2)),
            E::Sub(a, b) => format!("{} - {}", wrap(a, 1), wrap(b, 2)),
            E::Mul(a, b) => {
                // A quotient on the left is parenthesised: `(a/2) b`, never `a/2 b`.
                let l = if matches!(**a, E::Div(..)) {
                    format!("({})", a.print())
                } else {
                    wrap(a, 2)
                };
                let r = wrap(b, 4);
                if r.starts_with(|c: char| c.is_ascii_alphabetic() || c == '(') {
                    format!("{l} {r}")
                } else {
                    format!("{l} * {r}")
                }
            }
            E::Div(a, b) => format!("{}/{}", wrap(a, 2), wrap(b, 4)),
            // `^` is right-associative: a power as a base is parenthesised.
            E::Pow(a, p, 1) if *p >= 0 => format!("{}^{p}", base(a)),
            E::Pow(a, p, r) => {
                let e = if *r == 1 {
                    format!("({p})")
                } else {
                    format!("({p}/{r})")
                };
                format!("{}^{e}", base(a))
            }
            E::F(g, a) => format!("{}({})", g.name(), a.print()),
        }
    }

    /// The value at `pt` in plain `f64`, `None` outside the domain.
    fn val(&self, pt: &HashMap<String, f64>) -> Option<f64> {
        let v = match self {
            E::Num(k, d) => *k as f64 / *d as f64,
            E::Pi => PI,
            E::Sym(s) => *pt.get(*s)?,
            E::Neg(a) => -a.val(pt)?,
            E::Add(a, b) => a.val(pt)? + b.val(pt)?,
            E::Sub(a, b) => a.val(pt)? - b.val(pt)?,
            E::Mul(a, b) => a.val(pt)? * b.val(pt)?,
            E::Div(a, b) => {
                let d = b.val(pt)?;
                if d == 0.0 {
                    return None;
                }
                a.val(pt)? / d
            }
            E::Pow(a, p, r) => {
                let x = a.val(pt)?;
                if x == 0.0 && *p <= 0 {
                    return None;
                }
                let root = match *r {
                    1 => x,
                    r if r % 2 == 1 => x.signum() * x.abs().powf(1.0 / r as f64),
                    _ if x < 0.0 => return None,
                    r => x.powf(1.0 / r as f64),
                };
                root.powi(i32::try_from(*p).ok()?)
            }
            E::F(g, a) => {
                let x = a.val(pt)?;
                match g {
                    Fun::Sqrt if x < 0.0 => return None,
                    Fun::Sqrt => x.sqrt(),
                    Fun::Sin => x.sin(),
                    Fun::Cos => x.cos(),
                    Fun::Tan => x.tan(),
                    Fun::Exp => x.exp(),
                    Fun::Ln if x <= 0.0 => return None,
                    Fun::Ln => x.ln(),
                    Fun::Abs => x.abs(),
                }
            }
        };
        v.is_finite().then_some(v)
    }

    /// What the declarations make of its sign (sound, not complete).
    fn sign(&self, sc: &Scope) -> Sg {
        match self {
            E::Num(k, _) if *k > 0 => Sg::Pos,
            E::Num(k, _) if *k < 0 => Sg::Neg,
            E::Num(..) => Sg::NonNeg,
            E::Pi => Sg::Pos,
            E::Sym(n) => decl_sign(sc.decl(n)),
            E::Neg(a) => a.sign(sc).neg(),
            E::Add(a, b) => match (a.sign(sc), b.sign(sc)) {
                (Sg::Pos, x) | (x, Sg::Pos) if x.nonneg() => Sg::Pos,
                (Sg::NonNeg, Sg::NonNeg) => Sg::NonNeg,
                (Sg::Neg, Sg::Neg) => Sg::Neg,
                _ => Sg::Any,
            },
            E::Sub(a, b) => add((**a).clone(), neg((**b).clone())).sign(sc),
            E::Mul(a, b) | E::Div(a, b) => {
                let (x, y) = (a.sign(sc), b.sign(sc));
                let nonzero = x.nonzero() && y.nonzero();
                let pos = |s: Sg| s == Sg::Pos;
                let negs = |s: Sg| s == Sg::Neg;
                match () {
                    _ if (pos(x) && pos(y)) || (negs(x) && negs(y)) => Sg::Pos,
                    _ if (pos(x) && negs(y)) || (negs(x) && pos(y)) => Sg::Neg,
                    _ if x.nonneg() && y.nonneg() && matches!(self, E::Mul(..)) => Sg::NonNeg,
                    _ if nonzero => Sg::NonZero,
                    _ => Sg::Any,
                }
            }
            E::Pow(a, p, r) => {
                let x = a.sign(sc);
                if *r % 2 == 0 {
                    // Even roots: defined only for a nonnegative base.
                    return if x == Sg::Pos { Sg::Pos } else { Sg::NonNeg };
                }
                match (x, p % 2 == 0) {
                    (x, true) if x.nonzero() => Sg::Pos,
                    (_, true) => Sg::NonNeg,
                    (Sg::NonNeg, false) => Sg::NonNeg,
                    (x, false) => x,
                }
            }
            E::F(g, a) => match g {
                Fun::Sqrt if a.sign(sc) == Sg::Pos => Sg::Pos,
                Fun::Sqrt => Sg::NonNeg,
                Fun::Exp => Sg::Pos,
                Fun::Abs if a.sign(sc).nonzero() => Sg::Pos,
                Fun::Abs => Sg::NonNeg,
                _ => Sg::Any,
            },
        }
    }

    fn size(&self) -> usize {
        match self {
            E::Num(..) | E::Pi | E::Sym(_) => 1,
            E::Neg(a) | E::Pow(a, _, _) | E::F(_, a) => 1 + a.size(),
            E::Add(a, b) | E::Sub(a, b) | E::Mul(a, b) | E::Div(a, b) => 1 + a.size() + b.size(),
        }
    }

    /// The tree with its `k`-th node (pre-order) replaced by `g(node)`.
    fn map_at(&self, k: &mut usize, g: &dyn Fn(&E) -> E) -> E {
        if *k == 0 {
            *k = usize::MAX;
            return g(self);
        }
        *k = k.wrapping_sub(1);
        let b = |x: &E, k: &mut usize| Box::new(x.map_at(k, g));
        match self {
            E::Num(..) | E::Pi | E::Sym(_) => self.clone(),
            E::Neg(a) => E::Neg(b(a, k)),
            E::Pow(a, p, r) => E::Pow(b(a, k), *p, *r),
            E::F(h, a) => E::F(*h, b(a, k)),
            E::Add(x, y) => {
                let x = b(x, k);
                E::Add(x, b(y, k))
            }
            E::Sub(x, y) => {
                let x = b(x, k);
                E::Sub(x, b(y, k))
            }
            E::Mul(x, y) => {
                let x = b(x, k);
                E::Mul(x, b(y, k))
            }
            E::Div(x, y) => {
                let x = b(x, k);
                E::Div(x, b(y, k))
            }
        }
    }
}

/// The terms of `e` with products of sums multiplied out and small powers of sums
/// expanded; everything else (quotients' denominators, functions) is kept whole.
fn expand(e: &E) -> Vec<E> {
    match e {
        E::Add(a, b) => [expand(a), expand(b)].concat(),
        E::Sub(a, b) => {
            let mut t = expand(a);
            t.extend(expand(b).into_iter().map(negate));
            t
        }
        E::Neg(a) => expand(a).into_iter().map(negate).collect(),
        E::Mul(a, b) => {
            let (x, y) = (expand(a), expand(b));
            let mut out = Vec::new();
            for u in &x {
                for v in &y {
                    out.push(times(u, v));
                }
            }
            out
        }
        E::Div(a, d) => expand(a)
            .into_iter()
            .map(|t| match t {
                E::Neg(t) => neg(div(*t, (**d).clone())),
                t => div(t, (**d).clone()),
            })
            .collect(),
        E::Pow(a, k, 1) if (2..=3).contains(k) && matches!(**a, E::Add(..) | E::Sub(..)) => {
            let factors = vec![(**a).clone(); *k as usize];
            expand(&product(factors))
        }
        _ => vec![e.clone()],
    }
}

fn negate(t: E) -> E {
    match t {
        E::Neg(x) => *x,
        t => neg(t),
    }
}

/// The product of two terms, a sign in front.
fn times(u: &E, v: &E) -> E {
    match (u, v) {
        (E::Neg(a), E::Neg(b)) => mul((**a).clone(), (**b).clone()),
        (E::Neg(a), b) | (b, E::Neg(a)) => neg(mul((**a).clone(), b.clone())),
        (a, b) => mul(a.clone(), b.clone()),
    }
}

mod oracle;
mod pairs;
