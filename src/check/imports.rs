//! `use [..] from "file" with …`: the verified claims of another file, instantiated,
//! become facts here, with the conditions they were derived under.

use super::elimination::Fact;
use super::entry::Exports;
use super::signs::{respects_sign, sign_of};
use super::walk::{Checker, Known};
use crate::diag::{Cited, Code, FactRef};
use crate::lower::{Condition, Need};
use crate::normal::atom::{self, AtomId};
use crate::normal::print::plain;
use crate::normal::{Rat, Sign};
use crate::syntax::ast::{Assign, Label, Span};

/// The imported file, for messages.
struct From<'a> {
    path: &'a str,
    exports: &'a Exports,
}

impl Checker<'_, '_> {
    /// Imports the claims `labels` of `path`, instantiated by `with`.
    pub(super) fn import(
        &mut self,
        labels: &[Label],
        path: &str,
        path_span: Span,
        with: &[Assign],
    ) {
        let exports = match self.loader.import(&self.name.clone(), path) {
            Ok(e) => e,
            Err(mut d) => {
                d.primary = Some((path_span, String::new()));
                self.report.input_error = true;
                self.report.diagnostics.push(d);
                return self.import_failed(labels);
            }
        };
        let from = From {
            path,
            exports: &exports,
        };
        let Some(subs) = self.with_values(with, &from) else {
            return self.import_failed(labels);
        };
        for l in labels {
            let Some(eqs) = exports.claims.get(&l.name) else {
                let (why, hint) = match (&exports.error, exports.lets.get(&l.name)) {
                    (_, Some(value)) => (
                        format!(
                            "[{}] names a `let` in \"{path}\", not a claim: `use` imports verified claims",
                            l.name
                        ),
                        format!("define it here too: `let {} = {value}`", l.name),
                    ),
                    (Some(e), None) => (
                        format!("\"{path}\" does not check: {e}"),
                        "not found, or not verified there".to_string(),
                    ),
                    (None, None) => (
                        format!("\"{path}\" has no verified equation [{}]", l.name),
                        "not found, or not verified there".to_string(),
                    ),
                };
                self.error(Code::ImportFailed, why, l.span, &hint);
                self.import_failed(std::slice::from_ref(l));
                if exports.lets.contains_key(&l.name) && !self.scope.is_declared(&l.name) {
                    let line = self.line(l.span);
                    let why = crate::diag::Text::from("which the `use` on line ")
                        .line(line)
                        .and(" did not bring in");
                    self.failed_names.insert(l.name.clone(), (line, why));
                }
                continue;
            };
            let label = self.new_label(&Some(l.clone()));
            for (eq, conds) in eqs {
                let Some((value, divisors)) = self.instantiate(l, eq, conds, &subs, &from) else {
                    return;
                };
                self.facts.push(Known {
                    label: label.clone(),
                    fact: Fact {
                        value,
                        name: Cited::of(FactRef::Label(l.name.clone())),
                    },
                    divisors,
                });
            }
        }
    }

    /// Labels a failed `use` did not bring in (the error is reported): a step citing
    /// one is not checked, rather than a second error.
    fn import_failed(&mut self, labels: &[Label]) {
        for l in labels {
            let line = self.line(l.span);
            self.failed_labels.insert(l.name.clone(), line);
        }
    }

    /// The values `with` gives: only parameters the other file declares, each with the
    /// sign declared there. `None` after reporting a bad one.
    fn with_values(&mut self, with: &[Assign], from: &From<'_>) -> Option<Vec<(AtomId, Rat)>> {
        let path = from.path;
        let mut subs = Vec::new();
        for a in with {
            let name = &a.name.name;
            let base = name.trim_end_matches('\'');
            if from.exports.unknowns.iter().any(|u| u == name || u == base) {
                self.error(
                    Code::BadWith,
                    format!("`with` cannot set `{name}`: it is an unknown of \"{path}\""),
                    a.name.span,
                    "only parameters can be instantiated",
                );
                return None;
            }
            let Some(declared) = from.exports.signs.get(name).copied() else {
                self.error(
                    Code::BadWith,
                    format!("`with` sets `{name}`, which is not a symbol of \"{path}\""),
                    a.name.span,
                    "only the symbols declared there can be instantiated",
                );
                return None;
            };
            let v = self.lower(&a.value, &mut Vec::new())?;
            if let Err(m) = respects_sign(name, declared, &v, &self.env.signs) {
                self.error(
                    Code::BadWith,
                    format!("{m} (in \"{path}\")"),
                    a.value.span,
                    "",
                );
                return None;
            }
            if let Some(unit) = from.exports.units.get(name) {
                let what = format!("`with` gives `{name}` of \"{path}\"");
                if !self.value_in_unit(&what, unit, &a.value) {
                    return None;
                }
            }
            subs.push((atom::sym(name), v));
        }
        Some(subs)
    }

    /// One imported equation and its conditions, instantiated; `None` after reporting why
    /// it cannot be used here.
    fn instantiate(
        &mut self,
        l: &Label,
        eq: &Rat,
        conds: &[Condition],
        subs: &[(AtomId, Rat)],
        from: &From<'_>,
    ) -> Option<(Rat, Vec<Condition>)> {
        let path = from.path;
        let map = |a: AtomId| subs.iter().find(|s| s.0 == a).map(|s| s.1.clone());
        let inst = |r: &Rat| {
            if subs.is_empty() {
                Ok(r.clone())
            } else {
                crate::normal::subst::Subst::new(&map, &self.env.signs).rat(r)
            }
        };
        let v = match inst(eq) {
            Ok(r) => r,
            Err(e) => {
                self.error(Code::NoValue, e.to_string(), l.span, "");
                return None;
            }
        };
        // The conditions it was derived under travel with it; one that the instantiation
        // makes false makes the import no use.
        let mut divisors = Vec::new();
        for (c0, need) in conds {
            let c = inst(c0).unwrap_or_else(|_| Rat::zero());
            let sign = sign_of(&c, &self.env.signs);
            let (fails, what) = match need {
                Need::NonZero => (c.is_zero(), "!= 0"),
                Need::Positive => (sign.is_nonpos(), "> 0"),
                Need::NonNegative => (sign == Sign::Neg, ">= 0"),
            };
            if fails {
                self.error(
                    Code::DivisionByZero,
                    format!(
                        "[{}] from \"{path}\" holds only where {} {what}, which is false here",
                        l.name,
                        plain(c0)
                    ),
                    l.span,
                    "the instantiation breaks a condition the claim was derived under",
                );
                return None;
            }
            divisors.push((c, *need));
        }
        self.imported_signs_hold(l, &v, from)?;
        if !v.atoms().iter().any(|a| self.is_unknown(*a))
            && !v.is_zero()
            && sign_of(&v, &self.env.signs).is_nonzero()
        {
            self.error(
                Code::FalseFacts,
                format!(
                    "[{}] from \"{path}\", instantiated here, is false: {} = 0",
                    l.name,
                    plain(&v)
                ),
                l.span,
                "the instantiation contradicts the imported fact",
            );
            return None;
        }
        Some((v, divisors))
    }

    /// Symbols left as they are must carry at least the sign the source assumed.
    fn imported_signs_hold(&mut self, l: &Label, v: &Rat, from: &From<'_>) -> Option<()> {
        let mut syms = Vec::new();
        crate::decide::symbols_in(v, &mut syms);
        for x in syms {
            let Some(name) = atom::sym_name(x) else {
                continue;
            };
            let need = from
                .exports
                .signs
                .get(&name)
                .copied()
                .unwrap_or(Sign::Unknown);
            let have = self.env.signs.declared(x);
            let implied = match need {
                Sign::Unknown => true,
                Sign::Pos => have == Sign::Pos,
                Sign::NonNeg => matches!(have, Sign::Pos | Sign::NonNeg),
                Sign::NonZero => matches!(have, Sign::Pos | Sign::NonZero),
                _ => have == need,
            };
            if !implied {
                self.error(
                    Code::BadWith,
                    format!(
                        "[{}] from \"{}\" holds when `{name}` has the sign declared there, which this file does not declare",
                        l.name, from.path
                    ),
                    l.span,
                    "declare the same sign here, or instantiate it with `with`",
                );
                return None;
            }
        }
        Some(())
    }
}
