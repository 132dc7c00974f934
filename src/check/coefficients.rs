//! `by [eom], [shm] comparing coefficients of theta`: the cited equations, each linear
//! and homogeneous in a `time` symbol and its derivatives, are combined (without
//! division) until only the symbol itself is left, `c theta = 0`; a motion that is not
//! zero at every instant then gives `c = 0`, and the link holds when its two sides
//! differ by a multiple of such a `c` that the declared signs show defined.

use super::signs::sign_of;
use super::step::LinkInput;
use super::walk::Checker;
use super::{Justification, Status};
use crate::diag::{Code, Diagnostic, FactRef};
use crate::normal::atom::{self, AtomId};
use crate::normal::print::plain;
use crate::normal::Rat;
use crate::syntax::ast::Name;
use foldhash::{HashMap, HashMapExt};

/// A linear form: each atom (the symbol or one of its derivatives) with its coefficient.
type Form = Vec<(AtomId, Rat)>;

impl Checker<'_, '_> {
    /// Decides `a = b` by comparing coefficients of `of` in the facts the link cites.
    pub(super) fn compare_coefficients(
        &mut self,
        input: &LinkInput<'_>,
        of: &Name,
        (a, b): (&Rat, &Rat),
    ) -> Result<Status, Diagnostic> {
        let span = input.span;
        let refuse = |why: String| Diagnostic::error(Code::NotVerified, why, of.span, "undecided");
        if input.link.op != crate::syntax::ast::RelOp::Eq {
            return Err(refuse(
                "comparing coefficients gives equations: it justifies `=` only".into(),
            ));
        }
        if self.scope.names.get(&of.name) != Some(&super::scope::Decl::Time) {
            return Err(refuse(format!(
                "not verified: `{}` is not declared with `time`; coefficients are compared in a quantity that varies with time, which the facts hold at every instant",
                of.name
            )));
        }
        let known = self.facts_in(input.by(), input.subs).unwrap_or_default();
        let mut forms = Vec::new();
        let mut cited: Vec<FactRef> = Vec::new();
        for k in &known {
            let value = self
                .apply_where(input.subs, &k.fact.value)
                .map_err(|e| refuse(format!("the `where` substitution fails: {e}")))?;
            let Some(form) = linear_form(&value, &of.name) else {
                return Err(refuse(format!(
                    "not verified: {} is not linear in `{}` and its derivatives with coefficients free of them, so its coefficients cannot be compared",
                    k.fact.name.fact, of.name
                ))
                .note(format!("the fact: {} = 0", plain(&value))));
            };
            forms.push(form);
            if !cited.contains(&k.fact.name.fact) {
                cited.push(k.fact.name.fact.clone());
            }
        }
        let theta = atom::sym(&of.name);
        let coefficients = eliminate_derivatives(forms, theta);
        let diff = a.sub(b).map_err(|e| refuse(e.to_string()))?;
        let holds = diff.is_zero()
            || coefficients
                .iter()
                .any(|c| self.multiple_of(&diff, c, &of.name));
        if holds {
            // The cited facts' own conditions, then the comparison's.
            let mut side_conditions: Vec<String> = known
                .iter()
                .flat_map(|k| &k.divisors)
                .map(|(v, need)| {
                    let op = match need {
                        crate::lower::Need::NonZero => "!=",
                        crate::lower::Need::Positive => ">",
                        crate::lower::Need::NonNegative => ">=",
                    };
                    format!("{} {op} 0", plain(v))
                })
                .collect();
            // The link's own divisors the signs do not show nonzero are assumed.
            side_conditions.extend(
                input
                    .divisors
                    .iter()
                    .filter(|(v, need)| {
                        *need != crate::lower::Need::NonZero
                            || !sign_of(v, &self.env.signs).is_nonzero()
                    })
                    .map(|(v, _)| format!("{} != 0", plain(v))),
            );
            side_conditions.dedup();
            side_conditions.push(format!("{} is not zero at every instant", of.name));
            // The fact this claim adds carries the cited facts' conditions; that the
            // motion is not zero at every instant is the premise of the file's
            // equations of motion, said once, here.
            self.conditions
                .extend(known.iter().flat_map(|k| k.divisors.iter().cloned()));
            return Ok(Status::Verified {
                how: Justification::Facts(cited),
                side_conditions,
            });
        }
        let found = coefficients
            .iter()
            .map(|c| format!("{} = 0", plain(c)))
            .collect::<Vec<_>>();
        let d = Diagnostic::error(
            Code::NotVerified,
            format!(
                "not verified: comparing coefficients of `{}` does not give this step",
                of.name
            ),
            span,
            "undecided",
        );
        Err(if found.is_empty() {
            d.note(format!(
                "the cited facts, with the derivatives of `{}` eliminated, leave no equation c {} = 0",
                of.name, of.name
            ))
        } else {
            d.note(format!("comparing coefficients gives {}", found.join(", ")))
                .note(format!("left − right = {}", plain(&diff)))
        })
    }

    /// Whether `diff = q c` with `q` free of `of` (and its derivatives) and defined: its
    /// denominator shown nonzero by the declared signs.
    fn multiple_of(&self, diff: &Rat, c: &Rat, of: &str) -> bool {
        let Ok(q) = diff.div(c) else {
            return false;
        };
        if mentions(&q, of) {
            return false;
        }
        Rat::poly(q.den().clone()).is_ok_and(|d| sign_of(&d, &self.env.signs).is_nonzero())
    }
}

/// Whether `r` mentions the symbol `of` or one of its derivatives.
fn mentions(r: &Rat, of: &str) -> bool {
    let mut syms = Vec::new();
    crate::decide::symbols_in(r, &mut syms);
    syms.iter().any(|a| is_of(*a, of).is_some())
        || syms.iter().any(
            |a| matches!(atom::get(*a), atom::Atom::At(s, _) if s.trim_end_matches('\'') == of),
        )
}

/// The order of the derivative atom `a` is of the symbol `of` (`theta''` → 2).
fn is_of(a: AtomId, of: &str) -> Option<usize> {
    let n = atom::sym_str(a)?;
    let base = n.trim_end_matches('\'');
    (base == of).then(|| n.len() - base.len())
}

/// `value` as a linear form in `of` and its derivatives, when it is one: no term free
/// of them, and coefficients that do not mention them.
fn linear_form(value: &Rat, of: &str) -> Option<Form> {
    let xs: Vec<AtomId> = value
        .atoms()
        .into_iter()
        .filter(|a| is_of(*a, of).is_some())
        .collect();
    let signs = crate::normal::Assumptions::default();
    let at = |ones: Option<AtomId>| {
        let map = |a: AtomId| {
            xs.contains(&a).then(|| {
                if Some(a) == ones {
                    Rat::one()
                } else {
                    Rat::zero()
                }
            })
        };
        crate::normal::subst::Subst::new(&map, &signs)
            .rat(value)
            .ok()
    };
    if !at(None)?.is_zero() {
        return None;
    }
    let mut form = Vec::new();
    let mut sum = Rat::zero();
    for x in &xs {
        let c = at(Some(*x))?;
        if mentions(&c, of) {
            return None;
        }
        sum = sum.add(&c.mul(&Rat::atom(*x)).ok()?).ok()?;
        form.push((*x, c));
    }
    // Linear: the form is the whole value (nothing inside a function, no products).
    (sum.sub(value).ok()?.is_zero() && !mentions_inside(value, &xs)).then_some(form)
}

/// Whether a symbol of `xs` stands inside another atom of `value` (`sin(theta)`).
fn mentions_inside(value: &Rat, xs: &[AtomId]) -> bool {
    value.atoms().into_iter().any(|a| {
        if xs.contains(&a) {
            return false;
        }
        let mut inner = Vec::new();
        crate::decide::symbols_in(&Rat::atom(a), &mut inner);
        inner.iter().any(|s| xs.contains(s))
    })
}

/// The coefficients `c` of the equations `c theta = 0` that the forms give once every
/// derivative of `theta` is eliminated, highest first, by cross-multiplying (never
/// dividing: each combination holds wherever the forms do).
fn eliminate_derivatives(mut forms: Vec<Form>, theta: AtomId) -> Vec<Rat> {
    let name = atom::sym_str(theta).unwrap_or_default();
    let mut derivs: Vec<(usize, AtomId)> = forms
        .iter()
        .flatten()
        .filter_map(|(a, _)| Some((is_of(*a, name)?, *a)))
        .filter(|(k, _)| *k > 0)
        .collect();
    derivs.sort_by(|x, y| y.cmp(x));
    derivs.dedup();
    for (_, d) in derivs {
        let coeff = |f: &Form| f.iter().find(|(a, _)| *a == d).map(|(_, c)| c.clone());
        let Some(p) = forms.iter().position(|f| coeff(f).is_some()) else {
            continue;
        };
        let pivot = forms.remove(p);
        let pd = coeff(&pivot).unwrap_or_else(Rat::one);
        forms = forms
            .into_iter()
            .filter_map(|f| match coeff(&f) {
                None => Some(f),
                Some(fd) => combine(&f, &pd, &pivot, &fd),
            })
            .collect();
    }
    forms
        .into_iter()
        .filter(|f| f.iter().all(|(a, _)| *a == theta))
        .filter_map(|f| f.into_iter().next().map(|(_, c)| c))
        .filter(|c| !c.is_zero())
        .collect()
}

/// `pd f − fd pivot`, the zero coefficients dropped.
fn combine(f: &Form, pd: &Rat, pivot: &Form, fd: &Rat) -> Option<Form> {
    let mut out: HashMap<AtomId, Rat> = HashMap::new();
    for (a, c) in f {
        let v = pd.mul(c).ok()?;
        let e = out.entry(*a).or_insert_with(Rat::zero);
        *e = e.add(&v).ok()?;
    }
    for (a, c) in pivot {
        let v = fd.mul(c).ok()?;
        let e = out.entry(*a).or_insert_with(Rat::zero);
        *e = e.sub(&v).ok()?;
    }
    let mut form: Form = out.into_iter().filter(|(_, c)| !c.is_zero()).collect();
    form.sort_by_key(|(a, _)| *a);
    Some(form)
}

impl Checker<'_, '_> {
    /// Two equations of motion that cannot both hold while a `time` symbol moves
    /// (`theta'' = -4 theta` and `theta'' = -9 theta`): each fact linear in the symbol
    /// and its derivatives, with both the symbol and a derivative in it, is compared,
    /// and a coefficient the declared signs show nonzero leaves only `theta = 0` at
    /// every instant. Says which symbol and what the comparison gives.
    pub(super) fn motion_forced_still(
        &self,
        values: &[super::elimination::Fact],
    ) -> Option<String> {
        let mut times: Vec<&String> = self
            .scope
            .names
            .iter()
            .filter(|(_, d)| **d == super::scope::Decl::Time)
            .map(|(n, _)| n)
            .collect();
        times.sort();
        for name in times {
            let theta = atom::sym(name);
            let forms: Vec<Form> = values
                .iter()
                .filter_map(|f| linear_form(&f.value, name))
                .filter(|f| {
                    f.iter().any(|(a, _)| *a == theta) && f.iter().any(|(a, _)| *a != theta)
                })
                .collect();
            if forms.len() < 2 {
                continue;
            }
            let nonzero = eliminate_derivatives(forms, theta)
                .into_iter()
                .find(|c| sign_of(c, &self.env.signs).is_nonzero());
            if let Some(c) = nonzero {
                return Some(format!(
                    "comparing coefficients of `{name}` gives ({}) {name} = 0 with a nonzero coefficient, so `{name}` would be zero at every instant: these equations of motion describe different motions",
                    plain(&c)
                ));
            }
        }
        None
    }
}
