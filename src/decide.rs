//! Deciding `A = B`: equal by normal form, not equal by an exact argument or a
//! checked counterexample, else undecided. Nothing is ever decided equal by sampling.

use crate::diag::Mistake;
use crate::interval::{Interval, Prec};
use crate::lower::Need;
use crate::normal::atom::{self, Atom, AtomId};
use crate::normal::print::plain;
use crate::normal::{Assumptions, Poly, Rat, Sign, Q};
use foldhash::{HashMap, HashMapExt};
use num_bigint::BigInt;
use num_traits::{One, ToPrimitive, Zero};
use std::collections::BTreeMap;

/// Values of the symbols at which two sides differ, and the sides' values there.
#[derive(Clone, Debug, PartialEq)]
pub struct Counterexample {
    /// `symbol = value`, sorted by name.
    pub values: Vec<(String, Q)>,
    /// The left side's value (exact, or a decimal approximation with `≈`).
    pub lhs: String,
    /// The right side's value.
    pub rhs: String,
}

impl Counterexample {
    /// The note that states it (`counterexample: at m = 2 the left side is …`).
    pub fn note(&self) -> crate::diag::Note {
        crate::diag::Note::Counterexample {
            at: self
                .values
                .iter()
                .map(|(n, q)| (n.clone(), show_q(q)))
                .collect(),
            left: self.lhs.clone(),
            right: self.rhs.clone(),
        }
    }

    /// `m = 2, L = 3`.
    pub fn assignment(&self) -> String {
        self.values
            .iter()
            .map(|(n, q)| format!("{n} = {}", show_q(q)))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

fn show_q(q: &Q) -> String {
    if q.denom().is_one() {
        q.numer().to_string()
    } else {
        format!("{}/{}", q.numer(), q.denom())
    }
}

/// The answer to `A = B`.
#[derive(Clone, Debug, PartialEq)]
pub enum Verdict {
    /// `A − B` normalises to exactly zero.
    Equal,
    /// Established unequal.
    NotEqual {
        /// `A − B` in normal form.
        difference: Rat,
        /// Whether the difference is a nonzero rational function of independent atoms.
        exact: bool,
        /// A checked counterexample, where one was found.
        counterexample: Option<Counterexample>,
        /// What the difference says went wrong, when it is simple.
        diagnosis: Option<Diagnosis>,
    },
    /// Neither could be established.
    Undecided {
        /// Why.
        why: String,
    },
}

/// `v` with its counterexample re-checked by `stands` (the guard, on the values as
/// `f64`s) before anyone prints it: a counterexample that does not stand is dropped, and
/// then "not equal" needs the exact argument, else the answer is undecided.
pub fn guarded(
    v: Verdict,
    stands: impl Fn(&HashMap<String, f64>) -> Result<(), String>,
) -> Verdict {
    let Verdict::NotEqual {
        difference,
        exact,
        counterexample: Some(c),
        diagnosis,
    } = v
    else {
        return v;
    };
    if c.values.is_empty() {
        return Verdict::NotEqual {
            difference,
            exact,
            counterexample: Some(c),
            diagnosis,
        };
    }
    let point: Option<HashMap<String, f64>> = c
        .values
        .iter()
        .map(|(n, q)| Some((n.clone(), q.to_f64()?)))
        .collect();
    let why = match point.map(|p| stands(&p)) {
        Some(Ok(())) => {
            return Verdict::NotEqual {
                difference,
                exact,
                counterexample: Some(c),
                diagnosis,
            }
        }
        Some(Err(why)) => why,
        None => "its values are out of floating-point range".into(),
    };
    if exact {
        return Verdict::NotEqual {
            difference,
            exact,
            counterexample: None,
            diagnosis,
        };
    }
    Verdict::Undecided {
        why: format!(
            "the difference {} is not zero in normal form, but the one counterexample found ({}) is not confirmed: {why}",
            plain(&difference),
            c.assignment()
        ),
    }
}

/// Decides `a = b` under the declared signs.
pub fn decide(a: &Rat, b: &Rat, s: &Assumptions) -> Verdict {
    decide_where(a, b, s, &[])
}

/// Decides `a = b` where the sides are defined: a counterexample must also satisfy
/// `defined` (divisors nonzero, arguments of `ln` positive, of square roots nonnegative).
pub fn decide_where(a: &Rat, b: &Rat, s: &Assumptions, defined: &[(Rat, Need)]) -> Verdict {
    decide_with(a, b, s, defined, true)
}

/// The verdict alone, as fast as possible: when the difference is a nonzero rational
/// function of independent atoms, "not equal" needs no counterexample, so none is
/// searched for and no diagnosis is written (for bulk decisions; the verdict is the
/// same as [`decide`]'s).
pub fn decide_verdict(a: &Rat, b: &Rat, s: &Assumptions) -> Verdict {
    decide_with(a, b, s, &[], false)
}

fn decide_with(
    a: &Rat,
    b: &Rat,
    s: &Assumptions,
    defined: &[(Rat, Need)],
    explain: bool,
) -> Verdict {
    let d = match a.sub(b) {
        Ok(d) => d,
        Err(e) => {
            return Verdict::Undecided {
                why: format!("could not form the difference: {e}"),
            }
        }
    };
    if d.is_zero() {
        return Verdict::Equal;
    }
    // Related angles, large powers kept factored, products of abs and roots.
    let d = crate::normal::settle(&d, s);
    if d.is_zero() || zero_where_defined(&d, s, defined) {
        return Verdict::Equal;
    }
    // Square roots of integers that share a factor (sqrt(p) sqrt(q) against sqrt(p q),
    // p and q primes too large to find by trial division): over a coprime basis.
    let d = match coprime_radicals(&d) {
        Some(r) if r.is_zero() => return Verdict::Equal,
        Some(r) => r,
        None => d,
    };
    // A nonzero function of independent quantities is nonzero somewhere in the region
    // the declarations allow only when that region has interior.
    let mut syms = Vec::new();
    symbols_in(&d, &mut syms);
    let interior = crate::normal::ranges::have_interior(s, &syms);
    let exact = independent(&d) && interior;
    if exact && !explain {
        return Verdict::NotEqual {
            difference: d,
            exact,
            counterexample: None,
            diagnosis: None,
        };
    }
    let counterexample = find_counterexample_where(a, b, s, defined);
    if !exact && counterexample.is_none() && !interior {
        return Verdict::Undecided {
            why: format!(
                "the difference {} is not zero in normal form, but the declared intervals may leave no room for it to be nonzero (an interval of one point, or bounds rigor cannot compare), and no checked counterexample was found",
                plain(&d)
            ),
        };
    }
    if !exact && counterexample.is_none() {
        let dependent: Vec<String> = d
            .atoms()
            .into_iter()
            .filter(|x| !independent_atom(*x))
            .map(|x| crate::normal::print::atom_plain(atom::get(x)))
            .collect();
        return Verdict::Undecided {
            why: format!(
                "the difference {} is not zero in normal form, but it involves {}, between which rigor cannot rule out further relations, and no checked counterexample was found",
                plain(&d),
                dependent.join(", ")
            ),
        };
    }
    Verdict::NotEqual {
        diagnosis: diagnose(a, b, &d),
        difference: d,
        exact,
        counterexample,
    }
}

/// Whether `d` is zero wherever the conditions `defined` hold (each `ln`'s argument
/// positive, divisors nonzero, radicands nonnegative: where the sides are defined), by
/// merging logarithms that those conditions make defined, all on one set. Every `ln`
/// atom of a normal form has an argument that is positive wherever the `ln` it came
/// from is defined (`func::ln` splits off only positive
/// factors and even powers), so the atoms of `ln(c)` are positive where `c > 0`; and
/// where `c > 0` exactly when `K > 0` for one quantity `K`
/// (`positive_where`: `1/x`, `x^3` and `x` give
/// `x`), logarithms covered by conditions of one `K` may merge. `ln(1/x) = -ln(x)` and
/// `ln(x^3) = 3 ln(x)` are then equal under the condition x > 0, as `x/x = 1` is under
/// x != 0. Sides defined on different sets stay unverified: `ln(x y) = ln(x) + ln(y)`
/// (`x y > 0` has no such `K`: the left side is defined for x, y < 0 too), and
/// `ln((x + 1)^2) = 2 ln(x + 1)`, which drops the absolute value of
/// `2 ln(abs(x + 1))`, the classic slip.
pub fn zero_where_defined(d: &Rat, s: &Assumptions, defined: &[(Rat, Need)]) -> bool {
    let has_ln = |r: &Rat| {
        r.atoms()
            .into_iter()
            .any(|a| matches!(atom::get(a), Atom::Ln(_)))
    };
    if d.is_zero() || !has_ln(d) {
        return d.is_zero();
    }
    // Each logarithm the conditions cover, with the `K` of a condition that covers it.
    let mut covered: Vec<(AtomId, Poly)> = Vec::new();
    for (c, need) in defined {
        if *need != Need::Positive {
            continue;
        }
        let (Some(k), Ok(l)) = (
            crate::normal::merge::positive_where(c, s),
            crate::normal::func::ln(c, s),
        ) else {
            continue;
        };
        for a in l.atoms() {
            if matches!(atom::get(a), Atom::Ln(_)) {
                covered.push((a, k.clone()));
            }
        }
    }
    if covered.is_empty() {
        return false;
    }
    // Logarithms merge when the signs show their arguments positive, or conditions of
    // one `K` cover them all.
    let may_merge = |us: &[&Rat]| {
        let ids: Vec<AtomId> = us
            .iter()
            .filter(|u| s.rat(u) != Sign::Pos)
            .map(|u| atom::intern(Atom::Ln((*u).clone())))
            .collect();
        let Some(first) = ids.first() else {
            return true;
        };
        covered.iter().filter(|(a, _)| a == first).any(|(_, k)| {
            ids.iter()
                .all(|id| covered.iter().any(|(a, k2)| a == id && k2 == k))
        })
    };
    crate::normal::merge::merged_logs_with(d, s, &may_merge).is_some_and(|m| m.is_zero())
}

/// `d` with square roots of positive integers rewritten over a coprime basis of their
/// radicands (`sqrt(p q) = sqrt(p) sqrt(q)`), when two radicands share a factor.
fn coprime_radicals(d: &Rat) -> Option<Rat> {
    use num_integer::Integer;
    let roots: Vec<(AtomId, BigInt)> = d
        .atoms()
        .into_iter()
        .filter_map(|a| match atom::get(a) {
            Atom::Sqrt(p) => p
                .as_constant()
                .filter(|q| q.is_integer() && q.numer() > &BigInt::one())
                .map(|q| (a, q.to_integer())),
            _ => None,
        })
        .collect();
    if roots.len() < 2 {
        return None;
    }
    let mut basis: Vec<BigInt> = roots.iter().map(|r| r.1.clone()).collect();
    let mut split = false;
    for _ in 0..64 {
        basis.sort();
        basis.dedup();
        let pair = (0..basis.len())
            .flat_map(|i| (i + 1..basis.len()).map(move |j| (i, j)))
            .find(|&(i, j)| !basis[i].gcd(&basis[j]).is_one());
        let Some((i, j)) = pair else {
            break;
        };
        let g = basis[i].gcd(&basis[j]);
        let (a, b) = (&basis[i] / &g, &basis[j] / &g);
        basis = basis
            .into_iter()
            .enumerate()
            .filter(|(k, _)| *k != i && *k != j)
            .map(|(_, x)| x)
            .chain([g, a, b])
            .filter(|x| !x.is_one())
            .collect();
        split = true;
    }
    if !split {
        return None;
    }
    let signs = Assumptions::new();
    let mut values = Vec::new();
    for (a, n) in &roots {
        let mut rest = n.clone();
        let mut v = Rat::one();
        for b in &basis {
            while !b.is_one() && (&rest % b).is_zero() {
                rest /= b;
                let s =
                    crate::normal::func::sqrt(&Rat::constant(Q::from_integer(b.clone())), &signs)
                        .ok()?;
                v = v.mul(&s).ok()?;
            }
        }
        if !rest.is_one() {
            return None;
        }
        values.push((*a, v));
    }
    let map = |a: AtomId| values.iter().find(|v| v.0 == a).map(|v| v.1.clone());
    crate::normal::subst::Subst::new(&map, &signs).rat(d).ok()
}

/// Atoms that satisfy no algebraic relation rigor does not already apply.
fn independent_atom(a: AtomId) -> bool {
    match atom::get(a) {
        Atom::Sym(_) | Atom::Pi | Atom::Moment(..) => true,
        // An instant holding a kept factor is not in canonical form.
        Atom::At(_, u) => !crate::normal::power::has_kept(u),
        // Square roots of distinct primes (rigor splits numeric radicands into primes
        // by trial division up to 10⁴, so a radicand below 10⁸ is a prime).
        // A negative radicand (`sqrt(-1)`) is not a real quantity and is never independent.
        Atom::Sqrt(p) => p.as_constant().is_some_and(|q| {
            q.is_integer() && q > Q::zero() && q.to_integer() < BigInt::from(100_000_000)
        }),
        _ => false,
    }
}

/// Whether every atom of `r` is independent, so a nonzero normal form is a nonzero function.
pub fn independent(r: &Rat) -> bool {
    r.atoms().into_iter().all(independent_atom)
}

/// How the two sides of a refuted `=` differ: the kind of mistake, which every room
/// matches on, and the one sentence that says it in a diagnostic.
#[derive(Clone, Debug, PartialEq)]
pub struct Diagnosis {
    /// The kind.
    pub mistake: Mistake,
    /// Whether it is about a whole side (a constant factor, a sign): then it says it
    /// best, before any one term.
    pub whole: bool,
    /// The sentence: `the two sides have opposite signs (a sign error?)`.
    pub text: String,
}

impl Diagnosis {
    fn new(mistake: Mistake, text: impl Into<String>) -> Diagnosis {
        Diagnosis {
            mistake,
            whole: false,
            text: text.into(),
        }
    }

    /// A one-term diagnosis (`check/terms.rs`).
    pub(crate) fn term(mistake: Mistake, text: String) -> Diagnosis {
        Diagnosis::new(mistake, text)
    }

    fn whole(mistake: Mistake, text: impl Into<String>) -> Diagnosis {
        Diagnosis {
            whole: true,
            ..Diagnosis::new(mistake, text)
        }
    }
}

impl std::fmt::Display for Diagnosis {
    /// Its sentence.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.text)
    }
}

/// How `a` differs from `b` (`d` = `a − b`), when it is simple.
pub fn diagnose(a: &Rat, b: &Rat, d: &Rat) -> Option<Diagnosis> {
    if b.is_zero() {
        return Some(Diagnosis::new(
            Mistake::ZeroSide,
            "the right side is 0 but the left side is not",
        ));
    }
    if a.is_zero() {
        return Some(Diagnosis::new(
            Mistake::ZeroSide,
            "the left side is 0 but the right side is not",
        ));
    }
    if let Ok(r) = a.div(b) {
        if let Some(c) = r.as_constant() {
            if c == -Q::one() {
                return Some(Diagnosis::whole(
                    Mistake::Sign,
                    "the two sides have opposite signs (a sign error?)",
                ));
            }
            return Some(Diagnosis::whole(
                Mistake::Factor,
                format!(
                    "the left side is {} × the right side (a constant factor)",
                    show_q(&c)
                ),
            ));
        }
        let mut syms = Vec::new();
        symbols_in(&r, &mut syms);
        if syms.is_empty() && r.num().len() == 1 && r.den().len() == 1 {
            return Some(Diagnosis::whole(
                Mistake::Factor,
                format!(
                    "the left side is {} × the right side (a constant factor)",
                    plain(&r)
                ),
            ));
        }
        if r.num().len() == 1 && r.den().len() == 1 {
            let one_symbol = match r.atoms().as_slice() {
                [x] => atom::sym_name(*x).is_some(),
                _ => false,
            };
            let (mistake, note) = if one_symbol {
                (Mistake::Power, "a wrong power?")
            } else {
                (Mistake::Factor, "a missing or extra factor?")
            };
            return Some(Diagnosis::new(
                mistake,
                format!("the left side is {} × the right side ({note})", plain(&r)),
            ));
        }
    }
    let terms_of = |r: &Rat| -> Vec<String> {
        r.num()
            .terms()
            .iter()
            .filter_map(|(m, q)| Rat::new(Poly::term(m.clone(), q.clone()), r.den().clone()).ok())
            .map(|t| plain(&t))
            .collect()
    };
    if d.num().len() <= 3 {
        let n = d.num().len();
        let (s, them) = if n == 1 {
            ("", "the term")
        } else {
            ("s", "the terms")
        };
        let inertia = about_inertia(a) || about_inertia(b);
        let pa = match (inertia && parallel_axis_terms(d), n) {
            (false, _) => "",
            (true, 1) => ": a parallel-axis term (mass × squared distance)?",
            (true, _) => ": parallel-axis terms (mass × squared distance)?",
        };
        if has_terms(a, d) {
            return Some(Diagnosis::new(
                Mistake::ExtraTerm,
                format!(
                    "the left side has {n} extra term{s}: {}{pa}",
                    terms_of(d).join(", ")
                ),
            ));
        }
        if has_terms(b, &d.neg()) {
            return Some(Diagnosis::new(
                Mistake::MissingTerm,
                format!(
                    "the left side is missing {them} {} that the right side has{pa}",
                    terms_of(&d.neg()).join(", ")
                ),
            ));
        }
        return Some(Diagnosis::new(
            Mistake::Difference,
            format!("the two sides differ by {} (left − right){pa}", plain(d)),
        ));
    }
    None
}

/// Whether `r` is about moments of inertia: it holds a symbol named `I`, `I_…` or
/// `J…`, or a moment of a body (`int(x^2, B)`).
fn about_inertia(r: &Rat) -> bool {
    let mut syms = Vec::new();
    symbols_in(r, &mut syms);
    let named = syms
        .iter()
        .filter_map(|a| crate::normal::atom::sym_name(*a))
        .any(|n| n == "I" || n.starts_with("I_") || n.starts_with('J'));
    named
        || r.atoms().iter().any(|a| {
            matches!(
                crate::normal::atom::get(*a),
                crate::normal::Atom::Moment(..)
            )
        })
}

/// Whether every term of `d` (over a constant denominator) is a mass times a squared
/// distance: one mass-like symbol (`m`, `M`, `m_1`, …) to the first power, and symbols
/// of total degree 2 in even powers (`m d^2`, `c^2 m/4`) — what a parallel-axis step
/// adds or forgets.
fn parallel_axis_terms(d: &Rat) -> bool {
    let mass_like = |n: &str| {
        let base = n.split('_').next().unwrap_or(n);
        base == "m" || base == "M"
    };
    d.den().as_constant().is_some()
        && !d.num().terms().is_empty()
        && d.num().terms().iter().all(|(mono, _)| {
            let mut masses = 0;
            let mut rest = 0;
            for &(a, e) in mono.pairs() {
                match crate::normal::atom::sym_name(a) {
                    Some(n) if mass_like(&n) && e == 1 => masses += 1,
                    Some(_) if e % 2 == 0 => rest += e,
                    _ => return false,
                }
            }
            masses == 1 && rest == 2
        })
}

/// Whether every term of `t` is a term of `r` (over the same denominator).
fn has_terms(r: &Rat, t: &Rat) -> bool {
    r.den() == t.den()
        && t.num()
            .terms()
            .iter()
            .all(|tt| r.num().terms().iter().any(|x| x == tt))
}

/// Symbols occurring anywhere in `r`, arguments of functions included.
pub fn symbols_in(r: &Rat, out: &mut Vec<AtomId>) {
    for a in r.atoms() {
        symbols_in_atom(a, out);
    }
}

fn symbols_in_poly(p: &Poly, out: &mut Vec<AtomId>) {
    for a in p.atoms() {
        symbols_in_atom(a, out);
    }
}

fn symbols_in_atom(a: AtomId, out: &mut Vec<AtomId>) {
    match atom::get(a) {
        Atom::Sym(_) => {
            if !out.contains(&a) {
                out.push(a)
            }
        }
        Atom::Pi | Atom::Moment(..) => {}
        Atom::At(..) => {
            if !out.contains(&a) {
                out.push(a)
            }
        }
        Atom::Sqrt(p) | Atom::Root(p, _) | Atom::Abs(p) | Atom::Factor(p) => {
            symbols_in_poly(p, out)
        }
        Atom::Sin(u) | Atom::Cos(u) | Atom::Exp(u) | Atom::Ln(u) => symbols_in(u, out),
        Atom::Pow(b, e) => {
            symbols_in(b, out);
            symbols_in(e, out);
        }
    }
}

const CANDIDATES: [(i64, i64); 12] = [
    (2, 1),
    (3, 1),
    (1, 2),
    (5, 1),
    (7, 3),
    (11, 4),
    (13, 1),
    (3, 5),
    (17, 2),
    (19, 7),
    (23, 3),
    (29, 11),
];

/// Values far from 1, for the second round of the counterexample search.
const SPREAD: [(i64, i64); 6] = [(1000, 1), (1, 9), (41, 1), (5, 7), (97, 1), (1, 1000)];

/// Searches a few points that respect the declared signs for one where `a` and `b`
/// provably differ (exact rationals, or disjoint rigorous enclosures).
pub fn find_counterexample(a: &Rat, b: &Rat, s: &Assumptions) -> Option<Counterexample> {
    find_counterexample_where(a, b, s, &[])
}

/// [`find_counterexample`] at points where every condition of `defined` provably holds.
pub fn find_counterexample_where(
    a: &Rat,
    b: &Rat,
    s: &Assumptions,
    defined: &[(Rat, Need)],
) -> Option<Counterexample> {
    // Every symbol of the written sides gets a value, also one that cancelled from
    // both normal forms but stays in a condition (`m g/(m + 2/5 m)`: `m != 0`).
    let mut syms = Vec::new();
    symbols_in(a, &mut syms);
    symbols_in(b, &mut syms);
    for (c, _) in defined {
        symbols_in(c, &mut syms);
    }
    syms.sort_by(|x, y| atom::cmp_atoms(*x, *y));
    // The first point where the sides differ, kept while a better one is looked for:
    // one where they differ by more than a millionth of their size, which the guard's
    // floating-point check can confirm (at y = 1/1000, `a/y^6 + ln(2 + y^2)` and
    // `a/y^6 + ln(2 - y^2)` differ, but by 10⁻²⁴ of their size).
    let mut first: Option<Counterexample> = None;
    // Ten points near 1, then sixteen far from it (large, tiny) with every pattern of
    // signs the declarations allow: `abs` and roots of squares need both signs.
    for k in 0..26usize {
        let mut point: HashMap<AtomId, Q> = HashMap::new();
        for (i, sym) in syms.iter().enumerate() {
            let (n, d) = if k < 10 {
                CANDIDATES[(i * 5 + k * 7 + k / 3) % CANDIDATES.len()]
            } else {
                SPREAD[(i * 3 + k) % SPREAD.len()]
            };
            let t = Q::new(BigInt::from((i * 3 + k * 5) % 9 + 1), BigInt::from(10));
            match crate::normal::ranges::sample(s, *sym, &t) {
                crate::normal::ranges::Sample::At(q) => {
                    point.insert(*sym, q);
                    continue;
                }
                // A value outside an interval nobody can bound is no counterexample.
                crate::normal::ranges::Sample::Unusable => return None,
                crate::normal::ranges::Sample::Free => {}
            }
            let mut q = Q::new(BigInt::from(n), BigInt::from(d));
            let sign = s.declared(*sym);
            let flip = if k < 10 {
                (i + k) % 3 == 1
            } else {
                ((k - 10) >> (i % 4)) & 1 == 1
            };
            // Far from 1: a symbol made negative is large, so that it dominates a sum
            // with positive ones (`m + R < 0` needs `m < -R`).
            if k >= 10 && flip && matches!(sign, Sign::Unknown | Sign::NonZero) {
                q = Q::from_integer(BigInt::from(1000 + i as i64));
            }
            if matches!(sign, Sign::Unknown | Sign::NonZero) && flip {
                q = -q;
            }
            if matches!(sign, Sign::Neg | Sign::NonPos) {
                q = -q;
            }
            point.insert(*sym, q);
        }
        let mut ev = Evaluator {
            point: &point,
            prec: Prec::default(),
            memo: HashMap::new(),
        };
        let holds = defined.iter().all(|(c, need)| {
            ev.rat(c).is_some_and(|v| match need {
                Need::NonZero => v.is_positive() || v.is_negative(),
                Need::Positive => v.is_positive(),
                Need::NonNegative => v.is_positive() || (v.lo() == v.hi() && v.lo().is_zero()),
            })
        });
        if !holds {
            continue;
        }
        let (Some(va), Some(vb)) = (ev.rat(a), ev.rat(b)) else {
            continue;
        };
        if va.disjoint(&vb) {
            let well_apart = {
                let gap = if va.hi() < vb.lo() {
                    vb.lo() - va.hi()
                } else {
                    va.lo() - vb.hi()
                };
                let size = [va.lo(), va.hi(), vb.lo(), vb.hi()]
                    .into_iter()
                    .map(num_traits::Signed::abs)
                    .fold(Q::zero(), |m, q| if q > m { q } else { m });
                gap * Q::from_integer(BigInt::from(1_000_000)) > size
            };
            if !well_apart && first.is_some() {
                continue;
            }
            let show = |v: &Interval| {
                if v.lo() == v.hi() {
                    show_q(v.lo())
                } else {
                    format!("≈ {}", v.to_decimal_string(8))
                }
            };
            let mut values: BTreeMap<String, Q> = BTreeMap::new();
            for (sym, q) in &point {
                if let Some(n) = atom::sym_name(*sym) {
                    values.insert(n, q.clone());
                }
            }
            let c = Counterexample {
                values: values.into_iter().collect(),
                lhs: show(&va),
                rhs: show(&vb),
            };
            if well_apart {
                return Some(c);
            }
            first = Some(c);
        }
    }
    first
}

/// `p` at `point` (every atom of `p` a symbol with a value there) as one fraction
/// `(numerator, denominator > 0)`, unreduced: the terms are summed without a gcd, the
/// caller reduces once. The guard's points are mostly dyadic (denominators powers of
/// two), whose sums stay aligned by shifts.
fn exact_sum(p: &Poly, point: &HashMap<AtomId, Q>) -> (BigInt, BigInt) {
    let mut num = BigInt::zero();
    let mut den = BigInt::one();
    for (m, q) in p.terms() {
        let (mut tn, mut td) = (q.numer().clone(), q.denom().clone());
        for &(a, e) in m.pairs() {
            if let Some(v) = point.get(&a) {
                tn *= v.numer().pow(e);
                td *= v.denom().pow(e);
            }
        }
        (num, den) = frac_add((num, den), (tn, td));
    }
    (num, den)
}

/// `a + b` for fractions with positive denominators, unreduced; a common denominator
/// by shifting when both are powers of two, else the least one (so that the
/// denominator of a long sum stays the lcm of its terms').
fn frac_add(a: (BigInt, BigInt), b: (BigInt, BigInt)) -> (BigInt, BigInt) {
    let two_power = |d: &BigInt| crate::interval::two_exponent(d).map(|k| k as usize);
    if a.1 == b.1 {
        return (a.0 + b.0, a.1);
    }
    match (two_power(&a.1), two_power(&b.1)) {
        (Some(x), Some(y)) if x >= y => (a.0 + (b.0 << (x - y)), a.1),
        (Some(x), Some(y)) => ((a.0 << (y - x)) + b.0, b.1),
        _ => {
            let g = num_integer::Integer::gcd(&a.1, &b.1);
            let (ga, gb) = (&a.1 / &g, &b.1 / &g);
            (a.0 * &gb + b.0 * &ga, ga * b.1)
        }
    }
}

/// Rigorous evaluation of normal forms at a rational point.
pub struct Evaluator<'a> {
    /// Values of the symbols.
    pub point: &'a HashMap<AtomId, Q>,
    /// Working precision.
    pub prec: Prec,
    memo: HashMap<AtomId, Option<Interval>>,
}

impl<'a> Evaluator<'a> {
    /// An evaluator at `point`.
    pub fn new(point: &'a HashMap<AtomId, Q>) -> Evaluator<'a> {
        Evaluator {
            point,
            prec: Prec::default(),
            memo: HashMap::new(),
        }
    }

    /// An evaluator at `point` that starts from the values `memo` holds for atoms (as
    /// [`Evaluator::values`] returned them at the same point or a point extending it).
    pub fn with_values(
        point: &'a HashMap<AtomId, Q>,
        prec: Prec,
        memo: HashMap<AtomId, Interval>,
    ) -> Evaluator<'a> {
        Evaluator {
            point,
            prec,
            memo: memo.into_iter().map(|(a, v)| (a, Some(v))).collect(),
        }
    }

    /// The atoms' values computed so far (those that could be evaluated).
    pub fn values(self) -> HashMap<AtomId, Interval> {
        self.memo
            .into_iter()
            .filter_map(|(a, v)| v.map(|v| (a, v)))
            .collect()
    }

    /// An enclosure of `r` at the point, `None` where undefined or not evaluable.
    pub fn rat(&mut self, r: &Rat) -> Option<Interval> {
        if let Some(q) = self.exact(r) {
            return q.map(Interval::point);
        }
        let n = self.poly(r.num())?;
        if r.den().is_one() {
            return Some(n);
        }
        let d = self.poly(r.den())?;
        n.div(&d, self.prec)
    }

    /// Exact rational value when every atom is a symbol with a value: `Some(None)` where
    /// the denominator vanishes, `None` when exact evaluation does not apply.
    fn exact(&self, r: &Rat) -> Option<Option<Q>> {
        let ids = r.atoms();
        if !ids.iter().all(|a| self.point.contains_key(a)) {
            return None;
        }
        let huge = |p: &Poly| {
            p.terms()
                .iter()
                .any(|(m, _)| m.pairs().iter().any(|t| t.1 > 4096))
        };
        if huge(r.num()) || huge(r.den()) {
            return None;
        }
        let (nn, nd) = exact_sum(r.num(), self.point);
        let (dn, dd) = exact_sum(r.den(), self.point);
        if dn.is_zero() {
            return Some(None);
        }
        Some(Some(Q::new(nn * dd, nd * dn)))
    }

    fn poly(&mut self, p: &Poly) -> Option<Interval> {
        let mut total = Interval::point(Q::zero());
        for (m, q) in p.terms() {
            let mut t = Interval::point(q.clone());
            for &(a, e) in m.pairs() {
                let v = self.atom(a)?;
                t = t.mul(&v.powi(i64::from(e), self.prec)?, self.prec)?;
            }
            total = total.add(&t, self.prec)?;
        }
        Some(total)
    }

    fn atom(&mut self, a: AtomId) -> Option<Interval> {
        if let Some(v) = self.memo.get(&a) {
            return v.clone();
        }
        let v = self.atom_uncached(a);
        self.memo.insert(a, v.clone());
        v
    }

    fn atom_uncached(&mut self, a: AtomId) -> Option<Interval> {
        let p = self.prec;
        match atom::get(a) {
            Atom::Sym(_) | Atom::At(..) => self.point.get(&a).map(|q| Interval::point(q.clone())),
            Atom::Pi => Interval::pi(p),
            Atom::Sqrt(x) => self.poly(x)?.sqrt(p),
            Atom::Moment(..) => None,
            // The real principal root; odd roots of negatives are negative.
            Atom::Root(x, n) => self.poly(x)?.real_root(*n, p),
            Atom::Abs(x) => self.poly(x)?.abs(),
            Atom::Factor(x) => self.poly(x),
            Atom::Sin(u) => self.rat(u)?.sin(p),
            Atom::Cos(u) => self.rat(u)?.cos(p),
            Atom::Exp(u) => self.rat(u)?.exp(p),
            Atom::Ln(u) => self.rat(u)?.ln(p),
            Atom::Pow(b, e) => {
                let bv = self.rat(b)?;
                match e.as_constant() {
                    Some(q) if q.is_integer() => bv.powi(q.to_integer().to_i64()?, p),
                    _ => {
                        if !bv.is_positive() {
                            return None;
                        }
                        let ev = self.rat(e)?;
                        ev.mul(&bv.ln(p)?, p)?.exp(p)
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn fraction_sums_are_exact(terms in prop::collection::vec((-1000i64..1000, 0u32..12, 1i64..40), 1..30)) {
            // Denominators that are powers of two (shifted), equal, or neither (lcm).
            let mut acc = (BigInt::zero(), BigInt::one());
            let mut want = Q::zero();
            for (n, k, odd) in terms {
                let d = if odd % 3 == 0 { BigInt::one() << (k as usize) } else { BigInt::from(odd) };
                want += Q::new(n.into(), d.clone());
                acc = frac_add(acc, (n.into(), d));
            }
            prop_assert!(acc.1 > BigInt::zero());
            prop_assert_eq!(Q::new(acc.0, acc.1), want);
        }
    }
}
