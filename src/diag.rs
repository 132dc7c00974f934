//! Diagnostics as data, and their rendering in the style of the Rust compiler.

use crate::syntax::ast::Span;

/// How serious a diagnostic is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Severity {
    /// A failed step or bad input.
    Error,
    /// Verified, but with something to note (a side condition).
    Warning,
    /// Information.
    Note,
}

impl Severity {
    /// `error`, `warning`, `note`.
    pub fn as_str(self) -> &'static str {
        match self {
            Severity::Error => "error",
            Severity::Warning => "warning",
            Severity::Note => "note",
        }
    }
}

/// Every diagnostic code rigor emits: one table, with `docs/errors.md` as its index.
/// Rooms decide by these variants; the text `E0301` is made only for output
/// ([`Code::as_str`]).
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Code {
    /// `E0001`: A syntax error.
    Syntax,
    /// `E0002`: A file cannot be read.
    Unreadable,
    /// `E0101`: An expression has no value (an unknown function, a bad integrand, a root of a negative…).
    NoValue,
    /// `E0201`: A name used but never declared.
    Undeclared,
    /// `E0202`: A label given twice.
    DuplicateLabel,
    /// `E0203`: A name declared twice (or a `let` redefined).
    DeclaredTwice,
    /// `E0205`: `by [..]` or `result` names a label that does not exist.
    UnknownLabel,
    /// `E0206`: A `use` that cannot be read or resolved.
    ImportFailed,
    /// `E0207`: A special case that `where` cannot make.
    BadWhere,
    /// `E0208`: A `with` that cannot be applied to an imported claim.
    BadWith,
    /// `E0301`: An `=` step shown false.
    Refuted,
    /// `E0302`: A step neither verified nor refuted.
    NotVerified,
    /// `E0303`: An inequality (`!=`, `<`, `<=`, `>`, `>=`) that is false or not shown.
    Inequality,
    /// `E0304`: An approximation (`~=`) that does not hold.
    Approximation,
    /// `E0305`: A division by zero: a side condition that fails.
    DivisionByZero,
    /// `E0306`: Facts that are false or contradict each other.
    FalseFacts,
    /// `E0401`: Units that disagree.
    Units,
    /// `E0402`: A bad unit declaration.
    BadUnit,
    /// `E0403`: A symbol without a unit, in a file that declares units.
    NoUnit,
    /// `E0901`: A size limit was reached (nesting, terms, exponents, file size).
    SizeLimit,
    /// `E0902`: The time budget ran out.
    TimeBudget,
    /// `E0903`: rigor's internal check (the guard) disagrees with a verdict.
    GuardDisagrees,
    /// `W0101`: A product after `/` read as a factor above the line.
    Reading,
    /// `W0102`: A body with negative mass.
    NegativeMass,
    /// `W0401`: One kind of quantity in different scales.
    MixedScales,
    /// `N0205`: Not checked because of an earlier mistake.
    NotChecked,
    /// `N0206`: A consequence of the first mistake (the likely root, tried).
    Consequence,
}

impl Code {
    /// Every code, in the order of the index.
    pub const ALL: &'static [Code] = &[
        Code::Syntax,
        Code::Unreadable,
        Code::NoValue,
        Code::Undeclared,
        Code::DuplicateLabel,
        Code::DeclaredTwice,
        Code::UnknownLabel,
        Code::ImportFailed,
        Code::BadWhere,
        Code::BadWith,
        Code::Refuted,
        Code::NotVerified,
        Code::Inequality,
        Code::Approximation,
        Code::DivisionByZero,
        Code::FalseFacts,
        Code::Units,
        Code::BadUnit,
        Code::NoUnit,
        Code::SizeLimit,
        Code::TimeBudget,
        Code::GuardDisagrees,
        Code::Reading,
        Code::NegativeMass,
        Code::MixedScales,
        Code::NotChecked,
        Code::Consequence,
    ];

    /// The code as printed: `E0301`.
    pub fn as_str(self) -> &'static str {
        match self {
            Code::Syntax => "E0001",
            Code::Unreadable => "E0002",
            Code::NoValue => "E0101",
            Code::Undeclared => "E0201",
            Code::DuplicateLabel => "E0202",
            Code::DeclaredTwice => "E0203",
            Code::UnknownLabel => "E0205",
            Code::ImportFailed => "E0206",
            Code::BadWhere => "E0207",
            Code::BadWith => "E0208",
            Code::Refuted => "E0301",
            Code::NotVerified => "E0302",
            Code::Inequality => "E0303",
            Code::Approximation => "E0304",
            Code::DivisionByZero => "E0305",
            Code::FalseFacts => "E0306",
            Code::Units => "E0401",
            Code::BadUnit => "E0402",
            Code::NoUnit => "E0403",
            Code::SizeLimit => "E0901",
            Code::TimeBudget => "E0902",
            Code::GuardDisagrees => "E0903",
            Code::Reading => "W0101",
            Code::NegativeMass => "W0102",
            Code::MixedScales => "W0401",
            Code::NotChecked => "N0205",
            Code::Consequence => "N0206",
        }
    }

    /// The kind of failure a diagnostic of this code reports; `None` for warnings and
    /// notes. What was wrong in a refuted or unverified step is its [`Mistake`]
    /// ([`Diagnostic::mistake`]).
    pub fn failure(self) -> Option<FailureKind> {
        Some(match self {
            Code::Syntax
            | Code::Unreadable
            | Code::NoValue
            | Code::Undeclared
            | Code::DuplicateLabel
            | Code::DeclaredTwice
            | Code::UnknownLabel
            | Code::ImportFailed
            | Code::BadWhere
            | Code::BadWith => FailureKind::Input,
            Code::NotVerified | Code::GuardDisagrees => FailureKind::NotVerified,
            Code::Units | Code::BadUnit | Code::NoUnit => FailureKind::Units,
            Code::SizeLimit | Code::TimeBudget => FailureKind::Limit,
            Code::FalseFacts => FailureKind::FalseFacts,
            Code::Refuted | Code::Inequality | Code::Approximation | Code::DivisionByZero => {
                FailureKind::Refuted
            }
            Code::Reading | Code::NegativeMass | Code::MixedScales => return None,
            Code::NotChecked | Code::Consequence => return None,
        })
    }
}

impl std::fmt::Display for Code {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// The kind of failure a diagnostic reports, from its code ([`Code::failure`]).
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FailureKind {
    /// A relation shown false (or a division shown to be by zero).
    Refuted,
    /// Neither verified nor refuted.
    NotVerified,
    /// Units that disagree or are not declared.
    Units,
    /// Input rigor cannot read: syntax, names, labels, imports, `where`, `with`.
    Input,
    /// Givens that are false or contradict each other.
    FalseFacts,
    /// A size limit or the time budget.
    Limit,
}

/// What a step that does not hold got wrong, as the checker found it (one term as
/// written, or a whole side); the words for it are made once, beside it.
#[non_exhaustive]
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Mistake {
    /// A term, or a whole side, with the wrong sign.
    Sign,
    /// A constant factor, or a factor of several quantities, off.
    Factor,
    /// One power of a symbol too many or too few (a term, or a side by a power).
    Power,
    /// The left side lacks terms that the right side has.
    MissingTerm,
    /// The left side has terms that should not be there.
    ExtraTerm,
    /// The sides differ by a few terms that neither side holds as written.
    Difference,
    /// One side is 0 and the other is not.
    ZeroSide,
    /// Unknowns that no fact determines: a fact is missing.
    MissingFact,
    /// A quantity declared with `symbols`, as given, that the facts determine: with it
    /// an unknown the step follows. Its name.
    DeclaredGiven(String),
}

/// How a fact is cited: by its label, or, when it has none, by the line it is on.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum FactRef {
    /// `[Fx]`.
    Label(String),
    /// `line 12` (1-based, in the file checked).
    Line(usize),
}

impl FactRef {
    /// The name JSON gives it: the label without brackets, or `line 12`.
    pub fn key(&self) -> String {
        match self {
            FactRef::Label(l) => l.clone(),
            FactRef::Line(n) => format!("line {n}"),
        }
    }
}

impl std::fmt::Display for FactRef {
    /// `[Fx]` or `line 12`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FactRef::Label(l) => write!(f, "[{l}]"),
            FactRef::Line(n) => write!(f, "line {n}"),
        }
    }
}

/// A fact as an elimination used it: itself, or differentiated `derivative` times (a
/// constraint's velocity and acceleration forms). Written `[noslip]''`.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Cited {
    /// The fact.
    pub fact: FactRef,
    /// How many times it was differentiated with respect to time.
    pub derivative: usize,
}

impl Cited {
    /// The fact itself, not differentiated.
    pub fn of(fact: FactRef) -> Cited {
        Cited {
            fact,
            derivative: 0,
        }
    }
}

impl std::fmt::Display for Cited {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}{}", self.fact, "'".repeat(self.derivative))
    }
}

/// Facts as a message cites them: `[Fx], [MG], line 12`.
pub fn cite<T: std::fmt::Display>(facts: &[T]) -> String {
    facts
        .iter()
        .map(ToString::to_string)
        .collect::<Vec<_>>()
        .join(", ")
}

/// What a piece of a [`Text`] cites.
#[derive(Clone, Debug, PartialEq)]
pub enum Cite {
    /// A list of facts, written by [`cite`].
    Facts(Vec<Cited>),
    /// A line of the file checked, written as its number.
    Line(usize),
}

/// Words, with the places where they cite facts or lines kept as data: a tool that
/// shows the checked file under other line numbers (lint, which checks a derivation made
/// from a document) renumbers them with [`Text::renumber`], never by reading the words.
/// It reads as the `str` it is.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Text {
    text: String,
    cites: Vec<(std::ops::Range<usize>, Cite)>,
}

impl Text {
    /// Appends words.
    pub fn push_str(&mut self, s: &str) {
        self.text.push_str(s);
    }

    /// The text with `s` appended.
    pub fn and(mut self, s: &str) -> Text {
        self.push_str(s);
        self
    }

    /// The text with another appended, citations and all.
    pub fn then(mut self, other: &Text) -> Text {
        let at = self.text.len();
        self.text.push_str(&other.text);
        self.cites.extend(
            other
                .cites
                .iter()
                .map(|(r, c)| (r.start + at..r.end + at, c.clone())),
        );
        self
    }

    /// Texts one after the other, with `sep` between them.
    pub fn join(texts: &[Text], sep: &str) -> Text {
        let mut out = Text::default();
        for (i, t) in texts.iter().enumerate() {
            if i > 0 {
                out.push_str(sep);
            }
            out = out.then(t);
        }
        out
    }

    /// `[label] (line 12)`: a label and the line it is on.
    pub fn label_at(label: &str, line: usize) -> Text {
        Text::from(format!("[{label}] (line ")).line(line).and(")")
    }

    /// The text with a list of facts appended (`[Fx], line 12`).
    pub fn facts(self, facts: &[FactRef]) -> Text {
        let cited: Vec<Cited> = facts.iter().cloned().map(Cited::of).collect();
        self.cited(&cited)
    }

    /// The text with a list of facts as an elimination used them appended (`[Fx]'`).
    pub fn cited(mut self, facts: &[Cited]) -> Text {
        self.push_cite(Cite::Facts(facts.to_vec()));
        self
    }

    /// The text with a line number appended.
    pub fn line(mut self, line: usize) -> Text {
        self.push_cite(Cite::Line(line));
        self
    }

    fn push_cite(&mut self, c: Cite) {
        let start = self.text.len();
        match &c {
            Cite::Facts(fs) => self.text.push_str(&cite(fs)),
            Cite::Line(n) => self.text.push_str(&n.to_string()),
        }
        self.cites.push((start..self.text.len(), c));
    }

    /// Whether it cites any fact.
    pub fn cites_facts(&self) -> bool {
        self.cites
            .iter()
            .any(|(_, c)| matches!(c, Cite::Facts(fs) if !fs.is_empty()))
    }

    /// The same words with every line cited mapped by `map`. A fact on a line `map`
    /// has no number for is left out of its list (unless it is all the list has), a
    /// fact a list names twice once mapped is named once, and a lone line with no new
    /// number keeps its old one.
    pub fn renumber(&self, map: &dyn Fn(usize) -> Option<usize>) -> Text {
        let mut out = Text::default();
        let mut at = 0;
        for (range, c) in &self.cites {
            out.push_str(&self.text[at..range.start]);
            at = range.end;
            match c {
                Cite::Line(n) => out.push_cite(Cite::Line(map(*n).unwrap_or(*n))),
                Cite::Facts(fs) => {
                    let mut mapped: Vec<Cited> = Vec::new();
                    for f in fs {
                        let f = match f.fact {
                            FactRef::Line(n) => match map(n) {
                                Some(m) => Cited {
                                    fact: FactRef::Line(m),
                                    derivative: f.derivative,
                                },
                                None => continue,
                            },
                            _ => f.clone(),
                        };
                        if !mapped.contains(&f) {
                            mapped.push(f);
                        }
                    }
                    if mapped.is_empty() {
                        mapped = fs.clone();
                    }
                    out.push_cite(Cite::Facts(mapped));
                }
            }
        }
        out.push_str(&self.text[at..]);
        out
    }
}

impl Text {
    /// The words.
    pub fn as_str(&self) -> &str {
        &self.text
    }
}

impl std::ops::Deref for Text {
    type Target = str;
    fn deref(&self) -> &str {
        &self.text
    }
}

impl std::fmt::Display for Text {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.text)
    }
}

impl From<String> for Text {
    fn from(text: String) -> Text {
        Text {
            text,
            cites: Vec::new(),
        }
    }
}

impl From<&str> for Text {
    fn from(text: &str) -> Text {
        Text::from(text.to_string())
    }
}

impl PartialEq<str> for Text {
    fn eq(&self, other: &str) -> bool {
        self.text == other
    }
}

impl PartialEq<&str> for Text {
    fn eq(&self, other: &&str) -> bool {
        self.text == *other
    }
}

/// A note under a diagnostic, as data: the expressions and values it states are kept
/// apart from its words, which are made by its `Display` (and typeset by the worked
/// solutions).
#[non_exhaustive]
#[derive(Clone, Debug, PartialEq)]
pub enum Note {
    /// Words.
    Text(Text),
    /// A side as written, in rigor's syntax: `left side:  L^2 m/12`.
    Side {
        /// The left side (else the right).
        left: bool,
        /// Its normal form.
        value: String,
    },
    /// Both sides once the facts are used: `with the facts (after using [a]): left …,
    /// right …`.
    Reduced {
        /// The facts used.
        using: Vec<FactRef>,
        /// The left side.
        left: String,
        /// The right side.
        right: String,
    },
    /// The difference of the sides left once the facts are used: `after using the
    /// facts, left − right = …`.
    Remainder {
        /// Whether the facts eliminated unknowns (`after eliminating what the facts
        /// give`) rather than being substituted.
        eliminated: bool,
        /// The difference.
        value: String,
    },
    /// A point where the sides differ: `counterexample: at m = 2 the left side is 4 and
    /// the right side 3`.
    Counterexample {
        /// `symbol = value`, each shown.
        at: Vec<(String, String)>,
        /// The left side's value there.
        left: String,
        /// The right side's value there.
        right: String,
    },
    /// How to declare quantities so that the step can be checked, with the names it is
    /// about.
    Declare {
        /// The quantities.
        names: Vec<String>,
        /// What to do.
        words: Text,
    },
}

impl Note {
    /// The same note with the lines it cites mapped (see [`Text::renumber`]).
    pub fn renumber(&self, map: &dyn Fn(usize) -> Option<usize>) -> Note {
        match self {
            Note::Text(t) => Note::Text(t.renumber(map)),
            Note::Reduced { using, left, right } => {
                let t = Text::default().facts(using).renumber(map);
                let Some((_, Cite::Facts(using))) = t.cites.into_iter().next() else {
                    return self.clone();
                };
                let using = using.into_iter().map(|c| c.fact).collect();
                Note::Reduced {
                    using,
                    left: left.clone(),
                    right: right.clone(),
                }
            }
            Note::Declare { names, words } => Note::Declare {
                names: names.clone(),
                words: words.renumber(map),
            },
            other => other.clone(),
        }
    }

    /// The same note with the values of sides it shows rewritten by `f` (how a view
    /// writes them; the points of a counterexample are left as they are).
    pub fn map_values(&self, f: impl Fn(&str) -> String) -> Note {
        match self {
            Note::Side { left, value } => Note::Side {
                left: *left,
                value: f(value),
            },
            Note::Reduced { using, left, right } => Note::Reduced {
                using: using.clone(),
                left: f(left),
                right: f(right),
            },
            Note::Remainder { eliminated, value } => Note::Remainder {
                eliminated: *eliminated,
                value: f(value),
            },
            other => other.clone(),
        }
    }
}

impl std::fmt::Display for Note {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Note::Text(t) => f.write_str(t),
            Note::Side { left: true, value } => write!(f, "left side:  {value}"),
            Note::Side { left: false, value } => write!(f, "right side: {value}"),
            Note::Reduced { using, left, right } if using.is_empty() => {
                write!(f, "with the facts: left {left}, right {right}")
            }
            Note::Reduced { using, left, right } => write!(
                f,
                "with the facts (after using {}): left {left}, right {right}",
                cite(using)
            ),
            Note::Remainder {
                eliminated: false,
                value,
            } => write!(f, "after using the facts, left − right = {value}"),
            Note::Remainder {
                eliminated: true,
                value,
            } => write!(
                f,
                "after eliminating what the facts give, left − right = {value}"
            ),
            Note::Counterexample { at, left, right } if at.is_empty() => {
                write!(f, "the left side is {left}, the right side {right}")
            }
            Note::Counterexample { at, left, right } => {
                let at: Vec<String> = at.iter().map(|(n, v)| format!("{n} = {v}")).collect();
                write!(
                    f,
                    "counterexample: at {} the left side is {left} and the right side {right}",
                    at.join(", ")
                )
            }
            Note::Declare { words, .. } => f.write_str(words),
        }
    }
}

impl From<String> for Note {
    fn from(s: String) -> Note {
        Note::Text(s.into())
    }
}

impl From<&str> for Note {
    fn from(s: &str) -> Note {
        Note::Text(s.into())
    }
}

impl From<Text> for Note {
    fn from(t: Text) -> Note {
        Note::Text(t)
    }
}

/// A limit of rigor's work that a refusal met, so that a front end can say how to raise
/// it (the library's words say the limit, never a flag).
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reached {
    /// The number of terms of an intermediate result.
    Terms(usize),
    /// The number of digits of a number.
    Digits(u64),
    /// The time one claim may take.
    ClaimTime,
    /// The time one file may take.
    FileBudget,
    /// The size of a file read, in bytes.
    FileSize(u64),
}

/// A message about a spot in a source.
#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    /// Severity.
    pub severity: Severity,
    /// A stable code, e.g. `E0301`.
    pub code: Code,
    /// The headline; it makes sense on its own.
    pub message: Text,
    /// The spot and what to say under it.
    pub primary: Option<(Span, String)>,
    /// Further lines (`= note: …`).
    pub notes: Vec<Note>,
    /// What the step got wrong, when the checker knows (a refuted or unverified `=`).
    pub mistake: Option<Mistake>,
    /// The limit it met, when it is a refusal at one.
    pub reached: Option<Reached>,
}

impl Diagnostic {
    /// An error with a primary span.
    pub fn error(
        code: Code,
        message: impl Into<Text>,
        span: Span,
        label: impl Into<String>,
    ) -> Diagnostic {
        Diagnostic {
            severity: Severity::Error,
            code,
            message: message.into(),
            primary: Some((span, label.into())),
            notes: Vec::new(),
            mistake: None,
            reached: None,
        }
    }

    /// The same diagnostic, with the limit it met.
    pub fn reached(mut self, r: Reached) -> Diagnostic {
        self.reached = Some(r);
        self
    }

    /// The same diagnostic, with what the step got wrong.
    pub fn with_mistake(mut self, m: Option<Mistake>) -> Diagnostic {
        self.mistake = m;
        self
    }

    /// The kind of failure it reports (from its code); `None` for warnings and notes.
    pub fn failure(&self) -> Option<FailureKind> {
        self.code.failure()
    }

    /// Adds a note.
    pub fn note(mut self, n: impl Into<Note>) -> Diagnostic {
        self.notes.push(n.into());
        self
    }

    /// Adds a note in place.
    pub fn add_note(&mut self, n: impl Into<Note>) {
        self.notes.push(n.into());
    }

    /// Adds a note when `cond` holds.
    pub fn note_if(self, cond: bool, n: impl Into<Note>) -> Diagnostic {
        if cond {
            self.note(n)
        } else {
            self
        }
    }
}

/// 1-based line and column (in characters) of byte offset `at`.
pub fn line_col(src: &str, at: usize) -> (usize, usize) {
    let at = at.min(src.len());
    let mut at = at;
    while !src.is_char_boundary(at) {
        at -= 1;
    }
    let before = &src[..at];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let col = src[line_start..at].chars().count() + 1;
    (line, col)
}

/// Where the lines of a text start: line and column lookups by binary search, so that a
/// report of many diagnostics on a large file is not quadratic.
pub struct LineIndex<'a> {
    src: &'a str,
    starts: Vec<usize>,
}

impl<'a> LineIndex<'a> {
    /// The index of `src`.
    pub fn new(src: &'a str) -> LineIndex<'a> {
        let starts = std::iter::once(0)
            .chain(src.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        LineIndex { src, starts }
    }

    /// The text indexed.
    pub fn text(&self) -> &'a str {
        self.src
    }

    /// 1-based line and column (in characters) of byte offset `at`, as [`line_col`].
    pub fn line_col(&self, at: usize) -> (usize, usize) {
        let mut at = at.min(self.src.len());
        while !self.src.is_char_boundary(at) {
            at -= 1;
        }
        let line = self.starts.partition_point(|&s| s <= at).max(1);
        let start = self.starts[line - 1];
        (line, self.src[start..at].chars().count() + 1)
    }

    /// The text of 1-based line `line`, without its line ending.
    pub fn line(&self, line: usize) -> &'a str {
        let Some(&start) = self.starts.get(line.saturating_sub(1)) else {
            return "";
        };
        let end = self.starts.get(line).map_or(self.src.len(), |e| e - 1);
        self.src.get(start..end.max(start)).unwrap_or("")
    }
}

/// Renders a diagnostic against its source, without colour.
pub fn render(d: &Diagnostic, path: &str, src: &str) -> String {
    render_in(d, path, &LineIndex::new(src))
}

/// Renders a diagnostic against an indexed source (for many diagnostics of one file).
pub fn render_in(d: &Diagnostic, path: &str, idx: &LineIndex<'_>) -> String {
    let mut out = format!("{}[{}]: {}\n", d.severity.as_str(), d.code, d.message);
    if let Some((span, label)) = &d.primary {
        let (line, col) = idx.line_col(span.start);
        let gutter = line.to_string().len();
        let pad = " ".repeat(gutter);
        out.push_str(&format!("{pad}--> {path}:{line}:{col}\n"));
        out.push_str(&format!("{pad} |\n"));
        let text = idx.line(line);
        let text = text.trim_end_matches('\r');
        out.push_str(&format!("{line} | {text}\n"));
        let line_chars = text.chars().count();
        let start = col - 1;
        let (end_line, end_col) = idx.line_col(span.end.max(span.start));
        let end = if end_line == line {
            end_col - 1
        } else {
            line_chars
        };
        let width = end.saturating_sub(start).max(1);
        let marker = if width == 1 {
            "^".to_string()
        } else {
            "^".repeat(width)
        };
        let indent: String = text
            .chars()
            .take(start)
            .map(|c| if c == '\t' { '\t' } else { ' ' })
            .collect();
        out.push_str(&format!("{pad} | {indent}{marker} {label}\n").replace(" \n", "\n"));
    }
    for n in &d.notes {
        let gutter = d
            .primary
            .as_ref()
            .map_or(1, |(s, _)| idx.line_col(s.start).0.to_string().len());
        out.push_str(&format!("{} = {}\n", " ".repeat(gutter), n));
    }
    out
}

/// Levenshtein distance.
pub fn distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.iter().enumerate() {
        let mut cur = vec![i + 1];
        for (j, cb) in b.iter().enumerate() {
            let sub = prev[j] + usize::from(ca != cb);
            let del = prev[j + 1] + 1;
            let ins = cur[j] + 1;
            cur.push(sub.min(del).min(ins));
        }
        prev = cur;
    }
    prev[b.len()]
}

/// The candidate closest to `name` (edit distance within a third of its length, plus
/// one), for "did you mean …?".
pub fn closest<'c>(name: &str, candidates: &[&'c str]) -> Option<&'c str> {
    let limit = 2 + name.chars().count() / 3;
    candidates
        .iter()
        .map(|c| (distance(name, c), *c))
        .filter(|(d, _)| *d <= limit)
        .min()
        .map(|(_, c)| c)
}
