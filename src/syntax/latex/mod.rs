//! LaTeX math, as lecture notes write it, read into the same tree as FORMAT.md §1's own
//! syntax: `\frac`, `\sqrt[n]{}`, `^{}`, `_{}`, `\int_a^b f\,dy`, `\int f\,dm`, evaluation
//! brackets `\left[F\right]_a^b` and `F\Big|_a^b`, `\sin\beta`, `\cos^2\theta`, Greek
//! letters, `\dot x`, primes, `\left(…\right)`, `\cdot`, `\times`, spacing, `\text{}`,
//! `|x|`, and the relations `=`, `\approx` (`~=`), `\neq`, `<`, `\le`, `>`, `\ge`.
//!
//! Reading rules (LaTeX's own conventions, stated once):
//! - juxtaposed single letters multiply: `mL^2` is m·L², `mgd` is m·g·d;
//! - a letter with a subscript is one symbol: `I_G`, `k_{G}`, `I_{xx}`, `\theta_0`;
//! - `^` binds tighter than juxtaposition and is right-associative; `-x^2` is −(x²);
//! - an unbraced function argument runs over the factors juxtaposed after it, up to
//!   the next operator, function, fraction or explicit space: `\cos\omega t` is
//!   cos(ωt), `\sin x^2` is sin(x²), `\sin\theta\cos\theta` is sin θ·cos θ (the rules
//!   in full, with Leibniz notation, increments and `\times`, are in `physics.rs`);
//! - `\cos^2\theta` is (cos θ)²; `e^{x}` is exp(x) unless `e` is declared (then the
//!   checker reads it as a power of the symbol e; a lone `e` is the symbol e);
//! - the variable of an evaluation bracket is the one its lower limit names (`y=a`), or
//!   else the one single-letter symbol of the bracket that the limits do not use.
//!
//! The tokenizer is written with nom; the grammar is a recursive descent over the
//! tokens, with a nesting limit (never a stack overflow).

use super::ast::{BinOp, Chain, Expr, ExprKind, Func, Link, Reading, RelOp, Span};
use super::error::{ParseOptions, SyntaxError};
use num_bigint::BigInt;
use num_rational::BigRational;
use tokens::{tokens, Tok, GREEK};

mod memo;
mod physics;
mod tokens;

/// Parses a LaTeX math expression (no relation); spans are offset by `base`.
pub fn parse_latex_expr(text: &str, base: usize, opts: &ParseOptions) -> Result<Expr, SyntaxError> {
    let mut p = P::new(text, base, opts)?;
    let e = p.expr()?;
    p.trailer()?;
    Ok(e)
}

/// Parses a chain of relations `a = b = c` (`&` ignored, a trailing `\\`, `.` or `,`, a
/// `\text{…}` remark, `\tag{…}` and `\label{…}` dropped); links get no `by`.
pub fn parse_latex_chain(
    text: &str,
    base: usize,
    opts: &ParseOptions,
) -> Result<Chain, SyntaxError> {
    memo::remembered(text, base, opts, read_chain)
}

/// [`parse_latex_chain`] at offset 0, read afresh.
fn read_chain(text: &str, opts: &ParseOptions) -> Result<Chain, SyntaxError> {
    let base = 0;
    let mut p = P::new(text, base, opts)?;
    let first = p.expr()?;
    let mut links = Vec::new();
    while let Some((op, at)) = p.relop() {
        let rhs = p.expr()?;
        links.push(Link {
            op,
            span: Span::new(at.start, rhs.span.end),
            rhs,
            by: None,
            compare: None,
        });
    }
    p.trailer()?;
    if links.is_empty() {
        return Err(p.error_here("a relation (`=`, `\\approx`, `<`, …)"));
    }
    Ok(Chain { first, links })
}

/// Parses the links of a chain that continues an earlier display (`= b = c`).
pub fn parse_latex_links(
    text: &str,
    base: usize,
    opts: &ParseOptions,
) -> Result<Vec<Link>, SyntaxError> {
    let mut p = P::new(text, base, opts)?;
    let mut links = Vec::new();
    while let Some((op, at)) = p.relop() {
        let rhs = p.expr()?;
        links.push(Link {
            op,
            span: Span::new(at.start, rhs.span.end),
            rhs,
            by: None,
            compare: None,
        });
    }
    p.trailer()?;
    if links.is_empty() {
        return Err(p.error_here("a relation (`=`, `\\approx`, `<`, …)"));
    }
    Ok(links)
}

/// The macros whose braced argument is upright text: in a subscript, part of the name.
const UPRIGHT: [&str; 7] = [
    "mathrm",
    "text",
    "textrm",
    "operatorname",
    "mathit",
    "mathsf",
    "textit",
];

struct P {
    toks: Vec<(Tok, Span)>,
    pos: usize,
    depth: usize,
    max_depth: usize,
    end: usize,
    /// Open `|…|` bars: inside one, a `|` closes it rather than starting a factor.
    bars: usize,
    /// The math read, and the offset of its first byte: to see the spacing between
    /// tokens (`\cos\omega\,t`), which the tokens themselves drop.
    text: String,
    base: usize,
}

fn node(kind: ExprKind, span: Span) -> Expr {
    Expr::new(kind, span)
}

fn bin(op: BinOp, a: Expr, b: Expr) -> Expr {
    let span = a.span.to(b.span);
    node(ExprKind::Bin(op, Box::new(a), Box::new(b)), span)
}

fn num(n: i64, span: Span) -> Expr {
    node(ExprKind::Num(BigRational::from_integer(n.into())), span)
}

impl P {
    fn new(text: &str, base: usize, opts: &ParseOptions) -> Result<P, SyntaxError> {
        let mut toks = tokens(text, base)?;
        // Markup that carries no math.
        toks.retain(|(t, _)| *t != Tok::Ch('&'));
        Ok(P {
            toks,
            pos: 0,
            depth: 0,
            max_depth: opts.max_depth,
            end: base + text.len(),
            bars: 0,
            text: text.to_string(),
            base,
        })
    }

    fn peek(&self) -> Option<&Tok> {
        self.toks.get(self.pos).map(|t| &t.0)
    }

    fn peek_at(&self, k: usize) -> Option<&Tok> {
        self.toks.get(self.pos + k).map(|t| &t.0)
    }

    fn span(&self) -> Span {
        self.toks
            .get(self.pos)
            .map_or(Span::new(self.end, self.end), |t| t.1)
    }

    fn last_span(&self) -> Span {
        self.pos
            .checked_sub(1)
            .and_then(|k| self.toks.get(k))
            .map_or(Span::new(self.end, self.end), |t| t.1)
    }

    fn bump(&mut self) -> Option<(Tok, Span)> {
        let t = self.toks.get(self.pos).cloned();
        if t.is_some() {
            self.pos += 1;
        }
        t
    }

    fn is_ch(&self, c: char) -> bool {
        self.peek() == Some(&Tok::Ch(c))
    }

    fn is_cmd(&self, name: &str) -> bool {
        matches!(self.peek(), Some(Tok::Cmd(c)) if c == name)
    }

    fn eat_ch(&mut self, c: char) -> bool {
        let yes = self.is_ch(c);
        if yes {
            self.pos += 1;
        }
        yes
    }

    fn eat_cmd(&mut self, name: &str) -> bool {
        let yes = self.is_cmd(name);
        if yes {
            self.pos += 1;
        }
        yes
    }

    fn error_here(&self, wanted: &str) -> SyntaxError {
        let found = match self.peek() {
            None => "the end of the math".to_string(),
            Some(Tok::Cmd(c)) => format!("`\\{c}`"),
            Some(Tok::Letter(c)) | Some(Tok::Ch(c)) => format!("`{c}`"),
            Some(Tok::Num(_)) => "a number".into(),
        };
        SyntaxError::new(self.span(), format!("expected {wanted}, found {found}"))
    }

    fn expect_ch(&mut self, c: char, wanted: &str) -> Result<Span, SyntaxError> {
        if self.is_ch(c) {
            let s = self.span();
            self.pos += 1;
            Ok(s)
        } else {
            Err(self.error_here(wanted))
        }
    }

    fn nest(&mut self) -> Result<(), SyntaxError> {
        self.depth += 1;
        if self.depth > self.max_depth {
            return Err(SyntaxError::of_kind(
                self.span(),
                crate::syntax::SyntaxErrorKind::NestingLimit,
                format!("nesting deeper than {} levels", self.max_depth),
            ));
        }
        Ok(())
    }

    /// What may follow a relation: a `\text{…}` remark, `\tag`, `\label`, `\\`, `.`, `,`.
    fn trailer(&mut self) -> Result<(), SyntaxError> {
        loop {
            match self.peek() {
                None => return Ok(()),
                Some(Tok::Ch('.' | ',' | ';')) => self.pos += 1,
                Some(Tok::Cmd(c)) if matches!(c.as_str(), "\\" | "nonumber" | "notag") => {
                    self.pos += 1
                }
                Some(Tok::Cmd(c))
                    if matches!(c.as_str(), "text" | "tag" | "label" | "textrm" | "mbox") =>
                {
                    self.pos += 1;
                    self.skip_group()?;
                }
                _ => return Err(self.error_here("a relation, an operator or the end of the math")),
            }
        }
    }

    fn skip_group(&mut self) -> Result<(), SyntaxError> {
        let open = self.expect_ch('{', "`{`")?;
        let mut level = 1usize;
        while level > 0 {
            match self.bump() {
                None => return Err(SyntaxError::new(open, "unclosed `{`")),
                Some((Tok::Ch('{'), _)) => level += 1,
                Some((Tok::Ch('}'), _)) => level -= 1,
                _ => {}
            }
        }
        Ok(())
    }

    fn relop(&mut self) -> Option<(RelOp, Span)> {
        let at = self.span();
        let op = match self.peek()? {
            Tok::Ch('=') => RelOp::Eq,
            Tok::Ch('<') => {
                if self.peek_at(1) == Some(&Tok::Ch('=')) {
                    self.pos += 1;
                    RelOp::Le
                } else {
                    RelOp::Lt
                }
            }
            Tok::Ch('>') => {
                if self.peek_at(1) == Some(&Tok::Ch('=')) {
                    self.pos += 1;
                    RelOp::Ge
                } else {
                    RelOp::Gt
                }
            }
            Tok::Cmd(c) => match c.as_str() {
                "approx" | "simeq" | "thickapprox" => RelOp::Approx,
                "neq" | "ne" => RelOp::Ne,
                "le" | "leq" | "leqslant" => RelOp::Le,
                "ge" | "geq" | "geqslant" => RelOp::Ge,
                _ => return None,
            },
            _ => return None,
        };
        self.pos += 1;
        Some((op, at))
    }

    /// `expr = ["+" | "-"] term (("+" | "-") term)*`.
    fn expr(&mut self) -> Result<Expr, SyntaxError> {
        self.nest()?;
        let start = self.span();
        // As in rigor's own syntax, unary minus takes the first factor: `-L/2` is (−L)/2.
        let negate = self.eat_ch('-');
        if !negate {
            self.eat_ch('+');
        }
        let mut e = self.term_from(false, negate.then_some(start))?;
        loop {
            let op = if self.eat_ch('+') {
                BinOp::Add
            } else if self.eat_ch('-') {
                BinOp::Sub
            } else if self.eat_cmd("pm") || self.eat_cmd("mp") {
                return Err(SyntaxError::new(
                    self.last_span(),
                    "`\\pm` is two relations, not one",
                ));
            } else {
                break;
            };
            let t = self.term(false)?;
            e = bin(op, e, t);
        }
        self.depth -= 1;
        Ok(e)
    }

    /// Whether the next token can start a factor (for juxtaposition).
    fn starts_factor(&self, in_integral: bool) -> bool {
        if in_integral && self.at_differential() {
            return false;
        }
        match self.peek() {
            Some(Tok::Num(_) | Tok::Letter(_)) => true,
            Some(Tok::Ch('(' | '[' | '{')) => true,
            Some(Tok::Ch('|')) => self.bars == 0,
            Some(Tok::Cmd(c)) => {
                let c = c.as_str();
                GREEK.contains(&c)
                    || FUNCS.iter().any(|f| f.0 == c)
                    || [
                        "pi",
                        "frac",
                        "dfrac",
                        "tfrac",
                        "sqrt",
                        "left",
                        "int",
                        "dot",
                        "ddot",
                        "lvert",
                        "vert",
                        "mathrm",
                        "operatorname",
                        "varphi",
                        "vartheta",
                        "ell",
                        "mathit",
                    ]
                    .contains(&c)
            }
            _ => false,
        }
    }

    /// `term = factor (("\cdot" | "\times" | "*" | "/") factor | factor)*`.
    fn term(&mut self, in_integral: bool) -> Result<Expr, SyntaxError> {
        self.term_from(in_integral, None)
    }

    /// A term whose first factor is negated when `minus` (the `-` sign's span) is given.
    fn term_from(&mut self, in_integral: bool, minus: Option<Span>) -> Result<Expr, SyntaxError> {
        let mut e = self.factor()?;
        if let Some(m) = minus {
            let span = m.to(e.span);
            e = node(ExprKind::Neg(Box::new(e)), span);
        }
        loop {
            let op = if self.is_cmd("times") {
                e = self.times(e, in_integral)?;
                continue;
            } else if self.eat_cmd("cdot") || self.eat_ch('*') {
                BinOp::Mul
            } else if self.eat_ch('/') {
                BinOp::Div
            } else if self.is_ch('|') && self.bar_is_evaluation() {
                e = self.bar_evaluation(e)?;
                continue;
            } else if self.starts_factor(in_integral) {
                BinOp::Mul
            } else {
                return Ok(e);
            };
            let f = self.factor()?;
            e = bin(op, e, f);
        }
    }

    /// A `|` followed by `_` is an evaluation bar (`F \Big|_a^b`).
    fn bar_is_evaluation(&self) -> bool {
        self.peek_at(1) == Some(&Tok::Ch('_'))
    }

    /// `factor = primary ["'"…] ["^" arg]`.
    fn factor(&mut self) -> Result<Expr, SyntaxError> {
        self.nest()?;
        let start = self.span();
        let base = match self.slash_leibniz()? {
            Some(d) => d,
            None => self.primary()?,
        };
        let mut e = self.power(base)?;
        // The factor covers everything it consumed, closing braces and brackets too.
        e.span = start.to(self.last_span());
        self.depth -= 1;
        Ok(e)
    }

    fn power(&mut self, base: Expr) -> Result<Expr, SyntaxError> {
        if !self.eat_ch('^') {
            return Ok(base);
        }
        let exp = self.arg()?;
        // e^{x} is exp(x).
        if base.kind == ExprKind::Sym("e".into()) {
            let span = base.span.to(exp.span);
            return Ok(node(ExprKind::Call(Func::Exp, vec![exp]), span).read_as(Reading::EulerE));
        }
        Ok(bin(BinOp::Pow, base, exp))
    }

    /// TeX reads `\frac12` as 1 over 2: a whole number of several digits in argument
    /// position gives its first digit.
    fn split_digit(&mut self) {
        let Some((Tok::Num(q), span)) = self.toks.get(self.pos).cloned() else {
            return;
        };
        let digits = q.numer().to_string();
        if !q.is_integer() || digits.len() < 2 || span.end - span.start != digits.len() {
            return;
        }
        let (first, rest) = digits.split_at(1);
        let (Ok(a), Ok(b)) = (first.parse::<BigInt>(), rest.parse::<BigInt>()) else {
            return;
        };
        let cut = span.start + 1;
        self.toks[self.pos] = (
            Tok::Num(BigRational::from_integer(a)),
            Span::new(span.start, cut),
        );
        self.toks.insert(
            self.pos + 1,
            (
                Tok::Num(BigRational::from_integer(b)),
                Span::new(cut, span.end),
            ),
        );
    }

    /// A braced group or a single token's worth (`^2`, `^{-1}`, `\frac12`).
    fn arg(&mut self) -> Result<Expr, SyntaxError> {
        if self.eat_ch('{') {
            let e = self.expr()?;
            self.expect_ch('}', "`}`")?;
            return Ok(e);
        }
        match self.bump() {
            Some((Tok::Num(q), s)) => {
                // `^23` is ^2 then 3 in TeX; only the first digit is the argument.
                let digits = q.numer().to_string();
                if q.is_integer() && digits.len() > 1 {
                    return Err(SyntaxError::new(
                        s,
                        "write a power of several digits in braces: `^{23}`",
                    ));
                }
                Ok(node(ExprKind::Num(q), s))
            }
            Some((Tok::Letter(c), s)) => Ok(node(ExprKind::Sym(c.to_string()), s)),
            Some((Tok::Cmd(c), s)) if GREEK.contains(&c.as_str()) || c == "pi" => {
                self.pos -= 1;
                let _ = s;
                self.primary()
            }
            _ => {
                self.pos = self.pos.saturating_sub(1);
                Err(self.error_here("a braced argument `{…}`"))
            }
        }
    }

    fn primary(&mut self) -> Result<Expr, SyntaxError> {
        let Some((tok, span)) = self.bump() else {
            return Err(self.error_here("an expression"));
        };
        match tok {
            Tok::Num(q) => Ok(node(ExprKind::Num(q), span)),
            Tok::Letter(c) => self.symbol(c.to_string(), span),
            Tok::Ch('(') => self.group(')', span),
            Tok::Ch('[') => {
                let e = self.group(']', span)?;
                self.maybe_evaluation(e)
            }
            Tok::Ch('{') => self.group('}', span),
            Tok::Ch('|') => self.abs('|', span),
            Tok::Cmd(c) => self.command(&c, span),
            Tok::Ch(c) => {
                self.pos -= 1;
                Err(self.error_here(&format!("an expression (not `{c}`)")))
            }
        }
    }

    fn group(&mut self, close: char, open: Span) -> Result<Expr, SyntaxError> {
        let e = self.expr()?;
        if !self.eat_ch(close) {
            return Err(SyntaxError::new(
                open,
                format!("unclosed group: expected `{close}`"),
            ));
        }
        Ok(e)
    }

    fn abs(&mut self, close: char, open: Span) -> Result<Expr, SyntaxError> {
        self.bars += 1;
        let e = self.expr();
        self.bars -= 1;
        let e = e?;
        let end = self.span();
        let closed = if close == '|' {
            self.eat_ch('|')
        } else {
            self.eat_cmd("rvert") || self.eat_cmd("vert")
        };
        if !closed {
            return Err(SyntaxError::new(open, "unclosed `|`"));
        }
        Ok(node(ExprKind::Call(Func::Abs, vec![e]), open.to(end)))
    }

    /// A letter or Greek name, with a subscript and primes: one symbol.
    fn symbol(&mut self, mut name: String, span: Span) -> Result<Expr, SyntaxError> {
        let mut span = span;
        if self.eat_ch('_') {
            let sub = self.subscript()?;
            name = format!("{name}_{sub}");
            span = span.to(self.last_span());
        }
        while self.eat_ch('\'') {
            name.push('\'');
            span = span.to(self.last_span());
        }
        Ok(node(ExprKind::Sym(name), span))
    }

    /// The text of a subscript: letters, digits and Greek names (`{xx}`, `G`, `{0}`).
    fn subscript(&mut self) -> Result<String, SyntaxError> {
        let one = |t: &Tok| -> Option<String> {
            match t {
                Tok::Letter(c) => Some(c.to_string()),
                Tok::Num(q) if q.is_integer() => Some(q.numer().to_string()),
                Tok::Cmd(c) if GREEK.contains(&c.as_str()) => Some(c.clone()),
                _ => None,
            }
        };
        if !self.eat_ch('{') {
            // `K_\mathrm{rot}`: the macro's braced text is the subscript.
            if UPRIGHT.iter().any(|c| self.is_cmd(c)) && self.peek_at(1) == Some(&Tok::Ch('{')) {
                self.pos += 1;
                return self.subscript();
            }
            let t = self.peek().cloned();
            let s = t
                .as_ref()
                .and_then(one)
                .ok_or_else(|| self.error_here("a subscript"))?;
            self.pos += 1;
            return Ok(s);
        }
        let mut parts = String::new();
        // Braces inside the subscript (`_{\text{CM}}`) close before it does.
        let mut level = 1usize;
        loop {
            if self.eat_ch('}') {
                level -= 1;
                if level == 0 {
                    return Ok(parts);
                }
                continue;
            }
            if UPRIGHT.iter().any(|c| self.is_cmd(c)) {
                self.pos += 1;
                continue;
            }
            if self.eat_ch('{') {
                level += 1;
                continue;
            }
            if self.eat_ch(',') {
                continue;
            }
            let t = self.peek().cloned();
            match t.as_ref().and_then(one) {
                Some(s) => {
                    if !parts.is_empty() && s.len() > 1 && !parts.ends_with('_') {
                        parts.push('_');
                    }
                    parts.push_str(&s);
                    self.pos += 1;
                }
                None => return Err(self.error_here("a subscript of letters and digits")),
            }
        }
    }

    fn command(&mut self, c: &str, span: Span) -> Result<Expr, SyntaxError> {
        match c {
            "pi" => Ok(node(ExprKind::Pi, span)),
            "varphi" => self.symbol("phi".into(), span),
            "vartheta" => self.symbol("theta".into(), span),
            "varrho" => self.symbol("rho".into(), span),
            "ell" => self.symbol("l".into(), span),
            "Delta" | "delta" => self.increment(c, span),
            g if GREEK.contains(&g) => self.symbol(g.to_string(), span),
            "frac" | "dfrac" | "tfrac" => {
                if let Some(d) = self.leibniz(span)? {
                    return Ok(d);
                }
                self.split_digit();
                let a = self.arg()?;
                self.split_digit();
                let b = self.arg()?;
                Ok(bin(BinOp::Div, a, b))
            }
            "sqrt" => self.sqrt(span),
            "left" => self.left(span),
            "lvert" | "vert" => self.abs('v', span),
            "int" => self.integral(span),
            "dot" | "ddot" | "dddot" => {
                let inner = self.arg()?;
                let ExprKind::Sym(n) = inner.kind else {
                    return Err(SyntaxError::new(span, format!("`\\{c}` of something that is not a symbol")));
                };
                let primes = match c {
                    "dot" => "'",
                    "ddot" => "''",
                    _ => "'''",
                };
                // `\ddot{y}_B` is the acceleration of y_B: a subscript after the accent
                // names the symbol, as `\ddot{y_B}` would.
                let mut span = span.to(inner.span);
                let mut name = n;
                if !name.contains('_') && self.eat_ch('_') {
                    let sub = self.subscript()?;
                    name = format!("{name}_{sub}");
                    span = span.to(self.last_span());
                }
                Ok(node(ExprKind::Sym(format!("{name}{primes}")), span))
            }
            "mathrm" | "text" | "textrm" | "operatorname" | "mathit" => self.upright(span),
            "vec" | "hat" | "mathbf" | "boldsymbol" | "bm" | "overrightarrow" => Err(SyntaxError::new(
                span,
                format!("`\\{c}` marks a vector (or a unit vector): rigor reads scalar equations, so its components must be written out"),
            )),
            f => match FUNCS.iter().find(|x| x.0 == f) {
                Some((_, func)) => self.function(*func, span),
                None => Err(SyntaxError::new(
                    span,
                    format!("unknown LaTeX macro `\\{c}` in math: rigor reads \\frac, \\sqrt, \\int, \\sin, Greek letters and the like"),
                )),
            },
        }
    }

    /// `\mathrm{cm}`: a multi-letter name; `\mathrm{d}` is a differential (not here).
    fn upright(&mut self, span: Span) -> Result<Expr, SyntaxError> {
        let open = self.expect_ch('{', "`{` after the macro")?;
        let mut name = String::new();
        while let Some(Tok::Letter(c)) = self.peek() {
            name.push(*c);
            self.pos += 1;
        }
        if !self.eat_ch('}') || name.is_empty() {
            return Err(SyntaxError::new(
                open,
                "upright text in math is read only as a name of letters: `\\mathrm{cm}`",
            ));
        }
        self.symbol(name, span.to(self.last_span()))
    }

    fn sqrt(&mut self, span: Span) -> Result<Expr, SyntaxError> {
        if self.eat_ch('[') {
            let n = self.expr()?;
            self.expect_ch(']', "`]` after the index of the root")?;
            let x = self.arg()?;
            let one = num(1, n.span);
            let inv = bin(BinOp::Div, one, n);
            let whole = span.to(x.span);
            let mut e = bin(BinOp::Pow, x, inv);
            e.span = whole;
            return Ok(e);
        }
        let x = self.arg()?;
        let s = span.to(x.span);
        Ok(node(ExprKind::Call(Func::Sqrt, vec![x]), s))
    }

    /// `\left( … \right)`, `\left[ … \right]_a^b`, `\left| … \right|`, `\left. … \right|_a^b`.
    fn left(&mut self, span: Span) -> Result<Expr, SyntaxError> {
        let Some((open, _)) = self.bump() else {
            return Err(self.error_here("a delimiter after `\\left`"));
        };
        let e = self.expr()?;
        if !self.eat_cmd("right") {
            return Err(SyntaxError::new(span, "`\\left` without `\\right`"));
        }
        let Some((close, _)) = self.bump() else {
            return Err(self.error_here("a delimiter after `\\right`"));
        };
        let bar = |t: &Tok| {
            matches!(t, Tok::Ch('|'))
                || matches!(t, Tok::Cmd(c) if c == "vert" || c == "lvert" || c == "rvert")
        };
        if self.is_ch('_') && (matches!(close, Tok::Ch(']')) || bar(&close) || open == Tok::Ch('.'))
        {
            return self.evaluation(e);
        }
        if bar(&open) && bar(&close) {
            return Ok(node(
                ExprKind::Call(Func::Abs, vec![e]),
                span.to(self.last_span()),
            ));
        }
        match (open, close) {
            (Tok::Ch('['), Tok::Ch(']')) | (Tok::Ch('('), Tok::Ch(')')) => Ok(e),
            _ => Err(SyntaxError::new(span, "mismatched `\\left` and `\\right`")),
        }
    }

    fn maybe_evaluation(&mut self, e: Expr) -> Result<Expr, SyntaxError> {
        if self.is_ch('_') {
            return self.evaluation(e);
        }
        Ok(e)
    }

    /// `F \Big|_a^b` (the product so far is F).
    fn bar_evaluation(&mut self, e: Expr) -> Result<Expr, SyntaxError> {
        self.expect_ch('|', "`|`")?;
        self.evaluation(e)
    }

    /// `_{a}^{b}` after a bracket: `eval(F, v, a, b)`.
    fn evaluation(&mut self, f: Expr) -> Result<Expr, SyntaxError> {
        self.expect_ch('_', "`_` and the lower limit")?;
        let (var, lo) = self.limit_with_variable()?;
        self.expect_ch('^', "`^` and the upper limit")?;
        let hi = self.arg()?;
        let var = match var {
            Some(v) => v,
            None => evaluation_variable(&f, &lo, &hi).ok_or_else(|| {
                SyntaxError::new(
                    f.span.to(hi.span),
                    "which variable the limits are for is unclear: write the lower limit as `y=a`",
                )
            })?,
        };
        // To the last token read: the closing brace of `^{L}` too.
        let span = f.span.to(self.last_span());
        let v = node(ExprKind::Sym(var), lo.span);
        Ok(node(ExprKind::Call(Func::Eval, vec![f, v, lo, hi]), span))
    }

    /// A lower limit, possibly `y=a` (which names the variable).
    fn limit_with_variable(&mut self) -> Result<(Option<String>, Expr), SyntaxError> {
        let braced = self.eat_ch('{');
        if !braced {
            return Ok((None, self.arg()?));
        }
        let named = match (self.peek(), self.peek_at(1)) {
            (Some(Tok::Letter(c)), Some(Tok::Ch('='))) => Some(c.to_string()),
            (Some(Tok::Cmd(c)), Some(Tok::Ch('='))) if GREEK.contains(&c.as_str()) => {
                Some(c.clone())
            }
            _ => None,
        };
        if named.is_some() {
            self.pos += 2;
        }
        let e = self.expr()?;
        self.expect_ch('}', "`}`")?;
        Ok((named, e))
    }

    /// `\int_a^b f \, dy`, `\int f\,dm`.
    fn integral(&mut self, span: Span) -> Result<Expr, SyntaxError> {
        let mut bounds = None;
        if self.eat_ch('_') {
            let lo = self.arg()?;
            self.expect_ch('^', "`^` and the upper limit of the integral")?;
            let hi = self.arg()?;
            bounds = Some((lo, hi));
        } else if self.eat_ch('^') {
            let hi = self.arg()?;
            self.expect_ch('_', "`_` and the lower limit of the integral")?;
            let lo = self.arg()?;
            bounds = Some((lo, hi));
        }
        let f = if self.at_differential() {
            num(1, self.span())
        } else {
            self.nest()?;
            let t = self.term(true)?;
            self.depth -= 1;
            t
        };
        let (var, vspan) = self.differential()?;
        let whole = span.to(vspan);
        match bounds {
            Some((lo, hi)) => {
                if var == "m" {
                    return Err(SyntaxError::new(
                        vspan,
                        "needs context: `dm` with limits is a mass element defined in prose; write it in terms of a coordinate (dm = m/L dy)",
                    )
                    .with_kind(crate::syntax::error::SyntaxErrorKind::MassElementWithLimits));
                }
                let v = node(ExprKind::Sym(var), vspan);
                Ok(node(ExprKind::Call(Func::Int, vec![f, v, lo, hi]), whole))
            }
            None if var == "m" => {
                let v = node(ExprKind::Sym("dm".into()), vspan);
                Ok(node(ExprKind::Call(Func::Int, vec![f, v]), whole))
            }
            None => {
                let v = node(ExprKind::Sym(var), vspan);
                Ok(node(ExprKind::Call(Func::Int, vec![f, v]), whole))
            }
        }
    }

    /// Whether the next tokens are a differential `dy`, `\mathrm{d}y`, `d\theta`.
    fn at_differential(&self) -> bool {
        let is_var = |t: Option<&Tok>| match t {
            Some(Tok::Letter(_)) => true,
            Some(Tok::Cmd(c)) => GREEK.contains(&c.as_str()),
            _ => false,
        };
        match self.peek() {
            Some(Tok::Letter('d')) => is_var(self.peek_at(1)) && !self.is_factor_after(2),
            Some(Tok::Cmd(c)) if c == "mathrm" || c == "text" => {
                self.peek_at(1) == Some(&Tok::Ch('{'))
                    && self.peek_at(2) == Some(&Tok::Letter('d'))
                    && self.peek_at(3) == Some(&Tok::Ch('}'))
                    && is_var(self.peek_at(4))
            }
            _ => false,
        }
    }

    /// Whether a factor continues at `k` tokens ahead (then `d y` was a product, e.g.
    /// `d y z`? no: a differential ends the integrand, so only an operator may follow).
    fn is_factor_after(&self, k: usize) -> bool {
        matches!(self.peek_at(k), Some(Tok::Ch('^' | '_')))
    }

    fn differential(&mut self) -> Result<(String, Span), SyntaxError> {
        if !self.at_differential() {
            return Err(self.error_here("the differential of the integral (`dy`, `\\,dx`, `dm`)"));
        }
        let start = self.span();
        if self.eat_cmd("mathrm") || self.eat_cmd("text") {
            self.pos += 3;
        } else {
            self.pos += 1;
        }
        let name = match self.bump() {
            Some((Tok::Letter(c), _)) => c.to_string(),
            Some((Tok::Cmd(c), _)) => c,
            _ => return Err(self.error_here("a variable after `d`")),
        };
        Ok((name, start.to(self.last_span())))
    }

    /// `\sin x`, `\sin(x)`, `\sin^2\theta`, `\sin{x}`.
    fn function(&mut self, f: Func, span: Span) -> Result<Expr, SyntaxError> {
        let mut power = None;
        if self.eat_ch('^') {
            let p = self.arg()?;
            if matches!(&p.kind, ExprKind::Neg(_)) {
                return Err(SyntaxError::new(p.span, "`^{-1}` on a function is its inverse, which rigor does not read; write the power after the argument"));
            }
            power = Some(p);
        }
        let arg = if self.eat_ch('(') {
            let open = self.last_span();
            self.group(')', open)?
        } else if self.is_cmd("left") && self.peek_at(1) == Some(&Tok::Ch('(')) {
            self.pos += 1;
            let s = self.last_span();
            self.left(s)?
        } else if self.eat_ch('{') {
            let open = self.last_span();
            self.group('}', open)?
        } else {
            self.unbraced_argument()?
        };
        let s = span.to(arg.span);
        let call = node(ExprKind::Call(f, vec![arg]), s);
        Ok(match power {
            Some(p) => bin(BinOp::Pow, call, p),
            None => call,
        })
    }

    /// The argument of an unbraced function: see [`P::argument_run`].
    fn unbraced_argument(&mut self) -> Result<Expr, SyntaxError> {
        self.argument_run()
    }
}

/// The functions and their macros.
const FUNCS: [(&str, Func); 6] = [
    ("sin", Func::Sin),
    ("cos", Func::Cos),
    ("tan", Func::Tan),
    ("ln", Func::Ln),
    ("exp", Func::Exp),
    ("log", Func::Ln),
];

/// The variable of `[F]_lo^hi`: the one single-letter (or Greek) symbol of F that the
/// limits do not mention.
fn evaluation_variable(f: &Expr, lo: &Expr, hi: &Expr) -> Option<String> {
    let mut in_f = Vec::new();
    symbols(f, &mut in_f);
    let mut in_limits = Vec::new();
    symbols(lo, &mut in_limits);
    symbols(hi, &mut in_limits);
    let mut candidates: Vec<String> = in_f
        .into_iter()
        .filter(|n| !in_limits.contains(n))
        .filter(|n| n.chars().count() == 1 || GREEK.contains(&n.as_str()))
        .collect();
    candidates.sort();
    candidates.dedup();
    match candidates.as_slice() {
        [v] => Some(v.clone()),
        _ => None,
    }
}

fn symbols(e: &Expr, out: &mut Vec<String>) {
    match &e.kind {
        ExprKind::Sym(n) => out.push(n.clone()),
        ExprKind::Num(_) | ExprKind::Pi => {}
        ExprKind::Neg(a) => symbols(a, out),
        ExprKind::Bin(_, a, b) => {
            symbols(a, out);
            symbols(b, out);
        }
        ExprKind::Call(_, args) => args.iter().for_each(|a| symbols(a, out)),
    }
}

#[cfg(test)]
mod tests;
