//! The walk over a file: statements in order, declarations and scope, definitions and
//! bodies, givens and constraints. Claims are in `claims.rs`, imports in `imports.rs`,
//! deciding a link in `step.rs`.

use super::elimination::Fact;
use super::entry::{Exports, Loader};
use super::report::FileReport;
use super::scope::{undeclared, Decl, Scope};
use super::signs::sign_of;
use crate::calculus::{self, Wrt};
use crate::diag::Code;
use crate::diag::{Cited, Diagnostic, FactRef, Reached, Severity, Text};
use crate::lower::{build_body, sign_of_decl, Condition, Env, LowerError, Lowerer};
use crate::normal::atom::{self, AtomId};
use crate::normal::print::plain;
use crate::normal::{Rat, Sign};
use crate::syntax::ast::{BodyDef, Chain, Expr, File, Item, Label, RelOp, Span, StmtKind};
use foldhash::{HashMap, HashMapExt, HashSet, HashSetExt};

/// Facts in scope past which a new given is not checked against all the others for a
/// contradiction (each check eliminates them all); claims still refuse contradictory
/// facts they use.
const MAX_FACTS_CHECKED: usize = 48;

/// A fact in scope.
#[derive(Clone, Debug)]
pub(super) struct Known {
    /// The label it is cited by (`by [..]` selects on it), if any.
    pub label: Option<String>,
    /// The equation `value = 0` and how it is cited.
    pub fact: Fact,
    /// The conditions it holds under (divisors nonzero, arguments of `ln` positive,
    /// radicands nonnegative), met while deriving it.
    pub divisors: Vec<Condition>,
}

/// The limit of a refusal at one of the engine's limits, as a diagnostic records it.
pub(super) fn reached(l: crate::normal::Limit) -> Option<Reached> {
    use crate::normal::Limit;
    match l {
        Limit::Terms(n) => Some(Reached::Terms(n)),
        Limit::Digits(n) => Some(Reached::Digits(n)),
        Limit::Time => Some(Reached::ClaimTime),
        _ => None,
    }
}

/// Walks one file.
pub struct Checker<'l, 'o> {
    pub(super) report: FileReport,
    /// The file's name, as imports resolve relative to it.
    pub(super) name: String,
    pub(super) loader: &'l mut Loader<'o>,
    pub(super) scope: Scope,
    pub(super) env: Env,
    pub(super) facts: Vec<Known>,
    pub(super) labels: HashMap<String, Span>,
    /// Labels of givens and claims that did not hold (or could not be read), with
    /// their line: a later `by [..]` citing one is not checked rather than an error.
    pub(super) failed_labels: HashMap<String, usize>,
    /// For a failed claim whose equations are known, the quantities they would have
    /// brought into the facts (`claims::quantities`); empty when it would bring none
    /// (no `=` link, or a special case under `where`). A label not here may have
    /// brought anything.
    pub(super) failed_reach: HashMap<String, Vec<String>>,
    /// The equations of verified claims with `where`, with their substitutions: a
    /// special case, cited (`by [..]`) only by a claim with the same `where`.
    pub(super) special: Vec<(Vec<(AtomId, Rat)>, Known)>,
    /// The first given set aside because it contradicted the facts before it, as
    /// messages name it (`[two] (line 7)`).
    pub(super) contradicted: Option<Text>,
    /// Names already reported: undeclared ones, and those a failed `use` would have
    /// defined (a `let` of the other file), with why (`undeclared (line 7)`). A later
    /// use is not checked, rather than a second error for the same mistake.
    pub(super) failed_names: HashMap<String, (usize, Text)>,
    /// The failed names whose later use was already noted as not checked (once each).
    pub(super) noted_uses: HashSet<String>,
    pub(super) exports: Exports,
    body_coords: HashMap<String, Vec<String>>,
    /// Set when lowering ran out of time (the link is undecided).
    pub(super) timed_out: bool,
    /// Byte offset of the start of every line, for line numbers.
    line_starts: Vec<usize>,
    /// The conditions the last verified link holds under (its own and those of the
    /// facts it used): a claim that becomes a fact carries them.
    pub(super) conditions: Vec<Condition>,
    /// Definitions, bodies and time symbols as written, for the guard.
    pub(super) guard_env: crate::guard::GuardEnv,
    /// Which divisors the facts force to zero, for the facts in scope now (`zeros.rs`).
    pub(super) zero_memo: std::cell::RefCell<super::zeros::ZeroMemo>,
    /// Fact sets already found free of contradiction (`zeros.rs`).
    pub(super) consistent: std::cell::RefCell<super::zeros::Consistent>,
    /// Quantities declared `small`, with the order kept.
    pub(super) small: Vec<(String, u32)>,
    /// The labels `result` names (checked at the end of the file).
    results: Vec<Label>,
    /// Declared units of symbols; once any is declared, relations are checked for them.
    pub(super) units: HashMap<String, crate::units::Dim>,
    /// When the file's own time budget runs out (`Options::file_budget`), and whether
    /// that has been reported.
    pub(super) file_deadline: Option<(crate::clock::Deadline, bool)>,
}

impl<'l, 'o> Checker<'l, 'o> {
    /// A checker that will fill `report`.
    pub fn new(report: FileReport, name: String, loader: &'l mut Loader<'o>) -> Checker<'l, 'o> {
        let file_deadline = loader
            .opts
            .file_budget
            .and_then(|b| crate::clock::Deadline::after(b, loader.opts.clock))
            .map(|d| (d, false));
        Checker {
            report,
            name,
            loader,
            scope: Scope::default(),
            env: Env::default(),
            facts: Vec::new(),
            labels: HashMap::new(),
            failed_labels: HashMap::new(),
            failed_reach: HashMap::new(),
            special: Vec::new(),
            contradicted: None,
            failed_names: HashMap::new(),
            noted_uses: HashSet::new(),
            exports: Exports::default(),
            body_coords: HashMap::new(),
            timed_out: false,
            line_starts: Vec::new(),
            conditions: Vec::new(),
            guard_env: crate::guard::GuardEnv::default(),
            zero_memo: Default::default(),
            consistent: Default::default(),
            small: Vec::new(),
            results: Vec::new(),
            units: HashMap::new(),
            file_deadline,
        }
    }

    pub(super) fn error(&mut self, code: Code, msg: String, span: Span, label: &str) {
        self.report.input_error = true;
        self.report
            .diagnostics
            .push(Diagnostic::error(code, msg, span, label));
    }

    pub(super) fn line(&self, span: Span) -> usize {
        match self.line_starts.binary_search(&span.start) {
            Ok(i) => i + 1,
            Err(i) => i,
        }
    }

    /// Checks every statement; returns the report and what the file exports.
    pub fn run(mut self, mut file: File) -> (FileReport, Exports) {
        self.line_starts = std::iter::once(0)
            .chain(self.report.source.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        for item in &mut file.items {
            if let Item::Stmt(st) = item {
                super::reading::euler_e_as_declared(&mut st.kind, self.scope.is_declared("e"));
                for e in super::reading::exprs_of(&st.kind) {
                    super::reading::glued_after_slash(
                        e,
                        &self.report.source,
                        &mut self.report.diagnostics,
                    );
                }
                self.statement(&st.kind, st.span);
                if self.loader.opts.stop_at_determined_given && self.report.names_determined_given()
                {
                    break;
                }
            }
        }
        for l in std::mem::take(&mut self.results) {
            if !self.labels.contains_key(&l.name) {
                let hint = self.label_hint(&l.name);
                self.error(
                    Code::UnknownLabel,
                    format!("`result` names [{}], which no statement has", l.name),
                    l.span,
                    &hint,
                );
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
        self.exports.units = self.units.clone();
        if self.report.input_error {
            self.exports.error = self
                .report
                .diagnostics
                .iter()
                .find(|d| d.severity == Severity::Error)
                .map(|d| d.message.to_string());
        }
        self.report.env = std::mem::take(&mut self.env);
        (self.report, self.exports)
    }

    /// Reports undeclared names in `e`; true if all are declared.
    pub(super) fn declared(&mut self, e: &Expr) -> bool {
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
            if let Some((_, why)) = self.failed_names.get(name) {
                let msg = Text::from(format!("not checked: it uses `{name}`, ")).then(why);
                if self.noted_uses.insert(name.clone()) {
                    self.note_not_checked(msg, *span);
                }
                continue;
            }
            let hint = self.scope.undeclared_hint(name);
            self.error(
                Code::Undeclared,
                format!("undeclared symbol `{name}`"),
                *span,
                &hint,
            );
            let line = self.line(*span);
            self.failed_names.insert(
                name.clone(),
                (
                    line,
                    Text::from("which is undeclared (line ").line(line).and(")"),
                ),
            );
        }
        bad.is_empty()
    }

    pub(super) fn lower(&mut self, e: &Expr, divisors: &mut Vec<Condition>) -> Option<Rat> {
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
        if e.timed_out() {
            // Undecided, not bad input: the claim fails, the file is not malformed.
            self.timed_out = true;
            // Said as what it is (undecided), like the summary and the exit status.
            self.report.diagnostics.push(
                Diagnostic::error(
                    Code::TimeBudget,
                    "not verified: the claim ran out of its time budget",
                    e.span,
                    "undecided",
                )
                .reached(Reached::ClaimTime),
            );
            return;
        }
        match e.limit() {
            Some(l) => {
                let mut d = Diagnostic::error(Code::SizeLimit, e.to_string(), e.span, "");
                d.reached = reached(l);
                self.report.diagnostics.push(d);
                self.report.input_error = true;
            }
            None => self.error(Code::NoValue, e.to_string(), e.span, ""),
        }
    }

    fn declare(&mut self, name: &str, span: Span, d: Decl) -> bool {
        if let Some(prev) = self.scope.names.get(name) {
            let ok = matches!((prev, &d), (Decl::Symbol, Decl::Unknown));
            if !ok {
                self.error(
                    Code::DeclaredTwice,
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
                Code::DeclaredTwice,
                "`t` is the time variable declared by `time`".into(),
                span,
                "",
            );
            return false;
        }
        self.scope.names.insert(name.to_string(), d);
        true
    }

    pub(super) fn new_label(&mut self, label: &Option<Label>) -> Option<String> {
        let l = label.as_ref()?;
        if let Some(prev) = self.labels.get(&l.name).copied() {
            let line = self.line(prev);
            self.error(
                Code::DuplicateLabel,
                format!("duplicate label [{}]", l.name),
                l.span,
                &format!("[{}] was already used on line {line}", l.name),
            );
            return None;
        }
        self.labels.insert(l.name.clone(), l.span);
        Some(l.name.clone())
    }

    pub(super) fn fact_name(&self, label: &Option<String>, span: Span) -> Cited {
        Cited::of(match label {
            Some(l) => FactRef::Label(l.clone()),
            None => FactRef::Line(self.line(span)),
        })
    }

    fn statement(&mut self, kind: &StmtKind, span: Span) {
        match kind {
            StmtKind::Symbols { names, sign } => {
                for n in names {
                    if self.declare(&n.name, n.span, Decl::Symbol) {
                        self.env.signs.set(atom::sym(&n.name), sign_of_decl(*sign));
                        self.guard_env
                            .domains
                            .push((n.name.clone(), crate::guard::Domain::Sign(*sign)));
                    }
                }
            }
            StmtKind::Range {
                names,
                lo,
                lo_strict,
                hi,
                hi_strict,
            } => self.range(names, (lo, *lo_strict), (hi, *hi_strict)),
            StmtKind::Small { names, order } => {
                for n in names {
                    let base = n.name.trim_end_matches('\'');
                    if !self.scope.is_declared(base) {
                        self.declared(&Expr::new(
                            crate::syntax::ast::ExprKind::Sym(n.name.clone()),
                            n.span,
                        ));
                        continue;
                    }
                    self.small.retain(|(s, _)| *s != n.name);
                    self.small.push((n.name.clone(), *order));
                }
            }
            StmtKind::Result { labels } => {
                self.results.extend(labels.iter().cloned());
            }
            StmtKind::Time { names } => {
                if !self.scope.names.contains_key("t") {
                    self.scope.names.insert("t".into(), Decl::TimeVar);
                }
                for n in names {
                    if self.declare(&n.name, n.span, Decl::Time) {
                        self.env.time.insert(n.name.clone());
                        self.guard_env.time.insert(n.name.clone());
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
                            Code::Undeclared,
                            format!("units for undeclared symbol `{}`", d.name.name),
                            d.name.span,
                            &hint,
                        );
                        continue;
                    }
                    self.declare_unit(d);
                }
            }
            StmtKind::Body { name, def } => self.body(name, def),
            StmtKind::Let { name, value } => {
                let mut divs = Vec::new();
                let Some(v) = self.lower(value, &mut divs) else {
                    return;
                };
                if self.declare(&name.name, name.span, Decl::Def) {
                    let written = self.report.source.get(value.span.start..value.span.end);
                    self.exports
                        .lets
                        .insert(name.name.clone(), written.unwrap_or_default().to_string());
                    self.env.defs.insert(name.name.clone(), v);
                    self.guard_env.defs.insert(name.name.clone(), value.clone());
                }
            }
            StmtKind::Given { label, chain } | StmtKind::Constraint { label, chain } => {
                let is_constraint = matches!(kind, StmtKind::Constraint { .. });
                let label = self.new_label(label);
                self.fact_units(chain, span);
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

    /// `body B: …`: coordinates and their differentials are local to the statement.
    fn body(&mut self, name: &crate::syntax::ast::Name, def: &BodyDef) {
        if !self.declare(&name.name, name.span, Decl::Body) {
            return;
        }
        let coords: Vec<String> = match def {
            BodyDef::Concrete { ranges, .. } => ranges.iter().map(|r| r.var.name.clone()).collect(),
            BodyDef::Abstract { coords, .. } => coords.iter().map(|c| c.name.clone()).collect(),
        };
        // Names inside the body statement: coordinates and their differentials are local.
        let mut local = self.scope.clone();
        for c in &coords {
            local.names.insert(c.clone(), Decl::Symbol);
            local.names.insert(format!("d{c}"), Decl::Symbol);
        }
        let exprs: Vec<&Expr> = match def {
            BodyDef::Concrete { dm, ranges } => std::iter::once(dm)
                .chain(ranges.iter().flat_map(|r| [&r.from, &r.to]))
                .collect(),
            BodyDef::Abstract { mass, .. } => vec![mass],
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
                self.guard_env.bodies.insert(name.name.clone(), def.clone());
                self.body_coords.insert(name.name.clone(), coords);
                self.mass_sign(name);
            }
            Err(e) => self.lower_error(e),
        }
    }

    /// Warns (W0102) when a body's mass comes out negative: its bounds run backwards.
    fn mass_sign(&mut self, name: &crate::syntax::ast::Name) {
        let opts = crate::syntax::ParseOptions::default();
        let Ok(e) = crate::syntax::parse_expr(&format!("int(1, {})", name.name), &opts) else {
            return;
        };
        let Ok(mass) = Lowerer::new(&self.env).lower(&e) else {
            return;
        };
        if matches!(sign_of(&mass, &self.env.signs), Sign::Neg) {
            let mut d = Diagnostic::error(
                Code::NegativeMass,
                format!(
                    "the mass of `{}` comes out negative: {}",
                    name.name,
                    plain(&mass)
                ),
                name.span,
                "do its bounds run backwards?",
            );
            d.severity = Severity::Warning;
            self.report.diagnostics.push(
                d.note("each coordinate must run from its lower bound to its upper one (`y from -L/2 to L/2`)"),
            );
        }
    }

    fn given(&mut self, label: Option<String>, chain: &Chain, span: Span, constraint: bool) {
        let before = self.facts.len();
        let read = self.given_facts(&label, chain, span, constraint);
        if !read || !self.consistent_with_earlier(before, span) {
            if let Some(l) = label {
                let line = self.line(span);
                self.failed_labels.insert(l, line);
            }
        }
    }

    /// Whether the facts from index `before` on are consistent with the earlier ones;
    /// if not, they are taken back and the contradiction is reported (E0306), once, at
    /// the statement that brought it in. Facts that contradict each other would prove
    /// anything, whatever the names.
    fn consistent_with_earlier(&mut self, before: usize, span: Span) -> bool {
        if self.facts.len() == before || self.facts.len() > MAX_FACTS_CHECKED {
            return true;
        }
        // A fact that is one already in scope (or its negation) adds nothing: notes state
        // a relation they have just derived.
        let (old, new) = self.facts.split_at(before);
        let repeats = |k: &Known| {
            let neg = k.fact.value.neg();
            old.iter()
                .any(|o| o.fact.value == k.fact.value || o.fact.value == neg)
        };
        if new.iter().all(repeats) {
            return true;
        }
        let values: Vec<Fact> = self.facts.iter().map(|k| k.fact.clone()).collect();
        let found = self.consistent.borrow_mut().check(&values, &self.env.signs);
        let why = match found {
            Some(why) => Some((why, "no real values satisfy the facts with this one")),
            None => self
                .motion_forced_still(&values)
                .map(|w| (Text::from(w), "with this one, nothing moves")),
        };
        let Some((why, label)) = why else {
            return true;
        };
        let line = self.line(span);
        let name = self.facts[before].label.as_ref().map_or_else(
            || Text::from("the given at line ").line(line),
            |l| Text::label_at(l, line),
        );
        self.contradicted.get_or_insert(name);
        self.facts.truncate(before);
        self.report.diagnostics.push(
            Diagnostic::error(
                Code::FalseFacts,
                Text::from("the facts contradict each other: ").then(&why),
                span,
                label,
            )
            .note("nothing can be verified from contradictory facts; this fact is not used (check the givens and the declared signs)"),
        );
        self.report.input_error = true;
        false
    }

    /// The facts of a given or constraint; `false` when it could not be read (the
    /// error is reported).
    fn given_facts(
        &mut self,
        label: &Option<String>,
        chain: &Chain,
        span: Span,
        constraint: bool,
    ) -> bool {
        let mut divs = Vec::new();
        let Some(mut prev) = self.lower(&chain.first, &mut divs) else {
            return false;
        };
        let name = self.fact_name(label, span);
        for link in &chain.links {
            let Some(rhs) = self.lower(&link.rhs, &mut divs) else {
                return false;
            };
            if link.op == RelOp::Eq {
                let value = match prev.sub(&rhs) {
                    Ok(v) => v,
                    Err(e) => {
                        self.error(Code::NoValue, e.to_string(), link.span, "");
                        return false;
                    }
                };
                if value.is_zero() {
                    prev = rhs;
                    continue;
                }
                if sign_of(&value, &self.env.signs).is_nonzero()
                    || super::zeros::never_zero(&value, &self.env.signs)
                {
                    self.report.diagnostics.push(Diagnostic::error(
                        Code::FalseFacts,
                        format!(
                            "this fact is false under the declared signs: {} = {}",
                            plain(&prev),
                            plain(&rhs)
                        ),
                        link.span,
                        "the two sides can never be equal",
                    ));
                    self.report.input_error = true;
                    // Not a fact: from a false one anything would follow. Steps citing
                    // it are not checked (one mistake, one error).
                    return false;
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
                            name: Cited {
                                fact: name.fact.clone(),
                                derivative: k,
                            },
                        },
                        divisors: divs.clone(),
                    });
                }
            }
            prev = rhs;
        }
        true
    }

    /// `symbols lo < x < hi`: symbols with the sign and the interval the bounds give.
    fn range(&mut self, names: &[crate::syntax::ast::Name], lo: (&Expr, bool), hi: (&Expr, bool)) {
        let mut divs = Vec::new();
        let (Some(l), Some(h)) = (self.lower(lo.0, &mut divs), self.lower(hi.0, &mut divs)) else {
            return;
        };
        let (sign, range) = match super::signs::interval((l, lo.1), (h, hi.1), &self.env.signs) {
            Ok(x) => x,
            Err(why) => {
                self.error(
                    Code::DeclaredTwice,
                    why,
                    lo.0.span.to(hi.0.span),
                    "the lower bound must be below the upper bound",
                );
                return;
            }
        };
        for n in names {
            if self.declare(&n.name, n.span, Decl::Symbol) {
                let x = atom::sym(&n.name);
                self.env.signs.set(x, sign);
                self.env.signs.set_range(x, Some(range.clone()));
                self.guard_env.domains.push((
                    n.name.clone(),
                    crate::guard::Domain::Range {
                        lo: lo.0.clone(),
                        lo_strict: lo.1,
                        hi: hi.0.clone(),
                        hi_strict: hi.1,
                    },
                ));
            }
        }
    }

    /// "did you mean [..]?" for a label that names nothing.
    pub(super) fn label_hint(&self, name: &str) -> String {
        let mut sc = Scope::default();
        for k in self.labels.keys() {
            sc.names.insert(k.clone(), Decl::Symbol);
        }
        sc.suggest(name)
            .map_or("no statement has that label".into(), |s| {
                format!("did you mean [{s}]?")
            })
    }

    pub(super) fn is_unknown(&self, a: AtomId) -> bool {
        unknown_atom(&self.scope, a)
    }
}

/// Whether atom `a` is an unknown: declared so, a `time` symbol or derivative, or one of
/// those at an instant (`x'(T)`).
pub(super) fn unknown_atom(scope: &Scope, a: AtomId) -> bool {
    match atom::get(a) {
        crate::normal::Atom::Sym(n) => scope.is_unknown(n),
        crate::normal::Atom::At(n, _) => scope.is_unknown(n),
        _ => false,
    }
}
