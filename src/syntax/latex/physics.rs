//! LaTeX read as a physicist means it, where a literal reading of the letters would be
//! a product nobody wrote:
//!
//! - **Leibniz notation is a derivative.** `\frac{dx}{dt}`, `\frac{d^2x}{dt^2}`,
//!   `\frac{d}{dt}(…)`, `\frac{d}{dt}\left(…\right)`, with the `d` written `d`,
//!   `\mathrm{d}`, `\text{d}` or `\operatorname{d}`, and the same with a slash (`dx/dt`,
//!   `d^2x/dt^2`, `d/dt\,(m v)`): with respect to `t`, a lone symbol
//!   `x` gives `x'` (`x''`), the same tree as rigor's own syntax, and anything else
//!   `diff(…, t)`; with respect to another variable `y`, `diff(…, y)`. Both are marked
//!   [`Reading::Leibniz`]: the checker refuses such a derivative when its operand, as
//!   declared, does not vary with the variable (a constant `x` is an error asking for
//!   `time x`, never a derivative of zero). It is Leibniz notation only when the
//!   numerator starts with a `d` and the denominator is a differential `dt`, `dt^2`:
//!   `\frac{d}{2}` (a diameter) and `\frac{F}{dt}` stay quotients.
//! - **An increment is one symbol.** `\Delta x` is the symbol `Delta_x`, `\delta x`
//!   is `delta_x` (with subscripts: `\Delta x_B` is `Delta_x_B`), never Δ·x; a lone
//!   `\Delta` or `\delta` (`\delta = \frac{F L^3}{3EI}`) is the symbol itself, and the
//!   change of anything else (`\Delta(mv)`, `\Delta\dot x`) is refused.
//! - **A function takes the factors written after it.** An unbraced argument runs
//!   from the first factor (with its power) over the juxtaposed letters, Greek letters
//!   and numbers after it, up to the next operator (`+`, `−`, `\cdot`, `/`, a
//!   relation), function (also `e^{…}`), fraction, root, bracket, dotted symbol,
//!   differential or explicit space (`\,`, `\;`, `\:`, `\ `, `\quad`, `~`):
//!   `\cos\omega t` is cos(ωt), `\sin 2\pi f t` is sin(2πft), `\sin x^2` is sin(x²),
//!   while `\sin\theta\cos\theta` is sin θ·cos θ, `\cos\omega\,t` is (cos ω)·t and
//!   `\sin\theta\dot\theta` is sin θ·θ̇.
//! - **`\times` between two quantities is a cross product.** rigor has no vectors:
//!   `\times` is a multiplication only when one side is a plain number (no symbol:
//!   `3 \times 10^{4}`, `2 \times m`); between two quantities (`\omega \times r`) it is
//!   refused. The right side is the factors juxtaposed after the `\times`.

use super::super::ast::{BinOp, Expr, ExprKind, Func, Reading, Span};
use super::super::error::SyntaxError;
use super::tokens::{Tok, GREEK};
use super::{bin, node, P};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::ToPrimitive;

/// The highest order of a derivative written in Leibniz notation.
const MAX_ORDER: u32 = 9;

/// Spacing macros that end a function's argument (`\cos\omega\,t`).
const SPACES: [&str; 7] = [",", ";", ":", ">", " ", "quad", "qquad"];

/// Whether `e` is a plain number: nothing in it is a symbol.
fn is_number(e: &Expr) -> bool {
    !e.any(&|x| matches!(x.kind, ExprKind::Sym(_)))
}

/// The symbol name of a Greek-letter macro (`\varphi` is `phi`).
fn greek_name(c: &str) -> Option<&str> {
    match c {
        "varphi" => Some("phi"),
        "vartheta" => Some("theta"),
        "varrho" => Some("rho"),
        g if GREEK.contains(&g) => Some(g),
        _ => None,
    }
}

/// Whether `gap` (the text between two tokens) holds an explicit space: `\,`, `\;`,
/// `\:`, `\>`, `\ `, `\quad`, `\qquad` or `~`.
fn has_space(gap: &str) -> bool {
    let mut rest = gap;
    while let Some(i) = rest.find(['\\', '~']) {
        if rest[i..].starts_with('~') {
            return true;
        }
        let after = &rest[i + 1..];
        let letters = after
            .find(|c: char| !c.is_ascii_alphabetic())
            .unwrap_or(after.len());
        let name = if letters > 0 {
            &after[..letters]
        } else {
            after
                .char_indices()
                .nth(1)
                .map_or(after, |(k, _)| &after[..k])
        };
        if SPACES.contains(&name) {
            return true;
        }
        rest = &after[name.len().max(1).min(after.len())..];
    }
    false
}

impl P {
    /// Whether an explicit space (`\,`, `~`, …) stands before the token at `k`.
    fn spaced_before(&self, k: usize) -> bool {
        let (Some(prev), Some(cur)) = (
            k.checked_sub(1).and_then(|j| self.toks.get(j)),
            self.toks.get(k),
        ) else {
            return false;
        };
        let from = prev.1.end.saturating_sub(self.base);
        let to = cur.1.start.saturating_sub(self.base);
        self.text.get(from..to).is_some_and(has_space)
    }

    /// The unbraced argument of a function (`\cos\omega t`): the first factor with its
    /// power, then the letters, Greek letters and numbers juxtaposed after it (see the
    /// module's rules).
    pub(super) fn argument_run(&mut self) -> Result<Expr, SyntaxError> {
        let mut e = self.factor()?;
        while self.continues_argument() {
            let f = self.factor()?;
            e = bin(BinOp::Mul, e, f);
        }
        Ok(e)
    }

    /// Whether the next token goes on with a function's unbraced argument.
    fn continues_argument(&self) -> bool {
        if self.spaced_before(self.pos) || self.at_differential() {
            return false;
        }
        match self.peek() {
            Some(Tok::Num(_)) => true,
            // `e^{…}` is the exponential function: it ends the argument.
            Some(Tok::Letter('e')) => self.peek_at(1) != Some(&Tok::Ch('^')),
            Some(Tok::Letter(_)) => true,
            Some(Tok::Cmd(c)) => greek_name(c).is_some() || c == "pi" || c == "ell",
            _ => false,
        }
    }

    /// `left \times …`: a product when one side is a plain number, else refused as a
    /// cross product. The `\times` is the next token.
    pub(super) fn times(&mut self, left: Expr, in_integral: bool) -> Result<Expr, SyntaxError> {
        let at = self.span();
        self.pos += 1;
        let mut right = self.factor()?;
        while self.starts_factor(in_integral) && !(self.is_ch('|') && self.bar_is_evaluation()) {
            let f = self.factor()?;
            right = bin(BinOp::Mul, right, f);
        }
        if is_number(&left) || is_number(&right) {
            return Ok(bin(BinOp::Mul, left, right));
        }
        Err(SyntaxError::new(
            at,
            "needs context: `\\times` between two quantities is a cross product of vectors, which rigor does not read (write `\\cdot` for a product of scalars)",
        ))
    }

    /// `\Delta x`, `\delta\theta`: one increment symbol; a lone `\Delta` is a symbol.
    pub(super) fn increment(&mut self, c: &str, span: Span) -> Result<Expr, SyntaxError> {
        let of = match self.peek() {
            Some(Tok::Letter(l)) => Some(l.to_string()),
            Some(Tok::Cmd(g)) => greek_name(g).map(str::to_string),
            _ => None,
        };
        let Some(name) = of else {
            let changes = self.is_ch('(')
                || self.is_ch('[')
                || self.is_ch('{')
                || self.is_ch('|')
                || matches!(self.peek(), Some(Tok::Cmd(_)) if self.starts_factor(false));
            if changes {
                return Err(SyntaxError::new(
                    span,
                    format!("`\\{c}` of an expression is a change rigor does not read: name it, e.g. `\\{c} p` for the change of momentum"),
                ));
            }
            return self.symbol(c.to_string(), span);
        };
        self.pos += 1;
        let inner = self.symbol(name, self.last_span())?;
        let whole = span.to(inner.span);
        match inner.kind {
            ExprKind::Sym(n) if !n.contains('\'') => {
                Ok(node(ExprKind::Sym(format!("{c}_{n}")), whole))
            }
            _ => Err(SyntaxError::new(
                whole,
                format!("`\\{c}` of a derivative is a change rigor does not read: name it"),
            )),
        }
    }

    /// The length in tokens of a differential's `d` at token `k`: `d` (not `d_1`, not
    /// `d'`), `\mathrm{d}`, `\text{d}`, `\operatorname{d}`, `\mathit{d}`, `\rm d`.
    fn d_mark(&self, k: usize) -> Option<usize> {
        let at = |j: usize| self.toks.get(k + j).map(|t| &t.0);
        match at(0)? {
            Tok::Letter('d') => {
                let symbol = matches!(at(1), Some(Tok::Ch('_' | '\'')));
                (!symbol).then_some(1)
            }
            Tok::Cmd(c)
                if matches!(c.as_str(), "mathrm" | "text" | "operatorname" | "mathit")
                    && at(1) == Some(&Tok::Ch('{'))
                    && at(2) == Some(&Tok::Letter('d'))
                    && at(3) == Some(&Tok::Ch('}')) =>
            {
                Some(4)
            }
            _ => None,
        }
    }

    /// The index of the `}` that closes the `{` at token `k`.
    fn matching_brace(&self, k: usize) -> Option<usize> {
        let mut level = 0usize;
        for (j, (t, _)) in self.toks.iter().enumerate().skip(k) {
            match t {
                Tok::Ch('{') => level += 1,
                Tok::Ch('}') => {
                    level = level.checked_sub(1)?;
                    if level == 0 {
                        return Some(j);
                    }
                }
                _ => {}
            }
        }
        None
    }

    /// The order after a differential's `d` or variable: `^2`, `^{2}`, else 1.
    fn leibniz_order(&mut self) -> Result<u32, SyntaxError> {
        if !self.eat_ch('^') {
            return Ok(1);
        }
        let e = self.arg()?;
        let n = match &e.kind {
            ExprKind::Num(q) if q.is_integer() => q.to_integer().to_u32(),
            _ => None,
        };
        n.filter(|n| (1..=MAX_ORDER).contains(n)).ok_or_else(|| {
            SyntaxError::new(
                e.span,
                format!("the order of a derivative must be a whole number from 1 to {MAX_ORDER}"),
            )
        })
    }

    /// A denominator `{dt}`, `{\mathrm{d}t^2}`, `{d\theta}`, `{dx_1}` from the current
    /// token: the variable, its span and the order; `None` (position undefined) if it
    /// is not a differential. A differential with an order that is not one is an error.
    fn leibniz_denominator(&mut self) -> Result<Option<(String, Span, u32)>, SyntaxError> {
        let Some((name, span)) = self.differential_variable() else {
            return Ok(None);
        };
        let order = self.leibniz_order()?;
        Ok(self.eat_ch('}').then_some((name, span, order)))
    }

    /// `{dt`, `{\mathrm{d}\theta`, `{dx_1`: the variable of a differential opening a
    /// group, and its span; `None` (position undefined) if there is none.
    fn differential_variable(&mut self) -> Option<(String, Span)> {
        if !self.eat_ch('{') {
            return None;
        }
        self.pos += self.d_mark(self.pos)?;
        let first = match self.peek()? {
            Tok::Letter(c) => c.to_string(),
            Tok::Cmd(c) => greek_name(c)?.to_string(),
            _ => return None,
        };
        self.pos += 1;
        let var = self.symbol(first, self.last_span()).ok()?;
        match var.kind {
            ExprKind::Sym(name) if !name.contains('\'') => Some((name, var.span)),
            _ => None,
        }
    }

    /// `\frac{dx}{dt}`, `\frac{d^2x}{dt^2}`, `\frac{d}{dt}(…)`: the derivative, if the
    /// `\frac` (at `span`, its arguments next) is Leibniz notation.
    pub(super) fn leibniz(&mut self, span: Span) -> Result<Option<Expr>, SyntaxError> {
        let open = self.pos;
        if !self.is_ch('{') {
            return Ok(None);
        }
        let (Some(dlen), Some(close)) = (self.d_mark(open + 1), self.matching_brace(open)) else {
            return Ok(None);
        };
        // The numerator's `d` must be followed by its order, its operand or the end.
        let after_d = self.toks.get(open + 1 + dlen).map(|t| t.0.clone());
        self.pos = open + 1 + dlen;
        let operand_starts =
            matches!(after_d, Some(Tok::Ch('^' | '}'))) || self.starts_factor(false);
        self.pos = close + 1;
        let denominator = if operand_starts {
            self.leibniz_denominator()?
        } else {
            None
        };
        let Some((var, vspan, order)) = denominator else {
            self.pos = open;
            return Ok(None);
        };
        let after = self.pos;
        self.pos = open + 1 + dlen;
        let upper = self.leibniz_order()?;
        if upper != order {
            return Err(SyntaxError::new(
                span.to(self.toks[after - 1].1),
                format!("a derivative of order {upper} over `d{var}` to the power {order}: the orders must agree"),
            ));
        }
        let operand = if self.eat_ch('}') {
            None
        } else {
            let e = self.expr()?;
            self.expect_ch('}', "`}` closing the numerator")?;
            Some(e)
        };
        self.pos = after;
        let operand = match operand {
            Some(e) => e,
            None => self.leibniz_operand(span)?,
        };
        Ok(Some(derivative(operand, var, vspan, order, span)))
    }

    /// `dx/dt`, `d^2x/dt^2`, `\mathrm{d}\theta/\mathrm{d}t`, `d/dt (m v)` written with a
    /// slash: the derivative, if the next tokens are one (else nothing is consumed).
    pub(super) fn slash_leibniz(&mut self) -> Result<Option<Expr>, SyntaxError> {
        let start = self.pos;
        let span = self.span();
        let Some((operand, var, vspan, order)) = self.slash_leibniz_shape()? else {
            self.pos = start;
            return Ok(None);
        };
        let after = self.pos;
        self.pos = start + self.d_mark(start).unwrap_or(1);
        let upper = self.leibniz_order()?;
        self.pos = after;
        let span = span.to(self.last_span());
        if upper != order {
            return Err(SyntaxError::new(
                span,
                format!("a derivative of order {upper} over `d{var}` to the power {order}: the orders must agree"),
            ));
        }
        let operand = match operand {
            Some(e) => e,
            None => self.leibniz_operand(span)?,
        };
        Ok(Some(derivative(operand, var, vspan, order, span)))
    }

    /// Whether the next tokens are `d[^n]x / d t[^n]` or `d[^n] / d t[^n]`: the symbol
    /// above the line (none for the operator), the variable, its span and the order
    /// below the line; the position is then after them.
    #[allow(clippy::type_complexity)]
    fn slash_leibniz_shape(
        &mut self,
    ) -> Result<Option<(Option<Expr>, String, Span, u32)>, SyntaxError> {
        let Some(dlen) = self.d_mark(self.pos) else {
            return Ok(None);
        };
        self.pos += dlen;
        if self.is_ch('^') {
            self.pos += 1;
            self.arg()?;
        }
        let operand = if self.is_ch('/') {
            None
        } else {
            let Some(name) = self.variable_name() else {
                return Ok(None);
            };
            let Ok(sym) = self.symbol(name, self.last_span()) else {
                return Ok(None);
            };
            Some(sym)
        };
        if !self.eat_ch('/') {
            return Ok(None);
        }
        let Some(dlen) = self.d_mark(self.pos) else {
            return Ok(None);
        };
        self.pos += dlen;
        let Some(var) = self.variable_name() else {
            return Ok(None);
        };
        let Ok(v) = self.symbol(var, self.last_span()) else {
            return Ok(None);
        };
        let ExprKind::Sym(name) = v.kind else {
            return Ok(None);
        };
        if name.contains('\'') {
            return Ok(None);
        }
        let order = self.leibniz_order()?;
        Ok(Some((operand, name, v.span, order)))
    }

    /// A letter or Greek letter next, consumed: its name.
    fn variable_name(&mut self) -> Option<String> {
        let name = match self.peek()? {
            Tok::Letter(c) => c.to_string(),
            Tok::Cmd(c) => greek_name(c)?.to_string(),
            _ => return None,
        };
        self.pos += 1;
        Some(name)
    }

    /// What `\frac{d}{dt}` differentiates: a bracket (with its power), else the
    /// juxtaposed factors after it, as a function's argument.
    fn leibniz_operand(&mut self, span: Span) -> Result<Expr, SyntaxError> {
        let bracket = self.is_ch('(') || self.is_ch('[') || self.is_ch('{') || self.is_cmd("left");
        if bracket {
            return self.factor();
        }
        if self.starts_factor(false) {
            return self.argument_run();
        }
        Err(SyntaxError::new(
            span.to(self.last_span()),
            "a derivative `\\frac{d}{dt}` with nothing after it to differentiate",
        ))
    }
}

/// The derivative of `operand` by `var` of order `order`: `x'` for a lone symbol with
/// respect to `t`, else `diff(operand, var[, order])` marked as Leibniz notation.
fn derivative(operand: Expr, var: String, vspan: Span, order: u32, span: Span) -> Expr {
    let whole = span.to(operand.span).to(vspan);
    if var == "t" {
        if let ExprKind::Sym(n) = &operand.kind {
            if n != "t" {
                let primes = "'".repeat(order as usize);
                return node(ExprKind::Sym(format!("{n}{primes}")), whole);
            }
        }
    }
    let mut args = vec![operand, node(ExprKind::Sym(var), vspan)];
    if order > 1 {
        let n = BigRational::from_integer(BigInt::from(order));
        args.push(node(ExprKind::Num(n), vspan));
    }
    node(ExprKind::Call(Func::Diff, args), whole).read_as(Reading::Leibniz)
}
