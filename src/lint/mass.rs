//! Chains through `\int f\,dm` when the notes declare no body: the mass element is
//! defined in prose, so such an integral has no value rigor can compute. What can
//! still be checked is what holds for every mass distribution: a step that only moves
//! constants across integrals and adds or splits them (linearity), such as the
//! parallel-axis expansion `\int ((x+a)^2 + (y+b)^2)\,dm = \int (x^2+y^2)\,dm +
//! \int (a^2+b^2)\,dm + 2a\int x\,dm + 2b\int y\,dm`.
//!
//! Reading convention: a symbol written outside every integral of a step cannot be the
//! integration variable, so it is constant over the body and may cross an integral.
//! Each side is read as Σ cᵢ ∫ fᵢ dm + r; the step holds for every body when
//! Σ cᵢ fᵢ agrees on both sides as a function and the r agree, which two claims check
//! through the one checker entry. Anything else needs context, never fails: the step
//! may hold for the body the notes mean.

use super::{free, ChainReport, Checked, Verdict};
use crate::check::Options;
use crate::diag::Code;
use crate::diag::Diagnostic;
use crate::syntax::ast::{BinOp, Chain, Expr, ExprKind, Func, Span};
use crate::syntax::print::source;

/// Whether a tree integrates over `dm` with no body declared (`\int r^2\,dm`).
pub(super) fn prose_mass(e: &Expr) -> bool {
    e.any(&|n| {
        matches!(&n.kind, ExprKind::Call(Func::Int, args)
            if args.len() == 2 && matches!(&args[1].kind, ExprKind::Sym(v) if v == "dm"))
    })
}

/// A side read as Σ cᵢ ∫ fᵢ dm + r (as source text).
#[derive(Default)]
struct Linear {
    /// Each integral's coefficient times its integrand: cᵢ·fᵢ.
    under: Vec<String>,
    /// The terms outside integrals.
    rest: Vec<String>,
}

impl Linear {
    fn scaled(self, by: impl Fn(&str) -> String) -> Linear {
        Linear {
            under: self.under.iter().map(|t| by(t)).collect(),
            rest: self.rest.iter().map(|t| by(t)).collect(),
        }
    }

    fn plus(mut self, other: Linear) -> Linear {
        self.under.extend(other.under);
        self.rest.extend(other.rest);
        self
    }

    fn sum(terms: &[String]) -> String {
        if terms.is_empty() {
            "0".into()
        } else {
            terms.join(" + ")
        }
    }
}

/// The side as Σ cᵢ ∫ fᵢ dm + r, if it is linear in its integrals over `dm`.
fn linear(e: &Expr) -> Option<Linear> {
    if !prose_mass(e) {
        return Some(Linear {
            under: Vec::new(),
            rest: vec![source(e)],
        });
    }
    match &e.kind {
        ExprKind::Call(Func::Int, args) if args.len() == 2 => {
            (!prose_mass(&args[0])).then(|| Linear {
                under: vec![source(&args[0])],
                rest: Vec::new(),
            })
        }
        ExprKind::Neg(a) => Some(linear(a)?.scaled(|t| format!("(-({t}))"))),
        ExprKind::Bin(BinOp::Add, a, b) => Some(linear(a)?.plus(linear(b)?)),
        ExprKind::Bin(BinOp::Sub, a, b) => {
            Some(linear(a)?.plus(linear(b)?.scaled(|t| format!("(-({t}))"))))
        }
        ExprKind::Bin(BinOp::Mul, a, b) if !prose_mass(a) => {
            let c = source(a);
            Some(linear(b)?.scaled(|t| format!("(({c}) * ({t}))")))
        }
        ExprKind::Bin(BinOp::Mul, a, b) if !prose_mass(b) => {
            let c = source(b);
            Some(linear(a)?.scaled(|t| format!("(({t}) * ({c}))")))
        }
        ExprKind::Bin(BinOp::Div, a, b) if !prose_mass(b) => {
            let c = source(b);
            Some(linear(a)?.scaled(|t| format!("(({t}) / ({c}))")))
        }
        _ => None,
    }
}

/// Whether the step `a = b` holds for every mass distribution.
fn holds_for_every_body(a: &Expr, b: &Expr, (opts, cache): (&Options, &Checked)) -> bool {
    let (Some(l), Some(r)) = (linear(a), linear(b)) else {
        return false;
    };
    if l.under.is_empty() && r.under.is_empty() {
        return false;
    }
    let mut names = Vec::new();
    free(a, &mut Vec::new(), &mut names);
    free(b, &mut Vec::new(), &mut names);
    let mut time: Vec<String> = names
        .iter()
        .filter(|n| n.ends_with('\''))
        .map(|n| n.trim_end_matches('\'').to_string())
        .collect();
    time.sort();
    time.dedup();
    let reals: Vec<&String> = names
        .iter()
        .filter(|n| !n.ends_with('\'') && !time.contains(n))
        .collect();
    let mut deriv = String::new();
    if !reals.is_empty() {
        let reals: Vec<&str> = reals.iter().map(|s| s.as_str()).collect();
        deriv.push_str(&format!("symbols {}\n", reals.join(" ")));
    }
    if !time.is_empty() {
        deriv.push_str(&format!("time {}\n", time.join(" ")));
    }
    deriv.push_str(&format!(
        "claim {} = {}\nclaim {} = {}\n",
        Linear::sum(&l.under),
        Linear::sum(&r.under),
        Linear::sum(&l.rest),
        Linear::sum(&r.rest)
    ));
    let checked = cache.report("step", &deriv, opts);
    checked.claims.len() == 2 && checked.ok()
}

/// A chain that integrates over a mass element the notes define in prose (`\int y^2
/// dm = \int_{-L/2}^{L/2} y^2 \frac{m}{L}\,dy = \frac{mL^2}{12}`): each of its steps up
/// to the first expression free of such integrals holds for every body (linearity) or
/// needs context, and runs of each are reported as chains; the steps from that
/// expression on are a chain of their own, checked as any other.
pub(super) fn over_prose_mass(
    chain: Chain,
    opts: (&Options, &Checked),
) -> (Vec<ChainReport>, Option<Chain>) {
    let exprs: Vec<&Expr> = chain.exprs().collect();
    let Some(k) = exprs.iter().rposition(|e| prose_mass(e)) else {
        return (Vec::new(), Some(chain));
    };
    let last = (k + 1).min(exprs.len() - 1);
    let mut reports: Vec<ChainReport> = Vec::new();
    for i in 1..=last.max(1) {
        let (Some(a), Some(b)) = (exprs.get(i - 1), exprs.get(i)) else {
            break;
        };
        let verdict = if holds_for_every_body(a, b, opts) {
            Verdict::Verified
        } else {
            Verdict::NeedsContext
        };
        let span = a.span.to(b.span);
        match reports.last_mut() {
            Some(r) if r.verdict == verdict => r.span = r.span.to(span),
            _ => reports.push(ChainReport::new(span, verdict, Vec::new())),
        }
    }
    for r in &mut reports {
        if r.verdict == Verdict::NeedsContext {
            r.reason = Some(super::Reason::ProseMass);
            r.diagnostics.push(needs_body(r.span));
        }
    }
    let rest = (k + 2 < exprs.len()).then(|| Chain {
        first: exprs[k + 1].clone(),
        links: chain.links[k + 1..].to_vec(),
    });
    (reports, rest)
}

fn needs_body(span: Span) -> Diagnostic {
    Diagnostic::error(
        Code::NotVerified,
        "needs context: it integrates over dm, a mass element the notes define in prose; \
         declare the body in a `rigor: body …` comment to have it checked",
        span,
        "",
    )
}
