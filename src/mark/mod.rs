//! `rigor mark`: a class's submissions against a reference derivation. Each submission is
//! checked as `check` does, and its first failing step is classified in a small
//! vocabulary. Its names are matched by role onto the reference's (`names.rs`), its facts
//! placed against the problem's (`facts.rs`: the problem's, the student's own
//! assumption, contradictory, an import the tutor does not allow), and the last claim
//! about each of the reference's results is credited only when it holds in the
//! submission, rests on none but the problem's facts, and equals the reference's result
//! (`compare.rs`, through the one checker entry).

mod compare;
pub mod facts;
pub mod names;

use crate::check::{check_source, FileReport, Options, Resolver};
use crate::diag::{line_col, Diagnostic};
use crate::diag::{Code, FailureKind, Mistake};
use crate::syntax::ast::{Chain, Item, StmtKind};
use crate::syntax::print;
pub use compare::Memo;
use compare::{Batch, Checked, Slot};
use facts::{ClaimAt, Fact, FactKind, Standing};
pub use names::Mapped;
use names::Terms;

/// The kinds of first mistake (README, "rigor mark").
pub const KINDS: [&str; 13] = [
    "sign",
    "factor",
    "power",
    "missing_term",
    "extra_term",
    "missing_fact",
    "undeclared",
    "syntax",
    "import",
    "units",
    "false_fact",
    "undecided",
    "not_read",
];

/// A result of the reference.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Expected {
    /// The claim's label.
    pub label: String,
    /// The first expression of the claim, as written (`x''`).
    pub lhs: String,
    /// The same, printed in rigor's syntax (how a submission's quantity is compared).
    pub quantity: String,
    /// The reference's `time` symbols and unknowns that its result's value does not use:
    /// a submission's value may not use them either (`F = m g sin(beta) + m x''` is not
    /// yet an answer, `x'' = x''` never one).
    pub not_in_value: Vec<String>,
}

/// Why a result that may equal the reference's earns nothing.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Why {
    /// It rests on a fact the problem does not give.
    OwnAssumption {
        /// The fact's label, if it has one.
        label: Option<String>,
        /// Its line.
        line: usize,
        /// What it is.
        kind: FactKind,
    },
    /// It rests on facts that contradict each other (E0306).
    Contradiction {
        /// The fact's label, if it has one.
        label: Option<String>,
        /// Its line.
        line: usize,
    },
    /// It rests on a `use` the tutor does not allow.
    Import {
        /// The `use`'s line.
        line: usize,
    },
    /// The claim, on this line, does not hold in the submission.
    DoesNotFollow {
        /// The claim's line.
        line: usize,
    },
    /// The quantity is written with a name no fact of the submission matches to the
    /// reference's.
    Unmatched {
        /// The submission's name.
        name: String,
    },
}

/// What became of one expected result in a submission.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// The submission's result holds in its work, from the problem's facts, and equals
    /// the reference's.
    Right,
    /// It differs from the reference's.
    Wrong,
    /// The submission has no claim for it.
    Missing,
    /// rigor could not compare them; the text says why.
    Undecided(String),
    /// It may equal the reference's, but earns nothing: see [`Why`].
    NotCredited(Why),
}

/// One expected result, marked.
#[derive(Clone, Debug)]
pub struct ResultMark {
    /// The reference's result.
    pub expected: Expected,
    /// What became of it.
    pub outcome: Outcome,
    /// The line of the submission's claim marked (its last about the quantity).
    pub line: Option<usize>,
    /// Lines of earlier claims about the quantity that disagree with the one marked.
    pub earlier: Vec<usize>,
}

/// The first failing step, or input error.
#[derive(Clone, Debug)]
pub struct FirstMistake {
    /// Its line.
    pub line: usize,
    /// Its kind ([`KINDS`]).
    pub kind: &'static str,
    /// The diagnostic, as `check` reports it.
    pub diagnostic: Diagnostic,
}

/// One submission, marked.
#[derive(Clone, Debug)]
pub struct Row {
    /// The submission's name.
    pub file: String,
    /// Links verified and in all.
    pub steps: (usize, usize),
    /// The first failing step.
    pub first_failure: Option<FirstMistake>,
    /// Each expected result and its outcome.
    pub results: Vec<ResultMark>,
    /// Why the submission could not be marked at all, if it could not.
    pub unreadable: Option<String>,
    /// The submission's check report (for feedback).
    pub report: Option<FileReport>,
    /// Names the submission declared differently, mapped by role onto the reference's
    /// (`Ig` → `I_G`, `P` → −`F`), each justified by a fact of the problem.
    pub mapping: Vec<Mapped>,
    /// Names that took a role by their place but that no fact of the problem justifies.
    pub unmatched: Vec<String>,
    /// The submission's facts the problem does not give, contradictory ones and refused
    /// imports (whatever rests on them).
    pub own: Vec<Fact>,
}

impl Row {
    /// Results right and expected.
    pub fn results_score(&self) -> (usize, usize) {
        let right = self
            .results
            .iter()
            .filter(|r| r.outcome == Outcome::Right)
            .count();
        (right, self.results.len())
    }
}

/// The chain of the claim labelled `label` in a checked file.
fn claim_chain<'r>(r: &'r FileReport, label: &str) -> Option<&'r Chain> {
    r.ast.as_ref()?.items.iter().find_map(|i| match i {
        Item::Stmt(s) => match &s.kind {
            StmtKind::Claim {
                label: Some(l),
                chain,
                ..
            } if l.name == label => Some(chain),
            _ => None,
        },
        _ => None,
    })
}

fn text(r: &FileReport, s: crate::syntax::ast::Span) -> String {
    r.source
        .get(s.start..s.end)
        .unwrap_or("")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

/// The reference's `time` symbols and unknowns.
fn dynamic_names(r: &FileReport) -> Vec<String> {
    let mut out = Vec::new();
    for item in r.ast.iter().flat_map(|a| &a.items) {
        if let Item::Stmt(st) = item {
            if let StmtKind::Time { names } | StmtKind::Unknowns { names } = &st.kind {
                out.extend(names.iter().map(|n| n.name.clone()));
            }
        }
    }
    out
}

/// The reference's results: those `result` names, else every labelled claim.
pub fn expected(reference: &FileReport) -> Vec<Expected> {
    let Some(ast) = &reference.ast else {
        return Vec::new();
    };
    let mut named: Vec<String> = Vec::new();
    let mut labelled: Vec<String> = Vec::new();
    for item in &ast.items {
        if let Item::Stmt(s) = item {
            match &s.kind {
                StmtKind::Result { labels } => named.extend(labels.iter().map(|l| l.name.clone())),
                StmtKind::Claim { label: Some(l), .. } => labelled.push(l.name.clone()),
                _ => {}
            }
        }
    }
    let labels = if named.is_empty() { labelled } else { named };
    let dynamic = dynamic_names(reference);
    labels
        .into_iter()
        .filter_map(|label| {
            let chain = claim_chain(reference, &label)?;
            let value = chain.links.last().map_or(&chain.first, |l| &l.rhs);
            let in_value = names::names_in(value);
            Some(Expected {
                lhs: text(reference, chain.first.span),
                quantity: print::source(&chain.first),
                not_in_value: dynamic
                    .iter()
                    .filter(|n| !in_value.contains(n))
                    .cloned()
                    .collect(),
                label,
            })
        })
        .collect()
}

/// The kind of a failing step's diagnosis, as the CSV names it: from its code and the
/// mistake the checker found, never from its words.
pub fn kind(d: &Diagnostic) -> &'static str {
    match d.failure() {
        Some(FailureKind::Units) => return "units",
        // A given that is false, facts that contradict each other: bad input in
        // `check` (E0306), never "could not decide".
        Some(FailureKind::FalseFacts) => return "false_fact",
        _ => {}
    }
    match d.code {
        Code::Syntax | Code::Unreadable => return "syntax",
        Code::Undeclared => return "undeclared",
        Code::ImportFailed => return "import",
        _ => {}
    }
    match d.mistake {
        Some(Mistake::Sign) => "sign",
        Some(Mistake::Power) => "power",
        Some(Mistake::Factor) => "factor",
        Some(Mistake::MissingFact) => "missing_fact",
        Some(Mistake::ExtraTerm) => "extra_term",
        Some(Mistake::MissingTerm | Mistake::Difference) => "missing_term",
        Some(Mistake::ZeroSide | Mistake::DeclaredGiven(_)) | None => "undecided",
    }
}

/// The row of a submission that could not be read: every result missing.
pub fn unreadable(name: &str, why: String, expected: &[Expected]) -> Row {
    Row {
        file: name.to_string(),
        steps: (0, 0),
        first_failure: None,
        results: expected
            .iter()
            .map(|e| ResultMark {
                expected: e.clone(),
                outcome: Outcome::Missing,
                line: None,
                earlier: Vec::new(),
            })
            .collect(),
        unreadable: Some(why),
        report: None,
        mapping: Vec::new(),
        unmatched: Vec::new(),
        own: Vec::new(),
    }
}

/// A given or constraint of the reference.
struct RefFact {
    /// Its label; an unlabelled one is given `ref_line_N` (its line) for the comparisons.
    label: String,
    /// The names it uses (primes dropped).
    names: Vec<String>,
    /// Where the made-up label goes in the reference's text, for an unlabelled one.
    insert_at: Option<usize>,
}

/// The givens and constraints of the reference: a submission's facts are compared with
/// them one at a time.
fn ref_facts(r: &FileReport) -> Vec<RefFact> {
    let idx = crate::diag::LineIndex::new(&r.source);
    let mut out = Vec::new();
    for item in r.ast.iter().flat_map(|a| &a.items) {
        let Item::Stmt(st) = item else { continue };
        let (label, chain, keyword) = match &st.kind {
            StmtKind::Given { label, chain } => (label, chain, "given"),
            StmtKind::Constraint { label, chain } => (label, chain, "constraint"),
            _ => continue,
        };
        let names = chain.exprs().flat_map(names::names_in).collect();
        let fact = match label {
            Some(l) => RefFact {
                label: l.name.clone(),
                names,
                insert_at: None,
            },
            // Only where the statement starts with its keyword, as written.
            None if r
                .source
                .get(st.span.start..)
                .is_some_and(|t| t.starts_with(keyword)) =>
            {
                RefFact {
                    label: format!("ref_line_{}", idx.line_col(st.span.start).0),
                    names,
                    insert_at: Some(st.span.start + keyword.len()),
                }
            }
            None => continue,
        };
        out.push(fact);
    }
    out
}

/// The mappings tried first: the role pairs as found, and no mapping at all.
fn first_variants(base: &[Mapped]) -> Vec<Vec<Mapped>> {
    if base.is_empty() {
        vec![Vec::new()]
    } else {
        vec![base.to_vec(), Vec::new()]
    }
}

/// The mappings tried when some facts are still not the problem's: `best` with the sign
/// of one, or of two, of the submission's names for the reference's moving quantities
/// and unknowns turned (`P → −F`: friction drawn the other way; `s → −x` and `phi →
/// −theta` together: positions measured down the slope). A name the submission shares
/// with the reference may be turned too (`F → −F`).
fn flipped_variants(best: &[Mapped], sub_names: &[String], dynamic: &[String]) -> Vec<Vec<Mapped>> {
    let mut names: Vec<Mapped> = best.to_vec();
    for n in dynamic {
        let taken = best.iter().any(|m| &m.from == n || &m.to == n);
        if !taken && sub_names.contains(n) {
            names.push(Mapped {
                from: n.clone(),
                to: n.clone(),
                negated: false,
            });
        }
    }
    let flippable: Vec<usize> = (0..names.len())
        .filter(|&k| dynamic.contains(&names[k].to))
        .collect();
    let turned = |ks: &[usize]| -> Vec<Mapped> {
        let mut v = names.clone();
        for &k in ks {
            v[k].negated = !v[k].negated;
        }
        v.retain(|m| m.from != m.to || m.negated);
        v
    };
    let mut out: Vec<Vec<Mapped>> = flippable.iter().map(|&k| turned(&[k])).collect();
    if flippable.len() <= 4 {
        for (i, &a) in flippable.iter().enumerate() {
            for &b in &flippable[i + 1..] {
                out.push(turned(&[a, b]));
            }
        }
    }
    out
}

/// What a submission is marked with: the reference, its facts and results, the
/// submission's claims and facts, and how the comparisons are checked.
struct Ctx<'a> {
    reference: &'a FileReport,
    expected: &'a [Expected],
    sub: &'a FileReport,
    claims: &'a [ClaimAt<'a>],
    facts: &'a [Fact],
    refs: &'a [RefFact],
    dynamic: &'a [String],
    known: &'a [String],
    opts: &'a Options,
    resolver: &'a dyn Resolver,
    memo: &'a Memo,
}

/// The mappings `variants`, each planned, all checked in one batch; the best one (the
/// most facts the problem's; the earlier on a tie) with its score.
fn best_of(cx: &Ctx<'_>, variants: Vec<Vec<Mapped>>) -> (Plan, Checked, usize) {
    let labels: Vec<(usize, String)> = cx
        .refs
        .iter()
        .filter_map(|r| Some((r.insert_at?, format!(" [{}]", r.label))))
        .collect();
    let mut batch = Batch::new(cx.reference, &labels, cx.memo);
    let mut plans: Vec<Plan> = variants
        .into_iter()
        .map(|v| {
            plan(
                &mut batch,
                v,
                (cx.claims, cx.facts),
                cx.expected,
                (cx.refs, cx.dynamic, cx.known),
                cx.sub,
            )
        })
        .collect();
    let checked = batch.run(&cx.reference.path, cx.opts, cx.resolver);
    let score = |p: &Plan| {
        (0..cx.facts.len())
            .filter(|&i| implied(p, i, &checked))
            .count()
    };
    let best = (0..plans.len())
        .max_by_key(|&k| (score(&plans[k]), std::cmp::Reverse(k)))
        .unwrap_or(0);
    let plan = plans.swap_remove(best);
    let n = score(&plan);
    (plan, checked, n)
}

/// A claim of the submission about an expected result.
struct Candidate {
    /// Index into the submission's claims.
    claim: usize,
    /// Its comparison with the reference's result; `None` when its value uses
    /// quantities the result's value may not.
    line: Option<Slot>,
    /// The submission's names in the side that names the quantity.
    names: Vec<String>,
    /// Names of its value, in the reference's terms, that the reference does not have
    /// (it is not compared then).
    foreign: Vec<String>,
}

/// What one mapping appended to the batch.
struct Plan {
    terms: Terms,
    /// Per fact, per relation: its comparisons, one per reference fact that could imply it.
    facts: Vec<Vec<Vec<Slot>>>,
    /// Per expected result, the submission's claims about it, in order.
    results: Vec<Vec<Candidate>>,
}

/// The submission's claims about `e` in `terms`: those with the quantity on one side
/// (`x'' = …` or `… = x''`, `P = …` for `F` when `P → −F`), each compared (when its
/// other side is an answer: no quantity the reference's value does without) by the
/// claim `quantity = value by [label]` appended to the reference.
fn candidates(
    e: &Expected,
    (terms, known): (&Terms, &[String]),
    claims: &[ClaimAt<'_>],
    batch: &mut Batch<'_>,
) -> Vec<Candidate> {
    let mut out = Vec::new();
    for (k, c) in claims.iter().enumerate() {
        let last = c.chain.links.last().map_or(&c.chain.first, |l| &l.rhs);
        let (side, value) = if terms.names_quantity(&c.chain.first, &e.quantity).is_some() {
            (&c.chain.first, last)
        } else if terms.names_quantity(last, &e.quantity).is_some() {
            (last, &c.chain.first)
        } else {
            continue;
        };
        let value = terms.expr(value);
        let in_value = names::names_in(&value);
        let foreign: Vec<String> = in_value
            .iter()
            .filter(|n| !known.contains(n))
            .cloned()
            .collect();
        let answer = foreign.is_empty() && !in_value.iter().any(|n| e.not_in_value.contains(n));
        let line = answer.then(|| {
            batch.claim(&format!(
                "{} = {} by [{}]",
                print::source(&terms.named(side)),
                print::source(&value),
                e.label
            ))
        });
        out.push(Candidate {
            claim: k,
            line,
            names: names::names_in(side),
            foreign,
        });
    }
    out
}

/// Appends, for `map`, each relation of each fact still in question compared with each
/// of the reference's facts alone, and each claim about a result.
fn plan(
    batch: &mut Batch<'_>,
    map: Vec<Mapped>,
    (claims, facts): (&[ClaimAt<'_>], &[Fact]),
    expected: &[Expected],
    (ref_facts, ref_dynamic, known): (&[RefFact], &[String], &[String]),
    sub: &FileReport,
) -> Plan {
    let terms = Terms::new(sub, &map);
    let facts = facts
        .iter()
        .map(|f| {
            if f.standing != Standing::Own {
                return Vec::new();
            }
            facts::in_terms(f, &terms)
                .iter()
                .map(|(rel, names)| {
                    // A fact with a name the reference does not have, or about a
                    // quantity the reference's fact does not mention, cannot follow
                    // from it alone.
                    if names.iter().any(|n| !known.contains(n)) {
                        return Vec::new();
                    }
                    let dynamic: Vec<&String> =
                        names.iter().filter(|n| ref_dynamic.contains(n)).collect();
                    ref_facts
                        .iter()
                        .filter(|r| dynamic.iter().all(|n| r.names.contains(n)))
                        .map(|r| batch.claim(&format!("{rel} by [{}]", r.label)))
                        .collect()
                })
                .collect()
        })
        .collect();
    let results = expected
        .iter()
        .map(|e| candidates(e, (&terms, known), claims, batch))
        .collect();
    Plan {
        terms,
        facts,
        results,
    }
}

/// Whether fact `i` follows, under the plan's mapping, from the problem's facts: each
/// of its relations from one of them.
fn implied(p: &Plan, i: usize, checked: &Checked) -> bool {
    let rels = &p.facts[i];
    !rels.is_empty() && rels.iter().all(|r| r.iter().any(|s| checked.verified(s)))
}

/// Marks one submission (`name`, `text`) against the checked reference.
pub fn mark(
    reference: &FileReport,
    expected: &[Expected],
    (name, text_of): (&str, &str),
    opts: &Options,
    resolvers: (&dyn Resolver, &dyn Resolver),
    memo: &Memo,
) -> Row {
    let sub = check_source(name, text_of, opts, resolvers.1);
    let dynamic = dynamic_names(reference);
    let claims = facts::claims(&sub);
    let known = names::declared(reference);
    let mut facts = facts::collect(&sub, &known);
    let refs = ref_facts(reference);
    let (plan, checked) = {
        let cx = Ctx {
            reference,
            expected,
            sub: &sub,
            claims: &claims,
            facts: &facts,
            refs: &refs,
            dynamic: &dynamic,
            known: &known,
            opts,
            resolver: resolvers.0,
            memo,
        };
        let base = names::role_pairs(reference, &sub);
        let (plan, checked, score) = best_of(&cx, first_variants(&base));
        let open = facts.iter().filter(|f| f.standing == Standing::Own).count();
        if score < open {
            let flips = flipped_variants(plan.terms.map(), &names::declared(&sub), &dynamic);
            let (p2, c2, s2) = best_of(&cx, flips);
            if s2 > score {
                (p2, c2)
            } else {
                (plan, checked)
            }
        } else {
            (plan, checked)
        }
    };
    let plan = &plan;
    for (i, f) in facts.iter_mut().enumerate() {
        if implied(plan, i, &checked) {
            f.standing = Standing::Problem;
        }
    }
    // A name is matched when a fact of the problem, read through the mapping, has it.
    let (mapping, unmatched): (Vec<Mapped>, Vec<Mapped>) =
        plan.terms.map().iter().cloned().partition(|m| {
            facts
                .iter()
                .any(|f| f.standing == Standing::Problem && f.names.contains(&m.from))
        });
    let unmatched: Vec<String> = unmatched.into_iter().map(|m| m.from).collect();
    let results = expected
        .iter()
        .zip(&plan.results)
        .map(|(e, cands)| result(e, cands, (&claims, &facts), &checked, &unmatched))
        .collect();
    Row {
        file: name.to_string(),
        steps: (sub.verified(), sub.links()),
        first_failure: first_failure(&sub),
        results,
        unreadable: None,
        own: facts
            .into_iter()
            .filter(|f| f.standing != Standing::Problem)
            .collect(),
        report: Some(sub),
        mapping,
        unmatched,
    }
}

/// Why a fact earns nothing that rests on it, if it does.
fn why(f: &Fact) -> Option<Why> {
    match f.standing {
        Standing::Problem => None,
        Standing::Own => Some(Why::OwnAssumption {
            label: f.label.clone(),
            line: f.line,
            kind: f.kind,
        }),
        Standing::Contradiction => Some(Why::Contradiction {
            label: f.label.clone(),
            line: f.line,
        }),
        Standing::ImportFailed => Some(Why::Import { line: f.line }),
    }
}

/// One expected result: the submission's last claim about it, credited only when it
/// holds in the submission, rests on the problem's facts alone, names the quantity
/// through matched names, and equals the reference's result.
fn result(
    e: &Expected,
    cands: &[Candidate],
    (claims, facts): (&[ClaimAt<'_>], &[Fact]),
    checked: &Checked,
    unmatched: &[String],
) -> ResultMark {
    let mark = |outcome, line, earlier| ResultMark {
        expected: e.clone(),
        outcome,
        line,
        earlier,
    };
    let Some(last) = cands.last() else {
        // A claim with the reference's label about something else: never called right.
        return match claims
            .iter()
            .rev()
            .find(|c| c.label == Some(e.label.as_str()))
        {
            Some(c) => mark(
                Outcome::Undecided(format!(
                    "your [{}] does not state {} on one side",
                    e.label, e.lhs
                )),
                Some(c.line),
                Vec::new(),
            ),
            None => mark(Outcome::Missing, None, Vec::new()),
        };
    };
    let compared = |c: &Candidate| match &c.line {
        Some(s) => checked.outcome(s),
        None if !c.foreign.is_empty() => Outcome::Undecided(format!(
            "it uses names the problem does not have: {}",
            c.foreign.join(", ")
        )),
        None => Outcome::Undecided(
            "it is not yet written in the problem's given quantities alone".into(),
        ),
    };
    let o = compared(last);
    let earlier = cands[..cands.len() - 1]
        .iter()
        .filter(|c| c.line.is_some() && compared(c) != o)
        .map(|c| claims[c.claim].line)
        .collect();
    let claim = &claims[last.claim];
    let rests: Vec<&Fact> = facts::rests_on(last.claim, claims, facts)
        .into_iter()
        .map(|i| &facts[i])
        .collect();
    let import = rests.iter().find(|f| f.standing == Standing::ImportFailed);
    let blocked = rests.iter().find_map(|f| why(f));
    let unmatched = last.names.iter().find(|n| unmatched.contains(n));
    let outcome = match o {
        Outcome::Wrong => Outcome::Wrong,
        o => match (import, facts::holds(claim), blocked, unmatched) {
            (Some(f), ..) => Outcome::NotCredited(Why::Import { line: f.line }),
            (None, false, ..) => Outcome::NotCredited(Why::DoesNotFollow { line: claim.line }),
            (None, true, Some(w), _) => Outcome::NotCredited(w),
            (None, true, None, Some(n)) => Outcome::NotCredited(Why::Unmatched { name: n.clone() }),
            (None, true, None, None) => o,
        },
    };
    mark(outcome, Some(claim.line), earlier)
}

/// The first failing step (or input error): its line, kind and diagnostic.
fn first_failure(sub: &FileReport) -> Option<FirstMistake> {
    let d = sub
        .diagnostics
        .iter()
        .filter(|d| d.severity == crate::diag::Severity::Error)
        .min_by_key(|d| d.primary.as_ref().map_or(0, |p| p.0.start))?;
    let line = d
        .primary
        .as_ref()
        .map_or(0, |p| line_col(&sub.source, p.0.start).0);
    Some(FirstMistake {
        line,
        kind: kind(d),
        diagnostic: d.clone(),
    })
}
