//! Side conditions of a link (FORMAT.md §3): the divisors, arguments of `ln` and
//! radicands met while lowering it, those of the facts it used, and the divisors of
//! the elimination. One that the signs settle is dropped; one the facts or the values
//! substituted make false fails the link; the rest are reported as assumptions.

use super::signs::{essential_factor, sign_of};
use super::step::{LinkInput, Reduced};
use super::walk::Checker;
use crate::diag::Diagnostic;
use crate::diag::{Cited, Code, Text};
use crate::lower::{Condition, Need};
use crate::normal::print::plain;
use crate::normal::{Rat, Sign};

/// The conditions a link holds under: as text (those to report) and as values (all).
type Assumed = (Vec<String>, Vec<Condition>);

impl Checker<'_, '_> {
    /// The conditions a link holds under, as text and as values; an error when one fails.
    pub(super) fn side_conditions(
        &self,
        input: &LinkInput<'_>,
        red: &Reduced,
    ) -> Result<Assumed, Diagnostic> {
        self.substituted_to_zero(input, red)?;
        let apply = |d: &Condition| self.apply_where(input.subs, &d.0).ok().map(|v| (v, d.1));
        let mut all: Vec<Condition> = input.divisors.iter().filter_map(apply).collect();
        if !red.via.is_empty() {
            all.extend(
                self.inherited(red)
                    .into_iter()
                    .filter_map(|(_, d)| apply(d)),
            );
        }
        let steps = red.elim.as_ref().map_or(&[][..], |e| &e.steps[..]);
        // The step's own conditions and its facts' come first; then the elimination's.
        let own = all.len();
        all.extend(
            steps
                .iter()
                .filter_map(|s| s.divisor.clone().map(|d| (d, Need::NonZero))),
        );
        let mut conditions: Vec<String> = Vec::new();
        for (k, (d, need)) in all.iter().enumerate() {
            if let Some(text) = self.condition(d, *need, red, input, k >= own)? {
                if !conditions.contains(&text) {
                    conditions.push(text);
                }
            }
        }
        Ok((conditions, all))
    }

    /// The conditions of the facts a link used (a fact derived assuming `c != 0` holds
    /// only where `c != 0`), with the fact's name.
    fn inherited<'k>(&self, red: &'k Reduced) -> Vec<(&'k Cited, &'k Condition)> {
        red.allowed
            .iter()
            .filter(|k| red.used_names.contains(&k.fact.name))
            .flat_map(|k| k.divisors.iter().map(move |d| (&k.fact.name, d)))
            .collect()
    }

    /// A divisor that the values substituted make zero, said with where it came from.
    fn substituted_to_zero(&self, input: &LinkInput<'_>, red: &Reduced) -> Result<(), Diagnostic> {
        let own = input.divisors.iter().map(|d| (None, d));
        let inherited = if red.via.is_empty() {
            Vec::new()
        } else {
            self.inherited(red)
        };
        let all = own.chain(inherited.into_iter().map(|(n, d)| (Some(n), d)));
        for (from, (d0, need)) in all {
            let zero = self.apply_where(input.subs, d0).is_ok_and(|d| d.is_zero());
            if *need != Need::NonZero || !zero {
                continue;
            }
            let message = match from {
                Some(fact) => Text::from("this step uses ")
                    .cited(std::slice::from_ref(fact))
                    .and(&format!(
                        ", which holds only where {} != 0, and here it is 0",
                        plain(d0)
                    )),
                None if d0.as_constant().is_some() => {
                    "this step divides by zero at the value substituted (in `subs` or `eval`)"
                        .into()
                }
                None => format!("this step divides by {}, which `where` makes 0", plain(d0)).into(),
            };
            return Err(Diagnostic::error(
                Code::DivisionByZero,
                message,
                input.span,
                "division by zero",
            ));
        }
        Ok(())
    }

    /// One condition: `None` when the signs settle it, its text when it must be assumed.
    fn condition(
        &self,
        d: &Rat,
        need: Need,
        red: &Reduced,
        input: &LinkInput<'_>,
        elimination: bool,
    ) -> Result<Option<String>, Diagnostic> {
        let signs = &self.env.signs;
        let span = input.span;
        let steps = red.elim.as_ref().map_or(&[][..], |e| &e.steps[..]);
        let reduced =
            super::elimination::apply_steps(d, steps, signs).unwrap_or_else(|_| d.clone());
        if need == Need::NonZero {
            let zero = self.zero_by(&reduced, &red.scope);
            if zero && elimination {
                // rigor's own way of solving the facts divided by zero: that says nothing
                // about the step, which may well hold (solved another way).
                return Err(Diagnostic::error(
                    Code::NotVerified,
                    format!(
                        "not verified: solving the facts for the unknowns divides by {}, which the facts make zero; rigor could not settle this step another way",
                        plain(d)
                    ),
                    span,
                    "not verified",
                ));
            }
            if zero {
                return Err(Diagnostic::error(
                    Code::DivisionByZero,
                    format!(
                        "this step divides by {}, which is zero by the facts",
                        plain(d)
                    ),
                    span,
                    "division by zero",
                ));
            }
            return Ok(essential_factor(&reduced, signs).map(|e| format!("{} != 0", plain(&e))));
        }
        let s = sign_of(&reduced, signs);
        let (ok, bad, op) = if need == Need::Positive {
            (s == Sign::Pos, s.is_nonpos(), ">")
        } else {
            (s.is_nonneg(), s == Sign::Neg, ">=")
        };
        if ok {
            return Ok(None);
        }
        if bad {
            return Err(Diagnostic::error(
                Code::DivisionByZero,
                format!(
                    "this step takes ln or a square root of {}, which is not {op} 0 here",
                    plain(d)
                ),
                span,
                "outside the domain",
            ));
        }
        Ok(Some(format!("{} {op} 0", plain(&reduced))))
    }
}
