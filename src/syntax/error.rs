//! Syntax errors with byte spans, the parser's internal nom error type, and parse options.

use super::ast::Span;
use nom::error::{ErrorKind, ParseError};
use std::fmt;

/// A syntax error: what was expected, and where.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SyntaxError {
    /// The bytes the error is about (empty at the end of the input).
    pub span: Span,
    /// A message that makes sense on its own, e.g. "expected an expression after `+`".
    pub message: String,
    /// Its kind, for a reader that acts on it (lint), never on the message's words.
    pub kind: SyntaxKind,
}

/// The kind of a syntax error.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SyntaxKind {
    /// Input that does not read.
    #[default]
    Malformed,
    /// `\int … dm` with limits: a mass element defined in prose, not a coordinate.
    MassElementWithLimits,
}

impl SyntaxError {
    /// An error at `span`.
    pub fn new(span: Span, message: impl Into<String>) -> SyntaxError {
        SyntaxError {
            span,
            message: message.into(),
            kind: SyntaxKind::Malformed,
        }
    }

    /// The same error, of kind `kind`.
    pub fn of_kind(mut self, kind: SyntaxKind) -> SyntaxError {
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
}

impl<'a> ParseError<&'a str> for PError<'a> {
    fn from_error_kind(input: &'a str, _kind: ErrorKind) -> Self {
        PError {
            at: input,
            len: 0,
            message: None,
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
    Err(nom::Err::Failure(PError {
        at,
        len,
        message: Some(message.into()),
    }))
}

/// A recoverable "does not match here" at `at`.
pub(crate) fn no_match<'a, T>(at: &'a str) -> PResult<'a, T> {
    Err(nom::Err::Error(PError {
        at,
        len: 0,
        message: None,
    }))
}
