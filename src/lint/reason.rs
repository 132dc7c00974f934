//! Why a chain needs context, as a kind the reports carry (`--format json` says it as
//! `"reason"`, GitHub annotations in their title), with the `rigor:` comment that would
//! make the chain checkable where rigor knows it.

/// The class of a "needs context" verdict.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reason {
    /// LaTeX rigor does not read (an unknown macro, a vector).
    Unread,
    /// An integral over a mass element the notes define in prose.
    ProseMass,
    /// A step brings in a symbol nothing before it defines.
    NewSymbol,
    /// A relation stated, not derived: it does not hold for every value of its symbols.
    Stated,
    /// A premise the notes impose (before an implication arrow).
    Imposed,
    /// An approximation with nothing declared small and not between numbers.
    Approximation,
    /// It holds where symbols the notes never declared are positive.
    Sign,
    /// The facts in scope do not settle it.
    Undetermined,
    /// It could not be written as a derivation, so it was not checked.
    Unchecked,
}

impl Reason {
    /// The name the JSON report and annotations use.
    pub fn as_str(self) -> &'static str {
        match self {
            Reason::Unread => "unread",
            Reason::ProseMass => "prose-mass",
            Reason::NewSymbol => "new-symbol",
            Reason::Stated => "stated",
            Reason::Imposed => "imposed",
            Reason::Approximation => "approximation",
            Reason::Sign => "sign",
            Reason::Undetermined => "undetermined",
            Reason::Unchecked => "unchecked",
        }
    }
}
