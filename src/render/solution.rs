//! The worked solution as a sequence of blocks, shared by the LaTeX and Markdown
//! renderers: they differ only in how they write text, displays and problems.
//!
//! Math is LaTeX already (from [`super::expr`]); text is raw, as the user wrote it,
//! and each renderer escapes it for its own output.

use super::expr::{chain_latex_in, expr_latex_in, rel_latex, symbol, Ctx};
#[cfg(test)]
pub(crate) use super::pieces::break_sum;
pub(crate) use super::pieces::{note_inlines, rich, row_math, words_and_math};
use super::steps::{Steps, Work};
use super::Detail;
use crate::check::report::{ClaimReport, FileReport, Status};
use crate::diag::{line_col, Diagnostic, Note, Severity};
use crate::syntax::ast::{
    Assign, BodyDef, By, Chain, ExprKind, File, Item, Label, Name, ProsePart, SignDecl, Span, Stmt,
    StmtKind,
};

/// A piece of a paragraph.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Inline {
    /// Raw text.
    Text(String),
    /// Raw text in bold.
    Strong(String),
    /// Raw text in a typewriter font (a file name).
    Code(String),
    /// Inline math (LaTeX).
    Math(String),
}

/// The justification of a link.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Just {
    /// `by some words`: words, and the maths written between `$` typeset.
    Text(Vec<Inline>),
    /// `by [Fx], [MG]` (raw label names).
    Labels(Vec<String>),
}

/// One line of a displayed claim.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Row {
    /// The left-hand side, on the first line only (LaTeX).
    pub lhs: Option<String>,
    /// The relation (LaTeX).
    pub rel: &'static str,
    /// The right-hand side (LaTeX).
    pub rhs: String,
    /// The justification written after `by`.
    pub by: Option<Just>,
    /// `\text{where } …` on the last line (LaTeX).
    pub where_: Option<String>,
    /// The mark of a link that is not verified.
    pub flag: Option<Mark>,
}

/// What a problem shown in a document is: the mark of the link of a claim it is about,
/// or a diagnostic outside a claim by its severity.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum ProblemKind {
    /// About a link of a claim.
    Link(Mark),
    /// An error outside a claim.
    Error,
    /// A warning.
    Warning,
    /// A note.
    Note,
}

impl ProblemKind {
    /// `does not hold`, `error`, `warning`, ….
    pub(crate) fn words(self) -> &'static str {
        match self {
            ProblemKind::Link(m) => m.words(),
            ProblemKind::Error => "error",
            ProblemKind::Warning => "warning",
            ProblemKind::Note => "note",
        }
    }
}

/// A diagnostic shown in the document.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Problem {
    /// What it is.
    pub kind: ProblemKind,
    /// The 1-based line it points at.
    pub line: Option<usize>,
    /// The message (raw text).
    pub message: String,
    /// Its notes.
    pub notes: Vec<Note>,
}

/// A block of the document.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Block {
    /// A heading (level 1 for `#` after the title, 2 for `##`, …) with raw text.
    Heading(usize, String),
    /// A paragraph.
    Paragraph(Vec<Inline>),
    /// A displayed formula: `prefix` (raw text) before it, `note` (raw text) after it
    /// in parentheses, and a tag (raw label).
    Display {
        /// Raw text shown before the formula.
        prefix: Option<String>,
        /// The formula (LaTeX).
        math: String,
        /// Raw text shown after it in parentheses (`given`).
        note: Option<String>,
        /// The label, as a tag.
        tag: Option<String>,
    },
    /// A claim: aligned rows, its label as a tag.
    Claim {
        /// The rows, one per link.
        rows: Vec<Row>,
        /// The label.
        tag: Option<String>,
    },
    /// Diagnostics about the statement above.
    Problems(Vec<Problem>),
    /// The work the statement above skipped, filled in from the checker's computation
    /// (only with [`Detail::Steps`]).
    Working(Vec<Work>),
    /// Rendered diagnostics (rustc style) of a file that could not be read.
    Listing(Vec<String>),
}

/// A whole worked solution.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Solution {
    /// The title (raw text).
    pub title: String,
    /// The blocks in order.
    pub blocks: Vec<Block>,
}

/// The worked solution of a report, as written.
pub(crate) fn build(report: &FileReport) -> Solution {
    build_with(report, Detail::Written)
}

/// The worked solution of a report, with the work the file skipped filled in when
/// `detail` asks for it.
pub(crate) fn build_with(report: &FileReport, detail: Detail) -> Solution {
    let file_name = file_title(report);
    let Some(ast) = &report.ast else {
        let mut blocks = vec![Block::Paragraph(vec![
            Inline::Text("The file ".into()),
            Inline::Code(report.path.clone()),
            Inline::Text(" could not be read, so no worked solution was produced.".into()),
        ])];
        let idx = crate::diag::LineIndex::new(&report.source);
        let listing: Vec<String> = report
            .diagnostics
            .iter()
            .map(|d| crate::diag::render_in(d, &report.path, &idx))
            .collect();
        if !listing.is_empty() {
            blocks.push(Block::Listing(listing));
        }
        return Solution {
            title: file_name,
            blocks,
        };
    };
    Builder::new(report, ast, detail).run(file_name)
}

/// The title of a file without a `#` title: its name.
fn file_title(report: &FileReport) -> String {
    std::path::Path::new(&report.path)
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .filter(|n| !n.is_empty())
        .unwrap_or_else(|| "Worked solution".to_string())
}

/// Walks the file, keeping track of which diagnostics were shown.
struct Builder<'a> {
    report: &'a FileReport,
    ast: &'a File,
    ctx: Ctx,
    shown: Vec<bool>,
    blocks: Vec<Block>,
    /// Equation numbers of the labelled givens, constraints and claims, in document
    /// order: labels never appear in the output, their numbers do.
    numbers: std::collections::HashMap<String, usize>,
    /// What the derivation finds, for the "Find" line (said once, after the first
    /// declarations).
    find: Vec<String>,
    /// Where the file sits in a book, if it is one section of several.
    place: Option<&'a Place<'a>>,
    /// The work to fill in, with [`Detail::Steps`].
    steps: Option<Steps<'a>>,
}

/// What a derivation finds: the left sides of the claims `result [..]` names (the unknowns
/// in a left side that combines several quantities), or, with no `result`, those of its
/// claims whose left side is one quantity (`I_G = …`), each once.
fn sought(ast: &File, ctx: &Ctx) -> Vec<String> {
    let stmts = || {
        ast.items.iter().filter_map(|i| match i {
            Item::Stmt(st) => Some(&st.kind),
            _ => None,
        })
    };
    let named: Vec<&str> = stmts()
        .filter_map(|k| match k {
            StmtKind::Result { labels } => Some(labels.iter().map(|l| l.name.as_str())),
            _ => None,
        })
        .flatten()
        .collect();
    let unknowns: Vec<String> = stmts()
        .filter_map(|k| match k {
            StmtKind::Unknowns { names } => Some(names.iter().map(|n| n.name.clone())),
            _ => None,
        })
        .flatten()
        .collect();
    let mut out: Vec<String> = Vec::new();
    for k in stmts() {
        let StmtKind::Claim { label, chain, .. } = k else {
            continue;
        };
        let one = matches!(chain.first.kind, ExprKind::Sym(_));
        let wanted = if named.is_empty() {
            one
        } else {
            label
                .as_ref()
                .is_some_and(|l| named.contains(&l.name.as_str()))
        };
        if !wanted {
            continue;
        }
        // A result about a combination (`a b = k_G^2`) finds the unknowns it holds.
        let mut found = Vec::new();
        if !one {
            syms(&chain.first, &mut found);
            found.retain(|n| unknowns.contains(n));
        }
        let shown: Vec<String> = if found.is_empty() {
            vec![expr_latex_in(&chain.first, ctx)]
        } else {
            found.iter().map(|n| symbol(n)).collect()
        };
        for f in shown {
            if !out.contains(&f) {
                out.push(f);
            }
        }
    }
    out
}

/// The names of the symbols of `e`, each once, in the order written.
fn syms(e: &crate::syntax::ast::Expr, out: &mut Vec<String>) {
    match &e.kind {
        ExprKind::Sym(n) if !out.contains(n) => out.push(n.clone()),
        ExprKind::Neg(a) => syms(a, out),
        ExprKind::Bin(_, a, b) => {
            syms(a, out);
            syms(b, out);
        }
        ExprKind::Call(_, args) => args.iter().for_each(|a| syms(a, out)),
        _ => {}
    }
}

/// Equation numbers of a file's labelled givens, constraints and claims, in document
/// order (1, 2, …).
pub(crate) fn numbers_of(ast: &File) -> Numbers {
    let mut numbers = Numbers::new();
    for item in &ast.items {
        if let Item::Stmt(st) = item {
            let label = match &st.kind {
                StmtKind::Given { label, .. }
                | StmtKind::Constraint { label, .. }
                | StmtKind::Claim { label, .. } => label.as_ref(),
                _ => None,
            };
            if let Some(l) = label {
                let next = numbers.len() + 1;
                numbers.entry(l.name.clone()).or_insert(next);
            }
        }
    }
    numbers
}

/// Label → equation number.
pub(crate) type Numbers = std::collections::HashMap<String, usize>;

/// Where a file sits in a book of several: its section number, and every file's
/// section and equation numbers by path (as in [`FileReport::path`]), so that equations
/// are numbered `3.2` and a `use` of another file of the book becomes a reference to
/// its section and equations.
pub(crate) struct Place<'b> {
    /// The file's section (1-based).
    pub section: usize,
    /// Path → (section, numbers) of every file of the book.
    pub files: &'b std::collections::HashMap<String, (usize, Numbers)>,
}

/// Every readable file's section and equation numbers, by path.
pub(crate) fn book_numbers(
    reports: &[FileReport],
) -> std::collections::HashMap<String, (usize, Numbers)> {
    reports
        .iter()
        .enumerate()
        .filter_map(|(k, r)| Some((r.path.clone(), (k + 1, numbers_of(r.ast.as_ref()?)))))
        .collect()
}

/// The worked solution of a report as one section of a book.
pub(crate) fn build_in(report: &FileReport, place: &Place<'_>, detail: Detail) -> Solution {
    match &report.ast {
        Some(ast) => {
            let mut b = Builder::new(report, ast, detail);
            b.place = Some(place);
            b.run(file_title(report))
        }
        None => build(report),
    }
}

/// `dir/a.deriv` and `../b/c.deriv` → `b/c.deriv` (lexically, the leading `/` of an
/// absolute path dropped on both sides of a comparison; `None` above the root).
fn joined(base: &str, rel: &str) -> Option<String> {
    let dir = std::path::Path::new(base)
        .parent()
        .map(|p| p.to_string_lossy().into_owned())
        .unwrap_or_default();
    crate::check::normalise(format!("{dir}/{rel}").trim_start_matches('/'))
}

impl<'a> Builder<'a> {
    fn new(report: &'a FileReport, ast: &'a File, detail: Detail) -> Builder<'a> {
        let ctx = Ctx::from_file(ast);
        Builder {
            steps: (detail == Detail::Steps).then(|| Steps::new(&report.env, ast)),
            report,
            ast,
            find: sought(ast, &ctx),
            ctx,
            shown: vec![false; report.diagnostics.len()],
            blocks: Vec::new(),
            numbers: numbers_of(ast),
            place: None,
        }
    }

    /// A label as the output shows it: its equation number (`3.2` in a book), or
    /// (imported) its name.
    fn number(&self, label: &str) -> String {
        let prefix = self
            .place
            .map_or_else(String::new, |p| format!("{}.", p.section));
        self.numbers
            .get(label)
            .map_or_else(|| label.to_string(), |n| format!("{prefix}{n}"))
    }

    /// `From Section 2 we use (2.3)` for a `use` of another file of the book.
    fn cross_reference(&self, path: &str, labels: &[Label]) -> Option<Vec<Inline>> {
        let place = self.place?;
        let norm = |p: &str| joined("", p);
        let target = joined(&self.report.path, path)?;
        let (section, numbers) = place
            .files
            .iter()
            .find(|(k, _)| norm(k).as_deref() == Some(target.as_str()))
            .map(|(_, v)| v)?;
        let list: Vec<String> = labels
            .iter()
            .map(|l| {
                numbers
                    .get(&l.name)
                    .map_or_else(|| format!("({})", l.name), |n| format!("({section}.{n})"))
            })
            .collect();
        Some(vec![Inline::Text(format!(
            "From Section {section} we use {}",
            list.join(", ")
        ))])
    }

    fn run(mut self, file_name: String) -> Solution {
        let mut title = None;
        let mut prose: Vec<Inline> = Vec::new();
        let mut decls: Vec<Inline> = Vec::new();
        let mut decl_problems: Vec<Problem> = Vec::new();
        for item in &self.ast.items {
            let is_prose = matches!(item, Item::Prose { .. });
            let is_decl = matches!(item, Item::Stmt(s) if is_declaration(&s.kind));
            if !is_prose && !prose.is_empty() {
                self.blocks
                    .push(Block::Paragraph(std::mem::take(&mut prose)));
            }
            if !is_decl {
                self.finish_decls(&mut decls, &mut decl_problems);
            }
            match item {
                Item::Heading { level, text, .. } => {
                    if *level == 1 && title.is_none() {
                        title = Some(text.clone());
                    } else {
                        self.blocks
                            .push(Block::Heading((*level).max(1), text.clone()));
                    }
                }
                Item::Prose { parts, .. } => {
                    if !prose.is_empty() {
                        prose.push(Inline::Text(" ".into()));
                    }
                    for part in parts {
                        prose.push(match part {
                            ProsePart::Text(t) => Inline::Text(t.clone()),
                            ProsePart::Math(c) => Inline::Math(chain_latex_in(c, &self.ctx)),
                            ProsePart::MathExpr(e) => Inline::Math(expr_latex_in(e, &self.ctx)),
                        });
                    }
                }
                Item::Stmt(stmt) if is_declaration(&stmt.kind) => {
                    self.declaration(&stmt.kind, &mut decls);
                    decl_problems.extend(self.attach(stmt.span, false));
                }
                Item::Stmt(stmt) => self.statement(stmt),
            }
        }
        if !prose.is_empty() {
            self.blocks.push(Block::Paragraph(prose));
        }
        self.finish_decls(&mut decls, &mut decl_problems);
        self.results();
        self.checked_line();
        let rest: Vec<Problem> = self
            .report
            .diagnostics
            .iter()
            .zip(&self.shown)
            .filter(|(_, shown)| !**shown)
            .map(|(d, _)| self.problem(d, false))
            .collect();
        if !rest.is_empty() {
            self.blocks
                .push(Block::Heading(2, "Problems found by the checker".into()));
            self.blocks.push(Block::Problems(rest));
        }
        Solution {
            title: title.unwrap_or(file_name),
            blocks: self.blocks,
        }
    }

    /// The closing "Results" block: the claims `result [..]` names (each `first = last`
    /// of its chain), each boxed when it verified and marked otherwise.
    fn results(&mut self) {
        let mut named: Vec<&str> = Vec::new();
        for item in &self.ast.items {
            if let Item::Stmt(st) = item {
                if let StmtKind::Result { labels } = &st.kind {
                    named.extend(labels.iter().map(|l| l.name.as_str()));
                }
            }
        }
        let mut shown = Vec::new();
        for item in &self.ast.items {
            let Item::Stmt(st) = item else { continue };
            let StmtKind::Claim {
                label: Some(l),
                chain,
                ..
            } = &st.kind
            else {
                continue;
            };
            if !named.contains(&l.name.as_str()) {
                continue;
            }
            let last = chain.links.last().map_or(&chain.first, |k| &k.rhs);
            let op = chain
                .links
                .last()
                .map_or(crate::syntax::ast::RelOp::Eq, |k| k.op);
            let (first, last) = (
                expr_latex_in(&chain.first, &self.ctx),
                expr_latex_in(last, &self.ctx),
            );
            let tag = Some(self.number(&l.name));
            // Only a result every link of which verified is boxed; any other carries
            // the mark of its worst link, in the words the rest of the document uses.
            match self.result_mark(st, chain) {
                None => shown.push(Block::Display {
                    prefix: None,
                    math: format!("\\boxed{{{first} {} {last}}}", rel_latex(op)),
                    note: None,
                    tag,
                }),
                Some(flag) => shown.push(Block::Claim {
                    rows: vec![Row {
                        lhs: Some(first),
                        rel: rel_latex(op),
                        rhs: last,
                        by: None,
                        where_: None,
                        flag: Some(flag),
                    }],
                    tag,
                }),
            }
        }
        if !shown.is_empty() {
            self.blocks.push(Block::Heading(2, "Results".into()));
            self.blocks.extend(shown);
        }
    }

    /// The mark of a result that is not verified: "does not hold" when a link of its
    /// chain was shown false, else "not verified" when one is undecided, else "not
    /// checked" (including a claim the report does not hold); `None` when every link
    /// verified.
    fn result_mark(&self, stmt: &Stmt, chain: &Chain) -> Option<Mark> {
        let claim = self.claim_report(stmt);
        let statuses: Vec<Option<&Status>> = chain
            .links
            .iter()
            .enumerate()
            .map(|(k, link)| {
                claim
                    .and_then(|c| c.links.get(k))
                    .map(|l| &l.status)
                    .or_else(|| self.report.link_status(link.span))
            })
            .collect();
        if !statuses.is_empty() && statuses.iter().all(|s| s.is_some_and(Status::is_verified)) {
            return None;
        }
        let has = |f: fn(&Status) -> bool| statuses.iter().flatten().any(|s| f(s));
        Some(if has(|s| *s == Status::Failed) {
            Mark::DoesNotHold
        } else if has(|s| *s == Status::Undecided) {
            Mark::NotVerified
        } else {
            Mark::NotChecked
        })
    }

    /// What was checked, in one closing line.
    fn checked_line(&mut self) {
        let (verified, total) = (self.report.verified(), self.report.links());
        if total == 0 {
            return;
        }
        let mut conditions: Vec<String> = Vec::new();
        for c in &self.report.claims {
            for l in &c.links {
                if let Status::Verified {
                    side_conditions, ..
                } = &l.status
                {
                    for sc in side_conditions {
                        if !conditions.contains(sc) {
                            conditions.push(sc.clone());
                        }
                    }
                }
            }
        }
        let mut p = vec![Inline::Text(format!(
            "rigor verified {verified} of {total} steps"
        ))];
        let opts = crate::syntax::ParseOptions::default();
        for (k, sc) in conditions.iter().enumerate() {
            p.push(Inline::Text(
                if k == 0 { "; side conditions: " } else { ", " }.into(),
            ));
            p.push(match crate::syntax::parse_chain(sc, &opts) {
                Ok(ch) => Inline::Math(chain_latex_in(&ch, &self.ctx)),
                Err(_) => Inline::Code(sc.clone()),
            });
        }
        p.push(Inline::Text(".".into()));
        self.blocks.push(Block::Paragraph(p));
    }

    /// Ends a run of declarations: the "Given quantities" and "Find" sentences and their
    /// problems.
    fn finish_decls(&mut self, decls: &mut Vec<Inline>, problems: &mut Vec<Problem>) {
        let declared = !decls.is_empty() || !problems.is_empty();
        if !decls.is_empty() {
            let mut p = vec![
                Inline::Strong("Given quantities:".into()),
                Inline::Text(" ".into()),
            ];
            p.append(decls);
            p.push(Inline::Text(".".into()));
            self.blocks.push(Block::Paragraph(p));
        }
        if declared && !self.find.is_empty() {
            let find = std::mem::take(&mut self.find);
            self.blocks.push(Block::Paragraph(vec![
                Inline::Strong("Find:".into()),
                Inline::Text(" ".into()),
                Inline::Math(find.join(", ")),
                Inline::Text(".".into()),
            ]));
        }
        if !problems.is_empty() {
            self.blocks.push(Block::Problems(std::mem::take(problems)));
        }
    }

    /// Appends one declaration to the "Given quantities" sentence.
    fn declaration(&self, kind: &StmtKind, out: &mut Vec<Inline>) {
        if !out.is_empty() {
            out.push(Inline::Text("; ".into()));
        }
        let names = |ns: &[Name]| {
            ns.iter()
                .map(|n| symbol(&n.name))
                .collect::<Vec<_>>()
                .join(", ")
        };
        match kind {
            StmtKind::Symbols { names: ns, sign } => {
                let sign = match sign {
                    SignDecl::Any => "",
                    SignDecl::Positive => " > 0",
                    SignDecl::Nonnegative => " \\geq 0",
                    SignDecl::Nonzero => " \\neq 0",
                };
                out.push(Inline::Math(format!("{}{sign}", names(ns))));
            }
            StmtKind::Range {
                names: ns,
                lo,
                lo_strict,
                hi,
                hi_strict,
            } => {
                let op = |strict: &bool| if *strict { " < " } else { " \\leq " };
                out.push(Inline::Math(format!(
                    "{}{}{}{}{}",
                    expr_latex_in(lo, &self.ctx),
                    op(lo_strict),
                    names(ns),
                    op(hi_strict),
                    expr_latex_in(hi, &self.ctx)
                )));
            }
            StmtKind::Small { names: ns, order } => {
                out.push(Inline::Text("small: ".into()));
                out.push(Inline::Math(names(ns)));
                if *order > 1 {
                    out.push(Inline::Text(format!(" (to order {order})")));
                }
            }
            StmtKind::Time { names: ns } => {
                out.push(Inline::Text("functions of time ".into()));
                out.push(Inline::Math("t".into()));
                out.push(Inline::Text(": ".into()));
                out.push(Inline::Math(names(ns)));
            }
            StmtKind::Unknowns { .. } => {
                // Unknowns are not given: they go in the "Find" line.
                if matches!(out.last(), Some(Inline::Text(t)) if t == "; ") {
                    out.pop();
                }
            }
            StmtKind::Units { decls } => {
                out.push(Inline::Text("units: ".into()));
                for (k, d) in decls.iter().enumerate() {
                    if k > 0 {
                        out.push(Inline::Text(", ".into()));
                    }
                    out.push(Inline::Math(symbol(&d.name.name)));
                    out.push(Inline::Text(" in ".into()));
                    out.push(Inline::Math(crate::units::unit_latex(&d.unit)));
                }
            }
            _ => {}
        }
    }

    fn statement(&mut self, stmt: &Stmt) {
        let ctx = &self.ctx;
        match &stmt.kind {
            StmtKind::Body { name, def } => {
                let math = match def {
                    BodyDef::Concrete { dm, ranges } => {
                        let mut m = format!("dm = {}", expr_latex_in(dm, ctx));
                        for r in ranges {
                            m.push_str(&format!(
                                ",\\quad {} \\leq {} \\leq {}",
                                expr_latex_in(&r.from, ctx),
                                symbol(&r.var.name),
                                expr_latex_in(&r.to, ctx)
                            ));
                        }
                        m
                    }
                    BodyDef::Abstract {
                        mass,
                        coords,
                        centred,
                    } => {
                        let coords: Vec<String> = coords.iter().map(|c| symbol(&c.name)).collect();
                        let mut m = format!(
                            "\\text{{mass }} {},\\quad \\text{{coordinates }} {}",
                            expr_latex_in(mass, ctx),
                            coords.join(", ")
                        );
                        if *centred {
                            m.push_str(",\\quad \\text{centred at the centre of mass}");
                        }
                        m
                    }
                };
                self.blocks.push(Block::Display {
                    prefix: Some(format!("Body {}:", name.name)),
                    math,
                    note: None,
                    tag: None,
                });
            }
            StmtKind::Let { name, value } => {
                let math = format!("{} := {}", symbol(&name.name), expr_latex_in(value, ctx));
                self.blocks.push(Block::Display {
                    prefix: None,
                    math,
                    note: None,
                    tag: None,
                });
                if let Some(steps) = &mut self.steps {
                    let work = steps.integrals(&[value], &self.ctx);
                    if !work.is_empty() {
                        self.blocks.push(Block::Working(work));
                    }
                }
            }
            StmtKind::Given { label, chain } | StmtKind::Constraint { label, chain } => {
                let note = if matches!(stmt.kind, StmtKind::Given { .. }) {
                    "given"
                } else {
                    "constraint"
                };
                self.blocks.push(Block::Display {
                    prefix: None,
                    math: chain_latex_in(chain, ctx),
                    note: Some(note.into()),
                    tag: label.as_ref().map(|l| self.number(&l.name)),
                });
            }
            StmtKind::Claim {
                label,
                chain,
                where_,
            } => {
                let rows = self.claim_rows(stmt, chain, where_);
                self.blocks.push(Block::Claim {
                    rows,
                    tag: label.as_ref().map(|l| self.number(&l.name)),
                });
                let work = self.claim_work(stmt, chain);
                if !work.is_empty() {
                    self.blocks.push(Block::Working(work));
                }
            }
            StmtKind::Use {
                labels, path, with, ..
            } => {
                let mut p = self.cross_reference(path, labels).unwrap_or_else(|| {
                    vec![
                        Inline::Text("From ".into()),
                        Inline::Code(path.clone()),
                        Inline::Text(format!(" we use {}", label_list(labels))),
                    ]
                });
                if !with.is_empty() {
                    p.push(Inline::Text(" with ".into()));
                    p.push(Inline::Math(assignments(with, ctx)));
                }
                p.push(Inline::Text(".".into()));
                self.blocks.push(Block::Paragraph(p));
            }
            _ => {}
        }
        let in_claim = matches!(stmt.kind, StmtKind::Claim { .. });
        let problems = self.attach(stmt.span, in_claim);
        if !problems.is_empty() {
            self.blocks.push(Block::Problems(problems));
        }
    }

    fn claim_rows(&self, stmt: &Stmt, chain: &Chain, where_: &[Assign]) -> Vec<Row> {
        let claim = self.claim_report(stmt);
        let n = chain.links.len();
        chain
            .links
            .iter()
            .enumerate()
            .map(|(k, link)| {
                let status = claim
                    .and_then(|c| c.links.get(k))
                    .map(|l| &l.status)
                    .or_else(|| self.report.link_status(link.span));
                let flag = status.map_or(Some(Mark::NotChecked), mark);
                let by = link.by.as_ref().map(|(by, _)| match by {
                    By::Text(t) => Just::Text(words_and_math(t, &self.ctx)),
                    By::Labels(ls) => match &link.compare {
                        // `by (3), (4), comparing coefficients of θ`.
                        Some(x) => {
                            let cited: Vec<String> = ls
                                .iter()
                                .map(|l| format!("({})", self.number(&l.name)))
                                .collect();
                            Just::Text(vec![
                                Inline::Text(format!(
                                    "{}, comparing coefficients of ",
                                    cited.join(", ")
                                )),
                                Inline::Math(super::expr::symbol(&x.name)),
                            ])
                        }
                        None => Just::Labels(ls.iter().map(|l| self.number(&l.name)).collect()),
                    },
                });
                let where_ = (k + 1 == n && !where_.is_empty())
                    .then(|| format!("\\text{{where }} {}", assignments(where_, &self.ctx)));
                Row {
                    lhs: (k == 0).then(|| expr_latex_in(&chain.first, &self.ctx)),
                    rel: rel_latex(link.op),
                    rhs: expr_latex_in(&link.rhs, &self.ctx),
                    by,
                    where_,
                    flag,
                }
            })
            .collect()
    }

    /// The work a claim skipped (with [`Detail::Steps`]): for each link in turn, the
    /// integrals it writes, worked, then the unknowns it was verified with.
    fn claim_work(&mut self, stmt: &Stmt, chain: &Chain) -> Vec<Work> {
        let Some(mut steps) = self.steps.take() else {
            return Vec::new();
        };
        let claim = self.claim_report(stmt);
        let several = chain.links.len() > 1;
        let mut work = Vec::new();
        for (k, link) in chain.links.iter().enumerate() {
            let exprs: Vec<&crate::syntax::ast::Expr> = if k == 0 {
                vec![&chain.first, &link.rhs]
            } else {
                vec![&link.rhs]
            };
            work.extend(steps.integrals(&exprs, &self.ctx));
            let Some(report) = claim.and_then(|c| c.links.get(k)) else {
                continue;
            };
            if !report.status.is_verified() {
                continue;
            }
            let found = self.report.workings.iter().find(|w| w.span == report.span);
            let number = |l: &str| self.number(l);
            if let Some(w) = found {
                let line = several.then_some(k + 1);
                work.extend(
                    super::steps::elimination(
                        w,
                        link.op,
                        line,
                        &self.ctx,
                        &self.report.env,
                        &number,
                    )
                    .unwrap_or_default(),
                );
            }
        }
        self.steps = Some(steps);
        work
    }

    /// The report of the claim `stmt`: by span, else by line.
    fn claim_report(&self, stmt: &Stmt) -> Option<&'a ClaimReport> {
        let claims = &self.report.claims;
        claims.iter().find(|c| c.span == stmt.span).or_else(|| {
            let line = line_col(&self.report.source, stmt.span.start).0;
            claims.iter().find(|c| c.line == line)
        })
    }

    /// The diagnostics not shown yet that point into `span`, now marked shown.
    fn attach(&mut self, span: Span, in_claim: bool) -> Vec<Problem> {
        let mut found = Vec::new();
        for (k, d) in self.report.diagnostics.iter().enumerate() {
            let inside = d.primary.as_ref().is_some_and(|(s, _)| {
                s.start >= span.start && s.start < span.end.max(span.start + 1)
            });
            if inside && !self.shown[k] {
                self.shown[k] = true;
                found.push(self.problem(d, in_claim));
            }
        }
        found
    }

    /// The status of the link a diagnostic points at: the link with its span, else the
    /// narrowest link whose span holds its start.
    fn status_at(&self, d: &Diagnostic) -> Option<&'a Status> {
        let (span, _) = d.primary.as_ref()?;
        let links = self.report.claims.iter().flat_map(|c| &c.links);
        links
            .clone()
            .find(|l| l.span == *span)
            .or_else(|| {
                links
                    .filter(|l| l.span.start <= span.start && span.start < l.span.end)
                    .min_by_key(|l| l.span.end - l.span.start)
            })
            .map(|l| &l.status)
    }

    fn problem(&self, d: &Diagnostic, in_claim: bool) -> Problem {
        let kind = match d.severity {
            // In a claim, the mark of the link it is about.
            Severity::Error if in_claim => ProblemKind::Link(
                self.status_at(d)
                    .and_then(mark)
                    .unwrap_or(Mark::NotVerified),
            ),
            Severity::Error => ProblemKind::Error,
            Severity::Warning => ProblemKind::Warning,
            Severity::Note => ProblemKind::Note,
        };
        // The words under the caret are the hint ("the left side is 2 × the right side
        // (a constant factor)"): a document has no caret, so they lead the notes.
        let env = &self.report.env;
        let mut notes: Vec<Note> = d
            .notes
            .iter()
            .map(|n| n.map_values(|v| super::pieces::as_written(v, env)))
            .collect();
        if let Some((_, hint)) = d.primary.as_ref().filter(|(_, h)| !h.is_empty()) {
            if in_claim && d.severity == Severity::Error {
                notes.insert(0, Note::from(hint.as_str()));
            }
        }
        Problem {
            kind,
            line: d
                .primary
                .as_ref()
                .map(|(s, _)| line_col(&self.report.source, s.start).0),
            message: d.message.to_string(),
            notes,
        }
    }
}

/// The words for a link that did not verify, as every view says them: a link shown
/// false "does not hold" (E0301), one neither shown true nor false is "not verified"
/// (E0302), and one that could not be read or cites a failure is "not checked".
/// `None` for a verified link.
pub(crate) fn mark(s: &Status) -> Option<Mark> {
    match s {
        Status::Verified { .. } => None,
        Status::Failed => Some(Mark::DoesNotHold),
        Status::Undecided => Some(Mark::NotVerified),
        Status::Error | Status::NotChecked => Some(Mark::NotChecked),
    }
}

/// The mark of a link that did not verify.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Mark {
    /// Shown false.
    DoesNotHold,
    /// Neither verified nor refuted.
    NotVerified,
    /// Not checked.
    NotChecked,
}

impl Mark {
    /// The words every view uses for it.
    pub(crate) fn words(self) -> &'static str {
        match self {
            Mark::DoesNotHold => "does not hold",
            Mark::NotVerified => "not verified",
            Mark::NotChecked => "not checked",
        }
    }
}

fn is_declaration(kind: &StmtKind) -> bool {
    matches!(
        kind,
        StmtKind::Symbols { .. }
            | StmtKind::Range { .. }
            | StmtKind::Small { .. }
            | StmtKind::Time { .. }
            | StmtKind::Unknowns { .. }
            | StmtKind::Units { .. }
    )
}

/// `(IO), (X)`.
fn label_list(labels: &[Label]) -> String {
    labels
        .iter()
        .map(|l| format!("({})", l.name))
        .collect::<Vec<_>>()
        .join(", ")
}

/// `a = 1,\ b = 2` (LaTeX).
fn assignments(list: &[Assign], ctx: &Ctx) -> String {
    list.iter()
        .map(|a| {
            format!(
                "{} = {}",
                symbol(&a.name.name),
                expr_latex_in(&a.value, ctx)
            )
        })
        .collect::<Vec<_>>()
        .join(",\\ ")
}
