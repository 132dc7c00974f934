//! The work a file skipped, filled in from the engine's own computation (`rigor latex
//! --steps`): each integral evaluated stage by stage — the mass element substituted,
//! each antiderivative between its bounds, the value — and, for a link verified with
//! the facts, the unknowns the checker solved, from which facts, and the two sides once
//! their values are substituted.
//!
//! Integrals are recomputed with the engine's own functions (`lower`, `Lowerer`'s
//! scoping of bound variables, `calculus::antiderivative`, `subst_atom`,
//! `Body::integrate`) in the environment the checker ended the file with, and shown
//! only when their last stage is the value the checker computes for the integral as
//! written. Eliminations are the checker's record ([`Working`]). Every value is printed
//! by [`super::expr`] after a round trip through rigor's plain syntax, so it typesets
//! like the rest of the document; nothing here decides truth.

use super::expr::{expr_latex_in, rel_latex, symbol, Ctx};
use super::solution::Inline;
use crate::calculus::{antiderivative, Body};
use crate::check::report::Working;
use crate::diag::{Cited, FactRef};
use crate::lower::{lower, Env, Lowerer};
use crate::normal::atom::{self, Atom, AtomId};
use crate::normal::mono::Mono;
use crate::normal::print::plain;
use crate::normal::subst::{atom_depends_on, subst_atom};
use crate::normal::{Assumptions, Poly, Rat, Sign};
use crate::syntax::ast::{BinOp, BodyDef, Expr, ExprKind, File, Func, Item, RelOp, Span, StmtKind};

/// Work filled in: a sentence, then aligned lines (none when the sentence says it all).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Work {
    /// The sentence before the lines: raw text and math.
    pub lead: Vec<Inline>,
    /// The lines.
    pub lines: Vec<Line>,
}

impl Work {
    /// The lines as the rows of an aligned environment (each ending in a newline, `\\`
    /// between rows), the text of notes escaped by `text` for where it is set.
    pub(crate) fn rows(&self, text: impl Fn(&str) -> String) -> String {
        let mut out = String::new();
        for (i, l) in self.lines.iter().enumerate() {
            out.push_str(&format!("{} &{} {}", l.lhs, l.rel, l.rhs));
            if !l.note.is_empty() {
                out.push_str(" \\quad");
                for part in &l.note {
                    match part {
                        Inline::Math(m) => out.push_str(&format!(" {m}")),
                        Inline::Text(t) | Inline::Strong(t) | Inline::Code(t) => {
                            out.push_str(&format!("\\text{{{}}}", text(t)))
                        }
                    }
                }
            }
            if i + 1 < self.lines.len() {
                out.push_str(" \\\\");
            }
            out.push('\n');
        }
        out
    }
}

/// One aligned line of filled-in work: `lhs rel rhs` (LaTeX), then a note.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Line {
    /// The left side; empty on a continuation line.
    pub lhs: String,
    /// The relation (LaTeX); empty for a line that is one expression.
    pub rel: &'static str,
    /// The right side.
    pub rhs: String,
    /// Raw text and math after the line (`from (3)`).
    pub note: Vec<Inline>,
}

impl Line {
    fn new(lhs: String, rel: &'static str, rhs: String) -> Line {
        Line {
            lhs,
            rel,
            rhs,
            note: Vec::new(),
        }
    }
}

/// What the work of one file is computed from, and the integrals already worked.
pub(crate) struct Steps<'a> {
    env: &'a Env,
    ast: &'a File,
    /// The LaTeX of every integral worked so far: each is worked once per file.
    done: Vec<String>,
    /// The abstract bodies whose moments were explained once already.
    explained: Vec<String>,
}

/// One stage of an iterated integral, outermost first.
struct Stage {
    /// The variable's name and atom.
    var: String,
    x: AtomId,
    /// The bounds as written.
    lo: Expr,
    hi: Expr,
    /// The bounds as the engine lowered them.
    lo_v: Rat,
    hi_v: Rat,
    /// The signs the antiderivative is taken under (the variable bound).
    inside: Assumptions,
    /// The signs the bounds are substituted under.
    at: Assumptions,
}

/// A node with no span (the work is not in the file).
fn node(kind: ExprKind) -> Expr {
    Expr::new(kind, Span::new(0, 0))
}

/// `a op b`.
fn bin(op: BinOp, a: Expr, b: Expr) -> Expr {
    node(ExprKind::Bin(op, Box::new(a), Box::new(b)))
}

/// A normal form as an expression tree, through rigor's plain syntax.
fn tree(r: &Rat) -> Option<Expr> {
    crate::syntax::parse_expr(&plain(r), &crate::syntax::ParseOptions::default()).ok()
}

/// A plain-syntax text (as the checker records it) as an expression tree.
fn parsed(s: &str) -> Option<Expr> {
    crate::syntax::parse_expr(s, &crate::syntax::ParseOptions::default()).ok()
}

/// [`as_written`](super::pieces::as_written) as a tree.
fn shown(s: &str, env: &Env) -> Option<Expr> {
    parsed(&super::pieces::as_written(s, env)).or_else(|| parsed(s))
}

/// `env` with `vars` bound, as `Lowerer` binds them inside an integral: each knows
/// only its sign (no interval), and a `let` of the same name does not apply.
fn bind(env: &Env, vars: &[(String, Sign)]) -> Env {
    let mut e = env.clone();
    for (name, sign) in vars {
        let x = atom::sym(name);
        e.signs.set(x, *sign);
        e.signs.set_range(x, None);
        e.defs.remove(name);
    }
    e
}

/// The integrals of `e` that are not inside another binding form (`int`, `diff`,
/// `eval`, `subs`), in the order written.
fn integral_calls<'e>(e: &'e Expr, out: &mut Vec<&'e Expr>) {
    match &e.kind {
        ExprKind::Call(Func::Int, _) => out.push(e),
        ExprKind::Call(Func::Diff | Func::Eval | Func::Subs, _) => {}
        ExprKind::Call(_, args) => args.iter().for_each(|a| integral_calls(a, out)),
        ExprKind::Neg(a) => integral_calls(a, out),
        ExprKind::Bin(_, a, b) => {
            integral_calls(a, out);
            integral_calls(b, out);
        }
        _ => {}
    }
}

/// `∫_{lo}^{hi} … d var` around `inner`, for `stages` (outermost first).
fn wrap(stages: &[Stage], inner: Expr) -> Expr {
    stages.iter().rev().fold(inner, |e, st| {
        node(ExprKind::Call(
            Func::Int,
            vec![
                e,
                node(ExprKind::Sym(st.var.clone())),
                st.lo.clone(),
                st.hi.clone(),
            ],
        ))
    })
}

/// `[F]_{var=lo}^{var=hi}`.
fn bracket(big: Expr, st: &Stage) -> Expr {
    node(ExprKind::Call(
        Func::Eval,
        vec![
            big,
            node(ExprKind::Sym(st.var.clone())),
            st.lo.clone(),
            st.hi.clone(),
        ],
    ))
}

/// `$x$, then $y$, then $z$`, innermost first.
fn order_of(stages: &[Stage]) -> Vec<Inline> {
    let mut out = Vec::new();
    for (k, st) in stages.iter().rev().enumerate() {
        if k > 0 {
            out.push(Inline::Text(", then ".into()));
        }
        out.push(Inline::Math(symbol(&st.var)));
    }
    out
}

impl<'a> Steps<'a> {
    /// The work of a file checked in `env`.
    pub fn new(env: &'a Env, ast: &'a File) -> Steps<'a> {
        Steps {
            env,
            ast,
            done: Vec::new(),
            explained: Vec::new(),
        }
    }

    /// The work of every integral in `exprs` not worked before in this file.
    pub fn integrals(&mut self, exprs: &[&Expr], ctx: &Ctx) -> Vec<Work> {
        let mut calls = Vec::new();
        for e in exprs {
            integral_calls(e, &mut calls);
        }
        let mut out = Vec::new();
        for call in calls {
            let key = expr_latex_in(call, ctx);
            if self.done.contains(&key) {
                continue;
            }
            self.done.push(key);
            // The same integral written another way (over the body, then with its
            // variable) is worked once.
            if let Some((work, same)) = self.integral(call, ctx) {
                if let Some(b) = work.1.clone() {
                    self.explained.push(b);
                }
                let work = work.0;
                if !self.done.contains(&same) {
                    self.done.push(same);
                    out.push(work);
                }
            }
        }
        out
    }

    /// The work of one integral as written, if the engine evaluates it, and what it
    /// integrates (the integrand's normal form and the ranges), which says when two
    /// are the same.
    fn integral(&self, call: &Expr, ctx: &Ctx) -> Option<((Work, Option<String>), String)> {
        let ExprKind::Call(Func::Int, args) = &call.kind else {
            return None;
        };
        let value = lower(call, self.env).ok()?;
        let work = match args.as_slice() {
            [f, x] => {
                let ExprKind::Sym(name) = &x.kind else {
                    return None;
                };
                let (body_name, body) = self.body(name)?;
                match body {
                    Body::Concrete { .. } => self.over_body(f, &body_name, body, ctx),
                    Body::Abstract { .. } => self.in_moments(f, body, ctx),
                }
            }
            [_, _, _, _] => self.definite(call),
            _ => None,
        }?;
        let ((lead, rows), last, same) = work;
        // Shown only when it ends where the checker's own evaluation does.
        if last != value {
            return None;
        }
        let lines = chain(expr_latex_in(call, ctx), &rows, ctx);
        let explains = match args.as_slice() {
            [_, x] => match &x.kind {
                ExprKind::Sym(n) => self.body(n).map(|b| b.0),
                _ => None,
            },
            _ => None,
        };
        (!lines.is_empty()).then_some(((Work { lead, lines }, explains), same))
    }

    /// The body `int(f, name)` is over (`dm`: the only body), with its name.
    fn body(&self, name: &str) -> Option<(String, &'a Body)> {
        let bodies = &self.env.bodies;
        if name == "dm" && !bodies.contains_key("dm") {
            if bodies.len() != 1 {
                return None;
            }
            return bodies.iter().next().map(|(n, b)| (n.clone(), b));
        }
        bodies.get(name).map(|b| (name.to_string(), b))
    }

    /// The mass element and the ranges of a concrete body, as declared.
    fn declaration(&self, name: &str) -> Option<(&'a Expr, &'a [crate::syntax::ast::Range])> {
        self.ast.items.iter().find_map(|item| match item {
            Item::Stmt(st) => match &st.kind {
                StmtKind::Body {
                    name: n,
                    def: BodyDef::Concrete { dm, ranges },
                } if n.name == name => Some((dm, ranges.as_slice())),
                _ => None,
            },
            _ => None,
        })
    }

    /// `∫ f dm` over a concrete body: the mass element substituted, then each
    /// coordinate integrated in turn, innermost first (as `Body::integrate` does).
    fn over_body(&self, f: &Expr, name: &str, body: &Body, ctx: &Ctx) -> Option<Worked> {
        let Body::Concrete { density, ranges } = body else {
            return None;
        };
        let (dm, declared) = self.declaration(name)?;
        let vars = Lowerer::new(self.env).coordinate_signs(body);
        let inside = bind(self.env, &vars);
        let g = lower(f, &inside).ok()?.mul(density).ok()?;
        let mut stages = Vec::new();
        for ((x, lo_v, hi_v), r) in ranges.iter().zip(declared) {
            if atom::sym(&r.var.name) != *x {
                return None;
            }
            stages.push(Stage {
                var: r.var.name.clone(),
                x: *x,
                lo: r.from.clone(),
                hi: r.to.clone(),
                lo_v: lo_v.clone(),
                hi_v: hi_v.clone(),
                inside: inside.signs.clone(),
                at: inside.signs.clone(),
            });
        }
        let shown = match &f.kind {
            ExprKind::Num(q) if num_traits::One::is_one(q) => tree(density)?,
            _ => bin(BinOp::Mul, f.clone(), tree(density)?),
        };
        let same = content(&g, &stages);
        let (rows, last) = iterate(&stages, g, shown)?;
        let mut lead = vec![
            Inline::Text("With the mass element ".into()),
            Inline::Math(format!("dm = {}", expr_latex_in(dm, ctx))),
            Inline::Text(" of ".into()),
            Inline::Math(symbol(name)),
            Inline::Text(", integrating over ".into()),
        ];
        lead.extend(order_of(&stages));
        lead.push(Inline::Text(":".into()));
        Some(((lead, rows), last, same))
    }

    /// `int(f, x, a, b)`, nested definite integrals taken as one iterated integral:
    /// each bound lowered with the outer variables bound, as the engine does.
    fn definite(&self, call: &Expr) -> Option<Worked> {
        let mut stages = Vec::new();
        let mut scope = self.env.clone();
        let mut cur = call;
        while let ExprKind::Call(Func::Int, args) = &cur.kind {
            let [f, x, a, b] = args.as_slice() else {
                break;
            };
            let ExprKind::Sym(var) = &x.kind else {
                return None;
            };
            if var == "t" && !self.env.time.is_empty() {
                // Integrals over time follow `time` symbols: not worked here.
                if stages.is_empty() {
                    return None;
                }
                break;
            }
            let lo_v = lower(a, &scope).ok()?;
            let hi_v = lower(b, &scope).ok()?;
            let sign = Lowerer::new(&scope).range_sign(&lo_v, &hi_v);
            let inner = bind(&scope, &[(var.clone(), sign)]);
            stages.push(Stage {
                var: var.clone(),
                x: atom::sym(var),
                lo: a.clone(),
                hi: b.clone(),
                lo_v,
                hi_v,
                inside: inner.signs.clone(),
                at: scope.signs.clone(),
            });
            scope = inner;
            cur = f;
        }
        let g = lower(cur, &scope).ok()?;
        let same = content(&g, &stages);
        let (mut rows, last) = iterate(&stages, g, cur.clone())?;
        // The first row is the integral as written.
        rows.remove(0);
        let mut lead = vec![Inline::Text("Integrating over ".into())];
        lead.extend(order_of(&stages));
        lead.push(Inline::Text(":".into()));
        Some(((lead, rows), last, same))
    }

    /// `∫ f dm` over an abstract body: by linearity a sum of moments `∫ xⁱ yʲ dm`, then
    /// `∫ dm = m` and, for a centred body, the first moments zero (`Body::integrate`).
    fn in_moments(&self, f: &Expr, body: &Body, ctx: &Ctx) -> Option<Worked> {
        let Body::Abstract {
            name,
            mass,
            coords,
            centred,
        } = body
        else {
            return None;
        };
        let vars = Lowerer::new(self.env).coordinate_signs(body);
        let inside = bind(self.env, &vars);
        let fv = lower(f, &inside).ok()?;
        let last = body.integrate(&fv, &inside.signs).ok()?;
        let moments = moments(&fv, name, coords)?;
        let rows = vec![tree(&moments)?, tree(&last)?];
        let same = format!("{name}: {}", plain(&fv));
        if self.explained.contains(name) {
            let lead = vec![
                Inline::Text("In moments of ".into()),
                Inline::Math(symbol(name)),
                Inline::Text(":".into()),
            ];
            return Some(((lead, rows), last, same));
        }
        let int_of = |e: Expr| {
            let call = ExprKind::Call(Func::Int, vec![e, node(ExprKind::Sym(name.clone()))]);
            expr_latex_in(&node(call), ctx)
        };
        let mut lead = vec![
            Inline::Text("By linearity, in moments of ".into()),
            Inline::Math(symbol(name)),
            Inline::Text(", with ".into()),
            Inline::Math(format!(
                "{} = {}",
                int_of(node(ExprKind::Num(num_traits::One::one()))),
                expr_latex_in(&tree(mass)?, ctx)
            )),
        ];
        if *centred {
            let firsts: Vec<String> = coords
                .iter()
                .map(|c| int_of(node(ExprKind::Sym(c.0.clone()))))
                .collect();
            lead.push(Inline::Text(" and, the body being centred, ".into()));
            lead.push(Inline::Math(format!("{} = 0", firsts.join(" = "))));
        }
        lead.push(Inline::Text(":".into()));
        Some(((lead, rows), last, same))
    }
}

/// What an iterated integral integrates: its integrand's normal form and its ranges.
fn content(g: &Rat, stages: &[Stage]) -> String {
    let mut out = plain(g);
    for st in stages {
        out.push_str(&format!(
            " | {} from {} to {}",
            st.var,
            plain(&st.lo_v),
            plain(&st.hi_v)
        ));
    }
    out
}

/// A worked integral: its lead and rows (right sides, in order), its last value, and
/// what it integrates.
type Worked = ((Vec<Inline>, Vec<Expr>), Rat, String);

/// The rows of an iterated integral: the integrand shown under all the integrals,
/// then for each variable, innermost first, its antiderivative between the bounds and
/// what that leaves (for the last, the upper value minus the lower one too). Returns
/// the rows and the last value.
fn iterate(stages: &[Stage], g: Rat, shown: Expr) -> Option<(Vec<Expr>, Rat)> {
    let mut rows = vec![wrap(stages, shown)];
    let mut g = g;
    for (k, st) in stages.iter().enumerate().rev() {
        let big = antiderivative(&g, st.x, &st.inside).ok()?;
        rows.push(wrap(&stages[..k], bracket(tree(&big)?, st)));
        let hi = subst_atom(&big, st.x, &st.hi_v, &st.at).ok()?;
        let lo = subst_atom(&big, st.x, &st.lo_v, &st.at).ok()?;
        g = hi.sub(&lo).ok()?;
        if k == 0 && !lo.is_zero() {
            rows.push(bin(BinOp::Sub, tree(&hi)?, tree(&lo)?));
        }
        rows.push(wrap(&stages[..k], tree(&g)?));
    }
    Some((rows, g))
}

/// How many units wide the LaTeX of a formula is, roughly: a character or a command
/// is one (an integral sign three), spacing and grouping nothing (a fraction counts
/// both its parts, so this errs wide).
fn width(latex: &str) -> usize {
    let mut n = 0;
    let mut chars = latex.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '\\' => {
                let mut name = String::new();
                while let Some(&d) = chars.peek().filter(|d| d.is_ascii_alphabetic()) {
                    name.push(d);
                    chars.next();
                }
                n += match name.as_str() {
                    "" => usize::from(chars.next().is_some_and(|d| d != ',')),
                    "left" | "right" | "frac" | "mathit" => 0,
                    "int" => 3,
                    _ => 1,
                };
            }
            '{' | '}' | '_' | '^' | ' ' => {}
            _ => n += 1,
        }
    }
    n
}

/// The widest line of filled-in work, in [`width`] units, that fits inside the
/// quotation on the page.
const LINE_WIDTH: usize = 60;

/// The terms of a sum as written, each with the sign it is added with (`None` first).
fn terms(e: &Expr) -> Vec<(Option<BinOp>, &Expr)> {
    let mut out = Vec::new();
    let mut cur = e;
    while let ExprKind::Bin(op @ (BinOp::Add | BinOp::Sub), l, r) = &cur.kind {
        out.push((Some(*op), r.as_ref()));
        cur = l;
    }
    out.push((None, cur));
    out.reverse();
    out
}

/// `row` after `= `, as one line, or a sum too wide for the page broken before terms
/// onto continuation lines (`\quad + …`).
fn fit(lhs: &str, row: &Expr, ctx: &Ctx) -> Vec<String> {
    let whole = expr_latex_in(row, ctx);
    let parts = terms(row);
    if width(lhs) + width(&whole) <= LINE_WIDTH || parts.len() < 2 {
        return vec![whole];
    }
    let mut out: Vec<String> = Vec::new();
    let mut cur = String::new();
    for (op, t) in parts {
        let s = expr_latex_in(t, ctx);
        let needs = s.starts_with('-')
            || (op == Some(BinOp::Sub)
                && matches!(&t.kind, ExprKind::Bin(BinOp::Add | BinOp::Sub, ..)));
        let s = if needs {
            format!("\\left({s}\\right)")
        } else {
            s
        };
        let piece = match op {
            None => s,
            Some(BinOp::Sub) => format!("- {s}"),
            Some(_) => format!("+ {s}"),
        };
        let budget = LINE_WIDTH.saturating_sub(if out.is_empty() { width(lhs) } else { 4 });
        if !cur.is_empty() && width(&cur) + width(&piece) > budget {
            out.push(std::mem::take(&mut cur));
        }
        if !cur.is_empty() {
            cur.push(' ');
        }
        cur.push_str(&piece);
    }
    out.push(cur);
    out
}

/// `lhs = r₁ = r₂ …` as aligned lines, a row equal to the one before it dropped and a
/// row too wide broken after its terms.
fn chain(lhs: String, rows: &[Expr], ctx: &Ctx) -> Vec<Line> {
    let mut lines: Vec<Line> = Vec::new();
    let mut prev = lhs.clone();
    for r in rows {
        let latex = expr_latex_in(r, ctx);
        if latex == prev {
            continue;
        }
        prev = latex;
        let left = if lines.is_empty() {
            lhs.clone()
        } else {
            String::new()
        };
        for (k, piece) in fit(&left, r, ctx).into_iter().enumerate() {
            lines.push(if k == 0 {
                Line::new(left.clone(), "=", piece)
            } else {
                Line::new(String::new(), "", format!("\\quad {piece}"))
            });
        }
    }
    lines
}

/// `f` integrated term by term over an abstract body: each coefficient times its
/// moment `∫ xⁱ yʲ dm`, the mass and first moments not yet applied.
fn moments(f: &Rat, body: &str, coords: &[(String, AtomId)]) -> Option<Rat> {
    if coords.iter().any(|c| f.den().contains(c.1)) {
        return None;
    }
    let mut total = Rat::zero();
    for (m, q) in f.num().terms() {
        let mut exps = vec![0u32; coords.len()];
        let mut rest = Vec::new();
        for &(a, e) in m.pairs() {
            match coords.iter().position(|c| c.1 == a) {
                Some(i) => *exps.get_mut(i)? = e,
                None if coords.iter().any(|c| atom_depends_on(a, c.1)) => return None,
                None => rest.push((a, e)),
            }
        }
        let coeff = Rat::poly(Poly::term(Mono::from_pairs(rest)?, q.clone())).ok()?;
        let named = coords
            .iter()
            .zip(&exps)
            .map(|(c, e)| (c.0.clone(), *e))
            .collect();
        let moment = Rat::atom(atom::intern(Atom::Moment(body.to_string(), named)));
        total = total.add(&coeff.mul(&moment).ok()?).ok()?;
    }
    total.div(&Rat::poly(f.den().clone()).ok()?).ok()
}

/// How the document cites a fact the checker names `[Fx]`, `[noslip]''` or `line 12`:
/// `(3)`, `(5) differentiated twice`, `the equation on line 12`. `number` gives a
/// label's equation number.
fn cite(fact: &Cited, number: &dyn Fn(&str) -> String) -> String {
    let main = match &fact.fact {
        FactRef::Label(label) => format!("({})", number(label)),
        FactRef::Line(n) => format!("the equation on line {n}"),
    };
    match fact.derivative {
        0 => main,
        1 => format!("{main} differentiated"),
        2 => format!("{main} differentiated twice"),
        k => format!("{main} differentiated {k} times"),
    }
}

/// The work behind a link verified with the facts: the unknowns solved, each from its
/// fact, then the two sides with their values substituted (or the difference of the
/// sides as a multiple of one fact). `line` names the link in a claim of several.
pub(crate) fn elimination(
    w: &Working,
    op: RelOp,
    line: Option<usize>,
    ctx: &Ctx,
    env: &Env,
    number: &dyn Fn(&str) -> String,
) -> Option<Vec<Work>> {
    let latex = |s: &str| shown(s, env).map(|e| expr_latex_in(&e, ctx));
    let prefix = line.map_or_else(String::new, |k| format!("Line {k}: "));
    let mut out = Vec::new();
    // As a tutor says it: "From (4), θ̈ = …", one fact at a time.
    for (k, s) in w.solved.iter().enumerate() {
        let line = Line::new(latex(&s.unknown)?, "=", latex(&s.value)?);
        let from = if k == 0 && !prefix.is_empty() {
            format!("{prefix}from ")
        } else {
            "From ".to_string()
        };
        let mut lead = vec![Inline::Text(format!("{from}{}", cite(&s.fact, number)))];
        if let Some(d) = &s.divisor {
            lead.push(Inline::Text(", where ".into()));
            lead.push(Inline::Math(format!("{} \\neq 0", latex(d)?)));
        }
        lead.push(Inline::Text(":".into()));
        out.push(Work {
            lead,
            lines: vec![line],
        });
    }
    match &w.multiple {
        Some(m) => {
            let (difference, value) = (shown(&m.difference, env)?, shown(&m.value, env)?);
            let one = |e: &Expr| matches!(&e.kind, ExprKind::Num(q) if num_traits::One::is_one(q));
            let factor = shown(&m.factor, env)?;
            let product = match &factor.kind {
                _ if one(&factor) => value,
                ExprKind::Neg(f) if one(f) => node(ExprKind::Neg(Box::new(value))),
                _ => bin(BinOp::Mul, factor, value),
            };
            let fact = cite(&m.fact, number);
            let lead = match (out.is_empty(), prefix.is_empty()) {
                (false, _) => {
                    "Substituting, the difference of the two sides is a multiple of".to_string()
                }
                (true, true) => "The difference of the two sides is a multiple of".to_string(),
                (true, false) => {
                    format!("{prefix}the difference of the two sides is a multiple of")
                }
            };
            let zero = node(ExprKind::Num(num_traits::Zero::zero()));
            let mut lines = chain(expr_latex_in(&difference, ctx), &[product, zero], ctx);
            if let Some(last) = lines.last_mut() {
                last.note.push(Inline::Text(format!("by {fact}")));
            }
            out.push(Work {
                lead: vec![Inline::Text(format!("{lead} {fact}, so it is zero:"))],
                lines,
            });
        }
        None if !out.is_empty() => {
            let (lhs, rhs) = (latex(&w.lhs)?, latex(&w.rhs)?);
            let (lead, line) = if op == RelOp::Eq && lhs == rhs {
                (
                    "Substituting, both sides are",
                    Line::new(String::new(), "", lhs),
                )
            } else {
                (
                    "Substituting, the step reads",
                    Line::new(lhs, rel_latex(op), rhs),
                )
            };
            out.push(Work {
                lead: vec![Inline::Text(lead.into())],
                lines: vec![line],
            });
        }
        None => {}
    }
    (!out.is_empty()).then_some(out)
}
