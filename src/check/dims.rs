//! Units in a file (FORMAT.md §3, "Units"): the `units` statement, and dimensional
//! consistency of every relation once units are declared. Unit errors are found before
//! the algebra: a link whose sides disagree in units fails with both units named.

use super::walk::Checker;
use crate::diag::Code;
use crate::diag::Diagnostic;
use crate::syntax::ast::{Chain, Expr, Span, UnitDecl};
use crate::units::check::{dim_and_scales, mismatch, DimV, UnitEnv, UnitProblem};

impl Checker<'_, '_> {
    /// One `name: unit` of a `units` statement.
    pub(super) fn declare_unit(&mut self, d: &UnitDecl) {
        if self.units.contains_key(&d.name.name) {
            self.error(
                Code::BadUnit,
                format!("`{}` already has a unit", d.name.name),
                d.name.span,
                "a symbol has one unit",
            );
            return;
        }
        match crate::units::parse_unit(&d.unit) {
            Ok(u) => {
                self.units.insert(d.name.name.clone(), u);
            }
            Err(e) => {
                let start = d.unit_span.start + e.at;
                let span = Span::new(start, start + e.len.max(1));
                self.error(Code::BadUnit, e.message, span, "");
            }
        }
    }

    /// The dimensions of `exprs` when units are declared: `None` when units are not in
    /// use, or after reporting what is missing or inconsistent inside an expression.
    pub(super) fn dims(
        &mut self,
        exprs: &[&Expr],
        span: Span,
    ) -> Option<Vec<Result<DimV, UnitProblem>>> {
        if self.units.is_empty() {
            return None;
        }
        let env = UnitEnv {
            units: &self.units,
            defs: &self.guard_env.defs,
            bodies: &self.guard_env.bodies,
            time: &self.guard_env.time,
        };
        let mut missing = Vec::new();
        let mut mixed = Vec::new();
        let out: Vec<_> = exprs
            .iter()
            .map(|e| dim_and_scales(e, &env, &mut missing, &mut mixed))
            .collect();
        for m in mixed {
            let mut d = Diagnostic::error(Code::MixedScales, m.message, m.span, "mixed scales");
            d.severity = crate::diag::Severity::Warning;
            d.notes.extend(m.note.map(Into::into));
            self.report.diagnostics.push(d);
        }
        if !missing.is_empty() {
            missing.sort();
            self.error(
                Code::NoUnit,
                format!("no unit is declared for {}", missing.join(", ")),
                span,
                "with `units` in the file, every symbol in a relation needs one",
            );
            return None;
        }
        Some(out)
    }

    /// Whether `value`, given to a symbol in `unit` (by `where` or `use … with`), is in
    /// that unit; reports E0401 (bad input) if not. Where this file declares no units,
    /// the value's unit is unknown and nothing is said.
    pub(super) fn value_in_unit(
        &mut self,
        what: &str,
        unit: &crate::units::Dim,
        value: &Expr,
    ) -> bool {
        if self.units.is_empty() {
            return true;
        }
        let Some(dims) = self.dims(&[value], value.span) else {
            self.report.input_error = true;
            return false;
        };
        let problem = match &dims[0] {
            Err(p) => Some(p.clone()),
            Ok(DimV::D(d)) if !d.same(unit) => Some(UnitProblem {
                span: value.span,
                message: format!("{what} (in {}) a value in {}", unit.si(), d.si()),
                note: Some("a substitution must keep the units: the facts and claims that use it would mix quantities otherwise".into()),
            }),
            _ => None,
        };
        match problem {
            Some(p) => {
                self.report.input_error = true;
                self.report.diagnostics.push(Self::unit_diagnostic(p));
                false
            }
            None => true,
        }
    }

    /// A unit problem as a diagnostic.
    pub(super) fn unit_diagnostic(p: UnitProblem) -> Diagnostic {
        let mut d = Diagnostic::error(Code::Units, p.message, p.span, "inconsistent units");
        if let Some(n) = p.note {
            d.add_note(n);
        }
        d
    }

    /// Whether two sides of a link agree in units; the diagnostic if not.
    pub(super) fn link_units(
        a: &Result<DimV, UnitProblem>,
        b: &Result<DimV, UnitProblem>,
        span: Span,
    ) -> Option<Diagnostic> {
        match (a, b) {
            (Err(p), _) | (_, Err(p)) => Some(Self::unit_diagnostic(p.clone())),
            (Ok(DimV::D(x)), Ok(DimV::D(y))) if !x.same(y) => Some(Self::unit_diagnostic(
                mismatch(span, "the two sides are in different units", x, y),
            )),
            _ => None,
        }
    }

    /// The units of each expression of a chain (`None` when units are not in use).
    pub(super) fn chain_dims(
        &mut self,
        chain: &Chain,
        span: Span,
    ) -> Option<Vec<Result<DimV, UnitProblem>>> {
        let exprs: Vec<&Expr> = chain.exprs().collect();
        self.dims(&exprs, span)
    }

    /// A given or constraint must be consistent in units; an inconsistent fact is bad
    /// input.
    pub(super) fn fact_units(&mut self, chain: &Chain, span: Span) {
        let Some(dims) = self.chain_dims(chain, span) else {
            return;
        };
        for (i, link) in chain.links.iter().enumerate() {
            let at = if i == 0 {
                chain.first.span.to(link.span)
            } else {
                link.span
            };
            if let Some(d) = Self::link_units(&dims[i], &dims[i + 1], at) {
                self.report.input_error = true;
                self.report.diagnostics.push(d);
                return;
            }
        }
    }
}
