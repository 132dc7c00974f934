//! The right kind of mistake, named on the term as written: when changing one term of
//! a side (its sign, a constant factor, one power of a symbol) makes the link hold after
//! the facts are used, the diagnosis says which term and how.

use super::elimination::{apply_steps, Step};
use super::step::LinkInput;
use super::walk::Checker;
use crate::decide::Diagnosis;
use crate::diag::Mistake;
use crate::lower::Lowerer;
use crate::normal::atom;
use crate::normal::{Rat, Q};
use crate::syntax::ast::{BinOp, Expr, ExprKind};
use num_traits::{One, Zero};

/// The additive terms of `e` as written, each with its sign in the side.
fn terms(e: &Expr, sign: i8, out: &mut Vec<(Expr, i8)>) {
    match &e.kind {
        ExprKind::Bin(BinOp::Add, a, b) => {
            terms(a, sign, out);
            terms(b, sign, out);
        }
        ExprKind::Bin(BinOp::Sub, a, b) => {
            terms(a, sign, out);
            terms(b, -sign, out);
        }
        _ => out.push((e.clone(), sign)),
    }
}

impl Checker<'_, '_> {
    /// "the term `2/5 m x''` has the wrong sign", when one term explains the difference
    /// `d` (left − right after the facts, with the elimination's `steps`).
    pub(super) fn term_diagnosis(
        &self,
        input: &LinkInput<'_>,
        d: &Rat,
        steps: &[Step],
    ) -> Option<Diagnosis> {
        if d.is_zero() {
            return None;
        }
        // The right side first: it is what was just written. When a term of each side
        // explains it, both are named.
        let right = self.side_diagnosis(input, &input.link.rhs, -1, d, steps);
        if right.is_some() && !input.first_link {
            return right;
        }
        let left = self.side_diagnosis(input, input.lhs_expr, 1, d, steps);
        match (right, left) {
            // The right side's kind: it is what was just written.
            (Some(r), Some(l)) => Some(Diagnosis {
                text: format!("{} (or, on the left, {})", r.text, l.text),
                ..r
            }),
            (r, l) => r.or(l),
        }
    }

    /// The single-term explanation on one side (`sigma`: +1 left, −1 right).
    fn side_diagnosis(
        &self,
        input: &LinkInput<'_>,
        side: &Expr,
        sigma: i8,
        d: &Rat,
        steps: &[Step],
    ) -> Option<Diagnosis> {
        let mut ts = Vec::new();
        terms(side, 1, &mut ts);
        if ts.len() < 2 {
            return None;
        }
        // A term with the wrong sign is the likeliest slip: it is named before a term
        // off by a factor or a power, wherever it stands.
        let mut other = None;
        for (t, s) in &ts {
            let Some(u) = self.term_value(input, t, steps) else {
                continue;
            };
            let u = if s * sigma < 0 { u.neg() } else { u };
            if u.is_zero() {
                continue;
            }
            let written = self
                .report
                .source
                .get(t.span.start..t.span.end)
                .unwrap_or("?");
            match explain(d, &u, written) {
                // A missing or extra term is said by the whole-side diagnosis, which names
                // it in normal form.
                Some(Why::Extra) => {}
                Some(Why::Other(Mistake::Sign, text)) => {
                    return Some(Diagnosis::term(Mistake::Sign, text))
                }
                Some(Why::Other(mistake, text)) => {
                    other = other.or(Some(Diagnosis::term(mistake, text)));
                }
                None => {}
            }
        }
        other
    }

    /// A term's value, with the claim's `where` and the elimination's steps applied.
    fn term_value(&self, input: &LinkInput<'_>, t: &Expr, steps: &[Step]) -> Option<Rat> {
        let v = Lowerer::new(&self.env).lower(t).ok()?;
        let v = self.apply_where(input.subs, &v).ok()?;
        apply_steps(&v, steps, &self.env.signs).ok()
    }
}

/// What one term explains.
enum Why {
    /// It should not be there (said by the whole-side diagnosis).
    Extra,
    /// Any other single-term change: its kind, and the sentence.
    Other(Mistake, String),
}

/// How one term's contribution `u` (to left − right) explains the difference `d`.
fn explain(d: &Rat, u: &Rat, written: &str) -> Option<Why> {
    let r = d.div(u).ok()?;
    if let Some(c) = r.as_constant() {
        let two = Q::from_integer(2.into());
        if c == two {
            return Some(Why::Other(
                Mistake::Sign,
                format!("the term `{written}` has the wrong sign"),
            ));
        }
        let k = Q::one() - &c;
        if k.is_zero() {
            return Some(Why::Extra);
        }
        let factor = Q::one() / k;
        // A negative factor is a sign and a factor at once: not one slip.
        if factor < Q::zero() {
            return None;
        }
        return Some(Why::Other(
            Mistake::Factor,
            format!(
                "the term `{written}` is {} × what it should be",
                show(&factor)
            ),
        ));
    }
    // 1 − r = x or 1/x: one power of a symbol too few or too many.
    let rest = Rat::one().sub(&r).ok()?;
    let single = |v: &Rat| -> Option<String> {
        match v.atoms().as_slice() {
            [a] if v.num().len() == 1 && v.den().is_one() && v.num().degree_in(*a) == 1 => {
                atom::sym_name(*a).filter(|_| v.num().terms()[0].1.is_one())
            }
            _ => None,
        }
    };
    if let Some(x) = single(&rest) {
        return Some(Why::Other(
            Mistake::Power,
            format!("the term `{written}` has one power of {x} too few"),
        ));
    }
    if let Some(x) = Rat::one().div(&rest).ok().as_ref().and_then(single) {
        return Some(Why::Other(
            Mistake::Power,
            format!("the term `{written}` has one power of {x} too many"),
        ));
    }
    None
}

fn show(q: &Q) -> String {
    if q.denom().is_one() {
        q.numer().to_string()
    } else {
        format!("{}/{}", q.numer(), q.denom())
    }
}
