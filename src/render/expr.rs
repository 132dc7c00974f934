//! LaTeX of syntax-tree expressions and relation chains as written (never simplified),
//! with the fewest parentheses that keep the written meaning.
//!
//! Precedence, loosest first: `+ -`, then `* /` and juxtaposition, then unary minus,
//! then `^`. Division prints as `\frac`, so it never needs parentheses except as
//! the base of a power. Factors are separated by `\,` (a plain space after a number,
//! `\cdot` before a number). Every output has balanced braces, and nesting deeper than
//! [`MAX_DEPTH`] prints as `\cdots`, so pdflatex never runs out of grouping levels.

use crate::normal::print::symbol_latex;
use crate::syntax::ast::{BinOp, Chain, Expr, ExprKind, File, Func, Item, RelOp, StmtKind};
use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

/// The deepest nesting of sub-expressions rendered; deeper parts print as `\cdots`.
/// Sums and products of many terms do not count as nesting.
pub const MAX_DEPTH: usize = 40;

/// A non-integer number whose decimal needs more digits after the point than this
/// prints in scientific notation (`1.5 \times 10^{-20}`).
const MAX_DECIMALS: usize = 12;

/// What the renderer knows about the file an expression comes from.
///
/// `int(f, B)` is an integral over a body, `int(f, x)` an antiderivative, and the two
/// cannot be told apart from the expression alone. With [`Ctx::bodies`] set (see
/// [`Ctx::from_file`]) a two-argument `int` is over a body exactly when its second
/// argument is `dm` or a declared body. Without it ([`Ctx::default`]) a heuristic
/// decides: the second argument is a body when it is `dm`, starts with an uppercase
/// letter, or is not a variable-like name (a single lowercase letter or a lowercase
/// Greek letter name, optionally with a subscript or primes) — so `rod` and `B` are
/// bodies, and `x`, `x_1` and `theta` are variables.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Ctx {
    /// The declared bodies, if known.
    pub bodies: Option<Vec<String>>,
    /// Symbols that are differentials of body coordinates (`dy` for the coordinate
    /// `y`); they print as `dy`, `d\theta` rather than as one two-letter symbol.
    pub differentials: Vec<String>,
}

impl Ctx {
    /// The context of a file: its bodies and the differentials of their coordinates.
    pub fn from_file(file: &File) -> Ctx {
        let mut bodies = Vec::new();
        let mut differentials = Vec::new();
        for item in &file.items {
            if let Item::Stmt(stmt) = item {
                if let StmtKind::Body { name, def } = &stmt.kind {
                    bodies.push(name.name.clone());
                    if let crate::syntax::ast::BodyDef::Concrete { ranges, .. } = def {
                        for r in ranges {
                            differentials.push(format!("d{}", r.var.name));
                        }
                    }
                }
            }
        }
        Ctx {
            bodies: Some(bodies),
            differentials,
        }
    }

    /// Whether the second argument `name` of a two-argument `int` names a body.
    fn is_body(&self, name: &str) -> bool {
        if name == "dm" {
            return true;
        }
        match &self.bodies {
            Some(bodies) => bodies.iter().any(|b| b == name),
            None => !variable_like(name),
        }
    }
}

/// Lowercase Greek letter names (a variable may be one of these).
const GREEK_LOWER: &[&str] = &[
    "alpha", "beta", "gamma", "delta", "epsilon", "zeta", "eta", "theta", "iota", "kappa",
    "lambda", "mu", "nu", "xi", "rho", "sigma", "tau", "upsilon", "phi", "chi", "psi", "omega",
];

/// A single lowercase letter or lowercase Greek name, with optional subscript and primes.
fn variable_like(name: &str) -> bool {
    let name = name.trim_end_matches('\'');
    let base = name.split('_').next().unwrap_or("");
    let mut chars = base.chars();
    let single_lower =
        matches!((chars.next(), chars.next()), (Some(c), None) if c.is_ascii_lowercase());
    single_lower || GREEK_LOWER.contains(&base)
}

/// The LaTeX of an expression as written, with the default (heuristic) [`Ctx`].
pub fn expr_latex(e: &Expr) -> String {
    expr_latex_in(e, &Ctx::default())
}

/// The LaTeX of an expression as written, in the context of its file.
pub fn expr_latex_in(e: &Expr, ctx: &Ctx) -> String {
    Printer { ctx }.expr(e, 0, true)
}

/// The LaTeX of a relation chain `a = b \leq c` (justifications are not printed).
pub fn chain_latex(c: &Chain) -> String {
    chain_latex_in(c, &Ctx::default())
}

/// The LaTeX of a relation chain, in the context of its file.
pub fn chain_latex_in(c: &Chain, ctx: &Ctx) -> String {
    let mut out = expr_latex_in(&c.first, ctx);
    for link in &c.links {
        out.push(' ');
        out.push_str(rel_latex(link.op));
        out.push(' ');
        out.push_str(&expr_latex_in(&link.rhs, ctx));
    }
    out
}

/// The LaTeX of a relation operator: `=`, `\neq`, `<`, `\leq`, `>`, `\geq`, `\approx`.
pub fn rel_latex(op: RelOp) -> &'static str {
    match op {
        RelOp::Eq => "=",
        RelOp::Ne => "\\neq",
        RelOp::Lt => "<",
        RelOp::Le => "\\leq",
        RelOp::Gt => ">",
        RelOp::Ge => "\\geq",
        RelOp::Approx => "\\approx",
    }
}

/// The LaTeX of a symbol name (Greek letters, subscripts, primes as dots). Characters
/// other than ASCII letters, digits, `_` and `'` are dropped, so the result is always
/// valid LaTeX.
pub fn symbol(name: &str) -> String {
    let clean: String = name
        .chars()
        .filter(|c| c.is_ascii_alphanumeric() || *c == '_' || *c == '\'')
        .collect();
    if clean.is_empty() {
        return "?".to_string();
    }
    symbol_latex(&clean)
}

/// The LaTeX of an exact number: an integer as written, a number whose denominator
/// divides a power of ten as a decimal (`71/100` → `0.71`; scientific notation past
/// twelve decimals), any other as `\frac`.
pub fn number_latex(q: &BigRational) -> String {
    let neg = q.is_negative();
    let q = q.abs();
    let body = if q.is_integer() {
        q.numer().to_string()
    } else if let Some(k) = decimal_places(q.denom()) {
        let scaled = q.numer() * BigInt::from(10u32).pow(k) / q.denom();
        decimal(&scaled, k)
    } else {
        format!("\\frac{{{}}}{{{}}}", q.numer(), q.denom())
    };
    if neg {
        format!("-{body}")
    } else {
        body
    }
}

/// `Some(k)` when `d` divides `10^k` (the smallest such `k`).
fn decimal_places(d: &BigInt) -> Option<u32> {
    let (two, five) = (BigInt::from(2u32), BigInt::from(5u32));
    let mut d = d.clone();
    let (mut a, mut b) = (0u32, 0u32);
    while !d.is_zero() && d.is_even() {
        d /= &two;
        a = a.saturating_add(1);
    }
    while !d.is_zero() && (&d % &five).is_zero() {
        d /= &five;
        b = b.saturating_add(1);
    }
    if d.is_one() {
        Some(a.max(b))
    } else {
        None
    }
}

/// `scaled · 10^-k` (with `scaled > 0`) as a decimal or in scientific notation.
fn decimal(scaled: &BigInt, k: u32) -> String {
    let digits = scaled.to_string();
    let k = k as usize;
    if k <= MAX_DECIMALS {
        let padded = format!(
            "{}{digits}",
            "0".repeat((k + 1).saturating_sub(digits.len()))
        );
        let (int, frac) = padded.split_at(padded.len() - k);
        return format!("{int}.{frac}");
    }
    let exponent = digits.len() as i64 - 1 - k as i64;
    let (first, rest) = digits.split_at(1.min(digits.len()));
    let rest = rest.trim_end_matches('0');
    let mantissa = if rest.is_empty() {
        first.to_string()
    } else {
        format!("{first}.{rest}")
    };
    format!("{mantissa} \\times 10^{{{exponent}}}")
}

/// Binding strength of an expression's outermost operator, loosest first.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Prec {
    /// `+`, `-`.
    Sum,
    /// `*`, juxtaposition (a `/` prints as a self-delimiting `\frac`).
    Product,
    /// Unary minus.
    Neg,
    /// `^`.
    Power,
    /// Symbols, numbers, calls, fractions.
    Atom,
}

fn prec(e: &Expr) -> Prec {
    match &e.kind {
        ExprKind::Bin(BinOp::Add | BinOp::Sub, ..) => Prec::Sum,
        ExprKind::Bin(BinOp::Mul, ..) => Prec::Product,
        ExprKind::Neg(_) => Prec::Neg,
        ExprKind::Num(q) if q.is_negative() => Prec::Neg,
        ExprKind::Bin(BinOp::Pow, ..) => Prec::Power,
        _ => Prec::Atom,
    }
}

/// Whether the number prints as plain digits (an integer or a decimal, not negative).
fn plain_number(e: &Expr) -> bool {
    match &e.kind {
        ExprKind::Num(q) => {
            !q.is_negative() && (q.is_integer() || decimal_places(q.denom()).is_some())
        }
        _ => false,
    }
}

/// `\left(s\right)`.
fn paren(s: &str) -> String {
    format!("\\left({s}\\right)")
}

/// A function printed as an operator name: `\sin`, `\cos`, `\tan`, `\ln`.
fn operator_name(f: Func) -> Option<&'static str> {
    match f {
        Func::Sin => Some("\\sin"),
        Func::Cos => Some("\\cos"),
        Func::Tan => Some("\\tan"),
        Func::Ln => Some("\\ln"),
        _ => None,
    }
}

/// The printer, with the file context.
struct Printer<'a> {
    ctx: &'a Ctx,
}

impl Printer<'_> {
    /// `e` at nesting `depth`; `last` is false for a factor followed by another factor
    /// (then `\sin\beta` is written `\sin\left(\beta\right)` so the argument stays clear).
    fn expr(&self, e: &Expr, depth: usize, last: bool) -> String {
        if depth > MAX_DEPTH {
            return "\\cdots".to_string();
        }
        let d = depth + 1;
        match &e.kind {
            ExprKind::Num(q) => number_latex(q),
            ExprKind::Pi => "\\pi".to_string(),
            ExprKind::Sym(name) => self.symbol(name),
            ExprKind::Neg(inner) => {
                let s = self.expr(inner, d, last);
                if prec(inner) < Prec::Neg || s.starts_with('-') {
                    format!("-{}", paren(&s))
                } else {
                    format!("-{s}")
                }
            }
            ExprKind::Bin(BinOp::Add | BinOp::Sub, ..) => self.sum(e, depth, last),
            ExprKind::Bin(BinOp::Mul, ..) => self.product(e, depth, last),
            ExprKind::Bin(BinOp::Div, a, b) => {
                // `-L/2` is `(-L)/2`: a leading minus of a numerator that is not a sum
                // goes in front, `-\frac{L}{2}`.
                let den = self.expr(b, d, true);
                if let ExprKind::Neg(inner) = &a.kind {
                    return format!("-\\frac{{{}}}{{{den}}}", self.expr(inner, d, true));
                }
                let num = self.expr(a, d, true);
                match num.strip_prefix('-') {
                    Some(rest) if prec(a) > Prec::Sum => format!("-\\frac{{{rest}}}{{{den}}}"),
                    _ => format!("\\frac{{{num}}}{{{den}}}"),
                }
            }
            ExprKind::Bin(BinOp::Pow, base, exp) => self.power(base, exp, d, last),
            ExprKind::Call(f, args) => self.call(*f, args, d, last),
        }
    }

    fn symbol(&self, name: &str) -> String {
        if name == "dm" {
            return "dm".to_string();
        }
        if self.ctx.differentials.iter().any(|x| x == name) {
            if let Some(var) = name.strip_prefix('d') {
                return format!("d{}", symbol(var));
            }
        }
        symbol(name)
    }

    /// A sum, flattened along its left spine so long sums do not nest.
    fn sum(&self, e: &Expr, depth: usize, last: bool) -> String {
        let mut terms: Vec<(Option<BinOp>, &Expr)> = Vec::new();
        let mut cur = e;
        while let ExprKind::Bin(op @ (BinOp::Add | BinOp::Sub), l, r) = &cur.kind {
            terms.push((Some(*op), r));
            cur = l;
        }
        terms.push((None, cur));
        terms.reverse();
        let d = depth + 1;
        let mut out = String::new();
        for (op, t) in terms {
            let s = self.expr(t, d, last);
            match op {
                None => {
                    if prec(t) < Prec::Sum {
                        out.push_str(&paren(&s));
                    } else {
                        out.push_str(&s);
                    }
                }
                Some(op) => {
                    out.push_str(if op == BinOp::Add { " + " } else { " - " });
                    let needs = s.starts_with('-') || (op == BinOp::Sub && prec(t) == Prec::Sum);
                    out.push_str(&if needs { paren(&s) } else { s });
                }
            }
        }
        out
    }

    /// A product, flattened along its left spine.
    fn product(&self, e: &Expr, depth: usize, last: bool) -> String {
        let mut factors: Vec<&Expr> = Vec::new();
        let mut cur = e;
        while let ExprKind::Bin(BinOp::Mul, l, r) = &cur.kind {
            factors.push(r);
            cur = l;
        }
        factors.push(cur);
        factors.reverse();
        let d = depth + 1;
        let n = factors.len();
        let mut out = String::new();
        let mut prev_plain = false;
        for (i, f) in factors.into_iter().enumerate() {
            let is_last = last && i + 1 == n;
            let s = self.expr(f, d, is_last);
            let s = if prec(f) < Prec::Product || (i > 0 && s.starts_with('-')) {
                paren(&s)
            } else {
                s
            };
            if i > 0 {
                if s.starts_with(|c: char| c.is_ascii_digit()) {
                    out.push_str(" \\cdot ");
                } else if prev_plain || out.ends_with("\\right)") || s.starts_with("\\left(") {
                    out.push(' ');
                } else {
                    out.push_str("\\,");
                }
            }
            prev_plain = plain_number(f);
            out.push_str(&s);
        }
        out
    }

    fn power(&self, base: &Expr, exp: &Expr, d: usize, last: bool) -> String {
        let e = self.expr(exp, d, true);
        if let ExprKind::Call(f, args) = &base.kind {
            if let (Some(name), [arg]) = (operator_name(*f), args.as_slice()) {
                let positive_integer =
                    matches!(&exp.kind, ExprKind::Num(q) if q.is_integer() && q.is_positive());
                if positive_integer {
                    return format!("{name}^{{{e}}}{}", self.operator_arg(arg, d, last));
                }
            }
        }
        let b = self.expr(base, d, true);
        let simple = match &base.kind {
            ExprKind::Sym(_) | ExprKind::Pi => true,
            ExprKind::Num(_) => plain_number(base),
            ExprKind::Call(Func::Abs, _) => true,
            _ => false,
        };
        let b = if !simple {
            paren(&b)
        } else if b.contains('^') {
            format!("{{{b}}}")
        } else {
            b
        };
        format!("{b}^{{{e}}}")
    }

    /// The argument of `\sin` and friends: bare for a single symbol or number at the
    /// end of a product, else in parentheses.
    fn operator_arg(&self, arg: &Expr, d: usize, last: bool) -> String {
        let s = self.expr(arg, d, true);
        let bare =
            last && (matches!(arg.kind, ExprKind::Sym(_) | ExprKind::Pi) || plain_number(arg));
        if !bare {
            paren(&s)
        } else if s.starts_with('\\') {
            s
        } else {
            format!(" {s}")
        }
    }

    /// `d` followed by the variable, if `e` is a symbol.
    fn differential(&self, e: &Expr) -> Option<String> {
        match &e.kind {
            ExprKind::Sym(name) => Some(format!("d{}", symbol(name))),
            _ => None,
        }
    }

    /// The variable `x` of `diff(f, x)`, if a symbol.
    fn var(&self, e: &Expr) -> Option<String> {
        match &e.kind {
            ExprKind::Sym(name) => Some(symbol(name)),
            _ => None,
        }
    }

    /// An integrand or differentiated expression: parenthesised when it is a sum.
    fn operand(&self, e: &Expr, d: usize) -> String {
        let s = self.expr(e, d, true);
        if prec(e) == Prec::Sum {
            paren(&s)
        } else {
            s
        }
    }

    fn call(&self, f: Func, args: &[Expr], d: usize, last: bool) -> String {
        let ex = |e: &Expr| self.expr(e, d, true);
        if let (Some(name), [arg]) = (operator_name(f), args) {
            return format!("{name}{}", self.operator_arg(arg, d, last));
        }
        let done = match (f, args) {
            (Func::Sqrt, [a]) => Some(format!("\\sqrt{{{}}}", ex(a))),
            (Func::Exp, [a]) => Some(format!("e^{{{}}}", ex(a))),
            (Func::Abs, [a]) => Some(format!("\\left|{}\\right|", ex(a))),
            (Func::Int, [g, x, a, b]) => self.differential(x).map(|dx| {
                format!(
                    "\\int_{{{}}}^{{{}}} {} \\, {dx}",
                    ex(a),
                    ex(b),
                    self.operand(g, d)
                )
            }),
            (Func::Int, [g, x]) => match &x.kind {
                ExprKind::Sym(name) if name == "dm" => {
                    Some(format!("\\int {} \\, dm", self.operand(g, d)))
                }
                ExprKind::Sym(name) if self.ctx.is_body(name) => Some(format!(
                    "\\int_{{{}}} {} \\, dm",
                    symbol(name),
                    self.operand(g, d)
                )),
                _ => self
                    .differential(x)
                    .map(|dx| format!("\\int {} \\, {dx}", self.operand(g, d))),
            },
            (Func::Diff, [g, x]) => self
                .var(x)
                .map(|x| format!("\\frac{{d}}{{d{x}}}{}", paren(&ex(g)))),
            (Func::Diff, [g, x, n]) => self.var(x).map(|x| {
                let n = ex(n);
                format!("\\frac{{d^{{{n}}}}}{{d{x}^{{{n}}}}}{}", paren(&ex(g)))
            }),
            (Func::Eval, [g, x, a, b]) => self
                .var(x)
                .map(|x| format!("\\Big[{}\\Big]_{{{x}={}}}^{{{x}={}}}", ex(g), ex(a), ex(b))),
            (Func::Subs, [g, x, v]) => self
                .var(x)
                .map(|x| format!("\\left.{}\\right|_{{{x}={}}}", ex(g), ex(v))),
            _ => None,
        };
        done.unwrap_or_else(|| {
            let list: Vec<String> = args.iter().map(ex).collect();
            format!("\\operatorname{{{}}}{}", f.name(), paren(&list.join(", ")))
        })
    }
}
