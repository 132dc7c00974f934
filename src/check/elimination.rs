//! Eliminating unknowns with facts: sequential linear elimination (which is Gaussian
//! elimination over the field of rational functions in the parameters) and principal
//! roots of positive unknowns that appear only as `u^n`.

use crate::clock::Deadline;
use crate::diag::{Cited, Text};
use crate::normal::atom::{self, AtomId};
use crate::normal::subst::{atom_depends_on, subst_atom};
use crate::normal::{func, Assumptions, NormError, Poly, Rat, Sign};
use foldhash::{HashMap, HashMapExt, HashSet, HashSetExt};
use std::cell::RefCell;

/// Which atoms a fact is solved for first, and whether an atom may be solved for (given
/// whether solving divides by a quantity the signs do not show nonzero).
type Choice<'a> = (&'a dyn Fn(AtomId) -> bool, &'a dyn Fn(AtomId, bool) -> bool);

/// A fact `value = 0`, with the name it is cited by.
#[derive(Clone, Debug)]
pub struct Fact {
    /// The left side minus the right side.
    pub value: Rat,
    /// How it is cited (with the times it was differentiated).
    pub name: Cited,
}

/// The facts without repeats: a fact whose value is one before it, or its negation,
/// states nothing new (notes state a relation, then use it as stated). The first is
/// kept, so the facts are cited as before.
pub(super) fn distinct(facts: Vec<Fact>) -> Vec<Fact> {
    let mut out: Vec<Fact> = Vec::with_capacity(facts.len());
    for f in facts {
        if !out.iter().any(|g| same_up_to_sign(&g.value, &f.value)) {
            out.push(f);
        }
    }
    out
}

/// The values of [`distinct`]`(facts)`, without copying the facts.
pub(super) fn distinct_values(facts: &[Fact]) -> Vec<Rat> {
    let mut out: Vec<&Rat> = Vec::with_capacity(facts.len());
    for f in facts {
        if !out.iter().any(|g| same_up_to_sign(g, &f.value)) {
            out.push(&f.value);
        }
    }
    out.into_iter().cloned().collect()
}

/// `a = b` or `a = -b`, comparing in full (nothing hashed: that divides) only values with
/// the same monomials, as normal forms equal up to sign have.
fn same_up_to_sign(a: &Rat, b: &Rat) -> bool {
    same_monomials(a.num(), b.num())
        && same_monomials(a.den(), b.den())
        && (a == b || a.neg() == *b)
}

/// Whether `p` and `q` have the same monomials (their coefficients aside).
fn same_monomials(p: &Poly, q: &Poly) -> bool {
    p.terms().len() == q.terms().len() && p.terms().iter().zip(q.terms()).all(|(s, t)| s.0 == t.0)
}

/// One solved unknown.
#[derive(Clone, Debug)]
pub struct Step {
    /// The unknown.
    pub unknown: AtomId,
    /// Its value in terms of the remaining symbols.
    pub value: Rat,
    /// The fact it came from.
    pub fact: Cited,
    /// The divisor of the solution, when not known nonzero.
    pub divisor: Option<Rat>,
}

/// The outcome of eliminating unknowns from a target.
#[derive(Clone, Debug)]
pub struct Elimination {
    /// The target after substitution.
    pub target: Rat,
    /// The steps taken, in order.
    pub steps: Vec<Step>,
    /// A fact that reduced to a false statement (facts contradict), by name.
    pub contradiction: Option<Cited>,
    /// Unknowns left in the target that no fact determined.
    pub stuck: Vec<AtomId>,
    /// Whether the time budget ran out.
    pub timed_out: bool,
    /// The fact the target is a constant multiple of, when that settled it.
    pub multiple_of: Option<Cited>,
    /// When the target is left nonzero: a fact it is the quotient of by a factor the
    /// signs do not show nonzero (the fact's name and that factor), so that the step
    /// would follow where the factor is not zero.
    pub multiple_where: Option<(Cited, Rat)>,
}

/// Eliminates the unknowns in `target` using `facts`; then, if the target is still not
/// zero, any symbol that a remaining fact free of unknowns determines (a given such as
/// `g = 9.81`).
pub fn eliminate(
    target: &Rat,
    facts: &[Fact],
    is_unknown: &dyn Fn(AtomId) -> bool,
    signs: &Assumptions,
    deadline: Option<Deadline>,
) -> Result<Elimination, NormError> {
    // A constant multiple of one fact needs no elimination (and no side condition). Being
    // canonical, it has the fact's denominator and monomials: only such facts are tried.
    let may_be_multiple = |f: &&Fact| {
        target.is_zero()
            || (target.den() == f.value.den() && same_monomials(target.num(), f.value.num()))
    };
    for f in facts.iter().filter(may_be_multiple) {
        if let Ok(r) = target.div(&f.value) {
            if r.as_constant().is_some() {
                return Ok(Elimination {
                    target: Rat::zero(),
                    steps: Vec::new(),
                    contradiction: None,
                    stuck: Vec::new(),
                    timed_out: false,
                    multiple_of: Some(f.name.clone()),
                    multiple_where: None,
                });
            }
        }
    }
    let first = eliminate_with(target, facts, is_unknown, signs, deadline, false)?;
    if first.target.is_zero() || first.contradiction.is_some() || first.timed_out {
        return Ok(first);
    }
    let first = multiple_of_a_fact(first, facts, signs);
    if first.target.is_zero() {
        return Ok(first);
    }
    let used: Vec<&Cited> = first.steps.iter().map(|s| &s.fact).collect();
    let mut rest: Vec<Fact> = Vec::new();
    // Only facts free of unknowns (relations among the parameters, such as a given
    // `g = 9.81`) may determine a parameter: solving a law of motion for `g` would
    // divide by quantities nobody declared nonzero.
    for f in facts.iter().filter(|f| !used.contains(&&f.name)) {
        let v = match apply_steps(&f.value, &first.steps, signs) {
            Ok(v) => v,
            Err(_) => continue,
        };
        if !v.is_zero() && !v.atoms().iter().any(|a| is_unknown(*a)) {
            rest.push(Fact {
                value: v,
                name: f.name.clone(),
            });
        }
    }
    let any_symbol = |a: AtomId| atom::sym_str(a).is_some();
    let second = eliminate_with(&first.target, &rest, &any_symbol, signs, deadline, false)?;
    if !second.target.is_zero() {
        return Ok(first);
    }
    let mut steps = first.steps;
    steps.extend(second.steps);
    Ok(Elimination { steps, ..second })
}

/// After an elimination that left the target nonzero: a fact left over (the
/// elimination's steps applied) of which the target is a multiple, `target = r · fact`.
/// Where the fact holds and `r` is defined the target is zero, so the step follows when
/// the signs make `r`'s denominator nonzero: `a b = I_G/m` is `F/m - b F a/I_G = 0`
/// times `-I_G/F`, which needs `F != 0` (for `F = 0` the fact says nothing about `a b`),
/// whatever else the fact holds (unknowns such as `y_G''` included). A quotient by a
/// factor the signs do not show nonzero is never assumed: the fact and the factor are
/// kept for the explanation instead.
fn multiple_of_a_fact(mut e: Elimination, facts: &[Fact], signs: &Assumptions) -> Elimination {
    let used: Vec<&Cited> = e.steps.iter().map(|s| &s.fact).collect();
    let target_atoms = e.target.num().atoms();
    for f in facts.iter().filter(|f| !used.contains(&&f.name)) {
        let Ok(value) = apply_steps(&f.value, &e.steps, signs) else {
            continue;
        };
        // Cheap filter: a fact sharing no atom with the target's numerator is one of
        // which it is a multiple only through the whole fact in the denominator, that is
        // a fact the signs make false (which `contradiction` reports).
        if value.is_zero() || !value.num().atoms().iter().any(|a| target_atoms.contains(a)) {
            continue;
        }
        let Ok(r) = e.target.div(&value) else {
            continue;
        };
        if r.den().atoms().is_empty() || signs.poly(r.den()).is_nonzero() {
            e.target = Rat::zero();
            e.stuck.clear();
            e.multiple_of = Some(f.name.clone());
            e.multiple_where = None;
            return e;
        }
        // The step is the fact divided by a factor: its numerator divides the fact's.
        let divides = target_atoms.iter().all(|a| value.num().atoms().contains(a))
            && matches!(
                crate::normal::gcd::div_exact(value.num(), e.target.num()),
                Ok(Some(q)) if !q.atoms().is_empty()
            );
        if divides && e.multiple_where.is_none() {
            if let Ok(d) = Rat::poly(r.den().clone()) {
                e.multiple_where = Some((f.name.clone(), d));
            }
        }
    }
    e
}

fn eliminate_with(
    target: &Rat,
    facts: &[Fact],
    is_unknown: &dyn Fn(AtomId) -> bool,
    signs: &Assumptions,
    deadline: Option<Deadline>,
    strict: bool,
) -> Result<Elimination, NormError> {
    eliminate_left(target, facts, is_unknown, signs, deadline, strict).map(|(e, _)| e)
}

/// [`eliminate_with`], with the facts left over: each fact not used, the steps applied
/// (the same as [`apply_steps`] on it), in order, those that became zero or undefined
/// left out.
fn eliminate_left(
    target: &Rat,
    facts: &[Fact],
    is_unknown: &dyn Fn(AtomId) -> bool,
    signs: &Assumptions,
    deadline: Option<Deadline>,
    strict: bool,
) -> Result<(Elimination, Vec<Fact>), NormError> {
    let mut conditional = false;
    let mut target = target.clone();
    let mut facts: Vec<Fact> = facts.to_vec();
    // Each fact's solutions for the unknowns tried so far, kept while it is unchanged.
    let mut memo: Vec<Memo> = vec![Memo::new(); facts.len()];
    let mut steps = Vec::new();
    let mut contradiction = None;
    let mut timed_out = false;
    let mut multiple = None;
    loop {
        if deadline.is_some_and(|d| d.passed()) {
            timed_out = true;
            break;
        }
        let target_atoms = target.atoms();
        let unknowns = unknowns_of_target(&target_atoms, &facts, is_unknown);
        if unknowns.is_empty() {
            break;
        }
        // A multiple of a fact (by a factor with a denominator the signs make nonzero)
        // is zero by that fact: no division, no condition.
        if let Some(f) = facts
            .iter()
            .find(|f| multiple_of((&target, &target_atoms), &f.value, signs))
        {
            multiple = Some(f.name.clone());
            target = Rat::zero();
            break;
        }
        // The best (fact, unknown) pair: no division by a quantity of unknown sign if
        // possible, then the fact with fewest unknowns.
        let mut best = best_pair(&unknowns, (&facts, &mut memo), is_unknown, signs, strict)?;
        if best.as_ref().is_none_or(|b| b.0.divides) {
            // Every way to remove an unknown of the target divides: first remove another
            // unknown of the facts without dividing, if one can be.
            let mut others: Vec<AtomId> = Vec::new();
            let relevant = facts
                .iter()
                .filter(|f| unknowns.iter().any(|u| f.value.contains(*u)));
            for f in relevant {
                for a in f.value.atoms() {
                    if is_unknown(a) && !unknowns.contains(&a) && !others.contains(&a) {
                        others.push(a);
                    }
                }
            }
            others.sort_by(|a, b| atom::cmp_atoms(*a, *b));
            if let Some(b) = best_pair(&others, (&facts, &mut memo), is_unknown, signs, true)? {
                best = Some(b);
            }
        }
        let Some((_, i, u, sol)) = best else {
            break;
        };
        conditional |= sol.divisor.is_some();
        let fact = facts.remove(i);
        memo.remove(i);
        target = subst_atom(&target, u, &sol.value, signs)?;
        let found = substitute_in_facts(
            (facts, std::mem::take(&mut memo)),
            (u, &sol.value),
            is_unknown,
            signs,
            !conditional && contradiction.is_none(),
        )?;
        (facts, memo) = (found.0, found.1);
        contradiction = contradiction.or(found.2);
        steps.push(Step {
            unknown: u,
            value: sol.value,
            fact: fact.name,
            divisor: sol.divisor,
        });
    }
    // Related angles, large powers kept factored, products of abs and roots.
    let target = crate::normal::settle(&target, signs);
    let mut stuck = Vec::new();
    unknowns_within(&target, is_unknown, &mut stuck);
    stuck.sort_by(|a, b| atom::cmp_atoms(*a, *b));
    stuck.dedup();
    let e = Elimination {
        target,
        steps,
        contradiction,
        stuck,
        timed_out,
        multiple_of: multiple,
        multiple_where: None,
    };
    Ok((e, facts))
}

/// The unknowns to eliminate from a target, in content order (not id order: the same
/// file is checked the same way in every run). An unknown inside another atom of the
/// target (`sqrt(I_O/m)`) counts: substituting its value rebuilds that atom.
fn unknowns_of_target(
    target_atoms: &[AtomId],
    facts: &[Fact],
    is_unknown: &dyn Fn(AtomId) -> bool,
) -> Vec<AtomId> {
    let mut unknowns: Vec<AtomId> = target_atoms
        .iter()
        .copied()
        .filter(|a| is_unknown(*a))
        .collect();
    for f in facts {
        for a in f.value.atoms() {
            if is_unknown(a)
                && !unknowns.contains(&a)
                && target_atoms.iter().any(|t| atom_depends_on(*t, a))
            {
                unknowns.push(a);
            }
        }
    }
    unknowns.sort_by(|a, b| atom::cmp_atoms(*a, *b));
    unknowns
}

/// The facts kept after a substitution, their memos, and a contradiction found.
type Substituted = (Vec<Fact>, Vec<Memo>, Option<Cited>);

/// The remaining facts (and their memos) with `u` replaced by `value`: facts that become
/// zero or undefined are dropped. With `watch`, the first fact that becomes a nonzero
/// quantity free of unknowns is returned as a contradiction.
fn substitute_in_facts(
    (facts, memo): (Vec<Fact>, Vec<Memo>),
    (u, value): (AtomId, &Rat),
    is_unknown: &dyn Fn(AtomId) -> bool,
    signs: &Assumptions,
    watch: bool,
) -> Result<Substituted, NormError> {
    let mut contradiction = None;
    let mut kept = Vec::with_capacity(facts.len());
    let mut kept_memo = Vec::with_capacity(facts.len());
    for (f, m) in facts.into_iter().zip(memo) {
        let v = match subst_atom(&f.value, u, value, signs) {
            Ok(v) => v,
            // The substitution makes this fact undefined: it cannot be used further.
            Err(NormError::DivisionByZero) => continue,
            Err(e) => return Err(e),
        };
        if v.is_zero() {
            continue;
        }
        if watch
            && contradiction.is_none()
            && !v.atoms().iter().any(|a| is_unknown(*a))
            && signs.rat(&v).is_nonzero()
        {
            contradiction = Some(f.name.clone());
        }
        kept_memo.push(if v == f.value { m } else { Memo::new() });
        kept.push(Fact {
            value: v,
            name: f.name,
        });
    }
    Ok((kept, kept_memo, contradiction))
}

/// Whether `target` is `r · fact` for an `r` whose denominator the signs make nonzero.
/// (`atoms`: the target's.)
fn multiple_of((target, atoms): (&Rat, &[AtomId]), fact: &Rat, signs: &Assumptions) -> bool {
    if fact.is_zero() || target.is_zero() {
        return false;
    }
    // Cheap filter: every atom of the fact's numerator must occur in the target.
    if !fact.num().atoms().iter().all(|a| atoms.contains(a)) {
        return false;
    }
    target
        .div(fact)
        .is_ok_and(|r| r.den().atoms().is_empty() || signs.poly(r.den()).is_nonzero())
}

/// How good a (fact, unknown) pair is to solve: smaller is better, field by field.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct Rank {
    /// Solving divides by a quantity the signs do not show nonzero.
    divides: bool,
    /// The fact is not linear in the unknown.
    nonlinear: bool,
    /// The number of unknowns in the fact.
    unknowns: usize,
}

type Pair = (Rank, usize, AtomId, Solution);

/// A fact's ways of being solved (or none) for the unknowns tried, with the solution
/// once it was needed.
type Memo = foldhash::HashMap<AtomId, Option<(Setup, Option<Solution>)>>;

/// The best (fact, unknown) pair to solve: no division by a quantity of unknown sign if
/// possible (only such pairs when `strict`), then a fact linear in the unknown (so that
/// `v = R omega` is substituted before `v` is taken as a root of the energy equation,
/// whatever the order the facts are cited in), then the fact with fewest unknowns.
fn best_pair(
    unknowns: &[AtomId],
    (facts, memo): (&[Fact], &mut [Memo]),
    is_unknown: &dyn Fn(AtomId) -> bool,
    signs: &Assumptions,
    strict: bool,
) -> Result<Option<Pair>, NormError> {
    let mut best: Option<Pair> = None;
    // Each fact's number of unknowns, counted once.
    let mut counts: Vec<Option<usize>> = vec![None; facts.len()];
    for u in unknowns {
        for (i, f) in facts.iter().enumerate() {
            // A fact without `u` cannot be solved for it.
            if !f.value.num().contains(*u) {
                continue;
            }
            let n_unknowns = *counts[i]
                .get_or_insert_with(|| f.value.atoms().iter().filter(|a| is_unknown(**a)).count());
            // An equation of motion gives its highest derivative from the state: never
            // solve a fact for a derivative of which it holds a higher one (θ' from
            // θ'' = θ'/2), which would leave the state undetermined.
            if has_higher_derivative(&f.value, *u) {
                continue;
            }
            let nonlinear = f.value.num().degree_in(*u) != 1 || f.value.den().contains(*u);
            let at_best = Rank {
                divides: false,
                nonlinear,
                unknowns: n_unknowns,
            };
            if best.as_ref().is_some_and(|b| b.0 <= at_best) {
                continue;
            }
            let Some(m) = memo.get_mut(i) else {
                continue;
            };
            if !m.contains_key(u) {
                let s = setup(&f.value, *u, signs)?;
                m.insert(*u, s.map(|s| (s, None)));
            }
            let Some(Some((s, solution))) = m.get_mut(u) else {
                continue;
            };
            let rank = Rank {
                divides: s.divisor.is_some(),
                ..at_best
            };
            // Only the pair chosen needs its solution.
            if strict && rank.divides || best.as_ref().is_some_and(|b| rank >= b.0) {
                continue;
            }
            let sol = match solution {
                Some(sol) => sol.clone(),
                None => solution.insert(finish(s, signs)?).clone(),
            };
            best = Some((rank, i, *u, sol));
        }
    }
    Ok(best)
}

/// Whether `f` holds a higher time derivative of `u`'s symbol than `u`.
fn has_higher_derivative(f: &Rat, u: AtomId) -> bool {
    let Some(name) = atom::sym_str(u) else {
        return false;
    };
    let base = name.trim_end_matches('\'');
    let order = name.len() - base.len();
    f.atoms().iter().any(|a| {
        atom::sym_str(*a).is_some_and(|n| {
            let b = n.trim_end_matches('\'');
            b == base && n.len() - b.len() > order
        })
    })
}

/// A fact that gives `u` only through `u^n` (n ≥ 2) while `u` is not declared positive
/// or nonnegative, so that no principal root could be taken: its name and `n`.
pub fn power_only(facts: &[Fact], u: AtomId, signs: &Assumptions) -> Option<(Cited, u32)> {
    if matches!(signs.declared(u), Sign::Pos | Sign::NonNeg) {
        return None;
    }
    facts.iter().find_map(|f| {
        let n = f.value.num();
        if !n.contains(u) || f.value.den().contains(u) {
            return None;
        }
        match n.coeffs_in(u).as_slice() {
            [(0, _), (e, c)] | [(e, c)] if *e >= 2 && !c.contains(u) => Some((f.name.clone(), *e)),
            _ => None,
        }
    })
}

/// The unknowns in `r`, also inside the arguments of other atoms (`sqrt(I_O/m)`).
fn unknowns_within(r: &Rat, is_unknown: &dyn Fn(AtomId) -> bool, out: &mut Vec<AtomId>) {
    use crate::normal::Atom;
    let poly = |p: &Poly, out: &mut Vec<AtomId>| {
        if let Ok(r) = Rat::poly(p.clone()) {
            unknowns_within(&r, is_unknown, out);
        }
    };
    for a in r.atoms() {
        if is_unknown(a) {
            out.push(a);
            continue;
        }
        match atom::get(a) {
            Atom::Sym(_) | Atom::Pi | Atom::Moment(..) | Atom::At(..) => {}
            Atom::Sqrt(p) | Atom::Root(p, _) | Atom::Abs(p) | Atom::Factor(p) => poly(p, out),
            Atom::Sin(u) | Atom::Cos(u) | Atom::Exp(u) | Atom::Ln(u) => {
                unknowns_within(u, is_unknown, out)
            }
            Atom::Pow(b, e) => {
                unknowns_within(b, is_unknown, out);
                unknowns_within(e, is_unknown, out);
            }
        }
    }
}

#[derive(Clone)]
pub(super) struct Solution {
    pub(super) value: Rat,
    divisor: Option<Rat>,
}

/// `f = 0` as `lead · u^deg + rest = 0`, before the division that solves it.
#[derive(Clone)]
pub(super) struct Setup {
    lead: Rat,
    rest: Rat,
    pub(super) deg: u32,
    /// The divisor of the solution, when the signs do not make it nonzero.
    pub(super) divisor: Option<Rat>,
}

/// Whether `f = 0` can be solved for `u` — when `f` is linear in `u`, or (for a
/// positive unknown) involves `u` only as `u^n` — and how: everything but the division
/// ([`finish`]), which only the pair chosen needs.
pub(super) fn setup(f: &Rat, u: AtomId, signs: &Assumptions) -> Result<Option<Setup>, NormError> {
    let n = f.num();
    if !n.contains(u) {
        return Ok(None);
    }
    // u must not hide inside other atoms (sin(u), sqrt(u)…) or in the denominator.
    if f.den().contains(u) || n.atoms().iter().any(|a| *a != u && atom_depends_on(*a, u)) {
        return Ok(None);
    }
    let coeffs = n.coeffs_in(u);
    let deg = n.degree_in(u);
    let (lead, rest): (Poly, Poly) = match coeffs.as_slice() {
        [(0, c0), (e, c1)] if *e == deg => (c1.clone(), c0.clone()),
        [(e, c1)] if *e == deg => (c1.clone(), Poly::zero()),
        _ => return Ok(None),
    };
    if lead.atoms().contains(&u) {
        return Ok(None);
    }
    // u^n = … is solved only for u > 0 (or ≥ 0): the principal root.
    if deg != 1 && !matches!(signs.declared(u), Sign::Pos | Sign::NonNeg) {
        return Ok(None);
    }
    let lead = Rat::poly(lead)?;
    let rest = Rat::poly(rest)?;
    let divisor =
        (!signs.rat(&lead).is_nonzero() && lead.as_constant().is_none()).then(|| lead.clone());
    Ok(Some(Setup {
        lead,
        rest,
        deg,
        divisor,
    }))
}

/// The solution set up by [`setup`].
pub(super) fn finish(s: &Setup, signs: &Assumptions) -> Result<Solution, NormError> {
    let base = s.rest.neg().div(&s.lead)?;
    let value = if s.deg == 1 {
        base
    } else {
        func::root(&base, s.deg, signs)?
    };
    Ok(Solution {
        value,
        divisor: s.divisor.clone(),
    })
}

/// `target` with every unknown the facts determine replaced, and then every parameter
/// that a fact free of unknowns fixes (a given `g = 9.81`): the value of a side.
pub fn reduce_fully(
    target: &Rat,
    facts: &[Fact],
    is_unknown: &dyn Fn(AtomId) -> bool,
    signs: &Assumptions,
    deadline: Option<Deadline>,
) -> Result<Rat, NormError> {
    let first = eliminate_with(target, facts, is_unknown, signs, deadline, false)?;
    let mut rest: Vec<Fact> = Vec::new();
    for f in facts {
        if let Ok(v) = apply_steps(&f.value, &first.steps, signs) {
            if !v.is_zero() && !v.atoms().iter().any(|a| is_unknown(*a)) {
                rest.push(Fact {
                    value: v,
                    name: f.name.clone(),
                });
            }
        }
    }
    let any_symbol = |a: AtomId| atom::sym_str(a).is_some();
    Ok(eliminate_with(&first.target, &rest, &any_symbol, signs, deadline, true)?.target)
}

/// Whether `d` is zero by the facts, shown by eliminating atoms only with coefficients
/// that are provably nonzero (so the conclusion holds without side conditions), or by a
/// simple nonlinear consequence of one fact (`c^2 = 0`, `c F = 0` with `F > 0`).
pub fn zero_by_facts(d: &Rat, facts: &[Fact], signs: &Assumptions) -> bool {
    if d.is_zero() {
        return true;
    }
    if facts.iter().any(|f| forces_zero(&f.value, d, signs)) {
        return true;
    }
    let any_atom = |a: AtomId| !atom::is_pi(a);
    let Ok((e, left)) = eliminate_left(d, facts, &any_atom, signs, None, true) else {
        return false;
    };
    if e.target.is_zero() {
        return true;
    }
    // The facts left after the elimination may still force the reduced divisor to zero.
    left.iter().any(|f| forces_zero(&f.value, &e.target, signs))
}

/// Whether the fact `value = 0` forces `d = 0`: the fact's numerator is a power of a
/// common factor `g` of `d`'s numerator times something the signs make nonzero, so `g = 0`
/// (and `g` divides `d`).
fn forces_zero(value: &Rat, d: &Rat, signs: &Assumptions) -> bool {
    let (n, dn) = (value.num(), d.num());
    if n.is_zero() || dn.is_zero() {
        return false;
    }
    let Ok(g) = crate::normal::gcd::gcd(n, dn) else {
        return false;
    };
    if g.atoms().is_empty() {
        return false;
    }
    let mut u = n.clone();
    for _ in 0..64 {
        match crate::normal::gcd::div_exact(&u, &g) {
            Ok(Some(q)) => u = q,
            _ => break,
        }
    }
    u.atoms().is_empty() || signs.poly(&u).is_nonzero()
}

/// Whether a symbol declared with sign `declared` can take a value of sign `value`.
fn sign_compatible(declared: Sign, value: Sign, is_zero: bool) -> bool {
    match declared {
        Sign::Pos => !is_zero && !value.is_nonpos(),
        Sign::NonNeg => value != Sign::Neg,
        Sign::NonZero | Sign::Neg => !(is_zero || declared == Sign::Neg && value.is_nonneg()),
        Sign::NonPos => value != Sign::Pos,
        _ => true,
    }
}

/// A fact that the others make false (a nonzero quantity equal to zero, or a value for
/// a symbol against its declared sign), found by eliminating atoms with provably nonzero
/// coefficients only, described. The answer does not depend on the order of the
/// symbols' names: every solved symbol's final value is checked against its declared sign.
pub fn contradiction(facts: &[Fact], signs: &Assumptions) -> Option<Text> {
    contradiction_in(facts, signs, 2)
}

/// [`contradiction`], then again with what the facts left force to zero over the reals
/// added to them, `rounds` more times (`u^2 + v^2 = 0` and `(v - 1)^2 + u^2 = 0`
/// contradict each other only through `v = 0` and `v = 1`).
fn contradiction_in(facts: &[Fact], signs: &Assumptions, rounds: u32) -> Option<Text> {
    let says_zero = |name: &Cited| {
        Text::from("with the others, ")
            .cited(std::slice::from_ref(name))
            .and(" says a nonzero quantity is zero")
    };
    // A fact a substitution left unchanged is asked again in the next round: its sign
    // and whether it solves are remembered by value.
    let signed: RefCell<HashMap<Rat, bool>> = RefCell::default();
    let nonzero = |v: &Rat| {
        if let Some(known) = signed.borrow().get(v) {
            return *known;
        }
        let s = super::zeros::definite_sign(v, signs).is_nonzero();
        signed.borrow_mut().insert(v.clone(), s);
        s
    };
    let mut hopeless = HashSet::new();
    let mut fs: Vec<Fact> = facts.to_vec();
    let mut solved: Vec<(AtomId, Rat, Cited)> = Vec::new();
    for _ in 0..=facts.len() {
        if let Some(f) = fs.iter().find(|f| nonzero(&f.value)) {
            return Some(says_zero(&f.name));
        }
        // Only a solution without a divisor.
        let no_divisor = |_, divides: bool| !divides;
        let Some((i, u, value)) =
            first_solvable(&fs, signs, (&|_| false, &no_divisor), &mut hopeless)
        else {
            break;
        };
        let fact = fs.remove(i);
        let mut next = Vec::with_capacity(fs.len());
        for f in fs {
            match subst_atom(&f.value, u, &value, signs) {
                Ok(v) if !v.is_zero() => next.push(Fact {
                    value: v,
                    name: f.name,
                }),
                _ => {}
            }
        }
        fs = next;
        for s in &mut solved {
            if let Ok(v) = subst_atom(&s.1, u, &value, signs) {
                s.1 = v;
            }
        }
        solved.push((u, value, fact.name));
    }
    if let Some(f) = fs.iter().find(|f| nonzero(&f.value)) {
        return Some(says_zero(&f.name));
    }
    // What the facts left force to zero over the reals (the base of a power, each
    // square of a sum of squares) may be nonzero by the signs.
    let implied = super::zeros::consequences(&fs, signs);
    if let Some(f) = implied.iter().find(|f| nonzero(&f.value)) {
        return Some(says_zero(&f.name));
    }
    let against_sign = solved.into_iter().find_map(|(u, v, name)| {
        let declared = signs.declared(u);
        let value = super::zeros::definite_sign(&v, signs);
        (!sign_compatible(declared, value, v.is_zero())).then(|| {
            let x = unknown_name(u);
            let sign = match declared {
                Sign::Pos => "> 0",
                Sign::NonNeg => ">= 0",
                Sign::Neg => "< 0",
                Sign::NonPos => "<= 0",
                _ => "!= 0",
            };
            Text::from("with the others, ").cited(&[name]).and(&format!(
                " gives {x} = {}, against the declared {x} {sign}",
                crate::normal::print::plain(&v)
            ))
        })
    });
    if against_sign.is_some() || rounds == 0 || implied.is_empty() {
        return against_sign;
    }
    fs.extend(implied);
    contradiction_in(&fs, signs, rounds - 1)
}

/// The first fact, and in it the first atom (those `prefer` picks first, then in the
/// atoms' order; never π), that the fact solves for as `allowed` says (`allowed(u,
/// divides)`: whether solving for `u` may divide by something the signs do not show
/// nonzero): the fact's index, the atom and its value.
///
/// `hopeless` holds facts (by value) already found to solve for nothing under the same
/// `prefer` and `allowed`; it is added to.
fn first_solvable(
    fs: &[Fact],
    signs: &Assumptions,
    (prefer, allowed): Choice<'_>,
    hopeless: &mut HashSet<Rat>,
) -> Option<(usize, AtomId, Rat)> {
    for (i, f) in fs.iter().enumerate() {
        if hopeless.contains(&f.value) {
            continue;
        }
        let mut atoms = f.value.num().atoms();
        atoms.sort_by(|a, b| {
            prefer(*b)
                .cmp(&prefer(*a))
                .then_with(|| atom::cmp_atoms(*a, *b))
        });
        for u in atoms {
            if atom::is_pi(u) {
                continue;
            }
            // Set up first, divide only then.
            let Ok(Some(s)) = setup(&f.value, u, signs) else {
                continue;
            };
            if allowed(u, s.divisor.is_some()) {
                if let Ok(sol) = finish(&s, signs) {
                    return Some((i, u, sol.value));
                }
            }
        }
        hopeless.insert(f.value.clone());
    }
    None
}

/// The facts solved one after another (each value substituted into the facts after
/// it), for the guard's points: an unknown with any divisor (the point decides whether
/// it is zero there), a parameter only without one, so that a parameter a fact ties
/// (`I_O = m L^2/3`) gets its value from the others, while facts that hold only in a
/// degenerate case (`g m L (3 I_A - m L^2) = 0`) stay unsolved. The steps, in order,
/// and the facts left.
pub fn solve_for_point(
    facts: &[Fact],
    is_unknown: &dyn Fn(AtomId) -> bool,
    signs: &Assumptions,
) -> (Vec<Step>, Vec<Fact>) {
    let mut fs: Vec<Fact> = facts.to_vec();
    let mut steps = Vec::new();
    loop {
        let allowed =
            |u: AtomId, divides: bool| atom::sym_str(u).is_some() && (!divides || is_unknown(u));
        let Some((i, u, value)) =
            first_solvable(&fs, signs, (is_unknown, &allowed), &mut HashSet::new())
        else {
            return (steps, fs);
        };
        let fact = fs.remove(i);
        fs = fs
            .into_iter()
            .filter_map(|f| match subst_atom(&f.value, u, &value, signs) {
                Ok(v) if v.is_zero() => None,
                Ok(v) => Some(Fact {
                    value: v,
                    name: f.name,
                }),
                Err(_) => Some(f),
            })
            .collect();
        steps.push(Step {
            unknown: u,
            value,
            fact: fact.name,
            divisor: None,
        });
    }
}

/// The atoms that facts left over after an elimination still constrain. The facts are
/// solved, one after another, for unknowns that occur linearly with a coefficient the
/// signs make nonzero (so any values of the other quantities can be met by choosing the
/// unknowns); the atoms of every fact that cannot be satisfied that way are constrained.
/// A step may be called false only where its difference avoids these atoms.
pub fn constrained_atoms(
    facts: &[Fact],
    is_unknown: &dyn Fn(AtomId) -> bool,
    signs: &Assumptions,
) -> Vec<AtomId> {
    let mut fs: Vec<Rat> = facts
        .iter()
        .filter(|f| !f.value.is_zero())
        .map(|f| f.value.clone())
        .collect();
    'solve: loop {
        for (i, f) in fs.iter().enumerate() {
            let mut atoms = f.num().atoms();
            atoms.sort_by(|a, b| atom::cmp_atoms(*a, *b));
            for u in atoms {
                if !is_unknown(u) || f.num().degree_in(u) != 1 {
                    continue;
                }
                let Ok(Some(s)) = setup(f, u, signs) else {
                    continue;
                };
                if s.divisor.is_some() {
                    continue;
                }
                let Ok(sol) = finish(&s, signs) else {
                    continue;
                };
                let mut next = Vec::with_capacity(fs.len());
                for (j, g) in fs.iter().enumerate() {
                    if j == i {
                        continue;
                    }
                    match subst_atom(g, u, &sol.value, signs) {
                        Ok(v) if v.is_zero() => {}
                        Ok(v) => next.push(v),
                        // Undefined once solved: keep the fact as it was, constraining.
                        Err(_) => next.push(g.clone()),
                    }
                }
                fs = next;
                continue 'solve;
            }
        }
        break;
    }
    let mut out = Vec::new();
    for f in &fs {
        let mut found = Vec::new();
        crate::decide::symbols_in(f, &mut found);
        found.extend(
            f.atoms()
                .into_iter()
                .filter(|a| matches!(atom::get(*a), crate::normal::Atom::Moment(..))),
        );
        for a in found {
            if !out.contains(&a) {
                out.push(a);
            }
        }
    }
    out
}

/// The elimination a refutation needs: unknowns first, then (with `params`) every
/// parameter a fact free of unknowns fixes (with provably nonzero coefficients); the
/// target, the steps, and the facts that are left.
pub fn eliminate_all(
    target: &Rat,
    facts: &[Fact],
    is_unknown: &dyn Fn(AtomId) -> bool,
    signs: &Assumptions,
    deadline: Option<Deadline>,
    params: bool,
) -> Result<(Rat, Vec<Step>, Vec<Fact>), NormError> {
    let (first, left) = eliminate_left(target, facts, is_unknown, signs, deadline, false)?;
    let rest = |steps: &[Step]| -> Vec<Fact> {
        facts
            .iter()
            .filter_map(|f| {
                apply_steps(&f.value, steps, signs)
                    .ok()
                    .filter(|v| !v.is_zero())
                    .map(|v| Fact {
                        value: v,
                        name: f.name.clone(),
                    })
            })
            .collect()
    };
    if !params {
        return Ok((first.target, first.steps, left));
    }
    let params: Vec<Fact> = left
        .iter()
        .filter(|f| !f.value.atoms().iter().any(|a| is_unknown(*a)))
        .cloned()
        .collect();
    let any_symbol = |a: AtomId| atom::sym_str(a).is_some();
    let second = eliminate_with(&first.target, &params, &any_symbol, signs, deadline, true)?;
    let mut steps = first.steps;
    steps.extend(second.steps);
    let left = rest(&steps);
    Ok((second.target, steps, left))
}

/// Applies solved steps, in order, to another expression (e.g. a divisor).
pub fn apply_steps(r: &Rat, steps: &[Step], signs: &Assumptions) -> Result<Rat, NormError> {
    let mut cur = r.clone();
    for s in steps {
        cur = subst_atom(&cur, s.unknown, &s.value, signs)?;
    }
    Ok(cur)
}

/// `q` as text (helper for messages).
pub fn unknown_name(a: AtomId) -> String {
    atom::sym_name(a).unwrap_or_else(|| crate::normal::print::atom_plain(atom::get(a)))
}
