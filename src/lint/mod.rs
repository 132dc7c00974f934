//! `rigor lint`: the chains of equations inside lecture notes (Markdown with `$$…$$`,
//! LaTeX with `\[…\]`, `$$…$$`, `equation`, `align` and their starred forms). Each chain
//! is checked through the one checker entry, as a claim of a derivation made from the
//! document: its symbols declared as reals (or as the document's `rigor:` comments
//! say), a chain whose left side is a lone new symbol defining it for later chains.

mod extract;

use crate::check::{check_source, FileReport, MemoryResolver, Options, Status};
use crate::diag::Diagnostic;
use crate::syntax::ast::{Chain, Expr, ExprKind, Func, Span};
use crate::syntax::latex::{parse_latex_chain, parse_latex_links};
use crate::syntax::ParseOptions;
pub use extract::{pieces, DocKind, Piece};
use std::collections::HashSet;

/// The verdict on one chain.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// Every link holds.
    Verified,
    /// A link is false.
    Failed,
    /// It depends on something the document defines in prose, or rigor cannot read it.
    NeedsContext,
}

/// One chain of a document and what became of it.
#[derive(Clone, Debug)]
pub struct ChainReport {
    /// Where the chain is in the document.
    pub span: Span,
    /// The verdict.
    pub verdict: Verdict,
    /// For a failure or a need of context: why (diagnostics with document spans).
    pub diagnostics: Vec<Diagnostic>,
}

/// Everything found in one document.
#[derive(Clone, Debug, Default)]
pub struct LintReport {
    /// The document's name.
    pub path: String,
    /// Its text.
    pub source: String,
    /// Each chain, in document order.
    pub chains: Vec<ChainReport>,
}

impl LintReport {
    /// How many chains have this verdict.
    pub fn count(&self, v: &Verdict) -> usize {
        self.chains.iter().filter(|c| &c.verdict == v).count()
    }
}

/// Where a claim of the derivation came from: pieces of the document's text copied
/// into it, as (offset there, offset in the document, length).
type Part = Vec<(usize, usize, usize)>;

/// A chain's place in the derivation made from the document.
struct Placed {
    /// The claim of its first link (none for a definition of a new symbol).
    first: Option<Part>,
    /// The claim of the links after the first, if any.
    rest: Option<Part>,
    /// Where the whole chain is in the document.
    span: Span,
    /// Whether the first link states a relation for a lone symbol (a definition or a
    /// law the notes take from elsewhere).
    states: bool,
    /// Whether every symbol of the first link is one the document declared (in a
    /// `rigor:` comment) or defined: then a first link that does not hold is a mistake,
    /// not a relation taken from elsewhere.
    firm: bool,
}

/// Checks the chains of `doc`.
pub fn lint(name: &str, doc: &str, kind: DocKind, opts: &Options) -> LintReport {
    let mut report = LintReport {
        path: name.to_string(),
        source: doc.to_string(),
        chains: Vec::new(),
    };
    let mut deriv = String::new();
    let mut placed: Vec<Placed> = Vec::new();
    let mut declared: HashSet<String> = HashSet::new();
    // Names the document itself declared or defined (not those the linter assumed).
    let mut known: HashSet<String> = HashSet::new();
    // The last expression of the previous chain: a display starting with `=` goes on.
    let mut last: Option<Expr> = None;
    let popts = ParseOptions {
        max_depth: opts.parse.max_depth,
    };
    for piece in pieces(doc, kind) {
        match piece {
            Piece::Directive(text) => {
                if !parses(&text) {
                    continue;
                }
                for w in text.split_whitespace() {
                    let w = w
                        .trim_matches(|c: char| !c.is_alphanumeric() && c != '_')
                        .to_string();
                    declared.insert(w.clone());
                    known.insert(w);
                }
                deriv.push_str(&text);
                deriv.push('\n');
            }
            Piece::Math { text, start } => {
                for (line, off) in extract::chain_lines(&text) {
                    let at = start + off;
                    let lead = line.trim_start();
                    let continues = lead.starts_with(['=', '<', '>'])
                        || ["\\approx", "\\le", "\\ge", "\\neq", "\\simeq"]
                            .iter()
                            .any(|r| lead.starts_with(r));
                    let parsed = match (&last, continues) {
                        (Some(prev), true) => {
                            parse_latex_links(line, at, &popts).map(|links| Chain {
                                first: prev.clone(),
                                links,
                            })
                        }
                        _ => parse_latex_chain(line, at, &popts),
                    };
                    match parsed {
                        Err(e) => {
                            last = None;
                            report.chains.push(ChainReport {
                                span: e.span,
                                verdict: Verdict::NeedsContext,
                                diagnostics: vec![Diagnostic::error(
                                    "E0001", e.message, e.span, "",
                                )],
                            });
                        }
                        Ok(chain) => {
                            last = chain.links.last().map(|l| l.rhs.clone());
                            place(
                                &chain,
                                doc,
                                &mut deriv,
                                &mut placed,
                                (&mut declared, &mut known),
                            );
                        }
                    }
                }
            }
        }
    }
    let checked = check_source(name, &deriv, opts, &MemoryResolver::new());
    for p in placed {
        report.chains.push(verdict(&checked, &p));
    }
    report.chains.sort_by_key(|c| c.span.start);
    report
}

/// Writes a chain into the derivation: its new symbols declared, then as a `let` (a
/// lone new symbol on the left) and a claim of the rest, or as a claim.
fn place(
    chain: &Chain,
    doc: &str,
    deriv: &mut String,
    placed: &mut Vec<Placed>,
    (declared, known): (&mut HashSet<String>, &mut HashSet<String>),
) {
    let mut names = Vec::new();
    free(&chain.first, &mut Vec::new(), &mut names);
    if let Some(l) = chain.links.first() {
        free(&l.rhs, &mut Vec::new(), &mut names);
    }
    let firm = names
        .iter()
        .all(|n| known.contains(n.trim_end_matches('\'')) || n == "t");
    for l in chain.links.iter().skip(1) {
        free(&l.rhs, &mut Vec::new(), &mut names);
    }
    let defines = match &chain.first.kind {
        ExprKind::Sym(n) if !declared.contains(n.trim_end_matches('\'')) && !n.ends_with('\'') => {
            Some(n.clone())
        }
        _ => None,
    };
    declare(names, defines.as_ref(), deriv, declared);
    let text = |s: Span| doc.get(s.start..s.end).unwrap_or("");
    let last = chain.links.last().map_or(chain.first.span, |l| l.span);
    let chain_span = chain.first.span.to(last);
    let Some(link0) = chain.links.first() else {
        return;
    };
    let write = |kw: &str, pieces: &[Span], deriv: &mut String| -> Option<Part> {
        let mut stmt = format!("{kw} $$ ");
        for p in pieces {
            stmt.push_str(text(*p));
            stmt.push(' ');
        }
        stmt.push_str("$$\n");
        if !parses(&stmt) {
            return None;
        }
        let mut part = Vec::new();
        let mut at = deriv.len() + kw.len() + 4;
        for p in pieces {
            part.push((at, p.start, p.end - p.start));
            at += p.end - p.start + 1;
        }
        deriv.push_str(&stmt);
        Some(part)
    };
    let rest_span = chain
        .links
        .get(1)
        .map(|l| Span::new(l.span.start, last.end));
    let first_link = [
        chain.first.span,
        Span::new(link0.span.start, link0.span.end),
    ];
    let (first, states) = match &defines {
        Some(s) => {
            declared.insert(s.clone());
            known.insert(s.clone());
            let stmt = format!(
                "let $$ {} = {} $$\n",
                text(chain.first.span),
                text(link0.rhs.span)
            );
            if !parses(&stmt) {
                declared.remove(s);
                return;
            }
            deriv.push_str(&stmt);
            (None, true)
        }
        None => {
            // Checked as a claim; then, holding or not, taken as what the notes state.
            let claim = write("claim", &first_link, deriv);
            let _ = write("given", &first_link, deriv);
            (claim, matches!(chain.first.kind, ExprKind::Sym(_)))
        }
    };
    let rest = rest_span.and_then(|r| write("claim", &[link0.rhs.span, r], deriv));
    placed.push(Placed {
        first,
        rest,
        span: chain_span,
        states,
        firm,
    });
}

/// Whether a generated statement reads on its own (one bad statement must not stop
/// the rest of the document from being checked).
fn parses(stmt: &str) -> bool {
    crate::syntax::parse_file(stmt, &ParseOptions::default()).is_ok()
}

/// Declares the chain's new symbols: `time` for those written with primes.
fn declare(
    names: Vec<String>,
    defines: Option<&String>,
    deriv: &mut String,
    declared: &mut HashSet<String>,
) {
    let mut time = Vec::new();
    let mut reals = Vec::new();
    for n in names {
        let base = n.trim_end_matches('\'').to_string();
        if declared.contains(&base) || Some(&base) == defines || base == "t" || base == "dm" {
            continue;
        }
        declared.insert(base.clone());
        if n.ends_with('\'') {
            time.push(base);
        } else {
            reals.push(base);
        }
    }
    if !reals.is_empty() {
        deriv.push_str(&format!("symbols {}\n", reals.join(" ")));
    }
    if !time.is_empty() {
        deriv.push_str(&format!("time {}\n", time.join(" ")));
    }
}

/// Free symbol names of a tree (bound variables of `int`, `diff`, `subs`, `eval` left out).
fn free(e: &Expr, bound: &mut Vec<String>, out: &mut Vec<String>) {
    match &e.kind {
        ExprKind::Sym(n) if !bound.contains(n) => {
            if !out.contains(n) {
                out.push(n.clone());
            }
        }
        ExprKind::Sym(_) | ExprKind::Num(_) | ExprKind::Pi => {}
        ExprKind::Neg(a) => free(a, bound, out),
        ExprKind::Bin(_, a, b) => {
            free(a, bound, out);
            free(b, bound, out);
        }
        ExprKind::Call(f, args) => {
            let var = match (f, args.get(1).map(|a| &a.kind)) {
                (Func::Int | Func::Diff | Func::Subs | Func::Eval, Some(ExprKind::Sym(v))) => {
                    Some(v.clone())
                }
                _ => None,
            };
            for (i, a) in args.iter().enumerate() {
                if i == 1 && var.is_some() {
                    continue;
                }
                if i == 0 {
                    bound.extend(var.clone());
                    free(a, bound, out);
                    if var.is_some() {
                        bound.pop();
                    }
                } else {
                    free(a, bound, out);
                }
            }
        }
    }
}

/// The verdict on a placed chain, with its diagnostics moved to document positions.
/// The statuses and diagnostics (in document positions) of one claim part.
fn part_outcome(checked: &FileReport, part: &Part, whole: Span) -> (Vec<Status>, Vec<Diagnostic>) {
    // Each end of a span mapped on its own: a link's span runs across two pieces.
    let pos = |x: usize| {
        part.iter()
            .find(|(at, _, len)| x >= *at && x <= at + len)
            .map(|(at, doc, _)| x - at + doc)
    };
    let diagnostics = checked
        .diagnostics
        .iter()
        .filter(|d| {
            d.primary
                .as_ref()
                .is_some_and(|(s, _)| pos(s.start).is_some())
        })
        .cloned()
        .map(|mut d| {
            if let Some((s, _)) = d.primary.as_mut() {
                let start = pos(s.start).unwrap_or(whole.start);
                *s = Span::new(start, pos(s.end).unwrap_or(whole.end).max(start));
            }
            d
        })
        .collect();
    let first = part.first().map_or(0, |s| s.0);
    let statuses = checked
        .claims
        .iter()
        .filter(|c| c.span.start <= first && c.span.end > first)
        .flat_map(|c| c.links.iter().map(|l| l.status.clone()))
        .collect();
    (statuses, diagnostics)
}

/// The verdict on a placed chain: its later links must follow (else it failed); its
/// first link must hold on its own, or state a relation for a lone symbol.
fn verdict(checked: &FileReport, p: &Placed) -> ChainReport {
    let holds = |s: &[Status]| !s.is_empty() && s.iter().all(Status::is_verified);
    let refuted = ["E0301", "E0303", "E0304", "E0305", "E0401"];
    let (first_ok, mut first_diags) = match &p.first {
        Some(part) => {
            let (s, d) = part_outcome(checked, part, p.span);
            (holds(&s), d)
        }
        None => (true, Vec::new()),
    };
    if p.firm && !p.states && first_diags.iter().any(|x| refuted.contains(&x.code)) {
        return ChainReport {
            span: p.span,
            verdict: Verdict::Failed,
            diagnostics: first_diags,
        };
    }
    let report = |verdict, diagnostics| ChainReport {
        span: p.span,
        verdict,
        diagnostics,
    };
    if let Some(part) = &p.rest {
        let (s, d) = part_outcome(checked, part, p.span);
        if d.iter().any(|x| refuted.contains(&x.code)) {
            return report(Verdict::Failed, d);
        }
        if holds(&s) && (first_ok || p.states) {
            return report(Verdict::Verified, Vec::new());
        }
        first_diags.extend(d);
    } else if first_ok || (p.first.is_none() && p.states) {
        return report(Verdict::Verified, Vec::new());
    }
    // What the first link needs is context, not a mistake: notes state relations that
    // hold by definitions and laws given in prose.
    for d in &mut first_diags {
        if refuted.contains(&d.code) {
            d.code = "E0302";
            d.message = "needs context: this relation does not hold for every value of its symbols; the document must define or give it".into();
        }
    }
    if first_diags.is_empty() {
        first_diags.push(Diagnostic::error(
            "E0302",
            "needs context: this chain uses something the document defines elsewhere",
            p.span,
            "",
        ));
    }
    report(Verdict::NeedsContext, first_diags)
}
