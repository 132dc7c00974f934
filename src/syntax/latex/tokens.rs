//! The tokens of LaTeX math, read with nom: macros, numbers, letters and single
//! characters, each with its span; spacing macros dropped.

use super::super::ast::Span;
use super::super::error::SyntaxError;
use nom::branch::alt;
use nom::bytes::complete::take_while1;
use nom::character::complete::{anychar, char, digit0, digit1, satisfy};
use nom::combinator::{opt, recognize};
use nom::sequence::preceded;
use nom::{IResult, Parser};
use num_bigint::BigInt;
use num_rational::BigRational;

/// A LaTeX token.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Tok {
    /// `\name` or `\,` (one non-letter).
    Cmd(String),
    /// A number, exact.
    Num(BigRational),
    /// One ASCII letter.
    Letter(char),
    /// Any other character: `+ - * / ^ _ = < > ( ) [ ] { } | ' & , . ; :`.
    Ch(char),
}

/// Macros that only space or size things: skipped.
const IGNORED: [&str; 22] = [
    ",",
    ";",
    ":",
    "!",
    " ",
    "quad",
    "qquad",
    "displaystyle",
    "textstyle",
    "big",
    "Big",
    "bigg",
    "Bigg",
    "bigl",
    "bigr",
    "Bigl",
    "Bigr",
    "biggl",
    "biggr",
    "Biggl",
    "Biggr",
    "limits",
];

pub(super) const GREEK: [&str; 33] = [
    "alpha", "beta", "gamma", "delta", "epsilon", "zeta", "eta", "theta", "iota", "kappa",
    "lambda", "mu", "nu", "xi", "rho", "sigma", "tau", "upsilon", "phi", "chi", "psi", "omega",
    "Gamma", "Delta", "Theta", "Lambda", "Xi", "Pi", "Sigma", "Phi", "Psi", "Omega", "varrho",
];

fn number(i: &str) -> IResult<&str, &str> {
    recognize((digit1, opt(preceded(char('.'), digit0)))).parse(i)
}

fn command(i: &str) -> IResult<&str, &str> {
    preceded(
        char('\\'),
        alt((
            take_while1(|c: char| c.is_ascii_alphabetic()),
            recognize(anychar),
        )),
    )
    .parse(i)
}

fn other(i: &str) -> IResult<&str, char> {
    satisfy(|c| !c.is_whitespace()).parse(i)
}

/// The tokens of `text`, each with its span (offset by `base`); spacing dropped.
pub(super) fn tokens(text: &str, base: usize) -> Result<Vec<(Tok, Span)>, SyntaxError> {
    let mut out = Vec::new();
    let mut i = text;
    loop {
        let trimmed = i.trim_start_matches(|c: char| c.is_whitespace() || c == '~');
        let start = base + (text.len() - trimmed.len());
        if trimmed.is_empty() {
            return Ok(out);
        }
        let (rest, tok) = if let Ok((rest, n)) = number(trimmed) {
            let q = decimal(n).ok_or_else(|| {
                SyntaxError::new(
                    Span::new(start, start + n.len()),
                    "a number too long to read",
                )
            })?;
            (rest, Tok::Num(q))
        } else if let Ok((rest, c)) = command(trimmed) {
            (rest, Tok::Cmd(c.to_string()))
        } else if let Ok((rest, c)) = other(trimmed) {
            if c.is_ascii_alphabetic() {
                (rest, Tok::Letter(c))
            } else {
                (rest, Tok::Ch(c))
            }
        } else {
            return Ok(out);
        };
        let end = base + (text.len() - rest.len());
        let skip = matches!(&tok, Tok::Cmd(c) if IGNORED.contains(&c.as_str()));
        if !skip {
            out.push((tok, Span::new(start, end)));
        }
        i = rest;
    }
}

fn decimal(s: &str) -> Option<BigRational> {
    if s.len() > 400 {
        return None;
    }
    let (int, frac) = s.split_once('.').unwrap_or((s, ""));
    let digits: BigInt = format!("{int}{frac}").parse().ok()?;
    let den = BigInt::from(10).pow(u32::try_from(frac.len()).ok()?);
    Some(BigRational::new(digits, den))
}
