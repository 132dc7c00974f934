//! Tokens of the expression language: whitespace and comments, numbers, names, punctuation, and byte offsets.

use super::ast::Span;
use super::error::{
    failure, failure_of_kind, no_match, Fail, PResult, ParseOptions, SyntaxError, SyntaxErrorKind,
};
use nom::bytes::complete::take_while;
use nom::character::complete::{char, digit0, digit1, one_of, satisfy};
use nom::combinator::{opt, recognize};
use nom::sequence::{pair, preceded};
use nom::Parser;
use num_bigint::BigInt;
use num_rational::BigRational;

/// Words that end an expression: they introduce the next part of a statement.
pub(crate) const RESERVED: [&str; 5] = ["by", "where", "with", "from", "to"];

/// The largest power of ten a number literal may carry (`1e10000`).
const MAX_EXPONENT: i64 = 10_000;

/// The most digits a number literal may have.
const MAX_DIGITS: usize = 10_000;

/// What every parser needs to know besides its input.
///
/// Every parser's input is a suffix of one region of `base` (an expression, a statement,
/// the math between two `$`), so its absolute offset is `end - input.len()`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Cx<'a> {
    /// The text given to the top-level call; spans are byte offsets into it.
    pub base: &'a str,
    /// The offset in `base` of the end of the region being parsed.
    pub end: usize,
    /// The deepest nesting accepted (`ParseOptions::max_depth`).
    pub max_depth: usize,
    /// The tallest expression tree accepted (long flat sums and products).
    pub max_height: usize,
    /// Whether `%` starts a comment (statements) or is an ordinary character (expressions, prose).
    pub comments: bool,
    /// How the end of the region is called in messages ("the end of the statement").
    pub end_name: &'static str,
}

impl<'a> Cx<'a> {
    /// A context for parsing the region of `base` that ends at byte `end`.
    pub fn new(
        base: &'a str,
        end: usize,
        opts: &ParseOptions,
        comments: bool,
        end_name: &'static str,
    ) -> Cx<'a> {
        let max_height = opts.max_depth.saturating_mul(5).max(1000);
        Cx {
            base,
            end,
            max_depth: opts.max_depth,
            max_height,
            comments,
            end_name,
        }
    }

    /// The byte offset in `base` of `i`, a suffix of the region.
    pub fn pos(&self, i: &str) -> usize {
        self.end.saturating_sub(i.len())
    }

    /// The span from the start of `from` to the start of `to` (both suffixes of the region).
    pub fn span(&self, from: &str, to: &str) -> Span {
        Span::new(self.pos(from), self.pos(to))
    }

    /// The span of the first `len` bytes of `at`.
    pub fn span_len(&self, at: &str, len: usize) -> Span {
        let start = self.pos(at);
        Span::new(start, start.saturating_add(len))
    }

    /// The [`SyntaxError`] at the boundary of the parser, spans absolute in `base`.
    pub fn error(&self, e: Fail<'a>) -> SyntaxError {
        match e {
            nom::Err::Error(e) | nom::Err::Failure(e) => {
                let span = self.span_len(e.at, e.len);
                let message = e
                    .message
                    .unwrap_or_else(|| format!("unexpected {}", describe(self, e.at)));
                SyntaxError::of_kind(span, e.kind, message)
            }
            nom::Err::Incomplete(_) => SyntaxError::new(
                Span::new(self.base.len(), self.base.len()),
                "unexpected end of input",
            ),
        }
    }

    /// `depth + 1`, or the "nested too deeply" error at the token `at` if that is too deep.
    pub fn enter(&self, at: &'a str, depth: usize) -> PResult<'a, usize> {
        let deeper = depth.saturating_add(1);
        if deeper > self.max_depth {
            let message = format!("expression nested deeper than {} levels", self.max_depth);
            return failure_of_kind(
                at,
                token_len(at).max(1),
                SyntaxErrorKind::NestingLimit,
                message,
            );
        }
        Ok((at, deeper))
    }
}

/// Skips whitespace (newlines included) and, in statements, `%` comments.
pub(crate) fn ws<'a>(cx: &Cx<'a>, mut i: &'a str) -> &'a str {
    loop {
        i = i.trim_start();
        match i.strip_prefix('%') {
            Some(comment) if cx.comments => {
                i = comment
                    .find('\n')
                    .and_then(|n| comment.get(n..))
                    .unwrap_or("");
            }
            _ => return i,
        }
    }
}

/// Skips spaces and tabs, not newlines.
pub(crate) fn hspace(i: &str) -> &str {
    i.trim_start_matches([' ', '\t'])
}

/// The ASCII name of a Greek letter accepted in names (`β` → `beta`).
pub(crate) fn greek_name(c: char) -> Option<&'static str> {
    Some(match c {
        'α' => "alpha",
        'β' => "beta",
        'γ' => "gamma",
        'δ' => "delta",
        'ε' | 'ϵ' => "epsilon",
        'ζ' => "zeta",
        'η' => "eta",
        'θ' | 'ϑ' => "theta",
        'κ' => "kappa",
        'λ' => "lambda",
        'μ' | 'µ' => "mu",
        'ν' => "nu",
        'ξ' => "xi",
        'π' => "pi",
        'ρ' => "rho",
        'σ' => "sigma",
        'τ' => "tau",
        'φ' | 'ϕ' => "phi",
        'χ' => "chi",
        'ψ' => "psi",
        'ω' => "omega",
        'Γ' => "Gamma",
        'Δ' => "Delta",
        'Θ' => "Theta",
        'Λ' => "Lambda",
        'Φ' => "Phi",
        'Ψ' => "Psi",
        'Ω' => "Omega",
        _ => return None,
    })
}

/// Whether `c` may start a name.
fn name_start(c: char) -> bool {
    c.is_ascii_alphabetic() || greek_name(c).is_some()
}

/// Whether `c` may continue a name.
fn name_continue(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_' || greek_name(c).is_some()
}

/// A name as written and as stored.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Ident<'a> {
    /// The text as written, primes included.
    pub raw: &'a str,
    /// The stored name: Greek letters spelt out, primes kept (`θ_G''` → `theta_G''`).
    pub name: String,
}

/// `ident = letter (letter | digit | "_")* "'"*` where letters include the Greek ones.
pub(crate) fn ident(i: &str) -> PResult<'_, Ident<'_>> {
    let (rest, raw) = recognize((
        satisfy(name_start),
        take_while(name_continue),
        take_while(|c| c == '\''),
    ))
    .parse(i)?;
    let mut name = String::with_capacity(raw.len());
    for c in raw.chars() {
        match greek_name(c) {
            Some(spelt) => name.push_str(spelt),
            None => name.push(c),
        }
    }
    Ok((rest, Ident { raw, name }))
}

/// Whether `name` is one of the [`RESERVED`] words.
pub(crate) fn is_reserved(name: &str) -> bool {
    RESERVED.contains(&name)
}

/// `number = digits ["." digits] [("e" | "E") ["+" | "-"] digits] | "." digits ...`, exactly.
///
/// An `e` belongs to the number only when digits follow it, so `2e` is `2·e`.
pub(crate) fn number(i: &str) -> PResult<'_, BigRational> {
    let mantissa = (digit0, opt(preceded(char('.'), digit1)));
    let exponent = opt(preceded(
        one_of("eE"),
        recognize(pair(opt(one_of("+-")), digit1)),
    ));
    let (rest, ((whole, frac), exp)) = (mantissa, exponent).parse(i)?;
    if whole.is_empty() && frac.is_none() {
        return no_match(i);
    }
    let frac = frac.unwrap_or("");
    let len = i.len().saturating_sub(rest.len());
    if whole.len().saturating_add(frac.len()) > MAX_DIGITS {
        return failure(
            i,
            len,
            format!("number too long: at most {MAX_DIGITS} digits"),
        );
    }
    let too_big = || {
        failure(
            i,
            len,
            format!("number out of range: powers of ten go up to 1e{MAX_EXPONENT}"),
        )
    };
    let exp: i64 = match exp.map(|e| e.trim_start_matches('+').parse::<i64>()) {
        None => 0,
        Some(Ok(e)) if e.abs() <= MAX_EXPONENT => e,
        Some(_) => return too_big(),
    };
    let frac_len = i64::try_from(frac.len()).unwrap_or(i64::MAX);
    let Some(scale) = exp
        .checked_sub(frac_len)
        .filter(|s| s.abs() <= MAX_EXPONENT)
    else {
        return too_big();
    };
    let digits: BigInt = if whole.len() + frac.len() <= 18 {
        // At most 18 digits fit in a machine word: no text copied, no big-number parse.
        let word = whole
            .bytes()
            .chain(frac.bytes())
            .fold(0u64, |n, b| n * 10 + u64::from(b - b'0'));
        if scale == 0 {
            return Ok((rest, BigRational::from_integer(BigInt::from(word))));
        }
        BigInt::from(word)
    } else {
        match format!("{whole}{frac}").parse() {
            Ok(d) => d,
            Err(_) => return no_match(i),
        }
    };
    let ten_to = |n: i64| {
        num_traits::pow(
            BigInt::from(10u8),
            usize::try_from(n.unsigned_abs()).unwrap_or(0),
        )
    };
    let value = if scale >= 0 {
        BigRational::from_integer(digits * ten_to(scale))
    } else {
        BigRational::new(digits, ten_to(scale))
    };
    Ok((rest, value))
}

/// `punct`: after whitespace, the exact text `p`; returns the input at `p` and after it.
pub(crate) fn punct<'a>(cx: &Cx<'a>, i: &'a str, p: &str) -> Option<(&'a str, &'a str)> {
    let at = ws(cx, i);
    at.strip_prefix(p).map(|rest| (at, rest))
}

/// `keyword`: after whitespace, the whole word `w`; returns the input at `w` and after it.
pub(crate) fn keyword<'a>(cx: &Cx<'a>, i: &'a str, w: &str) -> Option<(&'a str, &'a str)> {
    let at = ws(cx, i);
    match ident(at) {
        Ok((rest, id)) if id.raw == w => Some((at, rest)),
        _ => None,
    }
}

/// The length of the token at the start of `i`, for error spans (0 at the end).
pub(crate) fn token_len(i: &str) -> usize {
    if let Ok((rest, _)) = ident(i) {
        return i.len().saturating_sub(rest.len());
    }
    let digits = i
        .bytes()
        .take_while(|b| b.is_ascii_digit() || *b == b'.')
        .count();
    if digits > 0 {
        return digits;
    }
    i.chars().next().map_or(0, char::len_utf8)
}

/// "`tok`" for the token at the start of `i`, or the name of the end of the region.
pub(crate) fn describe(cx: &Cx<'_>, i: &str) -> String {
    let len = token_len(i);
    match i.get(..len) {
        Some(tok) if !tok.is_empty() && len <= 40 => format!("`{tok}`"),
        Some(tok) if !tok.is_empty() => format!("`{}…`", tok.chars().take(30).collect::<String>()),
        _ => cx.end_name.to_string(),
    }
}

/// The committed error "expected `what`, found …" at the token after whitespace at `i`,
/// or, when only whitespace and comments remain, right where `i` starts.
pub(crate) fn expected<'a, T>(cx: &Cx<'a>, i: &'a str, what: &str) -> PResult<'a, T> {
    let at = ws(cx, i);
    let at_or_end = if at.is_empty() { i } else { at };
    failure(
        at_or_end,
        token_len(at),
        format!("expected {what}, found {}", describe(cx, at)),
    )
}

/// Succeeds when only whitespace (and comments) remain; otherwise says what was `wanted`.
pub(crate) fn end<'a>(cx: &Cx<'a>, i: &'a str, wanted: &str) -> PResult<'a, ()> {
    let at = ws(cx, i);
    if at.is_empty() {
        return Ok((at, ()));
    }
    if at.starts_with(')') {
        return failure(at, 1, "unmatched `)`");
    }
    expected(cx, i, wanted)
}
