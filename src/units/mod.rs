//! Physical units and dimensions (FORMAT.md §3, "Units"): the unit side of a `units`
//! statement is its own little language, parsed here with nom and never confused with
//! the file's symbols, and `check.rs` carries dimensions through expressions as written.

pub mod check;

use nom::branch::alt;
use nom::bytes::complete::{tag, take_while1};
use nom::character::complete::{char, digit1, multispace0};
use nom::combinator::{opt, recognize};
use nom::sequence::{delimited, preceded};
use nom::{IResult, Parser};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use std::fmt;

/// The seven SI base dimensions, in this order.
pub const BASE: [&str; 7] = ["kg", "m", "s", "A", "K", "mol", "cd"];

/// A dimension: rational exponents of the seven base units, and the scale of the unit
/// written (1 for SI units, 1/1000 for `mm`) to notice mixed scales.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Dim {
    /// Exponents of kg, m, s, A, K, mol, cd.
    pub exp: [BigRational; 7],
    /// The factor to SI (`km` is 1000 m).
    pub scale: BigRational,
}

fn q(n: i64) -> BigRational {
    BigRational::from_integer(BigInt::from(n))
}

impl Dim {
    /// Dimensionless, scale 1.
    pub fn one() -> Dim {
        Dim {
            exp: std::array::from_fn(|_| BigRational::zero()),
            scale: BigRational::one(),
        }
    }

    /// The base unit number `i`.
    pub fn base(i: usize) -> Dim {
        let mut d = Dim::one();
        if let Some(e) = d.exp.get_mut(i) {
            *e = BigRational::one();
        }
        d
    }

    /// Whether the two have the same dimension (scales aside).
    pub fn same(&self, o: &Dim) -> bool {
        self.exp == o.exp
    }

    /// Whether dimensionless.
    pub fn is_one(&self) -> bool {
        self.exp.iter().all(Zero::is_zero)
    }

    /// `self · o`.
    pub fn mul(&self, o: &Dim) -> Dim {
        Dim {
            exp: std::array::from_fn(|i| &self.exp[i] + &o.exp[i]),
            scale: &self.scale * &o.scale,
        }
    }

    /// `self / o`.
    pub fn div(&self, o: &Dim) -> Dim {
        self.mul(&o.pow(&-BigRational::one()))
    }

    /// `self^p` (scale raised only for whole powers).
    pub fn pow(&self, p: &BigRational) -> Dim {
        let scale = if p.is_integer() {
            num_traits::ToPrimitive::to_i32(&p.to_integer())
                .map_or_else(BigRational::one, |k| self.scale.pow(k))
        } else {
            BigRational::one()
        };
        Dim {
            exp: std::array::from_fn(|i| &self.exp[i] * p),
            scale,
        }
    }

    /// With scale 1 (its dimension only).
    pub fn si(&self) -> Dim {
        Dim {
            exp: self.exp.clone(),
            scale: BigRational::one(),
        }
    }
}

impl fmt::Display for Dim {
    /// `kg·m²/s²`, `1` for dimensionless.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let part = |name: &str, e: &BigRational| -> String {
            let e = e.abs();
            if e.is_one() {
                name.to_string()
            } else if e.is_integer() {
                let sup: String = e
                    .to_integer()
                    .to_string()
                    .chars()
                    .map(|c| match c {
                        '2' => '²',
                        '3' => '³',
                        '4' => '⁴',
                        '5' => '⁵',
                        '6' => '⁶',
                        '7' => '⁷',
                        '8' => '⁸',
                        '9' => '⁹',
                        '0' => '⁰',
                        '1' => '¹',
                        c => c,
                    })
                    .collect();
                format!("{name}{sup}")
            } else {
                format!("{name}^({e})")
            }
        };
        let num: Vec<String> = BASE
            .iter()
            .zip(&self.exp)
            .filter(|(_, e)| e.is_positive())
            .map(|(n, e)| part(n, e))
            .collect();
        let den: Vec<String> = BASE
            .iter()
            .zip(&self.exp)
            .filter(|(_, e)| e.is_negative())
            .map(|(n, e)| part(n, e))
            .collect();
        let top = if num.is_empty() {
            "1".to_string()
        } else {
            num.join("·")
        };
        if den.is_empty() {
            f.write_str(&top)
        } else {
            write!(f, "{top}/{}", den.join("·"))
        }
    }
}

/// The named units rigor knows, as (name, dimension in base exponents, scale).
fn named(name: &str) -> Option<Dim> {
    let e = |kg: i64, m: i64, s: i64, a: i64| {
        let mut d = Dim::one();
        d.exp[0] = q(kg);
        d.exp[1] = q(m);
        d.exp[2] = q(s);
        d.exp[3] = q(a);
        d
    };
    Some(match name {
        "kg" => e(1, 0, 0, 0),
        "g" => {
            let mut d = e(1, 0, 0, 0);
            d.scale = BigRational::new(1.into(), 1000.into());
            d
        }
        "m" => e(0, 1, 0, 0),
        "s" => e(0, 0, 1, 0),
        "A" => e(0, 0, 0, 1),
        "K" => Dim::base(4),
        "mol" => Dim::base(5),
        "cd" => Dim::base(6),
        "N" => e(1, 1, -2, 0),
        "J" => e(1, 2, -2, 0),
        "W" => e(1, 2, -3, 0),
        "Pa" => e(1, -1, -2, 0),
        "Hz" => e(0, 0, -1, 0),
        "C" => e(0, 0, 1, 1),
        "V" => e(1, 2, -3, -1),
        "rad" | "sr" => Dim::one(),
        _ => return None,
    })
}

/// Prefixes, where the prefixed name is not itself a unit.
fn prefix(c: char) -> Option<BigRational> {
    let ten = |k: i32| BigRational::from_integer(BigInt::from(10)).pow(k);
    Some(match c {
        'k' => ten(3),
        'M' => ten(6),
        'G' => ten(9),
        'm' => ten(-3),
        'u' | 'µ' => ten(-6),
        'c' => ten(-2),
        'n' => ten(-9),
        _ => return None,
    })
}

/// A unit name: a named unit, or a prefix and a named unit (`mm`, `kN`, `MPa`).
pub fn unit_name(name: &str) -> Option<Dim> {
    if let Some(d) = named(name) {
        return Some(d);
    }
    let mut chars = name.chars();
    let p = prefix(chars.next()?)?;
    let rest = chars.as_str();
    // Only prefixes of metres, seconds, grams and the derived units; never of kg.
    if rest == "kg" || rest.is_empty() {
        return None;
    }
    let mut d = named(rest)?;
    d.scale = &d.scale * p;
    Some(d)
}

/// Every unit name rigor knows (for suggestions).
pub fn known_names() -> Vec<&'static str> {
    vec![
        "kg", "g", "m", "s", "A", "K", "mol", "cd", "N", "J", "W", "Pa", "Hz", "C", "V", "rad",
        "sr", "km", "cm", "mm", "ms", "kN", "MPa", "kPa", "GPa", "kJ", "kW", "mA",
    ]
}

/// A unit as written, typeset upright with thin spaces and no package beyond amsmath
/// (`kg m^2` → `\mathrm{kg}\,\mathrm{m}^{2}`, `m/s^2` → `\mathrm{m}/\mathrm{s}^{2}`).
pub fn unit_latex(unit: &str) -> String {
    let mut out = String::new();
    let mut chars = unit.trim().chars().peekable();
    let mut pending_space = false;
    while let Some(c) = chars.next() {
        match c {
            c if c.is_alphabetic() => {
                let mut name = c.to_string();
                while let Some(n) = chars.peek().filter(|n| n.is_alphabetic()) {
                    name.push(*n);
                    chars.next();
                }
                if pending_space && !out.is_empty() && !out.ends_with('/') {
                    out.push_str("\\,");
                }
                pending_space = false;
                let name = if name == "u" {
                    "\\mu".to_string()
                } else {
                    name
                };
                out.push_str(&format!("\\mathrm{{{name}}}"));
            }
            '^' => {
                let mut exp = String::new();
                while let Some(n) = chars
                    .peek()
                    .filter(|n| n.is_ascii_digit() || matches!(n, '-' | '(' | ')' | '/' | ' '))
                {
                    if *n == ' ' && !exp.contains('(') {
                        break;
                    }
                    exp.push(*n);
                    chars.next();
                }
                let exp = exp
                    .trim()
                    .trim_start_matches('(')
                    .trim_end_matches(')')
                    .to_string();
                out.push_str(&format!("^{{{exp}}}"));
            }
            '/' => {
                out.push('/');
                pending_space = false;
            }
            '*' | ' ' | '·' => pending_space = true,
            '1' if out.is_empty() => out.push('1'),
            c => out.push(c),
        }
    }
    out
}

/// Why a unit did not parse: the byte offset in the unit text and the message.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnitError {
    /// Byte offset of the problem in the unit text.
    pub at: usize,
    /// Its length.
    pub len: usize,
    /// What is wrong.
    pub message: String,
}

type Res<'a, T> = IResult<&'a str, T>;

fn ws(i: &str) -> &str {
    multispace0::<&str, nom::error::Error<&str>>(i).map_or(i, |(r, _)| r)
}

fn exponent(i: &str) -> Res<'_, BigRational> {
    let int = |i| -> Res<'_, BigRational> {
        let (i, s) = recognize((opt(char('-')), digit1)).parse(i)?;
        Ok((
            i,
            s.parse::<BigInt>()
                .map_or_else(|_| q(0), BigRational::from_integer),
        ))
    };
    let frac = |i| -> Res<'_, BigRational> {
        let (i, (n, d)) = delimited(
            (char('('), multispace0),
            (
                recognize((opt(char('-')), digit1)),
                preceded((multispace0, char('/'), multispace0), digit1),
            ),
            (multispace0, char(')')),
        )
        .parse(i)?;
        let n: BigInt = n.parse().unwrap_or_default();
        let d: BigInt = d.parse().unwrap_or_else(|_| BigInt::one());
        if d.is_zero() {
            return Ok((i, q(0)));
        }
        Ok((i, BigRational::new(n, d)))
    };
    let paren_int = delimited((char('('), multispace0), int, (multispace0, char(')')));
    preceded(
        (multispace0, char('^'), multispace0),
        alt((frac, paren_int, int)),
    )
    .parse(i)
}

/// Parses a unit expression: `kg m^2`, `m/s^2`, `kg*m/s^2`, `m^(1/2)`, `1`.
pub fn parse_unit(text: &str) -> Result<Dim, UnitError> {
    let err = |rest: &str, len: usize, message: String| UnitError {
        at: text.len() - rest.len(),
        len,
        message,
    };
    let mut d = Dim::one();
    let mut i = ws(text);
    let mut dividing = false;
    let mut first = true;
    loop {
        if i.is_empty() {
            if first {
                return Err(err(i, 0, "an empty unit".into()));
            }
            return Ok(d);
        }
        if !first {
            if let Ok((r, _)) = tag::<&str, &str, nom::error::Error<&str>>("/")(i) {
                if dividing {
                    return Err(err(
                        i,
                        1,
                        "a second `/`: write `kg/(m s^2)` as `kg/m/s^2`, or use negative powers"
                            .into(),
                    ));
                }
                dividing = true;
                i = ws(r);
            } else if let Ok((r, _)) = tag::<&str, &str, nom::error::Error<&str>>("*")(i) {
                i = ws(r);
            } else if let Ok((r, _)) = tag::<&str, &str, nom::error::Error<&str>>("·")(i) {
                i = ws(r);
            }
        }
        let (rest, factor) = if let Ok((r, _)) = char::<&str, nom::error::Error<&str>>('1')(i) {
            (r, Dim::one())
        } else {
            let Ok((r, name)) =
                take_while1::<_, &str, nom::error::Error<&str>>(|c: char| c.is_alphabetic())(i)
            else {
                return Err(err(
                    i,
                    i.chars().next().map_or(0, char::len_utf8),
                    format!("unexpected `{}` in a unit", i.chars().next().unwrap_or(' ')),
                ));
            };
            let Some(u) = unit_name(name) else {
                let hint = crate::diag::closest(name, &known_names())
                    .map_or_else(String::new, |s| format!("; did you mean `{s}`?"));
                return Err(err(i, name.len(), format!("unknown unit `{name}`{hint}")));
            };
            (r, u)
        };
        let (rest, p) = match exponent(rest) {
            Ok((r, p)) => (r, p),
            Err(_) => (rest, BigRational::one()),
        };
        let factor = factor.pow(&p);
        d = if dividing {
            d.div(&factor)
        } else {
            d.mul(&factor)
        };
        first = false;
        i = ws(rest);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn show(s: &str) -> String {
        parse_unit(s).map_or_else(|e| format!("error: {}", e.message), |d| d.to_string())
    }

    #[test]
    fn units_parse_to_base_dimensions() {
        assert_eq!(show("kg m^2"), "kg·m²");
        assert_eq!(show("m/s^2"), "m/s²");
        assert_eq!(show("kg*m/s^2"), show("N"));
        assert_eq!(show("N m"), show("J"));
        assert_eq!(show("kg/m^3"), "kg/m³");
        assert_eq!(show("m^(1/2)"), "m^(1/2)");
        assert_eq!(show("rad"), "1");
        assert_eq!(show("1"), "1");
        assert_eq!(show("1/s"), "1/s");
        assert_eq!(show("Pa"), "kg/m·s²");
        assert_eq!(show("mm"), "m");
        assert_eq!(
            parse_unit("mm").map(|d| d.scale),
            Ok(BigRational::new(1.into(), 1000.into()))
        );
        assert_eq!(parse_unit("kN").map(|d| d.scale), Ok(q(1000)));
        assert_eq!(show("g"), "kg");
        assert_eq!(show("s^-1"), "1/s");
    }

    #[test]
    fn bad_units_say_why() {
        assert!(
            show("kgg").contains("unknown unit `kgg`"),
            "{}",
            show("kgg")
        );
        assert!(
            show("N m/s/s").contains("second `/`"),
            "{}",
            show("N m/s/s")
        );
        assert!(show("Nm").contains("unknown unit `Nm`"), "{}", show("Nm"));
        assert!(show("").contains("empty"));
        assert!(
            show("m + s").contains("unexpected `+`"),
            "{}",
            show("m + s")
        );
        assert!(show("mtr").contains("did you mean"), "{}", show("mtr"));
    }
}

#[cfg(test)]
mod latex_tests {
    use super::unit_latex;

    #[test]
    fn units_are_typeset_upright_with_thin_spaces() {
        assert_eq!(unit_latex("kg m^2"), r"\mathrm{kg}\,\mathrm{m}^{2}");
        assert_eq!(unit_latex("m/s^2"), r"\mathrm{m}/\mathrm{s}^{2}");
        assert_eq!(unit_latex("N"), r"\mathrm{N}");
        assert_eq!(
            unit_latex("kg*m/s^2"),
            r"\mathrm{kg}\,\mathrm{m}/\mathrm{s}^{2}"
        );
        assert_eq!(unit_latex("m^(1/2)"), r"\mathrm{m}^{1/2}");
        assert_eq!(unit_latex("1"), "1");
    }
}
