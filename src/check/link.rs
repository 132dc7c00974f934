//! The statement walker and the link checker of FORMAT.md §3.

use super::load::{Exports, ImportError, Loader};
use super::report::{cite, ClaimReport, FileReport, Justification, LinkReport, Status};
use super::scope::{undeclared, Decl, Scope};
use super::solve::{
    apply_steps, contradiction, eliminate, unknown_name, zero_by_facts, Elimination, Fact,
};
use crate::calculus::{self, Wrt};
use crate::decide::{decide, find_counterexample, Verdict};
use crate::diag::{Diagnostic, Severity};
use crate::interval::Prec;
use crate::lower::Need;
use crate::lower::{build_body, sign_of_decl, Env, LowerError, Lowerer};
use crate::normal::atom::{self, AtomId};
use crate::normal::print::plain;
use crate::normal::{Rat, Sign, Q};
use crate::syntax::ast::{
    Assign, BinOp, By, Chain, Expr, ExprKind, File, Item, RelOp, Span, StmtKind,
};
use num_bigint::BigInt;
use num_traits::{One, Signed};
use std::collections::{HashMap, HashSet};
use std::path::PathBuf;
use std::time::Instant;

/// A fact in scope.
#[derive(Clone, Debug)]
struct Known {
    /// The label it is cited by (`by [..]` selects on it), if any.
    label: Option<String>,
    fact: Fact,
    /// Divisors met while computing it.
    divisors: Vec<(Rat, crate::lower::Need)>,
}

/// Walks one file.
pub struct Checker<'l, 'o> {
    report: FileReport,
    dir: PathBuf,
    loader: &'l mut Loader<'o>,
    scope: Scope,
    env: Env,
    facts: Vec<Known>,
    labels: HashMap<String, Span>,
    exports: Exports,
    body_coords: HashMap<String, Vec<String>>,
    /// Set when lowering ran out of time (the link is undecided).
    timed_out: bool,
    /// Byte offset of the start of every line, for line numbers.
    line_starts: Vec<usize>,
    /// The conditions the last verified link holds under (its own and those of the
    /// facts it used): a claim that becomes a fact carries them.
    conditions: Vec<(Rat, Need)>,
}

impl<'l, 'o> Checker<'l, 'o> {
    /// A checker that will fill `report`.
    pub fn new(report: FileReport, dir: PathBuf, loader: &'l mut Loader<'o>) -> Checker<'l, 'o> {
        Checker {
            report,
            dir,
            loader,
            scope: Scope::default(),
            env: Env::default(),
            facts: Vec::new(),
            labels: HashMap::new(),
            exports: Exports::default(),
            body_coords: HashMap::new(),
            timed_out: false,
            line_starts: Vec::new(),
            conditions: Vec::new(),
        }
    }

    fn error(&mut self, code: &'static str, msg: String, span: Span, label: &str) {
        self.report.input_error = true;
        self.report
            .diagnostics
            .push(Diagnostic::error(code, msg, span, label));
    }

    fn line(&self, span: Span) -> usize {
        match self.line_starts.binary_search(&span.start) {
            Ok(i) => i + 1,
            Err(i) => i,
        }
    }

    /// Checks every statement; returns the report and what the file exports.
    pub fn run(mut self, file: File) -> (FileReport, Exports) {
        self.line_starts = std::iter::once(0)
            .chain(self.report.source.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        for item in &file.items {
            if let Item::Stmt(st) = item {
                self.statement(&st.kind, st.span);
            }
        }
        self.report.ast = Some(file);
        for (name, d) in &self.scope.names {
            match d {
                Decl::Symbol => {
                    let sign = self.env.signs.declared(atom::sym(name));
                    self.exports.signs.insert(name.clone(), sign);
                }
                Decl::Time => self.exports.unknowns.push(name.clone()),
                _ => {}
            }
        }
        self.exports
            .unknowns
            .extend(self.scope.unknowns.iter().cloned());
        if self.report.input_error {
            self.exports.error = self
                .report
                .diagnostics
                .iter()
                .find(|d| d.severity == Severity::Error)
                .map(|d| d.message.clone());
        }
        (self.report, self.exports)
    }

    /// Reports undeclared names in `e`; true if all are declared.
    fn declared(&mut self, e: &Expr) -> bool {
        let coords = self.body_coords.clone();
        let one_body = (coords.len() == 1)
            .then(|| coords.values().next().cloned())
            .flatten();
        let lookup = |n: &str| -> Option<Vec<String>> {
            if n == "dm" && !coords.contains_key("dm") {
                return one_body.clone();
            }
            coords.get(n).cloned()
        };
        let bad = undeclared(e, &self.scope, &lookup);
        for (name, span) in &bad {
            let hint = match self.scope.suggest(name) {
                Some(s) => format!("did you mean `{s}`?"),
                None => "declare it with `symbols`, `time` or `unknowns`".into(),
            };
            self.error("E0201", format!("undeclared symbol `{name}`"), *span, &hint);
        }
        bad.is_empty()
    }

    fn lower(&mut self, e: &Expr, divisors: &mut Vec<(Rat, crate::lower::Need)>) -> Option<Rat> {
        if !self.declared(e) {
            return None;
        }
        let mut lw = Lowerer::new(&self.env);
        match lw.lower(e) {
            Ok(v) => {
                divisors.extend(lw.divisors.into_iter().map(|d| (d.value, d.need)));
                Some(v)
            }
            Err(err) => {
                self.lower_error(err);
                None
            }
        }
    }

    fn lower_error(&mut self, e: LowerError) {
        if e.timeout {
            // Undecided, not bad input: the claim fails, the file is not malformed.
            self.timed_out = true;
            self.report.diagnostics.push(Diagnostic::error(
                "E0902",
                format!("not verified: {}", e.message),
                e.span,
                "undecided",
            ));
            return;
        }
        let code = if e.limit { "E0901" } else { "E0101" };
        self.error(code, e.message, e.span, "");
    }

    fn declare(&mut self, name: &str, span: Span, d: Decl) -> bool {
        if let Some(prev) = self.scope.names.get(name) {
            let ok = matches!((prev, &d), (Decl::Symbol, Decl::Unknown));
            if !ok {
                self.error(
                    "E0203",
                    format!("`{name}` is already declared"),
                    span,
                    "declared again here",
                );
                return false;
            }
            return true;
        }
        if name == "t"
            && !matches!(d, Decl::TimeVar)
            && self.scope.names.get("t") == Some(&Decl::TimeVar)
        {
            self.error(
                "E0203",
                "`t` is the time variable declared by `time`".into(),
                span,
                "",
            );
            return false;
        }
        self.scope.names.insert(name.to_string(), d);
        true
    }

    fn new_label(&mut self, label: &Option<crate::syntax::ast::Label>) -> Option<String> {
        let l = label.as_ref()?;
        if let Some(prev) = self.labels.get(&l.name).copied() {
            let line = self.line(prev);
            self.error(
                "E0202",
                format!("duplicate label [{}]", l.name),
                l.span,
                &format!("[{}] was already used on line {line}", l.name),
            );
            return None;
        }
        self.labels.insert(l.name.clone(), l.span);
        Some(l.name.clone())
    }

    fn fact_name(&self, label: &Option<String>, span: Span) -> String {
        match label {
            Some(l) => format!("[{l}]"),
            None => format!("line {}", self.line(span)),
        }
    }

    fn statement(&mut self, kind: &StmtKind, span: Span) {
        match kind {
            StmtKind::Symbols { names, sign } => {
                for n in names {
                    if self.declare(&n.name, n.span, Decl::Symbol) {
                        self.env.signs.set(atom::sym(&n.name), sign_of_decl(*sign));
                    }
                }
            }
            StmtKind::Time { names } => {
                if !self.scope.names.contains_key("t") {
                    self.scope.names.insert("t".into(), Decl::TimeVar);
                }
                for n in names {
                    if self.declare(&n.name, n.span, Decl::Time) {
                        self.env.time.insert(n.name.clone());
                    }
                }
            }
            StmtKind::Unknowns { names } => {
                for n in names {
                    if self.declare(&n.name, n.span, Decl::Unknown) {
                        self.scope.unknowns.insert(n.name.clone());
                    }
                }
            }
            StmtKind::Units { decls } => {
                for d in decls {
                    if !self.scope.is_declared(&d.name.name) {
                        let hint = self.scope.suggest(&d.name.name).map_or_else(
                            || "declare it first".to_string(),
                            |s| format!("did you mean `{s}`?"),
                        );
                        self.error(
                            "E0201",
                            format!("units for undeclared symbol `{}`", d.name.name),
                            d.name.span,
                            &hint,
                        );
                    }
                }
            }
            StmtKind::Body { name, def } => {
                if !self.declare(&name.name, name.span, Decl::Body) {
                    return;
                }
                let coords: Vec<String> = match def {
                    crate::syntax::ast::BodyDef::Concrete { ranges, .. } => {
                        ranges.iter().map(|r| r.var.name.clone()).collect()
                    }
                    crate::syntax::ast::BodyDef::Abstract { coords, .. } => {
                        coords.iter().map(|c| c.name.clone()).collect()
                    }
                };
                // Names inside the body statement: coordinates and their differentials are local.
                let mut local = self.scope.clone();
                for c in &coords {
                    local.names.insert(c.clone(), Decl::Symbol);
                    local.names.insert(format!("d{c}"), Decl::Symbol);
                }
                let exprs: Vec<&Expr> = match def {
                    crate::syntax::ast::BodyDef::Concrete { dm, ranges } => std::iter::once(dm)
                        .chain(ranges.iter().flat_map(|r| [&r.from, &r.to]))
                        .collect(),
                    crate::syntax::ast::BodyDef::Abstract { mass, .. } => vec![mass],
                };
                let saved = std::mem::replace(&mut self.scope, local);
                let ok = exprs.iter().all(|e| self.declared(e));
                self.scope = saved;
                if !ok {
                    return;
                }
                match build_body(&name.name, def, &self.env) {
                    Ok(b) => {
                        self.env.bodies.insert(name.name.clone(), b);
                        self.body_coords.insert(name.name.clone(), coords);
                    }
                    Err(e) => self.lower_error(e),
                }
            }
            StmtKind::Let { name, value } => {
                let mut divs = Vec::new();
                let Some(v) = self.lower(value, &mut divs) else {
                    return;
                };
                if self.declare(&name.name, name.span, Decl::Def) {
                    self.env.defs.insert(name.name.clone(), v);
                }
            }
            StmtKind::Given { label, chain } | StmtKind::Constraint { label, chain } => {
                let is_constraint = matches!(kind, StmtKind::Constraint { .. });
                let label = self.new_label(label);
                self.given(label, chain, span, is_constraint);
            }
            StmtKind::Claim {
                label,
                chain,
                where_,
            } => {
                let label = self.new_label(label);
                self.claim(label, chain, where_, span);
            }
            StmtKind::Use {
                labels,
                path,
                path_span,
                with,
            } => self.import(labels, path, *path_span, with),
        }
    }

    fn given(&mut self, label: Option<String>, chain: &Chain, span: Span, constraint: bool) {
        let mut divs = Vec::new();
        let Some(mut prev) = self.lower(&chain.first, &mut divs) else {
            return;
        };
        let name = self.fact_name(&label, span);
        for link in &chain.links {
            let Some(rhs) = self.lower(&link.rhs, &mut divs) else {
                return;
            };
            if link.op == RelOp::Eq {
                let value = match prev.sub(&rhs) {
                    Ok(v) => v,
                    Err(e) => {
                        self.error("E0101", e.to_string(), link.span, "");
                        return;
                    }
                };
                if value.is_zero() {
                    prev = rhs;
                    continue;
                }
                if sign_of(&value, &self.env.signs).is_nonzero() {
                    self.report.diagnostics.push(Diagnostic::error(
                        "E0306",
                        format!(
                            "this fact is false under the declared signs: {} = {}",
                            plain(&prev),
                            plain(&rhs)
                        ),
                        link.span,
                        "the two sides can never be equal",
                    ));
                    self.report.input_error = true;
                }
                let mut derivs = vec![value.clone()];
                if constraint {
                    // A constraint holds at all times: its unknowns are functions of time
                    // too (F' is a new unknown), never constants.
                    let time = self.env.time.clone();
                    let unknowns = self.scope.unknowns.clone();
                    let is_time = |b: &str| time.contains(b) || unknowns.contains(b);
                    let wrt = Wrt {
                        var: atom::sym("t"),
                        time: Some(&is_time),
                    };
                    let mut cur = value.clone();
                    for _ in 0..3 {
                        match calculus::diff(&cur, &wrt, &self.env.signs) {
                            Ok(d) if !d.is_zero() => {
                                derivs.push(d.clone());
                                cur = d;
                            }
                            _ => break,
                        }
                    }
                }
                for (k, v) in derivs.into_iter().enumerate() {
                    self.facts.push(Known {
                        label: label.clone(),
                        fact: Fact {
                            value: v,
                            name: format!("{name}{}", "'".repeat(k)),
                        },
                        divisors: divs.clone(),
                    });
                }
            }
            prev = rhs;
        }
    }

    fn is_unknown(&self, a: AtomId) -> bool {
        unknown_atom(&self.scope, a)
    }

    fn import(
        &mut self,
        labels: &[crate::syntax::ast::Label],
        path: &str,
        path_span: Span,
        with: &[Assign],
    ) {
        let dir = self.dir.clone();
        let exports = match self.loader.import(&dir, path) {
            Ok(e) => e,
            Err(ImportError::Msg(m)) => {
                self.error("E0206", m, path_span, "");
                return;
            }
        };
        let mut subs: Vec<(AtomId, Rat)> = Vec::new();
        for a in with {
            let name = &a.name.name;
            if !exports.signs.contains_key(name) && !exports.unknowns.iter().any(|u| u == name) {
                self.error(
                    "E0208",
                    format!("`with` sets `{name}`, which is not a symbol of \"{path}\""),
                    a.name.span,
                    "only the symbols declared there can be instantiated",
                );
                return;
            }
            let base = name.trim_end_matches('\'');
            if exports.unknowns.iter().any(|u| u == name || u == base) {
                self.error(
                    "E0208",
                    format!("`with` cannot set `{name}`: it is an unknown of \"{path}\""),
                    a.name.span,
                    "only parameters can be instantiated",
                );
                return;
            }
            let mut d = Vec::new();
            let Some(v) = self.lower(&a.value, &mut d) else {
                return;
            };
            let declared = exports.signs.get(name).copied().unwrap_or(Sign::Unknown);
            if let Err(m) = respects_sign(name, declared, &v, &self.env.signs) {
                self.error("E0208", format!("{m} (in \"{path}\")"), a.value.span, "");
                return;
            }
            subs.push((atom::sym(name), v));
        }
        let map = |a: AtomId| subs.iter().find(|s| s.0 == a).map(|s| s.1.clone());
        for l in labels {
            let Some(eqs) = exports.claims.get(&l.name) else {
                let why = match &exports.error {
                    Some(e) => format!("\"{path}\" does not check: {e}"),
                    None => format!("\"{path}\" has no verified equation [{}]", l.name),
                };
                self.error("E0206", why, l.span, "not found, or not verified there");
                continue;
            };
            let label = self.new_label(&Some(l.clone()));
            for (eq, conds) in eqs {
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
                        self.error("E0101", e.to_string(), l.span, "");
                        return;
                    }
                };
                // The conditions it was derived under travel with it; one that the
                // instantiation makes false makes the import no use.
                let mut divisors = Vec::new();
                for (c0, need) in conds {
                    let c = match inst(c0) {
                        Ok(c) => c,
                        Err(_) => Rat::zero(),
                    };
                    let sign = sign_of(&c, &self.env.signs);
                    let (fails, what) = match need {
                        Need::NonZero => (c.is_zero(), "!= 0"),
                        Need::Positive => (sign.is_nonpos(), "> 0"),
                        Need::NonNegative => (sign == Sign::Neg, ">= 0"),
                    };
                    if fails {
                        self.error(
                            "E0305",
                            format!(
                                "[{}] from \"{path}\" holds only where {} {what}, which is false here",
                                l.name,
                                plain(c0)
                            ),
                            l.span,
                            "the instantiation breaks a condition the claim was derived under",
                        );
                        return;
                    }
                    divisors.push((c, *need));
                }
                // Symbols left as they are must carry at least the sign the source assumed.
                let mut syms = Vec::new();
                crate::decide::symbols_in(&v, &mut syms);
                for x in syms {
                    let Some(name) = atom::sym_name(x) else {
                        continue;
                    };
                    let need = exports.signs.get(&name).copied().unwrap_or(Sign::Unknown);
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
                            "E0208",
                            format!("[{}] from \"{path}\" holds when `{name}` has the sign declared there, which this file does not declare", l.name),
                            l.span,
                            "declare the same sign here, or instantiate it with `with`",
                        );
                        return;
                    }
                }
                if !v.atoms().iter().any(|a| self.is_unknown(*a))
                    && !v.is_zero()
                    && sign_of(&v, &self.env.signs).is_nonzero()
                {
                    self.error(
                        "E0306",
                        format!(
                            "[{}] from \"{path}\", instantiated here, is false: {} = 0",
                            l.name,
                            plain(&v)
                        ),
                        l.span,
                        "the instantiation contradicts the imported fact",
                    );
                    return;
                }
                self.facts.push(Known {
                    label: label.clone(),
                    fact: Fact {
                        value: v,
                        name: format!("[{}]", l.name),
                    },
                    divisors,
                });
            }
        }
    }

    fn claim(&mut self, label: Option<String>, chain: &Chain, where_: &[Assign], span: Span) {
        let line = self.line(span);
        let claim = ClaimReport {
            label: label.clone(),
            span,
            line,
            links: Vec::new(),
        };
        let deadline = Instant::now() + self.loader.opts.timeout;
        crate::normal::poly::set_deadline(Some(deadline));
        self.timed_out = false;
        self.claim_inner(label, chain, where_, claim, deadline);
        crate::normal::poly::set_deadline(None);
    }

    fn claim_inner(
        &mut self,
        label: Option<String>,
        chain: &Chain,
        where_: &[Assign],
        mut claim: ClaimReport,
        deadline: Instant,
    ) {
        let span = claim.span;
        // `where`: substitutions applied to the claim and to the facts it uses.
        let mut subs: Vec<(AtomId, Rat)> = Vec::new();
        for a in where_ {
            let mut d = Vec::new();
            let name = &a.name.name;
            if !self.scope.is_declared(name) {
                self.declared(&Expr::new(ExprKind::Sym(name.clone()), a.name.span));
                return self.push_error_claim(claim, chain);
            }
            if self.scope.names.get(name) == Some(&Decl::Def) {
                self.error(
                    "E0207",
                    format!("`where` cannot set `{name}`: it is defined by `let`"),
                    a.name.span,
                    "set the symbols its definition is made of instead",
                );
                return self.push_error_claim(claim, chain);
            }
            if self.scope.is_unknown(name) {
                self.error(
                    "E0207",
                    format!("`where` cannot set the unknown `{name}`"),
                    a.name.span,
                    "`where` picks a special case of the parameters; the facts determine the unknowns",
                );
                return self.push_error_claim(claim, chain);
            }
            let x = atom::sym(name);
            if subs.iter().any(|s| s.0 == x) {
                self.error(
                    "E0207",
                    format!("`{name}` is set twice in this `where`"),
                    a.name.span,
                    "",
                );
                return self.push_error_claim(claim, chain);
            }
            let Some(v) = self.lower(&a.value, &mut d) else {
                return self.push_error_claim(claim, chain);
            };
            if let Err(m) = respects_sign(name, self.env.signs.declared(x), &v, &self.env.signs) {
                self.error(
                    "E0207",
                    m,
                    a.value.span,
                    "this value does not respect the declared sign",
                );
                return self.push_error_claim(claim, chain);
            }
            subs.push((x, v));
        }
        let mut divs = Vec::new();
        let Some(first) = self.lower(&chain.first, &mut divs) else {
            return self.push_error_claim(claim, chain);
        };
        let mut prev = first;
        let mut prev_divs = divs;
        let mut new_facts = Vec::new();
        for (i, link) in chain.links.iter().enumerate() {
            let span = if i == 0 {
                chain.first.span.to(link.span)
            } else {
                link.span
            };
            let mut divs = Vec::new();
            let Some(rhs) = self.lower(&link.rhs, &mut divs) else {
                claim.links.push(LinkReport {
                    span,
                    op: link.op,
                    lhs: None,
                    rhs: None,
                    status: if self.timed_out {
                        Status::Undecided
                    } else {
                        Status::Error
                    },
                });
                break;
            };
            let mut all_divs = prev_divs.clone();
            all_divs.extend(divs.iter().cloned());
            let by = link.by.as_ref().map(|b| &b.0);
            let status = self.check_link(&prev, &rhs, link, span, by, &subs, &all_divs, deadline);
            let status = status.unwrap_or_else(|d| {
                self.report.diagnostics.push(d);
                Status::Failed
            });
            if status.is_verified() && link.op == RelOp::Eq {
                if let Ok(v) = prev.sub(&rhs) {
                    if subs.is_empty() {
                        // The step's conditions (its own, the elimination's divisors and
                        // those of the facts it used) travel with the fact it becomes.
                        let mut conds = all_divs.clone();
                        for c in std::mem::take(&mut self.conditions) {
                            if !conds.iter().any(|d| d.0 == c.0 && d.1 == c.1) {
                                conds.push(c);
                            }
                        }
                        new_facts.push((v, conds));
                    }
                }
            }
            claim.links.push(LinkReport {
                span,
                op: link.op,
                lhs: Some(plain(&prev)),
                rhs: Some(plain(&rhs)),
                status,
            });
            prev = rhs;
            prev_divs = divs;
        }
        // A verified claim becomes a fact (the chain's equalities); with `where`, it is a
        // special case and adds nothing general.
        let name = self.fact_name(&label, span);
        for (v, divs) in &new_facts {
            self.facts.push(Known {
                label: label.clone(),
                fact: Fact {
                    value: v.clone(),
                    name: name.clone(),
                },
                divisors: divs.clone(),
            });
        }
        if let Some(l) = &label {
            if claim.verified() && !new_facts.is_empty() {
                self.exports.claims.insert(l.clone(), new_facts);
            }
        }
        self.report.claims.push(claim);
    }

    fn push_error_claim(&mut self, mut claim: ClaimReport, chain: &Chain) {
        let status = if self.timed_out {
            Status::Undecided
        } else {
            Status::Error
        };
        for (i, link) in chain.links.iter().enumerate() {
            let span = if i == 0 {
                chain.first.span.to(link.span)
            } else {
                link.span
            };
            claim.links.push(LinkReport {
                span,
                op: link.op,
                lhs: None,
                rhs: None,
                status: status.clone(),
            });
        }
        self.report.claims.push(claim);
    }

    /// The facts a link may use.
    fn facts_for(&mut self, by: Option<&By>) -> Result<Vec<Known>, ()> {
        match by {
            Some(By::Labels(ls)) => {
                let mut out = Vec::new();
                let mut bad = false;
                for l in ls {
                    let found: Vec<Known> = self
                        .facts
                        .iter()
                        .filter(|k| k.label.as_deref() == Some(l.name.as_str()))
                        .cloned()
                        .collect();
                    if found.is_empty() {
                        let known: Vec<String> = self.labels.keys().cloned().collect();
                        let hint = if self.labels.contains_key(&l.name) {
                            "that label names no equation that holds (a failed claim, or an inequality)".to_string()
                        } else if known.is_empty() {
                            "no labelled facts precede this line".into()
                        } else {
                            let mut sc = Scope::default();
                            for k in &known {
                                sc.names.insert(k.clone(), Decl::Symbol);
                            }
                            sc.suggest(&l.name)
                                .map_or("no fact before this line has that label".into(), |s| {
                                    format!("did you mean [{s}]?")
                                })
                        };
                        self.error(
                            "E0205",
                            format!("unknown label [{}]", l.name),
                            l.span,
                            &hint,
                        );
                        bad = true;
                    }
                    out.extend(found);
                }
                if bad {
                    Err(())
                } else {
                    Ok(out)
                }
            }
            _ => Ok(self.facts.clone()),
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn check_link(
        &mut self,
        lhs: &Rat,
        rhs: &Rat,
        link: &crate::syntax::ast::Link,
        span: Span,
        by: Option<&By>,
        subs: &[(AtomId, Rat)],
        divisors: &[(Rat, crate::lower::Need)],
        deadline: Instant,
    ) -> Result<Status, Diagnostic> {
        self.conditions.clear();
        let signs = self.env.signs.clone();
        // All `where` substitutions at once (simultaneous, not one after another).
        let map = |a: AtomId| subs.iter().find(|s| s.0 == a).map(|s| s.1.clone());
        let apply = |r: &Rat| -> Result<Rat, String> {
            if subs.is_empty() {
                return Ok(r.clone());
            }
            crate::normal::subst::Subst::new(&map, &signs)
                .rat(r)
                .map_err(|e| e.to_string())
        };
        let (a, b) = match (apply(lhs), apply(rhs)) {
            (Ok(a), Ok(b)) => (a, b),
            (Err(e), _) | (_, Err(e)) => {
                return Err(Diagnostic::error(
                    "E0101",
                    format!("the `where` substitution fails: {e}"),
                    span,
                    "",
                ))
            }
        };
        let mut diff = a
            .sub(&b)
            .map_err(|e| Diagnostic::error("E0101", e.to_string(), span, ""))?;
        if !diff.is_zero() {
            // Sines and cosines of related angles, rewritten in a common base angle.
            if crate::normal::trig::rebase(&diff, &signs).is_ok_and(|r| r.is_zero()) {
                diff = Rat::zero();
            }
        }
        // `by [..]` must name facts before this line, even where none is needed.
        if matches!(by, Some(By::Labels(_))) && self.facts_for(by).is_err() {
            return Ok(Status::Error);
        }
        if diff.is_zero() && divisors.is_empty() && link.op == RelOp::Eq {
            // An identity with nothing to assume: no facts needed.
            return Ok(Status::Verified {
                how: Justification::Identity,
                side_conditions: Vec::new(),
            });
        }
        let Ok(facts) = self.facts_for(by) else {
            return Ok(Status::Error);
        };
        let mut used_facts = Vec::new();
        for k in &facts {
            if let Ok(v) = apply(&k.fact.value) {
                used_facts.push(Fact {
                    value: v,
                    name: k.fact.name.clone(),
                });
            }
        }
        let scope = self.scope.clone();
        let is_unknown = |x: AtomId| unknown_atom(&scope, x);
        let elim = if diff.is_zero() {
            None
        } else {
            Some(
                eliminate(&diff, &used_facts, &is_unknown, &signs, Some(deadline)).map_err(
                    |e| match e {
                        crate::normal::NormError::DivisionByZero => Diagnostic::error(
                            "E0305",
                            "under the facts, this step divides by zero",
                            span,
                            "a denominator here is zero once the facts are used",
                        ),
                        e => Diagnostic::error("E0901", e.to_string(), span, ""),
                    },
                )?,
            )
        };
        let steps = elim.as_ref().map_or(&[][..], |e| &e.steps[..]);
        // The conditions of the facts this link used (a fact derived assuming c != 0
        // holds only where c != 0).
        let used_names: Vec<&str> = steps
            .iter()
            .map(|s| s.fact.as_str())
            .chain(elim.as_ref().and_then(|e| e.multiple_of.as_deref()))
            .collect();
        let fact_divs: Vec<(Rat, Need)> = facts
            .iter()
            .filter(|k| used_names.contains(&k.fact.name.as_str()))
            .flat_map(|k| k.divisors.iter().cloned())
            .collect();
        let reduce = |r: &Rat| apply_steps(r, steps, &signs);
        let (ra, rb) = match (reduce(&a), reduce(&b)) {
            (Ok(x), Ok(y)) => (x, y),
            _ => (a.clone(), b.clone()),
        };
        let via: Vec<String> = {
            let mut v: Vec<String> = steps
                .iter()
                .map(|s| s.fact.as_str())
                .chain(elim.as_ref().and_then(|e| e.multiple_of.as_deref()))
                .map(|f| {
                    f.trim_end_matches('\'')
                        .trim_start_matches('[')
                        .trim_end_matches(']')
                        .to_string()
                })
                .collect();
            v.dedup();
            let mut seen = HashSet::new();
            v.retain(|x| seen.insert(x.clone()));
            v
        };
        let how_eq = |via: &Vec<String>| {
            if via.is_empty() {
                Justification::Identity
            } else {
                Justification::Facts(via.clone())
            }
        };
        // Facts that contradict each other prove anything: refuse to use them.
        if !via.is_empty() {
            if let Some(c) = contradiction(&used_facts, &signs) {
                return Err(Diagnostic::error(
                    "E0306",
                    format!("the facts in scope contradict each other: {c}"),
                    span,
                    "checked against contradictory facts",
                )
                .note("nothing can be verified from contradictory facts; check the givens"));
            }
        }
        // Side conditions: divisors (and arguments of ln and square roots) the signs do not settle.
        let all_scope: Vec<Fact> = self
            .facts
            .iter()
            .filter_map(|k| {
                apply(&k.fact.value).ok().map(|v| Fact {
                    value: v,
                    name: k.fact.name.clone(),
                })
            })
            .collect();
        // A condition that the values substituted make false, said with where it came from.
        let own = divisors.iter().map(|d| (None, d));
        let inherited = facts
            .iter()
            .filter(|k| !via.is_empty() && used_names.contains(&k.fact.name.as_str()))
            .flat_map(|k| k.divisors.iter().map(move |d| (Some(k.fact.name.as_str()), d)));
        for (from, (d0, need)) in own.chain(inherited) {
            if *need != Need::NonZero || !apply(d0).is_ok_and(|d| d.is_zero()) {
                continue;
            }
            let message = match from {
                Some(fact) => format!(
                    "this step uses {fact}, which holds only where {} != 0, and here it is 0",
                    plain(d0)
                ),
                None if d0.as_constant().is_some() => "this step divides by zero at the value substituted (in `subs` or `eval`)".to_string(),
                None => format!("this step divides by {}, which `where` makes 0", plain(d0)),
            };
            return Err(Diagnostic::error("E0305", message, span, "division by zero"));
        }
        let mut conditions: Vec<String> = Vec::new();
        let mut all_divs: Vec<(Rat, Need)> = divisors
            .iter()
            .filter_map(|d| apply(&d.0).ok().map(|v| (v, d.1)))
            .collect();
        if !via.is_empty() {
            all_divs.extend(
                fact_divs
                    .iter()
                    .filter_map(|d| apply(&d.0).ok().map(|v| (v, d.1))),
            );
        }
        all_divs.extend(
            steps
                .iter()
                .filter_map(|s| s.divisor.clone().map(|d| (d, Need::NonZero))),
        );
        for (d, need) in &all_divs {
            let reduced = reduce(d).unwrap_or_else(|_| d.clone());
            let text = match need {
                Need::NonZero => {
                    if d.is_zero() {
                        return Err(Diagnostic::error(
                            "E0305",
                            "this step divides by zero at the value substituted (in `subs`, `eval` or `where`)",
                            span,
                            "division by zero",
                        ));
                    }
                    if reduced.is_zero() || zero_by_facts(&reduced, &all_scope, &signs) {
                        return Err(Diagnostic::error(
                            "E0305",
                            format!(
                                "this step divides by {}, which is zero by the facts",
                                plain(d)
                            ),
                            span,
                            "division by zero",
                        ));
                    }
                    let Some(essential) = essential_factor(&reduced, &signs) else {
                        continue;
                    };
                    format!("{} != 0", plain(&essential))
                }
                Need::Positive | Need::NonNegative => {
                    let s = sign_of(&reduced, &signs);
                    let (ok, bad, op) = if *need == Need::Positive {
                        (s == Sign::Pos, s.is_nonpos(), ">")
                    } else {
                        (s.is_nonneg(), s == Sign::Neg, ">=")
                    };
                    if ok {
                        continue;
                    }
                    if bad {
                        return Err(Diagnostic::error(
                            "E0305",
                            format!("this step takes ln or a square root of {}, which is not {op} 0 here", plain(d)),
                            span,
                            "outside the domain",
                        ));
                    }
                    format!("{} {op} 0", plain(&reduced))
                }
            };
            if !conditions.contains(&text) {
                conditions.push(text);
            }
        }
        if let Some(e) = &elim {
            if let Some(c) = &e.contradiction {
                return Err(Diagnostic::error(
                    "E0306",
                    format!("the facts in scope contradict each other: after eliminating unknowns, {c} says a nonzero quantity is zero"),
                    span,
                    "checked against contradictory facts",
                )
                .note("nothing can be verified from contradictory facts; check the givens"));
            }
        }
        let timed_out = elim.as_ref().is_some_and(|e| e.timed_out);
        let reduced_diff = elim.as_ref().map_or_else(Rat::zero, |e| e.target.clone());
        match link.op {
            RelOp::Eq => {
                if reduced_diff.is_zero() {
                    self.conditions = all_divs;
                    return Ok(Status::Verified {
                        how: how_eq(&via),
                        side_conditions: conditions,
                    });
                }
                // Undetermined unknowns are explained by `not_equal`; nothing is refuted then.
                let stuck = elim.as_ref().is_some_and(|e| !e.stuck.is_empty());
                let (ra, rb) = if stuck || timed_out {
                    (ra, rb)
                } else {
                    match self.unrefuted(
                        (&a, &b),
                        &diff,
                        (&used_facts, &all_scope),
                        matches!(by, Some(By::Labels(_))),
                        span,
                        deadline,
                    ) {
                        Err(d) => return Err(d),
                        Ok(Some(sides)) => sides,
                        Ok(None) => (ra, rb),
                    }
                };
                Err(self.not_equal(
                    &a,
                    &b,
                    &ra,
                    &rb,
                    elim.as_ref(),
                    &via,
                    span,
                    timed_out,
                    &all_divs,
                ))
            }
            RelOp::Ne => {
                // Like every inequality: verified when the signs show `lhs − rhs` nonzero.
                if reduced_diff.is_zero() {
                    return Err(Diagnostic::error(
                        "E0303",
                        "the two sides are equal, so `!=` is false",
                        span,
                        "",
                    ));
                }
                let d = ra
                    .sub(&rb)
                    .map_err(|e| Diagnostic::error("E0101", e.to_string(), span, ""))?;
                if sign_of(&d, &signs).is_nonzero() {
                    return Ok(Status::Verified {
                        how: Justification::Signs(via),
                        side_conditions: conditions,
                    });
                }
                let mut diag = Diagnostic::error(
                    "E0303",
                    "not verified: the declared signs do not show that the sides differ",
                    span,
                    "",
                )
                .note(format!(
                    "left − right = {}, which may be zero for some allowed values",
                    plain(&d)
                ));
                if let Verdict::NotEqual { .. } = decide(&ra, &rb, &signs) {
                    diag.notes.push("the sides are not identical, but `!=` claims they differ for every allowed value".into());
                }
                Err(diag)
            }
            RelOp::Lt | RelOp::Le | RelOp::Gt | RelOp::Ge => {
                let d = ra
                    .sub(&rb)
                    .map_err(|e| Diagnostic::error("E0101", e.to_string(), span, ""))?;
                let sign = sign_of(&d, &signs);
                let ok = match link.op {
                    RelOp::Lt => sign == Sign::Neg,
                    RelOp::Le => sign.is_nonpos(),
                    RelOp::Gt => sign == Sign::Pos,
                    _ => sign.is_nonneg(),
                };
                if ok {
                    return Ok(Status::Verified {
                        how: Justification::Signs(via),
                        side_conditions: conditions,
                    });
                }
                let mut diag = Diagnostic::error(
                    "E0303",
                    format!(
                        "not verified: `{}` does not follow from the declared signs",
                        link.op
                    ),
                    span,
                    "",
                )
                .note(format!("left − right = {}", plain(&d)));
                if let Some(e) = &elim {
                    if !e.stuck.is_empty() {
                        diag.notes
                            .push(format!("the facts do not determine {}", names(&e.stuck)));
                    }
                }
                if let Some(c) = violation(&ra, &rb, link.op, &signs) {
                    diag.message = format!(
                        "`{}` is false for some values allowed by the declared signs",
                        link.op
                    );
                    diag.notes.push(c);
                    Err(diag)
                } else {
                    diag.notes.push(format!("its sign is {}", describe(sign)));
                    Err(diag)
                }
            }
            RelOp::Approx => {
                // Each side's value: unknowns and fixed parameters replaced by the facts.
                let value = |r: &Rat| {
                    super::solve::reduce_fully(r, &used_facts, &is_unknown, &signs, Some(deadline))
                        .unwrap_or_else(|_| r.clone())
                };
                let (va, vb) = (value(&a), value(&b));
                self.approx(&va, &vb, &link.rhs, span, conditions)
            }
        }
    }

    /// A failing `=` step may be called false only if it fails in every situation the
    /// signs and all the facts in scope allow. When the facts could make it hold, or
    /// still constrain the quantities its difference is made of, the answer is "not
    /// verified" and this says why; otherwise the two sides reduced by every fact in
    /// scope, for the refutation to work on.
    fn unrefuted(
        &self,
        sides: (&Rat, &Rat),
        diff: &Rat,
        (cited, all): (&[Fact], &[Fact]),
        restricted: bool,
        span: Span,
        deadline: Instant,
    ) -> Result<Option<(Rat, Rat)>, Diagnostic> {
        let signs = &self.env.signs;
        let scope = &self.scope;
        let is_unknown = |x: AtomId| unknown_atom(scope, x);
        let elim = |facts: &[Fact], params: bool| {
            super::solve::eliminate_all(diff, facts, &is_unknown, signs, Some(deadline), params)
                .ok()
        };
        let not_verified = |headline: String, notes: Vec<String>| {
            let mut d = Diagnostic::error("E0302", headline, span, "not verified");
            d.notes = notes;
            d
        };
        let Some(full) = elim(all, true) else {
            return Ok(None);
        };
        if restricted
            && (full.0.is_zero() || elim(cited, true).map(|r| r.0) != Some(full.0.clone()))
        {
            let why = if full.0.is_zero() {
                "it follows from the facts in scope, but not from those cited"
            } else {
                "it does not follow from the facts cited, and the other facts in scope bear on it"
            };
            return Err(not_verified(
                format!("not verified from the facts cited: {why}"),
                vec!["cite every fact the step needs in `by [..]`, or drop `by [..]`".into()],
            ));
        }
        if full.0.is_zero() {
            return Err(not_verified(
                "not verified: rigor could not settle this step with the facts in scope".into(),
                Vec::new(),
            ));
        }
        // Unknowns only first (the sides read as written); parameters fixed by the facts
        // only when the facts still tie the difference's quantities.
        let mut tied = Vec::new();
        for (target, steps, left) in [elim(all, false), Some(full)].into_iter().flatten() {
            tied = tied_atoms(&target, &left, &is_unknown, signs);
            if tied.is_empty() {
                let reduce = |r: &Rat| apply_steps(r, &steps, signs);
                return Ok(match (reduce(sides.0), reduce(sides.1)) {
                    (Ok(x), Ok(y)) => Some((x, y)),
                    _ => None,
                });
            }
            if target.is_zero() {
                break;
            }
        }
        let Some((target, _, left)) = elim(all, true) else {
            return Ok(None);
        };
        let names: Vec<String> = tied
            .iter()
            .map(|a| crate::normal::print::atom_plain(&atom::get(*a)))
            .collect();
        let mut which: Vec<&str> = left
            .iter()
            .filter(|f| {
                tied.iter()
                    .any(|a| crate::normal::subst::depends_on(&f.value, *a))
            })
            .map(|f| f.name.as_str())
            .collect();
        which.dedup();
        let them = if names.len() == 1 { "it" } else { "them" };
        Err(not_verified(
            format!(
                "not verified: the facts in scope ({}) relate {}, so rigor cannot show that this step fails",
                which.join(", "),
                names.join(", ")
            ),
            vec![
                format!("after using the facts, left − right = {}", short(&plain(&target))),
                format!(
                    "if the facts determine {}, declare {them} with `unknowns` so that rigor solves for {them}",
                    names.join(", ")
                ),
            ],
        ))
    }

    #[allow(clippy::too_many_arguments)]
    fn not_equal(
        &self,
        a: &Rat,
        b: &Rat,
        ra: &Rat,
        rb: &Rat,
        elim: Option<&Elimination>,
        via: &[String],
        span: Span,
        timed_out: bool,
        defined: &[(Rat, Need)],
    ) -> Diagnostic {
        let using = if via.is_empty() {
            String::new()
        } else {
            format!(" (after using {})", cite(via))
        };
        let mut notes = vec![
            format!("left side:  {}", short(&plain(a))),
            format!("right side: {}", short(&plain(b))),
        ];
        if !via.is_empty() {
            notes.push(
                format!(
                    "with the facts{using}: left {} , right {}",
                    plain(ra),
                    plain(rb)
                )
                .replace(" ,", ","),
            );
        }
        if timed_out {
            let mut d = Diagnostic::error(
                "E0902",
                "not verified: the claim ran out of its time budget (see --timeout)",
                span,
                "undecided",
            );
            d.notes = notes;
            return d;
        }
        if let Some(e) = elim {
            if !e.stuck.is_empty() {
                let facts: Vec<Fact> = self.facts.iter().map(|k| k.fact.clone()).collect();
                let mut headline = format!(
                    "not verified: nothing in scope determines {}",
                    names(&e.stuck)
                );
                let mut powers = Vec::new();
                for u in &e.stuck {
                    if let Some((fact, n)) = super::solve::power_only(&facts, *u, &self.env.signs) {
                        let name = super::solve::unknown_name(*u);
                        headline =
                            format!("not verified: {fact} gives {name} only through {name}^{n}");
                        powers.push(format!(
                            "rigor takes the principal root only of an unknown declared positive: `symbols {name} > 0` before `unknowns {name}`"
                        ));
                    }
                }
                let mut d = Diagnostic::error(
                    "E0302",
                    headline,
                    span,
                    if powers.is_empty() {
                        "a fact may be missing"
                    } else {
                        "which root is meant?"
                    },
                );
                notes.push(format!(
                    "after eliminating what the facts give, left − right = {}",
                    plain(&e.target)
                ));
                let root_missing = !powers.is_empty();
                if root_missing {
                    notes.extend(powers);
                } else {
                    notes.push(format!(
                        "a fact about {} was needed but never given (or `by [..]` left it out)",
                        names(&e.stuck)
                    ));
                }
                if let Some(hint) = crate::decide::diagnose(ra, rb, &e.target)
                    .filter(|h| !root_missing && !h.starts_with("the two sides differ by"))
                {
                    notes.push(format!("if {} can take any value, {hint}", names(&e.stuck)));
                }
                d.notes = notes;
                return d;
            }
        }
        match crate::decide::decide_where(ra, rb, &self.env.signs, defined) {
            Verdict::NotEqual {
                diagnosis,
                counterexample,
                ..
            } => {
                let label = diagnosis
                    .clone()
                    .unwrap_or_else(|| "the two sides differ".into());
                let mut d = Diagnostic::error(
                    "E0301",
                    format!("this step does not hold{using}"),
                    span,
                    &label,
                );
                if let Some(c) = counterexample {
                    if c.values.is_empty() {
                        notes.push(format!(
                            "the left side is {}, the right side {}",
                            c.lhs, c.rhs
                        ));
                    } else {
                        notes.push(format!(
                            "counterexample: at {} the left side is {} and the right side {}",
                            c.assignment(),
                            c.lhs,
                            c.rhs
                        ));
                    }
                }
                d.notes = notes;
                d
            }
            Verdict::Undecided { why } => {
                let mut d = Diagnostic::error(
                    "E0302",
                    format!("not verified{using}: rigor can neither prove nor refute this step"),
                    span,
                    "undecided",
                );
                notes.push(why);
                d.notes = notes;
                d
            }
            Verdict::Equal => {
                let mut d = Diagnostic::error("E0302", "not verified", span, "");
                d.notes = notes;
                d
            }
        }
    }

    fn approx(
        &self,
        a: &Rat,
        b: &Rat,
        rhs: &Expr,
        span: Span,
        conditions: Vec<String>,
    ) -> Result<Status, Diagnostic> {
        let (c, ulp) = match literal_precision(rhs, &self.report.source) {
            Ok(x) => x,
            Err(why) => return Err(Diagnostic::error("E0304", why, span, "")),
        };
        let Ok(ratio) = a.div(b) else {
            return Err(Diagnostic::error(
                "E0304",
                "the right side of `~=` is zero",
                span,
                "",
            ));
        };
        // A/B must be a number; then A ≈ B when |c·A/B − c| ≤ ulp/2.
        let mut sy = Vec::new();
        crate::decide::symbols_in(&ratio, &mut sy);
        if !sy.is_empty() {
            return Err(Diagnostic::error(
                "E0304",
                format!(
                    "`~=` is not verified: the ratio of the sides, {}, is not a number",
                    plain(&ratio)
                ),
                span,
                "",
            ));
        }
        let point = HashMap::new();
        let mut ev = crate::decide::Evaluator::new(&point);
        ev.prec = Prec::new(128);
        let half = &ulp / Q::from_integer(BigInt::from(2));
        let err = ev.rat(&ratio).and_then(|r| {
            let ci = crate::interval::Interval::point(c.clone());
            r.mul(&ci, ev.prec)?.sub(&ci, ev.prec)?.abs()
        });
        match err {
            Some(e) if e.hi() <= &half => Ok(Status::Verified { how: Justification::Approx, side_conditions: conditions }),
            Some(e) if e.lo() > &half => Err(Diagnostic::error(
                "E0304",
                format!("`~=` does not hold at the precision written: the exact ratio is {}", plain(&ratio)),
                span,
                "not this close",
            )
            .note({
                let r = ev.rat(&ratio);
                let scaled = r
                    .as_ref()
                    .and_then(|r| r.mul(&crate::interval::Interval::point(c.clone()), ev.prec));
                format!(
                    "left / right ≈ {}; so where the right side says {}, the left side is ≈ {}, which does not round to {} at the precision written",
                    r.map_or_else(|| "?".into(), |r| r.to_decimal_string(6)),
                    show(&c),
                    scaled.map_or_else(|| "?".into(), |r| r.to_decimal_string(6)),
                    show(&c)
                )
            })),
            _ => Err(Diagnostic::error(
                "E0302",
                "`~=` is not verified: rigor could not bound the ratio precisely enough",
                span,
                "undecided",
            )),
        }
    }
}

/// The quantities of `target` (symbols, moments) that the facts left over still tie.
fn tied_atoms(
    target: &Rat,
    left: &[Fact],
    is_unknown: &dyn Fn(AtomId) -> bool,
    signs: &crate::normal::Assumptions,
) -> Vec<AtomId> {
    let constrained = super::solve::constrained_atoms(left, is_unknown, signs);
    let mut mine = Vec::new();
    crate::decide::symbols_in(target, &mut mine);
    mine.extend(
        target
            .atoms()
            .into_iter()
            .filter(|a| matches!(&*atom::get(*a), crate::normal::Atom::Moment(..))),
    );
    mine.into_iter()
        .filter(|a| constrained.contains(a) && !is_unknown(*a))
        .collect()
}

/// Whether atom `a` is an unknown: declared so, a `time` symbol or derivative, or one of
/// those at an instant (`x'(T)`).
fn unknown_atom(scope: &Scope, a: AtomId) -> bool {
    match &*atom::get(a) {
        crate::normal::Atom::Sym(n) => scope.is_unknown(n),
        crate::normal::Atom::At(n, _) => scope.is_unknown(n),
        _ => false,
    }
}

/// Whether `value` satisfies the sign declared for `name`; the message says why not.
pub(crate) fn respects_sign(
    name: &str,
    declared: Sign,
    value: &Rat,
    signs: &crate::normal::Assumptions,
) -> Result<(), String> {
    let s = sign_of(value, signs);
    let (ok, what) = match declared {
        Sign::Pos => (s == Sign::Pos, "> 0"),
        Sign::NonNeg => (s.is_nonneg(), ">= 0"),
        Sign::NonZero => (s.is_nonzero(), "!= 0"),
        Sign::Neg => (s == Sign::Neg, "< 0"),
        Sign::NonPos => (s.is_nonpos(), "<= 0"),
        Sign::Zero => (value.is_zero(), "= 0"),
        Sign::Unknown => (true, ""),
    };
    if ok {
        Ok(())
    } else {
        Err(format!(
            "`{name}` is declared {what}, but {} is not shown to be {what}; results that used the sign of `{name}` would not carry over",
            plain(value)
        ))
    }
}

fn show(q: &Q) -> String {
    if q.denom().is_one() {
        q.numer().to_string()
    } else {
        // Decimal form of a terminating fraction, else p/q.
        let mut d = q.denom().clone();
        let mut k = 0usize;
        let two = BigInt::from(2);
        let five = BigInt::from(5);
        while (&d % &two) == BigInt::from(0) || (&d % &five) == BigInt::from(0) {
            if (&d % &two) == BigInt::from(0) {
                d /= &two;
            } else {
                d /= &five;
            }
            k += 1;
            if k > 60 {
                break;
            }
        }
        if d.is_one() {
            let scaled = q * Q::from_integer(BigInt::from(10).pow(k as u32));
            let n = scaled.to_integer();
            let s = n.abs().to_string();
            let s = format!("{:0>width$}", s, width = k + 1);
            let (i, f) = s.split_at(s.len() - k);
            let f = f.trim_end_matches('0');
            let sign = if q.is_negative() { "-" } else { "" };
            if f.is_empty() {
                format!("{sign}{i}")
            } else {
                format!("{sign}{i}.{f}")
            }
        } else {
            format!("{}/{}", q.numer(), q.denom())
        }
    }
}

/// A normal form for a diagnostic: very long ones are cut, with their length said.
fn short(s: &str) -> String {
    const MAX: usize = 2000;
    if s.len() <= MAX {
        return s.to_string();
    }
    let mut cut = MAX;
    while !s.is_char_boundary(cut) {
        cut -= 1;
    }
    format!("{} … ({} characters in all)", &s[..cut], s.len())
}

fn names(ids: &[AtomId]) -> String {
    ids.iter()
        .map(|a| unknown_name(*a))
        .collect::<Vec<_>>()
        .join(", ")
}

fn describe(s: Sign) -> &'static str {
    match s {
        Sign::Zero => "zero",
        Sign::Pos => "positive",
        Sign::Neg => "negative",
        Sign::NonNeg => "nonnegative (it may be zero)",
        Sign::NonPos => "nonpositive (it may be zero)",
        Sign::NonZero => "nonzero but of unknown sign",
        Sign::Unknown => "not determined by the declared signs",
    }
}

/// The part of a divisor whose nonzeroness the signs do not show: the numerator with
/// constant and monomial factors of nonzero sign dropped (`None` if nothing is left).
fn essential_factor(d: &Rat, signs: &crate::normal::Assumptions) -> Option<Rat> {
    if signs.rat(d).is_nonzero() || d.as_constant().is_some() {
        return None;
    }
    let n = d.num();
    let mc = n.mono_content();
    let rest = n.div_mono(&mc).unwrap_or_else(|| n.clone()).primitive();
    let mut keep = Vec::new();
    for &(a, e) in mc.pairs() {
        if !signs.atom(a).is_nonzero() {
            keep.push((a, e));
        }
    }
    let keep = crate::normal::mono::Mono::from_pairs(keep)?;
    let out = Rat::poly(rest.mul_term(&keep, &Q::one()).ok()?).ok()?;
    if out.as_constant().is_some() || signs.rat(&out).is_nonzero() {
        return None;
    }
    Some(out)
}

/// The sign of `d`: term-wise from the declared signs, where constant factors such as
/// `1 − sqrt(2)/2` get their sign from a rigorous enclosure.
fn sign_of(d: &Rat, signs: &crate::normal::Assumptions) -> Sign {
    let s = signs.rat(d);
    if s != Sign::Unknown && s != Sign::NonZero {
        return s;
    }
    let n = grouped_sign(d.num(), signs);
    let den = grouped_sign(d.den(), signs);
    let den = match den {
        Sign::NonNeg => Sign::Pos,
        Sign::NonPos => Sign::Neg,
        x => x,
    };
    match (n, den) {
        (_, Sign::Unknown | Sign::NonZero) | (Sign::Unknown, _) => s,
        (n, den) => n.times(den),
    }
}

/// Groups the terms of `p` by their symbolic factor; each group's coefficient is a
/// constant (numbers, `pi`, numeric radicals) whose sign an enclosure decides.
fn grouped_sign(p: &crate::normal::Poly, signs: &crate::normal::Assumptions) -> Sign {
    use crate::normal::mono::Mono;
    let mut groups: Vec<(Mono, Vec<(Mono, Q)>)> = Vec::new();
    for (m, q) in p.terms() {
        let (mut sym, mut cst) = (Vec::new(), Vec::new());
        for &(a, e) in m.pairs() {
            let mut found = Vec::new();
            crate::decide::symbols_in(&Rat::atom(a), &mut found);
            if found.is_empty() {
                cst.push((a, e));
            } else {
                sym.push((a, e));
            }
        }
        let (Some(sym), Some(cst)) = (Mono::from_pairs(sym), Mono::from_pairs(cst)) else {
            return Sign::Unknown;
        };
        match groups.iter_mut().find(|g| g.0 == sym) {
            Some(g) => g.1.push((cst, q.clone())),
            None => groups.push((sym, vec![(cst, q.clone())])),
        }
    }
    let point = HashMap::new();
    let mut total = Sign::Zero;
    for (sym, coeff) in groups {
        let c = crate::normal::Poly::from_terms(coeff);
        let mut ev = crate::decide::Evaluator::new(&point);
        let cs = match Rat::poly(c).ok().and_then(|r| ev.rat(&r)) {
            Some(v) if v.is_positive() => Sign::Pos,
            Some(v) if v.is_negative() => Sign::Neg,
            _ => return Sign::Unknown,
        };
        let mut s = cs;
        for &(a, e) in sym.pairs() {
            s = s.times(signs.atom(a).pow(e));
        }
        total = total.plus(s);
    }
    total
}

/// A checked point where `a op b` is false, described.
fn violation(a: &Rat, b: &Rat, op: RelOp, signs: &crate::normal::Assumptions) -> Option<String> {
    let mut sy = Vec::new();
    crate::decide::symbols_in(a, &mut sy);
    crate::decide::symbols_in(b, &mut sy);
    // Reuse the counterexample search on `a` against `b`, then test the relation there.
    let c = find_counterexample(a, b, signs)?;
    let point: HashMap<AtomId, Q> = c
        .values
        .iter()
        .map(|(n, q)| (atom::sym(n), q.clone()))
        .collect();
    let mut ev = crate::decide::Evaluator::new(&point);
    let d = ev.rat(&a.sub(b).ok()?)?;
    let false_there = match op {
        RelOp::Lt => !d.is_negative() && (d.is_positive() || d.lo() >= &Q::from_integer(0.into())),
        RelOp::Le => d.is_positive(),
        RelOp::Gt => d.is_negative() || d.hi() <= &Q::from_integer(0.into()),
        _ => d.is_negative(),
    };
    false_there.then(|| {
        format!(
            "at {} the left side is {} and the right side {}",
            c.assignment(),
            c.lhs,
            c.rhs
        )
    })
}

/// The one number written on the right side of `~=` and the unit of its last written
/// digit: the side must be that number times symbols (`0.71 R`, `-9.8`, `0.6 m L^2`);
/// anything else is refused rather than guessed at (`2 * 0.30 R`, `1/0.3`).
fn literal_precision(e: &Expr, src: &str) -> Result<(Q, Q), String> {
    let mut found = Vec::new();
    let shape = number_times_symbols(e, src, false, false, &mut found);
    match (shape, found.as_slice()) {
        (true, [(q, ulp, false)]) => Ok((q.clone(), ulp.clone())),
        _ => Err(
            "the right side of `~=` must be one written number times symbols (`0.71 R`), whose precision says how close; write the number out (`0.60 R`, not `2 * 0.30 R`)"
                .into(),
        ),
    }
}

/// Whether `e` is a product or quotient of symbols and numbers; collects each number
/// with its precision and whether it divides.
fn number_times_symbols(
    e: &Expr,
    src: &str,
    neg: bool,
    divides: bool,
    found: &mut Vec<(Q, Q, bool)>,
) -> bool {
    match &e.kind {
        ExprKind::Num(q) => {
            let Some(ulp) = src.get(e.span.start..e.span.end).and_then(ulp_of) else {
                return false;
            };
            found.push((if neg { -q.clone() } else { q.clone() }, ulp, divides));
            true
        }
        ExprKind::Sym(_) | ExprKind::Pi => true,
        ExprKind::Neg(a) => number_times_symbols(a, src, !neg, divides, found),
        ExprKind::Bin(BinOp::Mul, a, b) => {
            number_times_symbols(a, src, neg, divides, found)
                && number_times_symbols(b, src, false, divides, found)
        }
        ExprKind::Bin(BinOp::Div, a, b) => {
            number_times_symbols(a, src, neg, divides, found)
                && number_times_symbols(b, src, false, !divides, found)
        }
        // A power or a function of symbols only (`R^2`, `sqrt(g/L)`).
        ExprKind::Bin(BinOp::Pow, base, _) => !has_number(base),
        ExprKind::Call(_, args) => !args.iter().any(has_number),
        ExprKind::Bin(..) => false,
    }
}

fn has_number(e: &Expr) -> bool {
    match &e.kind {
        ExprKind::Num(_) => true,
        ExprKind::Sym(_) | ExprKind::Pi => false,
        ExprKind::Neg(a) => has_number(a),
        ExprKind::Bin(_, a, b) => has_number(a) || has_number(b),
        ExprKind::Call(_, args) => args.iter().any(has_number),
    }
}

/// `0.71` → 1/100, `1.5e-3` → 1/10000, `3` → 1.
fn ulp_of(text: &str) -> Option<Q> {
    let t = text.trim();
    let (mant, exp) = match t.find(['e', 'E']) {
        Some(i) => (&t[..i], t[i + 1..].parse::<i32>().ok()?),
        None => (t, 0),
    };
    let decimals = mant.split_once('.').map_or(0, |(_, f)| f.len()) as i32;
    let k = decimals - exp;
    let ten = BigInt::from(10);
    Some(if k >= 0 {
        Q::new(BigInt::one(), ten.pow(k as u32))
    } else {
        Q::from_integer(ten.pow((-k) as u32))
    })
}
