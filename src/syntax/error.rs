//! Syntax errors with byte spans, the parser's internal nom error type, and parse options.

use super::ast::Span;
use nom::error::{ErrorKind, ParseError};
use std::fmt;

/// A syntax error: what kind, what was expected, and where.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SyntaxError {
    /// The bytes the error is about (empty at the end of the input).
    pub span: Span,
    /// What kind of error it is (the message says it in words).
    pub kind: SyntaxErrorKind,
    /// A message that makes sense on its own, e.g. "expected an expression after `+`".
    pub message: String,
}

/// The kinds of syntax errors: the parser's limits, and every other error.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SyntaxErrorKind {
    /// Parentheses, calls, unary minus or powers nested deeper than
    /// [`ParseOptions::max_depth`].
    NestingLimit,
    /// An expression with more operations inside one another than the parser builds
    /// (however it is nested: `a + b + … + z` a thousand times over).
    TooLarge,
    /// `\int … dm` with limits: a mass element defined in prose, not a coordinate (lint
    /// acts on this kind, never on the message's words).
    MassElementWithLimits,
    /// Any other error: the message says what was expected, or what was unexpected.
    Other,
}

impl SyntaxError {
    /// An error at `span` ([`SyntaxErrorKind::Other`]).
    pub fn new(span: Span, message: impl Into<String>) -> SyntaxError {
        SyntaxError::of_kind(span, SyntaxErrorKind::Other, message)
    }

    /// An error of the kind `kind` at `span`.
    pub fn of_kind(span: Span, kind: SyntaxErrorKind, message: impl Into<String>) -> SyntaxError {
        SyntaxError {
            span,
            kind,
            message: message.into(),
        }
    }

    /// The same error, of kind `kind`.
    pub fn with_kind(mut self, kind: SyntaxErrorKind) -> SyntaxError {
        self.kind = kind;
        self
    }
}

impl fmt::Display for SyntaxError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} (bytes {}..{})",
            self.message, self.span.start, self.span.end
        )
    }
}

impl std::error::Error for SyntaxError {}

/// Limits the parser applies to its input.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ParseOptions {
    /// The deepest nesting of parentheses, calls, unary minus and powers accepted;
    /// deeper input is a [`SyntaxError`], never a stack overflow.
    pub max_depth: usize,
}

impl Default for ParseOptions {
    fn default() -> ParseOptions {
        ParseOptions { max_depth: 200 }
    }
}

/// The nom error of the parsers: a position in the input, a length, and a message
/// once a rule has committed (`None` for a plain "this alternative does not match").
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct PError<'a> {
    /// The input where the error is, a subslice of the text being parsed.
    pub at: &'a str,
    /// How many bytes of `at` the error covers.
    pub len: usize,
    /// The message, if a rule has said what it expected.
    pub message: Option<String>,
    /// The kind of error the message describes.
    pub kind: SyntaxErrorKind,
}

impl<'a> ParseError<&'a str> for PError<'a> {
    fn from_error_kind(input: &'a str, _kind: ErrorKind) -> Self {
        PError {
            at: input,
            len: 0,
            message: None,
            kind: SyntaxErrorKind::Other,
        }
    }

    fn append(_input: &'a str, _kind: ErrorKind, other: Self) -> Self {
        other
    }

    /// Keep the error that says what was expected, then the one that got further.
    fn or(self, other: Self) -> Self {
        match (&self.message, &other.message) {
            (Some(_), None) => self,
            (None, Some(_)) => other,
            _ if self.at.len() < other.at.len() => self,
            _ => other,
        }
    }
}

/// A failed parse.
pub(crate) type Fail<'a> = nom::Err<PError<'a>>;

/// The result of a parser of this module tree.
pub(crate) type PResult<'a, T> = nom::IResult<&'a str, T, PError<'a>>;

/// A committed failure at `at`, `len` bytes long, saying `message`.
pub(crate) fn failure<'a, T>(
    at: &'a str,
    len: usize,
    message: impl Into<String>,
) -> PResult<'a, T> {
    failure_of_kind(at, len, SyntaxErrorKind::Other, message)
}

/// A committed failure of the kind `kind` at `at`, `len` bytes long, saying `message`.
pub(crate) fn failure_of_kind<'a, T>(
    at: &'a str,
    len: usize,
    kind: SyntaxErrorKind,
    message: impl Into<String>,
) -> PResult<'a, T> {
    Err(nom::Err::Failure(PError {
        at,
        len,
        message: Some(message.into()),
        kind,
    }))
}

/// A recoverable "does not match here" at `at`.
pub(crate) fn no_match<'a, T>(at: &'a str) -> PResult<'a, T> {
    Err(nom::Err::Error(PError {
        at,
        len: 0,
        message: None,
        kind: SyntaxErrorKind::Other,
    }))
}
