//! Signs: of a difference (term-wise from the declared signs, constants by a rigorous
//! enclosure), the part of a divisor the signs do not show nonzero, and whether a value
//! respects the sign declared for the symbol it replaces.

use crate::normal::print::plain;
use crate::normal::{Rat, Sign, Q};
use foldhash::{HashMap, HashMapExt};
use num_traits::One;

/// Whether `value` satisfies the sign declared for `name`; the message says why not.
pub(super) fn respects_sign(
    name: &str,
    declared: Sign,
    value: &Rat,
    signs: &crate::normal::Assumptions,
) -> Result<(), String> {
    let s = sign_of(value, signs);
    let (ok, what) = match declared {
        Sign::Pos => (s == Sign::Pos, "> 0"),
        Sign::NonNeg => (s.is_nonneg(), ">= 0"),
        Sign::NonZero => (s.is_nonzero(), "!= 0"),
        Sign::Neg => (s == Sign::Neg, "< 0"),
        Sign::NonPos => (s.is_nonpos(), "<= 0"),
        Sign::Zero => (value.is_zero(), "= 0"),
        Sign::Unknown => (true, ""),
    };
    if ok {
        Ok(())
    } else {
        Err(format!(
            "`{name}` is declared {what}, but {} is not shown to be {what}; results that used the sign of `{name}` would not carry over",
            plain(value)
        ))
    }
}

/// The sign and the interval that `symbols lo < x < hi` (`<=` where a bound is not
/// strict) declares, as `check` reads it; the message says why the interval is refused.
/// `lo` and `hi` are the bounds with whether each is excluded.
pub fn interval(
    (l, lo_strict): (Rat, bool),
    (h, hi_strict): (Rat, bool),
    signs: &crate::normal::Assumptions,
) -> Result<(Sign, crate::normal::Range), String> {
    let (sl, sh) = (sign_of(&l, signs), sign_of(&h, signs));
    let empty = l.sub(&h).is_ok_and(|d| {
        let s = sign_of(&d, signs);
        s == Sign::Pos || (s.is_nonneg() && (lo_strict || hi_strict))
    });
    if empty {
        return Err(format!(
            "the interval from {} to {} is empty",
            plain(&l),
            plain(&h)
        ));
    }
    let above = match sl {
        Sign::Pos => Sign::Pos,
        Sign::NonNeg | Sign::Zero if lo_strict => Sign::Pos,
        Sign::NonNeg | Sign::Zero => Sign::NonNeg,
        _ => Sign::Unknown,
    };
    let below = match sh {
        Sign::Neg => Sign::Neg,
        Sign::NonPos | Sign::Zero if hi_strict => Sign::Neg,
        Sign::NonPos | Sign::Zero => Sign::NonPos,
        _ => Sign::Unknown,
    };
    let sign = if above != Sign::Unknown { above } else { below };
    Ok((
        sign,
        crate::normal::Range {
            lo: l,
            lo_strict,
            hi: h,
            hi_strict,
        },
    ))
}

pub(super) fn describe(s: Sign) -> &'static str {
    match s {
        Sign::Zero => "zero",
        Sign::Pos => "positive",
        Sign::Neg => "negative",
        Sign::NonNeg => "nonnegative (it may be zero)",
        Sign::NonPos => "nonpositive (it may be zero)",
        Sign::NonZero => "nonzero but of unknown sign",
        Sign::Unknown => "not determined by the declared signs",
    }
}

/// The part of a divisor whose nonzeroness the signs do not show: the numerator with
/// constant and monomial factors of nonzero sign dropped (`None` if nothing is left).
pub(super) fn essential_factor(d: &Rat, signs: &crate::normal::Assumptions) -> Option<Rat> {
    if signs.rat(d).is_nonzero() || d.as_constant().is_some() {
        return None;
    }
    let n = d.num();
    let mc = n.mono_content();
    let rest = n.div_mono(&mc).unwrap_or_else(|| n.clone()).primitive();
    let mut keep = Vec::new();
    for &(a, e) in mc.pairs() {
        if !signs.atom(a).is_nonzero() {
            keep.push((a, e));
        }
    }
    let keep = crate::normal::mono::Mono::from_pairs(keep)?;
    let out = Rat::poly(rest.mul_term(&keep, &Q::one()).ok()?).ok()?;
    if out.as_constant().is_some() || signs.rat(&out).is_nonzero() {
        return None;
    }
    Some(out)
}

/// The sign of `d`: term-wise from the declared signs, where constant factors such as
/// `1 − sqrt(2)/2` get their sign from a rigorous enclosure.
pub(super) fn sign_of(d: &Rat, signs: &crate::normal::Assumptions) -> Sign {
    let s = signs.rat(d);
    if s != Sign::Unknown && s != Sign::NonZero {
        return s;
    }
    let n = grouped_sign(d.num(), signs);
    let den = grouped_sign(d.den(), signs);
    let den = match den {
        Sign::NonNeg => Sign::Pos,
        Sign::NonPos => Sign::Neg,
        x => x,
    };
    match (n, den) {
        (_, Sign::Unknown | Sign::NonZero) | (Sign::Unknown, _) => s,
        (n, den) => n.times(den),
    }
}

/// Groups the terms of `p` by their symbolic factor; each group's coefficient is a
/// constant (numbers, `pi`, numeric radicals) whose sign an enclosure decides.
fn grouped_sign(p: &crate::normal::Poly, signs: &crate::normal::Assumptions) -> Sign {
    use crate::normal::mono::Mono;
    let mut groups: Vec<(Mono, Vec<(Mono, Q)>)> = Vec::new();
    for (m, q) in p.terms() {
        let (mut sym, mut cst) = (Vec::new(), Vec::new());
        for &(a, e) in m.pairs() {
            let mut found = Vec::new();
            crate::decide::symbols_in(&Rat::atom(a), &mut found);
            if found.is_empty() {
                cst.push((a, e));
            } else {
                sym.push((a, e));
            }
        }
        let (Some(sym), Some(cst)) = (Mono::from_pairs(sym), Mono::from_pairs(cst)) else {
            return Sign::Unknown;
        };
        match groups.iter_mut().find(|g| g.0 == sym) {
            Some(g) => g.1.push((cst, q.clone())),
            None => groups.push((sym, vec![(cst, q.clone())])),
        }
    }
    let point = HashMap::new();
    let mut total = Sign::Zero;
    for (sym, coeff) in groups {
        let c = crate::normal::Poly::from_terms(coeff);
        let mut ev = crate::decide::Evaluator::new(&point);
        let cs = match Rat::poly(c).ok().and_then(|r| ev.rat(&r)) {
            Some(v) if v.is_positive() => Sign::Pos,
            Some(v) if v.is_negative() => Sign::Neg,
            _ => return Sign::Unknown,
        };
        let mut s = cs;
        for &(a, e) in sym.pairs() {
            s = s.times(signs.atom(a).pow(e));
        }
        total = total.plus(s);
    }
    total
}
