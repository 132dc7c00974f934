//! Printers of normal forms: plain text that rigor parses back, and LaTeX.
//!
//! Both order terms and factors by content ([`cmp_atoms`]), never by interned
//! ids, so equal values print identically in every run.

use super::atom::{cmp_atoms, get, Atom, AtomId};
use super::mono::Mono;
use super::poly::{Poly, Q};
use super::rat::Rat;
use num_bigint::{BigInt, BigUint};
use num_traits::{One, Signed, ToPrimitive};
use std::borrow::Cow;
use std::cell::OnceCell;
use std::cmp::Ordering;
use std::fmt::Write as _;

/// Output syntax.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Style {
    /// rigor's own expression syntax.
    Plain,
    /// LaTeX math.
    Latex,
}

/// Factors of a monomial in print order.
fn sorted_factors(m: &Mono) -> Vec<(AtomId, u32)> {
    let mut f: Vec<(AtomId, u32)> = m.pairs().to_vec();
    f.sort_by(|a, b| cmp_atoms(a.0, b.0));
    f
}

/// Terms of a polynomial in print order.
#[cfg(test)]
fn print_terms(p: &Poly) -> Vec<(Mono, Q)> {
    PrintKeys::of(p)
        .order()
        .into_iter()
        .map(|i| p.terms()[i].clone())
        .collect()
}

/// The first term of `p` in print order.
fn first_print_term(p: &Poly) -> Option<&(Mono, Q)> {
    let keys = PrintKeys::of(p);
    (0..p.len())
        .min_by(|&i, &j| keys.cmp(i, j))
        .map(|i| &p.terms()[i])
}

/// The sort keys of a polynomial's terms. A term's key is its degree and its factors as
/// `(rank, slot, exponent)` in print order, where `rank` numbers the polynomial's atoms
/// in [`cmp_atoms`] order (atoms that compare equal share a rank) and `slot` is the
/// atom's place in `atoms`. Comparing keys ([`PrintKeys::cmp`]) is [`cmp_monos`] without
/// comparing atoms again for every pair of terms. The factors of all the terms share one
/// list, so a long polynomial costs two allocations, not one per term.
struct PrintKeys {
    /// The polynomial's atoms in [`cmp_atoms`] order.
    atoms: Vec<AtomId>,
    /// Each term's degree and the range of its factors in `factors`.
    terms: Vec<(u64, usize, usize)>,
    factors: Vec<(usize, usize, u32)>,
}

impl PrintKeys {
    fn of(p: &Poly) -> PrintKeys {
        let mut atoms = p.atoms();
        atoms.sort_by(|a, b| cmp_atoms(*a, *b));
        // (atom, rank, slot), by atom id.
        let mut ranks: Vec<(AtomId, usize, usize)> = Vec::with_capacity(atoms.len());
        for (i, &a) in atoms.iter().enumerate() {
            let rank = match (i.checked_sub(1).and_then(|j| atoms.get(j)), ranks.last()) {
                (Some(&prev), Some(&(_, r, _))) if cmp_atoms(prev, a) == Ordering::Equal => r,
                _ => i,
            };
            ranks.push((a, rank, i));
        }
        ranks.sort_unstable_by_key(|t| t.0);
        let rank_of = |a: AtomId| {
            ranks
                .binary_search_by_key(&a, |t| t.0)
                .map_or((usize::MAX, usize::MAX), |i| (ranks[i].1, ranks[i].2))
        };
        let pairs = p.terms().iter().map(|(m, _)| m.pairs().len()).sum();
        let mut factors: Vec<(usize, usize, u32)> = Vec::with_capacity(pairs);
        let mut terms = Vec::with_capacity(p.len());
        for (m, _) in p.terms() {
            let start = factors.len();
            factors.extend(m.pairs().iter().map(|&(a, e)| {
                let (rank, slot) = rank_of(a);
                (rank, slot, e)
            }));
            // A stable sort, as `sorted_factors`: equal ranks keep the id order.
            factors[start..].sort_by_key(|t| t.0);
            terms.push((m.degree(), start, factors.len()));
        }
        PrintKeys {
            atoms,
            terms,
            factors,
        }
    }

    /// Term `i`'s factors in print order.
    fn factors(&self, i: usize) -> &[(usize, usize, u32)] {
        let (_, start, end) = self.terms[i];
        &self.factors[start..end]
    }

    /// [`cmp_monos`] of terms `i` and `j`.
    fn cmp(&self, i: usize, j: usize) -> Ordering {
        let (a, b) = (self.factors(i), self.factors(j));
        self.terms[j].0.cmp(&self.terms[i].0).then_with(|| {
            for (x, y) in a.iter().zip(b.iter()) {
                let o = x.0.cmp(&y.0).then(y.2.cmp(&x.2));
                if o != Ordering::Equal {
                    return o;
                }
            }
            b.len().cmp(&a.len())
        })
    }

    /// The indices of the terms in print order.
    fn order(&self) -> Vec<usize> {
        let mut order: Vec<usize> = (0..self.terms.len()).collect();
        // Ties (atoms that print alike) keep the terms' order, as a stable sort would.
        order.sort_unstable_by(|&i, &j| self.cmp(i, j).then(i.cmp(&j)));
        order
    }
}

/// The plain text of a normal form.
pub fn plain(r: &Rat) -> String {
    render(r, Style::Plain)
}

/// The LaTeX of a normal form.
pub fn latex(r: &Rat) -> String {
    render(r, Style::Latex)
}

/// Prints a normal form.
pub fn render(r: &Rat, style: Style) -> String {
    if r.den().is_one() {
        return poly(r.num(), style);
    }
    let (num, den) = (oriented_factors(r.num()), oriented_factors(r.den()));
    // value = (a/b) · num' / den' with num', den' primitive and their first printed term positive.
    let (cn, num) = primitive_for_print(&num);
    let (cd, den) = primitive_for_print(&den);
    let k = cn / cd;
    let (a, b) = (k.numer().clone(), k.denom().clone());
    let neg = a.is_negative();
    let a = a.abs();
    let num_single = num.len() == 1;
    let num_text = if num_single {
        let (m, _) = &num.terms()[0];
        term(m, &Q::from_integer(a.clone()), style)
    } else if a.is_one() {
        poly_as_is(&num, style)
    } else {
        match style {
            Style::Plain => format!("{} ({})", a, poly_as_is(&num, style)),
            Style::Latex => format!("{} \\left({}\\right)", a, poly_as_is(&num, style)),
        }
    };
    let den_poly = den.scale(&Q::from_integer(b.clone()));
    let den_text = poly_as_is(&den_poly, style);
    let sign = if neg { "-" } else { "" };
    match style {
        Style::Latex => format!("{sign}\\frac{{{num_text}}}{{{den_text}}}"),
        Style::Plain => {
            let num_text = if num_single || a.is_one() && num.len() == 1 {
                num_text
            } else if a.is_one() {
                format!("({num_text})")
            } else {
                num_text
            };
            let den_atomic = den_poly.len() == 1
                && den_poly.terms()[0].1.is_one()
                && den_poly.terms()[0].0.pairs().len() == 1
                && den_poly.terms()[0].0.pairs()[0].1 == 1;
            let den_text = if den_atomic {
                den_text
            } else {
                format!("({den_text})")
            };
            format!("{sign}{num_text}/{den_text}")
        }
    }
}

/// `p = c · p'` with `p'` having integer coprime coefficients and a positive first printed term.
fn primitive_for_print(p: &Poly) -> (Q, Poly) {
    let mut c = p.content();
    if first_print_term(p).is_some_and(|t| t.1.is_negative()) {
        c = -c;
    }
    (c.clone(), p.scale(&c.recip()))
}

/// Whether a kept factor's sum prints with a negative first term, so that it is printed
/// negated: `(x - a)` rather than the `(a - x)` the normal form may hold.
fn reads_negated(p: &Poly) -> bool {
    first_print_term(&oriented_factors(p)).is_some_and(|t| t.1.is_negative())
}

/// `p` with the sign of each term adjusted for the kept factors printed negated (an odd
/// power of a negated factor changes the term's sign). Printing only: the atoms
/// themselves are not changed, so the result is not `p`'s value.
fn oriented_factors(p: &Poly) -> Cow<'_, Poly> {
    let flips: Vec<AtomId> = p
        .atoms()
        .into_iter()
        .filter(|a| matches!(get(*a), Atom::Factor(s) if reads_negated(s)))
        .collect();
    if flips.is_empty() {
        return Cow::Borrowed(p);
    }
    Cow::Owned(Poly::from_terms(
        p.terms()
            .iter()
            .map(|(m, q)| {
                let odd = flips.iter().filter(|a| m.exp(**a) % 2 == 1).count() % 2 == 1;
                (m.clone(), if odd { -q } else { q.clone() })
            })
            .collect(),
    ))
}

/// A polynomial as a sum of terms.
pub fn poly(p: &Poly, style: Style) -> String {
    poly_as_is(&oriented_factors(p), style)
}

/// A polynomial as a sum of terms, its kept factors' signs already oriented.
fn poly_as_is(p: &Poly, style: Style) -> String {
    let mut out = String::new();
    write_poly(&mut out, p, style);
    out
}

/// Writes a polynomial as a sum of terms into `out`, in one pass over the terms in print
/// order: each atom's text is made once, and numbers are written in place, so the time
/// is linear in the length of the text (after the sort of the terms).
fn write_poly(out: &mut String, p: &Poly, style: Style) {
    if p.is_empty() {
        out.push('0');
        return;
    }
    let keys = PrintKeys::of(p);
    let infos: Vec<AtomPrint> = keys.atoms.iter().map(|&a| AtomPrint::new(a)).collect();
    out.reserve(p.len() * 8 + keys.factors.len() * 4);
    for (i, k) in keys.order().into_iter().enumerate() {
        let q = &p.terms()[k].1;
        let neg = q.is_negative();
        if i == 0 {
            if neg {
                out.push('-');
            }
        } else {
            out.push_str(if neg { " - " } else { " + " });
        }
        let factors = keys.factors(k).iter().map(|f| (&infos[f.1], f.2));
        write_term(out, factors, q.numer().magnitude(), q.denom(), style);
    }
}

/// One term `q·m` with `q > 0`.
fn term(m: &Mono, q: &Q, style: Style) -> String {
    let f = sorted_factors(m);
    let infos: Vec<AtomPrint> = f.iter().map(|t| AtomPrint::new(t.0)).collect();
    let mut s = String::new();
    let factors = infos.iter().zip(f.iter().map(|t| t.1));
    write_term(&mut s, factors, q.numer().magnitude(), q.denom(), style);
    s
}

/// What printing a factor needs of its atom, made once per polynomial.
struct AtomPrint {
    atom: &'static Atom,
    /// A square root of a whole number below 10 000: merged with the term's other such
    /// roots (to the first power) into one, which the parser splits back into the same primes.
    radicand: Option<BigInt>,
    /// The atom's text in each style, made when first needed.
    text: [OnceCell<String>; 2],
}

impl AtomPrint {
    fn new(a: AtomId) -> AtomPrint {
        let atom = get(a);
        let radicand = match atom {
            Atom::Sqrt(p) => p
                .as_constant()
                .filter(|c| c.is_integer() && c.to_integer() < BigInt::from(10_000))
                .map(|c| c.to_integer()),
            _ => None,
        };
        AtomPrint {
            atom,
            radicand,
            text: [OnceCell::new(), OnceCell::new()],
        }
    }

    fn text(&self, style: Style) -> &str {
        self.text[style as usize].get_or_init(|| atom_text(self.atom, style))
    }
}

/// Writes one term from its factors in print order and its coefficient `n/d` (`n > 0`):
/// `3 a^2 b/2`, `\frac{3 a^{2} b}{2}`; numeric square roots merged (`sqrt(2) sqrt(3)` →
/// `sqrt(6)`, written first).
fn write_term<'a>(
    out: &mut String,
    factors: impl Iterator<Item = (&'a AtomPrint, u32)> + Clone,
    n: &BigUint,
    d: &BigInt,
    style: Style,
) {
    let mut radical = BigInt::one();
    let mut others = 0usize;
    for (info, e) in factors.clone() {
        match (&info.radicand, e) {
            (Some(c), 1) => radical *= c,
            _ => others += 1,
        }
    }
    if others == 0 && radical.is_one() {
        let q = Q::new(BigInt::from(n.clone()), d.clone());
        out.push_str(&number(&q, style));
        return;
    }
    let frac = style == Style::Latex && !d.is_one();
    if frac {
        out.push_str("\\frac{");
    }
    if !n.is_one() {
        write_uint(out, n);
        out.push(' ');
    }
    let mut first = true;
    if !radical.is_one() {
        match style {
            Style::Plain => out.push_str("sqrt("),
            Style::Latex => out.push_str("\\sqrt{"),
        }
        write_int(out, &radical);
        out.push(if style == Style::Plain { ')' } else { '}' });
        first = false;
    }
    for (info, e) in factors {
        if info.radicand.is_some() && e == 1 {
            continue;
        }
        if !first {
            out.push(' ');
        }
        first = false;
        write_factor(out, info, e, style);
    }
    if frac {
        out.push_str("}{");
        write_int(out, d);
        out.push('}');
    } else if !d.is_one() {
        out.push('/');
        write_int(out, d);
    }
}

/// One factor `atom^e` of a term.
fn write_factor(out: &mut String, info: &AtomPrint, e: u32, style: Style) {
    if let (Atom::Root(p, n), true) = (info.atom, e > 1) {
        // A power of a root as one fractional power: (z)^(2/3), \sqrt[3]{z^{2}}.
        let _ = match style {
            Style::Plain => write!(out, "({})^({e}/{n})", poly(p, style)),
            Style::Latex => {
                let inner = if p.len() == 1 {
                    poly(p, style)
                } else {
                    paren(&poly(p, style), style)
                };
                write!(out, "\\sqrt[{n}]{{{inner}^{{{e}}}}}")
            }
        };
        return;
    }
    let base = info.text(style);
    if e == 1 {
        out.push_str(base);
        return;
    }
    let parens;
    let base = if needs_parens_for_power(info.atom) {
        parens = paren(base, style);
        parens.as_str()
    } else {
        base
    };
    match style {
        Style::Plain => {
            out.push_str(base);
            out.push('^');
            write_u64(out, u64::from(e));
        }
        Style::Latex => {
            let (f, rest) = match base.strip_prefix("\\sin").or(base.strip_prefix("\\cos")) {
                // \sin^2\beta
                Some(rest) => (&base[..4], rest),
                None => (base, ""),
            };
            out.push_str(f);
            out.push_str("^{");
            write_u64(out, u64::from(e));
            out.push('}');
            out.push_str(rest);
        }
    }
}

/// A machine word in decimal, without the formatting machinery.
fn write_u64(out: &mut String, mut v: u64) {
    let mut buf = [0u8; 20];
    let mut i = buf.len();
    loop {
        i -= 1;
        buf[i] = b'0' + (v % 10) as u8;
        v /= 10;
        if v == 0 {
            break;
        }
    }
    out.extend(buf[i..].iter().map(|&b| char::from(b)));
}

/// A whole number, in decimal.
fn write_uint(out: &mut String, n: &BigUint) {
    match n.to_u64() {
        Some(v) => write_u64(out, v),
        None => {
            let _ = write!(out, "{n}");
        }
    }
}

/// A whole number, in decimal, with its sign.
fn write_int(out: &mut String, n: &BigInt) {
    if n.is_negative() {
        out.push('-');
    }
    write_uint(out, n.magnitude());
}

fn number(q: &Q, style: Style) -> String {
    match style {
        Style::Plain => {
            if q.denom().is_one() {
                q.numer().to_string()
            } else {
                format!("{}/{}", q.numer(), q.denom())
            }
        }
        Style::Latex => {
            if q.denom().is_one() {
                q.numer().to_string()
            } else {
                let sign = if q.is_negative() { "-" } else { "" };
                format!("{sign}\\frac{{{}}}{{{}}}", q.numer().abs(), q.denom())
            }
        }
    }
}

fn needs_parens_for_power(a: &Atom) -> bool {
    matches!(a, Atom::Pow(..) | Atom::Root(..))
}

fn paren(s: &str, style: Style) -> String {
    match style {
        Style::Plain => format!("({s})"),
        Style::Latex => format!("\\left({s}\\right)"),
    }
}

/// Whether a normal form prints as a single factor (no parentheses needed as an argument of `^`).
fn is_atomic(r: &Rat) -> bool {
    r.den().is_one()
        && r.num().len() == 1
        && r.num().terms()[0].1.is_one()
        && r.num().terms()[0].0.pairs().len() == 1
        && r.num().terms()[0].0.pairs()[0].1 == 1
}

/// The plain text of one atom.
pub fn atom_plain(a: &Atom) -> String {
    atom_text(a, Style::Plain)
}

fn atom_text(a: &Atom, style: Style) -> String {
    let plain = style == Style::Plain;
    match a {
        Atom::Sym(s) => {
            if plain {
                s.clone()
            } else {
                symbol_latex(s)
            }
        }
        Atom::Pi => if plain { "pi" } else { "\\pi" }.into(),
        Atom::Sqrt(p) => {
            if plain {
                format!("sqrt({})", poly(p, style))
            } else {
                format!("\\sqrt{{{}}}", poly(p, style))
            }
        }
        Atom::Root(p, n) => {
            if plain {
                format!("({})^(1/{n})", poly(p, style))
            } else {
                format!("\\sqrt[{n}]{{{}}}", poly(p, style))
            }
        }
        // A kept factor prints as its sum in parentheses: `(x - a)^6000`.
        Atom::Factor(p) => {
            let p = if reads_negated(p) { p.neg() } else { p.clone() };
            paren(&poly(&p, style), style)
        }
        Atom::Abs(p) => {
            // |p| = |−p|: printed with a positive first term, `abs(a - b)`, whichever sign
            // the normal form holds (that depends on the order atoms were made in).
            let p = &if reads_negated(p) { p.neg() } else { p.clone() };
            if plain {
                format!("abs({})", poly(p, style))
            } else {
                format!("\\left|{}\\right|", poly(p, style))
            }
        }
        Atom::Sin(u) | Atom::Cos(u) | Atom::Ln(u) => {
            let name = match a {
                Atom::Sin(_) => "sin",
                Atom::Cos(_) => "cos",
                _ => "ln",
            };
            if plain {
                format!("{name}({})", render(u, style))
            } else if is_atomic(u) {
                format!("\\{name} {}", render(u, style))
            } else {
                format!("\\{name}\\left({}\\right)", render(u, style))
            }
        }
        Atom::Exp(u) => {
            if plain {
                format!("exp({})", render(u, style))
            } else {
                format!("e^{{{}}}", render(u, style))
            }
        }
        Atom::Pow(b, e) => {
            let bt = render(b, style);
            let bt = if is_atomic(b) && b.num().terms()[0].0.pairs().len() == 1 {
                bt
            } else {
                paren(&bt, style)
            };
            let et = render(e, style);
            if plain {
                let et = if e
                    .as_constant()
                    .is_some_and(|q| q.is_integer() && !q.is_negative())
                    || is_atomic(e)
                {
                    et
                } else {
                    format!("({et})")
                };
                format!("{bt}^{et}")
            } else {
                format!("{bt}^{{{et}}}")
            }
        }
        Atom::At(name, u) => {
            if plain {
                format!("subs({name}, t, {})", render(u, style))
            } else {
                format!("{}\\left({}\\right)", symbol_latex(name), render(u, style))
            }
        }
        Atom::Moment(body, exps) => {
            let inner = moment_integrand(exps, style);
            if plain {
                format!("int({inner}, {body})")
            } else {
                let inner = if inner == "1" { String::new() } else { inner };
                format!("\\int_{{{}}} {inner} \\, dm", symbol_latex(body))
            }
        }
    }
}

fn moment_integrand(exps: &[(String, u32)], style: Style) -> String {
    let mut parts = Vec::new();
    for (name, e) in exps {
        let name = match style {
            Style::Plain => name.clone(),
            Style::Latex => symbol_latex(name),
        };
        match (e, style) {
            (0, _) => {}
            (1, _) => parts.push(name),
            (e, Style::Plain) => parts.push(format!("{name}^{e}")),
            (e, Style::Latex) => parts.push(format!("{name}^{{{e}}}")),
        }
    }
    if parts.is_empty() {
        "1".into()
    } else {
        parts.join(" ")
    }
}

const GREEK: &[&str] = &[
    "alpha", "beta", "gamma", "delta", "epsilon", "zeta", "eta", "theta", "iota", "kappa",
    "lambda", "mu", "nu", "xi", "pi", "rho", "sigma", "tau", "upsilon", "phi", "chi", "psi",
    "omega", "Gamma", "Delta", "Theta", "Lambda", "Xi", "Pi", "Sigma", "Phi", "Psi", "Omega",
];

fn name_latex(s: &str) -> String {
    if GREEK.contains(&s) {
        format!("\\{s}")
    } else if s.chars().count() > 1 && s.chars().all(|c| c.is_ascii_alphabetic()) {
        format!("\\mathit{{{s}}}")
    } else {
        s.to_string()
    }
}

/// A symbol name in LaTeX: Greek letters, subscripts, and primes as dots.
pub fn symbol_latex(s: &str) -> String {
    let primes = s.chars().rev().take_while(|c| *c == '\'').count();
    let s = &s[..s.len() - primes];
    let (base, sub) = match s.split_once('_') {
        Some((b, rest)) => (b, Some(rest)),
        None => (s, None),
    };
    let mut out = name_latex(base);
    out = match primes {
        0 => out,
        1 => format!("\\dot{{{out}}}"),
        2 => format!("\\ddot{{{out}}}"),
        3 => format!("\\dddot{{{out}}}"),
        n => format!("{out}^{{({n})}}"),
    };
    if let Some(sub) = sub {
        let parts: Vec<String> = sub.split('_').map(name_latex).collect();
        let sub = parts.join(",");
        out = format!("{out}_{{{sub}}}");
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::normal::atom::{intern, sym};
    use num_traits::Zero;
    use proptest::prelude::*;

    /// Print order of monomials: higher degree first, then by content.
    fn cmp_monos(a: &Mono, b: &Mono) -> Ordering {
        b.degree().cmp(&a.degree()).then_with(|| {
            let (fa, fb) = (sorted_factors(a), sorted_factors(b));
            for (x, y) in fa.iter().zip(fb.iter()) {
                let o = cmp_atoms(x.0, y.0).then(y.1.cmp(&x.1));
                if o != Ordering::Equal {
                    return o;
                }
            }
            fb.len().cmp(&fa.len())
        })
    }

    /// Atoms whose print order is not their id order: mixed case, and atoms of
    /// other kinds (compared by their text).
    fn atoms() -> Vec<AtomId> {
        let mut v: Vec<AtomId> = ["b", "A", "a", "B", "x2", "x10"]
            .iter()
            .map(|n| sym(n))
            .collect();
        v.push(intern(Atom::Sqrt(Poly::atom(sym("b")))));
        v.push(intern(Atom::Sqrt(Poly::atom(sym("A")))));
        v
    }

    proptest! {
        /// The keyed sort is the comparison sort it replaces, term for term.
        #[test]
        fn keyed_order_is_the_monomial_comparison(
            ts in proptest::collection::vec(
                (proptest::collection::vec((0usize..8, 1u32..4), 0..4), 1i64..5), 0..12)
        ) {
            let ids = atoms();
            let p = Poly::from_terms(
                ts.into_iter()
                    .filter_map(|(m, c)| {
                        let m = m.into_iter().map(|(i, e)| (ids[i], e)).collect();
                        Some((Mono::from_pairs(m)?, Q::from_integer(BigInt::from(c))))
                    })
                    .filter(|t| !t.1.is_zero())
                    .collect(),
            );
            let mut want: Vec<(Mono, Q)> = p.terms().to_vec();
            want.sort_by(|a, b| cmp_monos(&a.0, &b.0));
            prop_assert_eq!(print_terms(&p), want.clone());
            prop_assert_eq!(first_print_term(&p), want.first());
        }
    }
}
