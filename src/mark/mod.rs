//! `rigor mark`: a class's submissions against a reference derivation. Each submission is
//! checked as `check` does; its first failing step is classified in a small vocabulary;
//! the reference's results are found in it (by label, else by the quantity on the left)
//! and compared exactly under the reference's declarations, through the one checker
//! entry.

use crate::check::{check_source, FileReport, Options, Resolver, Status};
use crate::diag::{line_col, Diagnostic};
use crate::diag::{Code, FailureKind, Mistake};
use crate::syntax::ast::{Chain, Expr, ExprKind, Item, StmtKind};

/// The kinds of first mistake (README, "rigor mark").
pub const KINDS: [&str; 11] = [
    "sign",
    "factor",
    "power",
    "missing_term",
    "extra_term",
    "missing_fact",
    "undeclared",
    "syntax",
    "units",
    "false_fact",
    "undecided",
];

/// A result of the reference: its label and the quantity on its left, as written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Expected {
    /// The claim's label.
    pub label: String,
    /// The first expression of the claim, as written (`x''`).
    pub lhs: String,
}

/// What became of one expected result in a submission.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// The submission's result equals the reference's.
    Right,
    /// It differs.
    Wrong,
    /// The submission has no claim for it.
    Missing,
    /// rigor could not compare them; the text says why.
    Undecided(String),
    /// The submission reaches it only through facts that are false or contradict each
    /// other (`given 0 = 1`): from those anything follows, so it earns nothing; the
    /// text says where they are.
    NotCredited(String),
}

/// One submission, marked.
#[derive(Clone, Debug)]
pub struct Row {
    /// The submission's name.
    pub file: String,
    /// Links verified and in all.
    pub steps: (usize, usize),
    /// The first failing step: line, kind, message.
    pub first_failure: Option<(usize, &'static str, String)>,
    /// Each expected result and its outcome.
    pub results: Vec<(Expected, Outcome)>,
    /// Why the submission could not be marked at all, if it could not.
    pub unreadable: Option<String>,
    /// The submission's check report (for feedback).
    pub report: Option<FileReport>,
    /// Names the submission declared differently, mapped by role onto the reference's
    /// (`Ig` → `I_G`) for comparing results.
    pub mapping: Vec<(String, String)>,
}

impl Row {
    /// Results right and expected.
    pub fn results_score(&self) -> (usize, usize) {
        let right = self
            .results
            .iter()
            .filter(|r| r.1 == Outcome::Right)
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
    labels
        .into_iter()
        .filter_map(|label| {
            let chain = claim_chain(reference, &label)?;
            Some(Expected {
                lhs: text(reference, chain.first.span),
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
            .map(|e| (e.clone(), Outcome::Missing))
            .collect(),
        unreadable: Some(why),
        report: None,
        mapping: Vec::new(),
    }
}

/// Marks one submission (`name`, `text`) against the checked reference.
pub fn mark(
    reference: &FileReport,
    expected: &[Expected],
    (name, text_of): (&str, &str),
    opts: &Options,
    resolvers: (&dyn Resolver, &dyn Resolver),
) -> Row {
    let sub = check_source(name, text_of, opts, resolvers.1);
    let links: Vec<(&crate::check::LinkReport, usize)> = sub
        .claims
        .iter()
        .flat_map(|c| c.links.iter().map(move |l| (l, c.line)))
        .collect();
    let verified = links.iter().filter(|(l, _)| l.status.is_verified()).count();
    let first_failure = first_failure(&sub);
    let mapping = role_mapping(reference, &sub);
    let how = (opts, resolvers.0, mapping.as_slice());
    let outcomes = compare_all(reference, expected, &sub, how);
    let results = expected
        .iter()
        .cloned()
        .zip(outcomes)
        .map(|(e, o)| {
            let o = match (o, resting_on_false_facts(&e, &sub, &mapping)) {
                (Outcome::Right | Outcome::Undecided(_), Some(why)) => Outcome::NotCredited(why),
                (o, _) => o,
            };
            (e, o)
        })
        .collect();
    Row {
        file: name.to_string(),
        steps: (verified, links.len()),
        first_failure,
        results,
        unreadable: None,
        report: Some(sub),
        mapping,
    }
}

/// The first failing step (or input error): its line, kind and message.
fn first_failure(sub: &FileReport) -> Option<(usize, &'static str, String)> {
    let d = sub
        .diagnostics
        .iter()
        .filter(|d| d.severity == crate::diag::Severity::Error)
        .min_by_key(|d| d.primary.as_ref().map_or(0, |p| p.0.start))?;
    let line = d
        .primary
        .as_ref()
        .map_or(0, |p| line_col(&sub.source, p.0.start).0);
    Some((line, kind(d), d.message.to_string()))
}

/// Where the submission's result for `e` rests on facts that are false or contradict
/// each other (`check` reports them as E0306): the submission has such facts and its
/// claim for `e` did not verify (a claim that verified did not use them: a false given
/// is never a fact, and contradictory facts fail every step that uses them). The text
/// says where they are.
fn resting_on_false_facts(
    e: &Expected,
    sub: &FileReport,
    mapping: &[(String, String)],
) -> Option<String> {
    let false_fact = sub
        .diagnostics
        .iter()
        .filter(|d| d.failure() == Some(FailureKind::FalseFacts))
        .min_by_key(|d| d.primary.as_ref().map_or(0, |p| p.0.start))?;
    let chain = submission_chain(e, sub, mapping)?;
    let verified = sub
        .claims
        .iter()
        .find(|c| {
            c.links
                .first()
                .is_some_and(|l| l.span.start == chain.first.span.start)
        })
        .is_some_and(|c| !c.links.is_empty() && c.links.iter().all(|l| l.status.is_verified()));
    if verified {
        return None;
    }
    let line = false_fact
        .primary
        .as_ref()
        .map_or(0, |p| line_col(&sub.source, p.0.start).0);
    Some(format!(
        "it rests on a fact that is false or contradicts the others, line {line}"
    ))
}

/// The submission's claim for an expected result: by label, else by the quantity on the
/// left under the name mapping.
fn submission_chain<'r>(
    e: &Expected,
    sub: &'r FileReport,
    mapping: &[(String, String)],
) -> Option<&'r Chain> {
    claim_chain(sub, &e.label).or_else(|| {
        let ast = sub.ast.as_ref()?;
        ast.items.iter().find_map(|i| match i {
            Item::Stmt(s) => match &s.kind {
                StmtKind::Claim { chain, .. }
                    if rename(&text(sub, chain.first.span), mapping) == e.lhs =>
                {
                    Some(chain)
                }
                _ => None,
            },
            _ => None,
        })
    })
}

/// The submission's claim for an expected result ([`submission_chain`]): its `lhs` and
/// last expression, renamed.
fn result_claim(e: &Expected, sub: &FileReport, mapping: &[(String, String)]) -> Option<String> {
    let chain = submission_chain(e, sub, mapping)?;
    let last = chain.links.last().map_or(chain.first.span, |l| l.rhs.span);
    Some(format!(
        "{} = {}",
        rename(&text(sub, chain.first.span), mapping),
        rename(&text(sub, last), mapping)
    ))
}

/// Every expected result in the submission, compared under the reference's
/// declarations: the submission's `lhs = last expression` checked as claims appended to
/// the reference, all in one check (unlabelled, so one that fails does not mark the
/// others "not checked"; one that holds adds only a consequence of the reference). If
/// the appended text cannot be read, each is checked alone.
fn compare_all(
    reference: &FileReport,
    expected: &[Expected],
    sub: &FileReport,
    (opts, resolver, mapping): (&Options, &dyn Resolver, &[(String, String)]),
) -> Vec<Outcome> {
    let claims: Vec<Option<String>> = expected
        .iter()
        .map(|e| result_claim(e, sub, mapping))
        .collect();
    let check = |wanted: &[&String]| {
        let mut source = format!("{}\n", reference.source);
        let mut lines = Vec::new();
        for c in wanted {
            lines.push(source.lines().count() + 1);
            source.push_str(&format!("claim {c}\n"));
        }
        (
            check_source(&reference.path, &source, opts, resolver),
            lines,
        )
    };
    let wanted: Vec<&String> = claims.iter().flatten().collect();
    let (r, lines) = check(&wanted);
    let batched = r.ast.is_some();
    let mut k = 0;
    claims
        .iter()
        .map(|c| {
            let Some(c) = c else {
                return Outcome::Missing;
            };
            k += 1;
            if batched {
                outcome_at(&r, lines[k - 1])
            } else {
                let (alone, at) = check(&[c]);
                outcome_at(&alone, at[0])
            }
        })
        .collect()
}

/// The outcome of the appended claim on `line` of a checked reference.
fn outcome_at(r: &FileReport, line: usize) -> Outcome {
    let Some(c) = r.claims.iter().find(|c| c.line == line) else {
        return Outcome::Undecided("the result could not be read in the reference's terms".into());
    };
    let inside = |d: &&Diagnostic| {
        d.primary
            .as_ref()
            .is_some_and(|p| p.0.start >= c.span.start && p.0.start <= c.span.end)
    };
    match c.links.first().map(|l| &l.status) {
        Some(Status::Verified { .. }) => Outcome::Right,
        // Shown false under the reference's facts: wrong, whatever the diagnostic (a
        // sign, a false inequality, a division by zero, units), as `check` says it.
        // Facts that contradict each other show nothing.
        Some(Status::Failed)
            if !r
                .diagnostics
                .iter()
                .filter(inside)
                .any(|d| d.failure() == Some(FailureKind::FalseFacts)) =>
        {
            Outcome::Wrong
        }
        Some(Status::Failed) => Outcome::Undecided(
            "the reference's facts contradict each other where it is checked".into(),
        ),
        _ => Outcome::Undecided(
            r.diagnostics
                .iter()
                .filter(inside)
                .map(|d| d.message.to_string())
                .next()
                .unwrap_or_else(|| "it uses names the reference does not declare".into()),
        ),
    }
}

/// The names a file declares (`symbols`, ranges, `time`, `unknowns`).
fn declared(r: &FileReport) -> Vec<String> {
    let mut out = Vec::new();
    for item in r.ast.iter().flat_map(|a| &a.items) {
        if let Item::Stmt(st) = item {
            let names = match &st.kind {
                StmtKind::Symbols { names, .. }
                | StmtKind::Range { names, .. }
                | StmtKind::Time { names }
                | StmtKind::Unknowns { names } => names,
                _ => continue,
            };
            out.extend(names.iter().map(|n| n.name.clone()));
        }
    }
    out
}

/// Symbols of an expression in order of first appearance (primes dropped), each with
/// the derivative orders it is used with (`x''` and `x` → x, {0, 2}).
fn symbols_in_order(e: &Expr, out: &mut Syms) {
    match &e.kind {
        ExprKind::Sym(n) => {
            let base = n.trim_end_matches('\'').to_string();
            let order = n.len() - base.len();
            match out.iter_mut().find(|(b, _)| *b == base) {
                Some((_, orders)) if !orders.contains(&order) => {
                    orders.push(order);
                    orders.sort_unstable();
                }
                Some(_) => {}
                None => out.push((base, vec![order])),
            }
        }
        ExprKind::Neg(x) => symbols_in_order(x, out),
        ExprKind::Bin(_, a, b) => {
            symbols_in_order(a, out);
            symbols_in_order(b, out);
        }
        ExprKind::Call(_, args) => args.iter().for_each(|a| symbols_in_order(a, out)),
        ExprKind::Num(_) | ExprKind::Pi => {}
    }
}

/// Symbols by first appearance, each with the derivative orders it is used with.
type Syms = Vec<(String, Vec<usize>)>;

/// The givens and constraints of a file, in order: label and symbols by first appearance.
fn facts_of(r: &FileReport) -> Vec<(Option<String>, Syms)> {
    let mut out = Vec::new();
    for item in r.ast.iter().flat_map(|a| &a.items) {
        if let Item::Stmt(st) = item {
            if let StmtKind::Given { label, chain } | StmtKind::Constraint { label, chain } =
                &st.kind
            {
                let mut syms = Vec::new();
                symbols_in_order(&chain.first, &mut syms);
                for l in &chain.links {
                    symbols_in_order(&l.rhs, &mut syms);
                }
                out.push((label.as_ref().map(|l| l.name.clone()), syms));
            }
        }
    }
    out
}

/// Names the submission declares and the reference does not, matched by role onto names
/// the reference declares and the submission does not: the symbol at the same position
/// (order of first appearance) in the same given or constraint — paired by label, else
/// by order among those whose labels differ — when the two have the same shape (as
/// many symbols, each used with the same derivatives: `a` for `x''` is not `x`). Each
/// name is mapped at most once.
pub fn role_mapping(reference: &FileReport, sub: &FileReport) -> Vec<(String, String)> {
    let (ref_names, sub_names) = (declared(reference), declared(sub));
    let (ref_facts, sub_facts) = (facts_of(reference), facts_of(sub));
    let labelled = |l: &Option<String>, other: &[(Option<String>, Syms)]| {
        l.as_ref()
            .is_some_and(|l| other.iter().any(|o| o.0.as_ref() == Some(l)))
    };
    let mut pairs: Vec<(&Syms, &Syms)> = Vec::new();
    for (l, syms) in &sub_facts {
        if let Some((_, r)) = ref_facts.iter().find(|o| l.is_some() && &o.0 == l) {
            pairs.push((syms, r));
        }
    }
    let unpaired_sub = sub_facts.iter().filter(|f| !labelled(&f.0, &ref_facts));
    let unpaired_ref = ref_facts.iter().filter(|f| !labelled(&f.0, &sub_facts));
    pairs.extend(unpaired_sub.zip(unpaired_ref).map(|(a, b)| (&a.1, &b.1)));
    let mut mapping: Vec<(String, String)> = Vec::new();
    for (s_syms, r_syms) in pairs {
        // The same shape: as many symbols, each used with the same derivatives.
        let same_shape =
            s_syms.len() == r_syms.len() && s_syms.iter().zip(r_syms).all(|(a, b)| a.1 == b.1);
        if !same_shape {
            continue;
        }
        for ((s, _), (r, _)) in s_syms.iter().zip(r_syms) {
            let candidate = s != r
                && sub_names.contains(s)
                && !ref_names.contains(s)
                && ref_names.contains(r)
                && !sub_names.contains(r);
            let fresh = !mapping.iter().any(|(a, b)| a == s || b == r);
            if candidate && fresh {
                mapping.push((s.clone(), r.clone()));
            }
        }
    }
    mapping
}

/// `text` with each whole name of `mapping` replaced (primes kept: `Ig'` → `I_G'`).
fn rename(text: &str, mapping: &[(String, String)]) -> String {
    if mapping.is_empty() {
        return text.to_string();
    }
    let mut out = String::with_capacity(text.len());
    let mut word = String::new();
    let flush = |word: &mut String, out: &mut String| {
        let to = mapping.iter().find(|(a, _)| a == word).map(|(_, b)| b);
        out.push_str(to.unwrap_or(word));
        word.clear();
    };
    for c in text.chars() {
        // `2Ig` is 2 times Ig: a number before a name is not part of it.
        let starts_name = c.is_alphabetic() || c == '_';
        if starts_name && !word.is_empty() && word.chars().all(|d| d.is_ascii_digit()) {
            out.push_str(&word);
            word.clear();
        }
        if c.is_alphanumeric() || c == '_' {
            word.push(c);
        } else {
            flush(&mut word, &mut out);
            out.push(c);
        }
    }
    flush(&mut word, &mut out);
    out
}

#[cfg(test)]
mod tests {
    use super::rename;

    #[test]
    fn renaming_replaces_whole_names_only() {
        let m = vec![("Ig".to_string(), "I_G".to_string())];
        assert_eq!(
            rename("Ig theta'' + Igx + 2Ig", &m),
            "I_G theta'' + Igx + 2I_G"
        );
        assert_eq!(rename("(m R^2 + Ig)/Ig'", &m), "(m R^2 + I_G)/I_G'");
    }
}
