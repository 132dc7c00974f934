//! What the checker found, as data: per file, per statement and per link.
//! Renderers read this; nothing here decides truth.

use crate::diag::{cite, Cited, Diagnostic, FactRef};
use crate::syntax::ast::{File, RelOp, Span};

/// How a verified link was justified.
#[derive(Clone, Debug, PartialEq)]
pub enum Justification {
    /// `A − B` normalises to zero.
    Identity,
    /// Zero after eliminating unknowns with these facts.
    Facts(Vec<FactRef>),
    /// An inequality whose sign follows from the declared signs (after any elimination).
    Signs(Vec<FactRef>),
    /// `~=`: the ratio rounds to 1 at the precision written.
    Approx,
    /// `~=` with small quantities: the sides agree up to this order in them.
    Small {
        /// The order kept.
        order: u32,
        /// The small quantities, by name.
        of: Vec<String>,
    },
}

impl std::fmt::Display for Justification {
    /// `identity`, `from [Fx], [MG]`, `signs`, `signs, from [aB]`, `approx`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Justification::Identity => f.write_str("identity"),
            Justification::Facts(fs) if fs.is_empty() => f.write_str("from the facts"),
            Justification::Facts(fs) => write!(f, "from {}", cite(fs)),
            Justification::Signs(fs) if fs.is_empty() => f.write_str("signs"),
            Justification::Signs(fs) => write!(f, "signs, from {}", cite(fs)),
            Justification::Approx => f.write_str("approx"),
            Justification::Small { order, of } => {
                let nth = if *order == 1 { "first" } else { "second" };
                let nth = if *order > 2 { "higher" } else { nth };
                write!(f, "to {nth} order in {}", of.join(", "))
            }
        }
    }
}

/// The outcome of one link.
#[derive(Clone, Debug, PartialEq)]
pub enum Status {
    /// Verified, with its justification and the side conditions assumed.
    Verified {
        /// Why it holds.
        how: Justification,
        /// Divisors assumed nonzero (`cos(beta) != 0`), as text.
        side_conditions: Vec<String>,
    },
    /// Shown false (or its check failed); the diagnostic explains.
    Failed,
    /// Neither verified nor refuted; the diagnostic explains.
    Undecided,
    /// Not checked because the statement could not be read (an input error).
    Error,
    /// Not checked because it cites (`by [..]`) a fact that did not hold; a note
    /// says which. The failure is reported once, where it happened.
    NotChecked,
}

impl Status {
    /// Whether verified.
    pub fn is_verified(&self) -> bool {
        matches!(self, Status::Verified { .. })
    }
}

/// One checked link `prev op rhs`.
#[derive(Clone, Debug, PartialEq)]
pub struct LinkReport {
    /// The span of the link (for the first link of a claim: from the claim's lhs to the rhs).
    pub span: Span,
    /// The relation.
    pub op: RelOp,
    /// Normal form of the left side (plain text), when it could be computed.
    pub lhs: Option<String>,
    /// Normal form of the right side.
    pub rhs: Option<String>,
    /// The outcome.
    pub status: Status,
    /// The unit of both sides, when the file declares units and they agree.
    pub units: Option<String>,
    /// What the link got wrong, when it failed or is not verified and the checker
    /// found the kind of mistake (as on its diagnostic).
    pub mistake: Option<crate::diag::Mistake>,
}

/// The work behind a link verified with the facts, kept for worked solutions that fill
/// in the steps (`rigor latex --steps`): the unknowns the elimination solved, in order,
/// and the two sides once their values are substituted. Expressions are plain text in
/// rigor's syntax.
#[derive(Clone, Debug, PartialEq)]
pub struct Working {
    /// The link's span (as in [`LinkReport::span`]).
    pub span: Span,
    /// Each unknown solved, in the order of the elimination: a value may hold unknowns
    /// solved after it, never one solved before.
    pub solved: Vec<Solved>,
    /// When the difference of the sides (after `solved`) is a multiple of one fact.
    pub multiple: Option<Multiple>,
    /// The left side after `where` and the substitutions.
    pub lhs: String,
    /// The right side after `where` and the substitutions.
    pub rhs: String,
}

/// One unknown solved from one fact.
#[derive(Clone, Debug, PartialEq)]
pub struct Solved {
    /// The unknown (`F`, `x''`).
    pub unknown: String,
    /// Its value.
    pub value: String,
    /// The fact, as cited: `[Fx]`, `[noslip]''` (the constraint differentiated twice),
    /// `line 12`.
    pub fact: Cited,
    /// The divisor of the solution, when the signs do not make it nonzero.
    pub divisor: Option<String>,
}

/// The difference of a link's sides as `factor · fact`.
#[derive(Clone, Debug, PartialEq)]
pub struct Multiple {
    /// The fact, as cited.
    pub fact: Cited,
    /// The fact's left side minus its right side (after the substitutions).
    pub value: String,
    /// The factor.
    pub factor: String,
    /// The difference of the link's sides (after the substitutions).
    pub difference: String,
}

/// One `claim` statement.
#[derive(Clone, Debug, PartialEq)]
pub struct ClaimReport {
    /// Its label, if any.
    pub label: Option<String>,
    /// The statement's span.
    pub span: Span,
    /// 1-based line of the statement.
    pub line: usize,
    /// Each link in order.
    pub links: Vec<LinkReport>,
}

impl ClaimReport {
    /// Whether every link verified.
    pub fn verified(&self) -> bool {
        self.links.iter().all(|l| l.status.is_verified())
    }
}

/// Everything about one file.
#[derive(Clone, Debug, Default)]
pub struct FileReport {
    /// The path as given.
    pub path: String,
    /// The text (empty if it could not be read).
    pub source: String,
    /// The parsed file, if it parsed.
    pub ast: Option<File>,
    /// Every claim, in order.
    pub claims: Vec<ClaimReport>,
    /// Verified links whose two sides, as written, the guard evaluated independently and
    /// found to agree at one point or more.
    pub guarded: usize,
    /// Every diagnostic, in source order.
    pub diagnostics: Vec<Diagnostic>,
    /// Whether the input was bad (syntax, undeclared symbol, unreadable file…): exit status 2.
    pub input_error: bool,
    /// The work behind each link verified with the facts (see [`Working`]).
    pub workings: Vec<Working>,
    /// The definitions, bodies and declared signs at the end of the file, so that a
    /// worked solution can show how the engine evaluates what the file wrote.
    pub env: crate::lower::Env,
}

impl FileReport {
    /// Whether a failure names a `symbols` quantity the facts determine
    /// (`Mistake::DeclaredGiven`): where `Options::stop_at_determined_given` stops.
    pub fn names_determined_given(&self) -> bool {
        self.diagnostics
            .iter()
            .any(|d| matches!(d.mistake, Some(crate::diag::Mistake::DeclaredGiven(_))))
    }

    /// Number of links checked.
    pub fn links(&self) -> usize {
        self.claims.iter().map(|c| c.links.len()).sum()
    }

    /// Number of verified links.
    pub fn verified(&self) -> usize {
        self.claims
            .iter()
            .flat_map(|c| &c.links)
            .filter(|l| l.status.is_verified())
            .count()
    }

    /// Number of links shown false.
    pub fn failed(&self) -> usize {
        self.count(|s| matches!(s, Status::Failed))
    }

    /// Number of links neither verified nor refuted.
    pub fn undecided(&self) -> usize {
        self.count(|s| matches!(s, Status::Undecided))
    }

    /// Number of links not checked because they cite a fact that did not hold.
    pub fn not_checked(&self) -> usize {
        self.count(|s| matches!(s, Status::NotChecked))
    }

    fn count(&self, f: impl Fn(&Status) -> bool) -> usize {
        self.claims
            .iter()
            .flat_map(|c| &c.links)
            .filter(|l| f(&l.status))
            .count()
    }

    /// Whether every link verified and there was no error.
    pub fn ok(&self) -> bool {
        !self.input_error && self.claims.iter().all(ClaimReport::verified)
    }

    /// The status of the link whose span is `span`, if checked.
    pub fn link_status(&self, span: Span) -> Option<&Status> {
        self.claims
            .iter()
            .flat_map(|c| &c.links)
            .find(|l| l.span == span)
            .map(|l| &l.status)
    }
}
