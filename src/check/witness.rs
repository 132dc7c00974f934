//! A point where every fact holds: an exact proof that a quantity is *not* forced to
//! zero by the facts, found once for a set of facts and used for every quantity asked
//! about under it.
//!
//! Whether the facts force a divisor to zero, and whether they contradict each other,
//! is decided by elimination (`elimination.rs`, `zeros.rs`), which costs an elimination
//! per question. Most answers are "no", and one real point settles them all: if every
//! fact is exactly zero at a point that also satisfies every declared sign, and `d` is
//! exactly nonzero there, then the facts do not force `d` to zero and do not contradict
//! each other.
//!
//! The point is found by solving the facts, one symbol of degree one at a time, giving
//! the symbols left over values that respect their declared signs, and working back.
//! Nothing found that way is trusted: the point is kept only when every fact evaluates
//! to exactly zero there (no denominator zero) and every value has its declared sign.
//! Angles enter only through `sin(x)` and `cos(x)` of a symbol `x` that appears nowhere
//! else, valued by a Pythagorean triple (a real angle has that sine and cosine); π is
//! kept as it is, and a value that is a nonzero rational function of π is nonzero (π is
//! transcendental). Any other kind of atom, or a declared interval, means no point is
//! looked for and the question goes to the elimination as before. Everything is exact
//! rational arithmetic.

use super::elimination::Fact;
use crate::normal::atom::{self, Atom, AtomId};
use crate::normal::subst::{atom_depends_on, subst_atom, Subst};
use crate::normal::{Assumptions, Poly, Rat, Sign, Q};
use foldhash::{HashMap, HashMapExt};
use num_bigint::BigInt;
use std::sync::{Arc, Mutex};

/// Facts past which no point is looked for (each solved symbol is substituted into the
/// facts left).
const MAX_FACTS: usize = 64;

/// Terms of a fact past which no point is looked for.
const MAX_TERMS: usize = 200;

/// Assignments of the free symbols tried before giving up.
const TRIES: usize = 4;

/// Exact values of symbols (and of `sin(x)`, `cos(x)` for the angles) at which every
/// fact it was found for is zero and every declared sign holds.
#[derive(Clone, Debug)]
pub struct Point {
    values: HashMap<AtomId, Rat>,
    /// The symbols valued only through their sine and cosine, with those.
    angles: HashMap<AtomId, (Q, Q)>,
}

/// What a fact's atom is to the point: a symbol to value, or the sine or cosine of an
/// angle symbol.
enum Kind {
    Symbol,
    /// The angle, and whether this is its cosine.
    Trig(AtomId, bool),
    /// π, kept as it is: a nonzero polynomial in π with rational coefficients is
    /// nonzero (π is transcendental).
    Pi,
}

fn kind(a: AtomId) -> Option<Kind> {
    let angle = |u: &Rat| {
        let x = u.as_atom()?;
        matches!(atom::get(x), Atom::Sym(_)).then_some(x)
    };
    match atom::get(a) {
        Atom::Sym(_) => Some(Kind::Symbol),
        Atom::Sin(u) => Some(Kind::Trig(angle(u)?, false)),
        Atom::Cos(u) => Some(Kind::Trig(angle(u)?, true)),
        Atom::Pi => Some(Kind::Pi),
        _ => None,
    }
}

/// The atoms of a point: its symbols, and the sines and cosines of its angles (each
/// with its angle and whether it is the cosine).
struct Atoms {
    symbols: Vec<AtomId>,
    trig: Vec<(AtomId, AtomId, bool)>,
    angles: Vec<AtomId>,
}

/// The atoms of `values`; `None` when an atom is of another kind, an angle also
/// appears bare, or a symbol is declared in an interval.
fn classify(values: &[&Rat], signs: &Assumptions) -> Option<Atoms> {
    let (mut symbols, mut trig, mut angles) = (Vec::new(), Vec::new(), Vec::new());
    for v in values {
        for a in v.atoms() {
            match kind(a)? {
                Kind::Symbol if !symbols.contains(&a) => symbols.push(a),
                Kind::Pi => {}
                Kind::Trig(x, cos) if !trig.iter().any(|t: &(AtomId, _, _)| t.0 == a) => {
                    trig.push((a, x, cos));
                    if !angles.contains(&x) {
                        angles.push(x);
                    }
                }
                _ => {}
            }
        }
    }
    let ranged = symbols
        .iter()
        .chain(&angles)
        .any(|a| signs.range(*a).is_some());
    if ranged || angles.iter().any(|x| symbols.contains(x)) {
        return None;
    }
    symbols.sort_by(|a, b| atom::cmp_atoms(*a, *b));
    angles.sort_by(|a, b| atom::cmp_atoms(*a, *b));
    Some(Atoms {
        symbols,
        trig,
        angles,
    })
}

/// Whether the value `r` (a number, or a rational function of π) has the declared
/// sign `s`: exactly for a number, by the signs of its terms (π > 0) otherwise.
fn has_sign(r: &Rat, s: Sign, signs: &Assumptions) -> bool {
    use num_traits::Signed;
    let Some(c) = r.as_constant() else {
        let known = signs.rat(r);
        return match s {
            Sign::Zero => false,
            Sign::Pos => known == Sign::Pos,
            Sign::Neg => known == Sign::Neg,
            Sign::NonNeg => known.is_nonneg(),
            Sign::NonPos => known.is_nonpos(),
            Sign::NonZero => known.is_nonzero(),
            _ => true,
        };
    };
    let c = &c;
    match s {
        Sign::Zero => num_traits::Zero::is_zero(c),
        Sign::Pos => c.is_positive(),
        Sign::Neg => c.is_negative(),
        Sign::NonNeg => !c.is_negative(),
        Sign::NonPos => !c.is_positive(),
        Sign::NonZero => !num_traits::Zero::is_zero(c),
        _ => true,
    }
}

/// The value given to the `i`-th free symbol on try `t`: distinct, away from small
/// integers that make sums cancel, with the declared sign; a symbol of unknown sign is
/// positive on the first try and takes both signs on the others.
fn free_value(i: usize, t: usize, s: Sign) -> Q {
    let v = Q::new(BigInt::from(3 * i + 5 + 7 * t), BigInt::from(i + 2 + 2 * t));
    let negative = match s {
        Sign::Zero => return Q::from_integer(BigInt::from(0)),
        Sign::Neg | Sign::NonPos => true,
        Sign::Pos | Sign::NonNeg => false,
        _ => t > 0 && (i + t) % 2 == 0,
    };
    if negative {
        -v
    } else {
        v
    }
}

/// The sine and cosine of the `i`-th angle on try `t`, by a Pythagorean triple, with
/// the angle's declared sign (a positive angle in the first quadrant, a negative one in
/// the fourth, zero for zero).
fn angle_value(i: usize, t: usize, s: Sign) -> (Q, Q) {
    const TRIPLES: [(i64, i64, i64); 4] = [(3, 4, 5), (5, 12, 13), (8, 15, 17), (7, 24, 25)];
    if s == Sign::Zero {
        return (Q::from_integer(0.into()), Q::from_integer(1.into()));
    }
    let (a, b, c) = TRIPLES[(i + t) % TRIPLES.len()];
    let sin = Q::new(BigInt::from(a), BigInt::from(c));
    let cos = Q::new(BigInt::from(b), BigInt::from(c));
    match s {
        Sign::Neg | Sign::NonPos => (-sin, cos),
        _ => (sin, cos),
    }
}

/// The value of `r` where the atoms have `values`, when it is defined and a number or
/// a rational function of π alone.
fn eval(r: &Rat, values: &HashMap<AtomId, Rat>, signs: &Assumptions) -> Option<Rat> {
    let map = |a: AtomId| values.get(&a).cloned();
    let v = Subst::new(&map, signs).rat(r).ok()?;
    v.atoms().into_iter().all(atom::is_pi).then_some(v)
}

/// A symbol `fact = 0` can be solved for (of degree one, not inside another atom nor in
/// the denominator), preferring a number as its coefficient, then a time derivative
/// (`m y'' = 0` is solved as `y'' = 0`, leaving the mass free), then the coefficient
/// with fewest terms; with the value it then has.
fn solvable(fact: &Rat, symbols: &[AtomId]) -> Option<(AtomId, Rat)> {
    let n = fact.num();
    type Rank = (bool, bool, usize);
    let mut best: Option<(Rank, AtomId, Poly, Poly)> = None;
    for &u in symbols {
        if !n.contains(u) || fact.den().contains(u) || n.degree_in(u) != 1 {
            continue;
        }
        if n.atoms().iter().any(|a| *a != u && atom_depends_on(*a, u)) {
            continue;
        }
        let coeffs = n.coeffs_in(u);
        let (lead, rest) = match coeffs.as_slice() {
            [(0, c0), (1, c1)] => (c1.clone(), c0.clone()),
            [(1, c1)] => (c1.clone(), Poly::zero()),
            _ => continue,
        };
        let derivative = atom::sym_str(u).is_some_and(|n| n.ends_with('\''));
        let rank = (!lead.atoms().is_empty(), !derivative, lead.len());
        if best.as_ref().is_none_or(|b| rank < b.0) {
            best = Some((rank, u, lead, rest));
        }
    }
    let (_, u, lead, rest) = best?;
    let value = Rat::poly(rest)
        .ok()?
        .neg()
        .div(&Rat::poly(lead).ok()?)
        .ok()?;
    Some((u, value))
}

/// The facts solved one symbol at a time: each step's symbol and its value in the
/// symbols solved after it and the free ones. `None` when a fact cannot be solved or
/// the facts leave a nonzero number (they contradict each other).
fn triangulate(
    facts: &[Fact],
    symbols: &[AtomId],
    signs: &Assumptions,
) -> Option<Vec<(AtomId, Rat)>> {
    // `0 = 0` holds everywhere.
    let mut left: Vec<Rat> = facts
        .iter()
        .filter(|f| !f.value.is_zero())
        .map(|f| f.value.clone())
        .collect();
    let mut steps = Vec::new();
    while !left.is_empty() {
        let (i, (u, value)) = left
            .iter()
            .enumerate()
            .find_map(|(i, f)| solvable(f, symbols).map(|s| (i, s)))?;
        left.remove(i);
        let mut next = Vec::with_capacity(left.len());
        for f in &left {
            let v = subst_atom(f, u, &value, signs).ok()?;
            if v.is_zero() {
                continue;
            }
            if v.atoms().is_empty() || v.num().len() > MAX_TERMS {
                return None;
            }
            next.push(v);
        }
        left = next;
        steps.push((u, value));
    }
    Some(steps)
}

/// A point where every fact is zero and every declared sign holds, when one is found
/// this way (see the module's header); `None` says nothing about the facts.
pub fn find(facts: &[Fact], signs: &Assumptions) -> Option<Point> {
    if facts.len() > MAX_FACTS || facts.iter().any(|f| f.value.num().len() > MAX_TERMS) {
        return None;
    }
    let values: Vec<&Rat> = facts.iter().map(|f| &f.value).collect();
    let atoms = classify(&values, signs)?;
    let steps = triangulate(facts, &atoms.symbols, signs)?;
    (0..TRIES).find_map(|t| {
        let point = assign(&steps, &atoms, t, signs)?;
        let holds = facts
            .iter()
            .all(|f| eval(&f.value, &point.values, signs).is_some_and(|c| c.is_zero()));
        holds.then_some(point)
    })
}

/// Values for the free symbols and angles (try `t`), then for the solved symbols from
/// the last step back; `None` when a value is undefined or against its declared sign.
fn assign(steps: &[(AtomId, Rat)], atoms: &Atoms, t: usize, signs: &Assumptions) -> Option<Point> {
    let mut values: HashMap<AtomId, Rat> = HashMap::new();
    let solved: Vec<AtomId> = steps.iter().map(|s| s.0).collect();
    let free = atoms.symbols.iter().filter(|a| !solved.contains(a));
    for (i, a) in free.enumerate() {
        values.insert(*a, Rat::constant(free_value(i, t, signs.declared(*a))));
    }
    let angles: HashMap<AtomId, (Q, Q)> = atoms
        .angles
        .iter()
        .enumerate()
        .map(|(i, x)| (*x, angle_value(i, t, signs.declared(*x))))
        .collect();
    for (a, x, cos) in &atoms.trig {
        let (s, c) = angles.get(x)?;
        values.insert(*a, Rat::constant(if *cos { c.clone() } else { s.clone() }));
    }
    for (u, value) in steps.iter().rev() {
        let c = eval(value, &values, signs)?;
        if !has_sign(&c, signs.declared(*u), signs) {
            return None;
        }
        values.insert(*u, c);
    }
    Some(Point { values, angles })
}

impl Point {
    /// Whether `d` is defined and nonzero at this point, extended to the symbols and
    /// angles `d` has and the facts do not (values of their declared signs): then the
    /// facts it was found for do not force `d` to zero. `false` says nothing.
    pub fn nonzero_at(&self, d: &Rat, signs: &Assumptions) -> bool {
        let (mut extra, mut trig, mut angles) = (Vec::new(), Vec::new(), Vec::new());
        for a in d.atoms() {
            if self.values.contains_key(&a) {
                continue;
            }
            match kind(a) {
                Some(Kind::Symbol) if !self.angles.contains_key(&a) => extra.push(a),
                Some(Kind::Trig(x, cos)) => {
                    trig.push((a, x, cos));
                    if !self.angles.contains_key(&x) && !angles.contains(&x) {
                        angles.push(x);
                    }
                }
                Some(Kind::Pi) => {}
                _ => return false,
            }
        }
        let bare = |x: &AtomId| extra.contains(x) || self.values.contains_key(x);
        let ranged = extra
            .iter()
            .chain(&angles)
            .any(|a| signs.range(*a).is_some());
        if ranged || angles.iter().any(bare) {
            return false;
        }
        let value = if extra.is_empty() && trig.is_empty() {
            eval(d, &self.values, signs)
        } else {
            extra.sort_by(|a, b| atom::cmp_atoms(*a, *b));
            angles.sort_by(|a, b| atom::cmp_atoms(*a, *b));
            let mut values = self.values.clone();
            for (i, a) in extra.iter().enumerate() {
                values.insert(*a, Rat::constant(free_value(i + 97, 0, signs.declared(*a))));
            }
            let new: HashMap<AtomId, (Q, Q)> = angles
                .iter()
                .enumerate()
                .map(|(i, x)| (*x, angle_value(i + 1, 0, signs.declared(*x))))
                .collect();
            for (a, x, cos) in trig {
                let Some((s, c)) = self.angles.get(&x).or_else(|| new.get(&x)) else {
                    return false;
                };
                values.insert(a, Rat::constant(if cos { c.clone() } else { s.clone() }));
            }
            eval(d, &values, signs)
        };
        value.is_some_and(|v| !v.is_zero())
    }
}

/// [`find`], remembered for the process: the same facts are asked about by the
/// divisors of a link, by the check of their consistency, and again in every check of
/// the same notes. A point is a point whatever the size limits; a point not found under
/// tight limits only sends the questions to the elimination.
pub fn remembered(facts: &[Fact], signs: &Assumptions) -> Option<Arc<Point>> {
    type Entry = Arc<(Vec<Rat>, Assumptions, Option<Arc<Point>>)>;
    static KNOWN: Mutex<Vec<Entry>> = Mutex::new(Vec::new());
    const KEEP: usize = 32;
    let lock = || KNOWN.lock().unwrap_or_else(|e| e.into_inner());
    let same = |e: &Entry| {
        let (v, s, _) = &**e;
        v.len() == facts.len() && v.iter().zip(facts).all(|(a, f)| *a == f.value) && s == signs
    };
    // A point of other facts under the same signs at which these facts hold too: the
    // facts grow a given or a verified claim at a time, and a link uses some of them.
    let holds = |e: &Entry| {
        let (v, s, p) = &**e;
        let p = p.as_ref()?;
        let new: Vec<&Fact> = facts.iter().filter(|f| !v.contains(&f.value)).collect();
        if new.len() > 2 || s != signs {
            return None;
        }
        let zero = |f: &&Fact| eval(&f.value, &p.values, signs).is_some_and(|c| c.is_zero());
        new.iter().all(zero).then(|| p.clone())
    };
    // The entries are searched outside the lock (the evaluations take a while, and the
    // other cores ask too): what was remembered when the search began.
    let known: Vec<Entry> = lock().clone();
    let found = match known.iter().find(|k| same(k)) {
        Some(k) => return k.2.clone(),
        None => known
            .iter()
            .find_map(holds)
            .or_else(|| find(facts, signs).map(Arc::new)),
    };
    let mut known = lock();
    if known.len() >= KEEP {
        known.pop();
    }
    let values = facts.iter().map(|f| f.value.clone()).collect();
    known.insert(0, Arc::new((values, signs.clone(), found.clone())));
    found
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::elimination::{contradiction, zero_by_facts};
    use crate::diag::{Cited, FactRef};
    use proptest::prelude::*;

    /// `text` read and lowered, `x` and `theta` being functions of time.
    fn r(text: &str, signs: &Assumptions) -> Rat {
        let e = crate::syntax::parse_expr(text, &crate::syntax::ParseOptions::default())
            .unwrap_or_else(|err| panic!("{text}: {err}"));
        let env = crate::lower::Env {
            signs: signs.clone(),
            time: ["x", "theta"].iter().map(|s| s.to_string()).collect(),
            ..Default::default()
        };
        crate::lower::lower(&e, &env).unwrap_or_else(|err| panic!("{text}: {err:?}"))
    }

    /// The facts `lhs - rhs` of `relations` (`lhs = rhs`).
    fn facts(relations: &[&str], signs: &Assumptions) -> Vec<Fact> {
        relations
            .iter()
            .enumerate()
            .map(|(i, rel)| {
                let (lhs, rhs) = rel.split_once('=').expect("a relation");
                Fact {
                    value: r(lhs, signs).sub(&r(rhs, signs)).unwrap(),
                    name: Cited::of(FactRef::Line(i + 1)),
                }
            })
            .collect()
    }

    fn positive(names: &[&str]) -> Assumptions {
        let mut signs = Assumptions::default();
        for n in names {
            signs.set(atom::sym(n), Sign::Pos);
        }
        signs
    }

    const ROLLING: [&str; 3] = [
        "m*x'' = m*g*sin(beta) - F",
        "I_G*theta'' = F*R",
        "x'' = R*theta''",
    ];

    #[test]
    fn a_point_of_the_rolling_laws_shows_their_divisors_nonzero() {
        let signs = positive(&["m", "g", "R", "I_G", "beta"]);
        let fs = facts(&ROLLING, &signs);
        let p = find(&fs, &signs).expect("the rolling laws hold at some point");
        for f in &fs {
            assert!(eval(&f.value, &p.values, &signs).is_some_and(|v| v.is_zero()));
        }
        for d in ["m*R^2 + I_G", "R", "m*g*sin(beta)", "F"] {
            let d = r(d, &signs);
            assert!(
                p.nonzero_at(&d, &signs),
                "{}",
                crate::normal::print::plain(&d)
            );
            assert!(!zero_by_facts(&d, &fs, &signs));
        }
        assert!(contradiction(&fs, &signs).is_none());
    }

    #[test]
    fn a_quantity_the_facts_force_to_zero_is_never_shown_nonzero() {
        let signs = positive(&["m", "g", "R", "I_G", "beta"]);
        let mut laws = ROLLING.to_vec();
        laws.push("I_G = m*R^2/2");
        let fs = facts(&laws, &signs);
        let p = find(&fs, &signs).expect("a point");
        let d = r("I_G - m*R^2/2", &signs);
        assert!(!p.nonzero_at(&d, &signs));
        assert!(zero_by_facts(&d, &fs, &signs));
        // `m x'' = 2/3 m g sin(beta)` follows: its difference is zero there too.
        assert!(!p.nonzero_at(&r("x'' - 2/3*g*sin(beta)", &signs), &signs));
    }

    #[test]
    fn facts_that_contradict_each_other_or_the_signs_have_no_point() {
        let none = Assumptions::default();
        assert!(find(&facts(&["q = 1", "q = 2"], &none), &none).is_none());
        let signs = positive(&["m"]);
        assert!(find(&facts(&["m = -2"], &signs), &signs).is_none());
        assert!(find(&facts(&["m = k", "k = -3"], &signs), &signs).is_none());
        // Without the sign, the same facts hold at a point.
        assert!(find(&facts(&["m = k", "k = -3"], &none), &none).is_some());
    }

    #[test]
    fn a_sine_and_cosine_are_those_of_a_real_angle() {
        // With N = m g cos(beta) and F = m g sin(beta), F^2 + N^2 = (m g)^2 wherever
        // the facts hold: independent values for the sine and cosine would show it
        // nonzero.
        let signs = positive(&["m", "g", "beta"]);
        let fs = facts(&["N = m*g*cos(beta)", "F = m*g*sin(beta)"], &signs);
        let p = find(&fs, &signs).expect("a point");
        assert!(!p.nonzero_at(&r("F^2 + N^2 - m^2*g^2", &signs), &signs));
        assert!(p.nonzero_at(&r("F + N - m*g", &signs), &signs));
        // An angle of the quantity only: real values too.
        assert!(!p.nonzero_at(&r("sin(phi)^2 + cos(phi)^2 - 1", &signs), &signs));
    }

    #[test]
    fn an_angle_written_bare_too_is_left_to_the_elimination() {
        let none = Assumptions::default();
        assert!(find(&facts(&["y = sin(theta) - theta"], &none), &none).is_none());
        let p = find(&facts(&["F = m*g*sin(beta)"], &none), &none).expect("a point");
        assert!(!p.nonzero_at(&r("beta", &none), &none));
        assert!(!p.nonzero_at(&r("sqrt(F^2 + 1)", &none), &none));
    }

    #[test]
    fn pi_is_kept_exact() {
        let signs = positive(&["rho", "R"]);
        let fs = facts(&["m = rho*pi*R^2"], &signs);
        let p = find(&fs, &signs).expect("a point");
        assert!(p.nonzero_at(&r("m", &signs), &signs));
        assert!(p.nonzero_at(&r("m - rho*R^2*22/7", &signs), &signs));
        assert!(!p.nonzero_at(&r("m/pi - rho*R^2", &signs), &signs));
    }

    #[test]
    fn a_declared_interval_is_left_to_the_elimination() {
        let mut signs = Assumptions::default();
        let range = crate::normal::Range {
            lo: Rat::zero(),
            lo_strict: true,
            hi: Rat::one(),
            hi_strict: true,
        };
        signs.set_range(atom::sym("s"), Some(range));
        assert!(find(&facts(&["y = 2*s"], &signs), &signs).is_none());
    }

    /// A small polynomial in `a, b, c, u, v` from its coefficients (each term a product
    /// of two of them, or one, or a number).
    fn poly(terms: &[(i64, usize, usize)]) -> Rat {
        let names = ["1", "a", "b", "c", "u", "v"];
        let none = Assumptions::default();
        let text: Vec<String> = terms
            .iter()
            .map(|(k, i, j)| format!("({k})*{}*{}", names[*i], names[*j]))
            .collect();
        r(&text.join(" + "), &none)
    }

    fn term() -> impl Strategy<Value = (i64, usize, usize)> {
        (-3i64..=3, 0usize..6, 0usize..6)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// Wherever the point says a quantity is not forced to zero, the elimination
        /// (which proves zeros) agrees, and facts with a point are never called
        /// contradictory.
        #[test]
        fn a_point_never_contradicts_the_elimination(
            fs in prop::collection::vec(prop::collection::vec(term(), 1..4), 1..4),
            d in prop::collection::vec(term(), 1..4),
            signed in any::<bool>(),
        ) {
            let signs = if signed { positive(&["a", "b"]) } else { Assumptions::default() };
            let fs: Vec<Fact> = fs
                .iter()
                .enumerate()
                .map(|(i, t)| Fact { value: poly(t), name: Cited::of(FactRef::Line(i + 1)) })
                .collect();
            let d = poly(&d);
            if let Some(p) = find(&fs, &signs) {
                for f in &fs {
                    prop_assert!(eval(&f.value, &p.values, &signs).is_some_and(|v| v.is_zero()));
                }
                prop_assert!(contradiction(&fs, &signs).is_none());
                if p.nonzero_at(&d, &signs) {
                    prop_assert!(!zero_by_facts(&d, &fs, &signs));
                }
            }
        }
    }

    /// A fact equal to one before it, or to its negation (`F = m a`, then `m a = F`), is
    /// left out, the first kept; a multiple (the relation halved) and facts that differ
    /// only in a coefficient are kept.
    #[test]
    fn repeats_and_negations_are_left_out_the_first_kept() {
        let signs = positive(&["m", "g", "a", "F"]);
        let fs = facts(
            &[
                "F = m*a",
                "m*a = F",
                "F/2 = m*a/2",
                "F = 2*m*a",
                "m*g = F + m*a",
                "F = m*a",
                "-F = -2*m*a",
            ],
            &signs,
        );
        let kept = crate::check::elimination::distinct(fs.clone());
        let lines: Vec<String> = kept.iter().map(|f| format!("{:?}", f.name.fact)).collect();
        assert_eq!(lines, ["Line(1)", "Line(3)", "Line(4)", "Line(5)"]);
        let values: Vec<_> = kept.iter().map(|f| f.value.clone()).collect();
        assert_eq!(crate::check::elimination::distinct_values(&fs), values);
    }

    /// A target that is a constant multiple of one fact is settled by that fact alone,
    /// before any unknown is eliminated (here `a`, which the first fact would give); one
    /// with the same monomials in other proportions is not.
    #[test]
    fn a_constant_multiple_of_a_fact_is_recognised() {
        let signs = positive(&["m", "g", "a", "F", "L"]);
        let fs = facts(&["a = g", "F*L = m*a/g"], &signs);
        let multiple = |lhs: &str, rhs: &str| {
            let target = r(lhs, &signs).sub(&r(rhs, &signs)).unwrap();
            let unknown = |x: AtomId| x == atom::sym("a");
            let e =
                crate::check::elimination::eliminate(&target, &fs, &unknown, &signs, None).unwrap();
            // Settled by the fact alone: no unknown solved for.
            assert!(e.multiple_of.is_none() || e.steps.is_empty(), "{e:?}");
            e.multiple_of.map(|c| format!("{:?}", c.fact))
        };
        assert_eq!(
            multiple("3*F*L/2", "3*m*a/(2*g)"),
            Some("Line(2)".to_string())
        );
        assert_eq!(multiple("m*a", "F*L*g"), Some("Line(2)".to_string()));
        assert_eq!(multiple("2*F*L", "m*a/g"), None);
    }
}
