//! A submission's facts against the problem's: each `given`, `constraint`, `use`, `let`
//! of one of the reference's quantities, and `where` value, with where it stands (the
//! problem's, the student's own assumption, contradicting the others, an import the
//! tutor does not allow), and the facts each claim rests on, followed through the claims
//! it cites.

use super::names::{self, Terms};
use crate::check::{FileReport, Justification, Status};
use crate::diag::{FactRef, FailureKind, LineIndex};
use crate::syntax::ast::{By, Chain, Expr, ExprKind, Item, Link, StmtKind};
use crate::syntax::print;
use std::collections::HashSet;

/// What a fact of the submission is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FactKind {
    /// `given`.
    Given,
    /// `constraint`.
    Constraint,
    /// `let` of a name the reference declares or defines (any other `let` is a name for
    /// an expression, and assumes nothing).
    Let,
    /// A `where` value of a claim.
    Where,
    /// `use … from`.
    Use,
}

/// Where a fact of the submission stands.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Standing {
    /// It follows from one of the problem's facts (rearranged, scaled, differentiated,
    /// in other names), or it is an import the tutor allows.
    Problem,
    /// The problem does not give it: the student's own assumption.
    Own,
    /// It contradicts the submission's other facts (E0306).
    Contradiction,
    /// A `use` that imported nothing: one the tutor does not allow, or one that failed.
    ImportFailed,
}

/// One fact of the submission.
#[derive(Clone, Debug)]
pub struct Fact {
    /// What it is.
    pub kind: FactKind,
    /// Its label, if it has one.
    pub label: Option<String>,
    /// Its line in the submission.
    pub line: usize,
    /// The labels it brings in (a `use`), else empty.
    pub imports: Vec<String>,
    /// Its relations (`lhs`, operator, `rhs`), as written.
    pub relations: Vec<(Expr, &'static str, Expr)>,
    /// The symbol names it uses.
    pub names: Vec<String>,
    /// Where it stands.
    pub standing: Standing,
}

/// A fact as a verified link cites it.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Cite {
    /// By its label.
    Label(String),
    /// An unlabelled fact, by its line.
    Line(usize),
}

/// The facts one verified link rested on, as the checker's justification cites them;
/// `None` when the justification does not say (`~=`: then it may rest on any fact
/// before it). The one place that reads the justification's fact references.
pub fn cited(status: &Status) -> Option<Vec<Cite>> {
    let facts = match status {
        Status::Verified {
            how: Justification::Facts(fs) | Justification::Signs(fs),
            ..
        } => fs,
        Status::Verified {
            how: Justification::Identity,
            ..
        } => return Some(Vec::new()),
        Status::Verified { .. } => return None,
        _ => return Some(Vec::new()),
    };
    Some(
        facts
            .iter()
            .map(|f| match f {
                FactRef::Line(n) => Cite::Line(*n),
                FactRef::Label(l) => Cite::Label(l.clone()),
            })
            .collect(),
    )
}

fn relations(chain: &Chain) -> Vec<(Expr, &'static str, Expr)> {
    let mut prev = &chain.first;
    let mut out = Vec::new();
    for l in &chain.links {
        out.push((prev.clone(), l.op.as_str(), l.rhs.clone()));
        prev = &l.rhs;
    }
    out
}

/// The submission's facts, in order. A `let` counts only when it names one of the
/// reference's quantities (`ref_names`); every `use` is a fact; its standing is set by
/// the caller, except contradictions (E0306 at its line) and refused imports (an error
/// at the `use`).
pub fn collect(sub: &FileReport, ref_names: &[String]) -> Vec<Fact> {
    let idx = LineIndex::new(&sub.source);
    let error_lines: Vec<(usize, Option<FailureKind>)> = sub
        .diagnostics
        .iter()
        .filter(|d| d.severity == crate::diag::Severity::Error)
        .filter_map(|d| {
            let p = d.primary.as_ref()?;
            Some((idx.line_col(p.0.start).0, d.failure()))
        })
        .collect();
    let mut out = Vec::new();
    for item in sub.ast.iter().flat_map(|a| &a.items) {
        let Item::Stmt(st) = item else { continue };
        let line = idx.line_col(st.span.start).0;
        let fact = |kind, label: Option<String>, relations: Vec<(Expr, &'static str, Expr)>| {
            let mut names = Vec::new();
            for (a, _, b) in &relations {
                names.extend(names::names_in(a));
                names.extend(names::names_in(b));
            }
            names.sort();
            names.dedup();
            let false_fact = error_lines
                .iter()
                .any(|(l, f)| *l == line && *f == Some(FailureKind::FalseFacts));
            Fact {
                kind,
                label,
                line,
                imports: Vec::new(),
                relations,
                names,
                standing: if false_fact {
                    Standing::Contradiction
                } else {
                    Standing::Own
                },
            }
        };
        match &st.kind {
            StmtKind::Given { label, chain } => {
                out.push(fact(
                    FactKind::Given,
                    label.as_ref().map(|l| l.name.clone()),
                    relations(chain),
                ));
            }
            StmtKind::Constraint { label, chain } => out.push(fact(
                FactKind::Constraint,
                label.as_ref().map(|l| l.name.clone()),
                relations(chain),
            )),
            StmtKind::Let { name, value } if ref_names.contains(&name.name) => {
                let sym = Expr::new(ExprKind::Sym(name.name.clone()), name.span);
                out.push(fact(FactKind::Let, None, vec![(sym, "=", value.clone())]));
            }
            StmtKind::Claim { where_, .. } if !where_.is_empty() => {
                let rel = where_
                    .iter()
                    .map(|a| {
                        let sym = Expr::new(ExprKind::Sym(a.name.name.clone()), a.name.span);
                        (sym, "=", a.value.clone())
                    })
                    .collect();
                out.push(fact(FactKind::Where, None, rel));
            }
            StmtKind::Use { labels, .. } => {
                let refused = error_lines
                    .iter()
                    .any(|(l, f)| *l == line && *f == Some(FailureKind::Input));
                let mut f = fact(FactKind::Use, None, Vec::new());
                f.imports = labels.iter().map(|l| l.name.clone()).collect();
                f.standing = if refused {
                    Standing::ImportFailed
                } else {
                    Standing::Problem
                };
                out.push(f);
            }
            _ => {}
        }
    }
    out
}

/// A claim of the submission: its label, line, chain and report.
pub struct ClaimAt<'r> {
    /// Its label.
    pub label: Option<&'r str>,
    /// Its line.
    pub line: usize,
    /// The chain.
    pub chain: &'r Chain,
    /// Whether it has `where` values.
    pub has_where: bool,
    /// Every link's status, in order (empty if it was not checked).
    pub statuses: Vec<&'r Status>,
}

/// The submission's claims, in order.
pub fn claims(sub: &FileReport) -> Vec<ClaimAt<'_>> {
    let idx = LineIndex::new(&sub.source);
    let mut out = Vec::new();
    for item in sub.ast.iter().flat_map(|a| &a.items) {
        let Item::Stmt(st) = item else { continue };
        if let StmtKind::Claim {
            label,
            chain,
            where_,
        } = &st.kind
        {
            let line = idx.line_col(st.span.start).0;
            let statuses = sub
                .claims
                .iter()
                .find(|c| c.line == line)
                .map(|c| c.links.iter().map(|l| &l.status).collect())
                .unwrap_or_default();
            out.push(ClaimAt {
                label: label.as_ref().map(|l| l.name.as_str()),
                line,
                chain,
                has_where: !where_.is_empty(),
                statuses,
            });
        }
    }
    out
}

/// Whether every link of a claim verified.
pub fn holds(c: &ClaimAt<'_>) -> bool {
    !c.statuses.is_empty() && c.statuses.iter().all(|s| s.is_verified())
}

/// The facts (indices into `facts`) the claim at `k` rests on: those its verified links
/// cite, those of the claims they cite (followed to the end), the `let`s of the
/// reference's quantities its expressions use, and its own `where` values; and the
/// labels it cites that nothing in the file gives (an import refused).
pub fn rests_on(k: usize, claims: &[ClaimAt<'_>], facts: &[Fact]) -> Vec<usize> {
    let mut out: Vec<usize> = Vec::new();
    let mut seen: HashSet<usize> = HashSet::new();
    let mut todo = vec![k];
    while let Some(c) = todo.pop() {
        if !seen.insert(c) {
            continue;
        }
        let claim = &claims[c];
        let mut add = |i: usize| {
            if !out.contains(&i) {
                out.push(i);
            }
        };
        // Its `let`s of the reference's quantities, and its `where` values.
        let used: Vec<String> = claim.chain.exprs().flat_map(names::names_in).collect();
        for (i, f) in facts.iter().enumerate() {
            let own_where = f.kind == FactKind::Where && f.line == claim.line;
            let let_used = f.kind == FactKind::Let && f.names.iter().any(|n| used.contains(n));
            if own_where || let_used {
                add(i);
            }
        }
        // A verified link: the facts the checker used (every fact and claim before it
        // when the justification does not say); any other: those it cites.
        let cites: Vec<Cite> = claim
            .chain
            .links
            .iter()
            .enumerate()
            .flat_map(|(i, l)| match claim.statuses.get(i) {
                Some(s) if s.is_verified() => cited(s).unwrap_or_else(|| {
                    let before = |line: usize| line < claim.line;
                    let lines = facts
                        .iter()
                        .map(|f| f.line)
                        .chain(claims.iter().map(|c| c.line));
                    lines.filter(|&n| before(n)).map(Cite::Line).collect()
                }),
                _ => written_cites(l),
            })
            .collect();
        for cite in cites {
            let fact = facts.iter().position(|f| match &cite {
                Cite::Label(l) => f.label.as_deref() == Some(l) || f.imports.contains(l),
                Cite::Line(n) => f.line == *n,
            });
            if let Some(i) = fact {
                add(i);
                continue;
            }
            let cited_claim = claims.iter().position(|o| match &cite {
                Cite::Label(l) => o.label == Some(l.as_str()),
                Cite::Line(n) => o.line == *n,
            });
            if let Some(j) = cited_claim {
                todo.push(j);
            }
        }
    }
    out.sort_unstable();
    out
}

/// The labels a link cites with `by`, as written.
fn written_cites(link: &Link) -> Vec<Cite> {
    match &link.by {
        Some((By::Labels(ls), _)) => ls.iter().map(|l| Cite::Label(l.name.clone())).collect(),
        _ => Vec::new(),
    }
}

/// The relations of `fact` in the reference's terms, printed (`lhs op rhs`). The name a
/// `let` or `where` gives a value keeps its meaning in the reference (`I_A = …` says
/// what the student took `I_A` to be).
pub(crate) fn in_terms(fact: &Fact, terms: &Terms) -> Vec<(String, Vec<String>)> {
    let named = matches!(fact.kind, FactKind::Let | FactKind::Where);
    fact.relations
        .iter()
        .map(|(a, op, b)| {
            let a = if named { terms.named(a) } else { terms.expr(a) };
            let b = terms.expr(b);
            let mut names = names::names_in(&a);
            names.extend(names::names_in(&b));
            (
                format!("{} {op} {}", print::source(&a), print::source(&b)),
                names,
            )
        })
        .collect()
}
