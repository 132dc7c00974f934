//! Eliminating unknowns with facts: sequential linear elimination (which is Gaussian
//! elimination over the field of rational functions in the parameters) and principal
//! roots of positive unknowns that appear only as `u^n`.

use crate::normal::atom::{self, AtomId};
use crate::normal::subst::{atom_depends_on, depends_on, subst_atom};
use crate::normal::{func, Assumptions, NormError, Poly, Rat, Sign};
use std::time::Instant;

/// A fact `value = 0`, with the name it is cited by.
#[derive(Clone, Debug)]
pub struct Fact {
    /// The left side minus the right side.
    pub value: Rat,
    /// `[Fx]` or `line 12`.
    pub name: String,
}

/// One solved unknown.
#[derive(Clone, Debug)]
pub struct Step {
    /// The unknown.
    pub unknown: AtomId,
    /// Its value in terms of the remaining symbols.
    pub value: Rat,
    /// The fact it came from.
    pub fact: String,
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
    pub contradiction: Option<String>,
    /// Unknowns left in the target that no fact determined.
    pub stuck: Vec<AtomId>,
    /// Whether the time budget ran out.
    pub timed_out: bool,
    /// The fact the target is a constant multiple of, when that settled it.
    pub multiple_of: Option<String>,
}

/// Eliminates the unknowns in `target` using `facts`; then, if the target is still not
/// zero, any symbol that a remaining fact free of unknowns determines (a given such as
/// `g = 9.81`).
pub fn eliminate(
    target: &Rat,
    facts: &[Fact],
    is_unknown: &dyn Fn(AtomId) -> bool,
    signs: &Assumptions,
    deadline: Option<Instant>,
) -> Result<Elimination, NormError> {
    // A constant multiple of one fact needs no elimination (and no side condition).
    for f in facts {
        if let Ok(r) = target.div(&f.value) {
            if r.as_constant().is_some() {
                return Ok(Elimination {
                    target: Rat::zero(),
                    steps: Vec::new(),
                    contradiction: None,
                    stuck: Vec::new(),
                    timed_out: false,
                    multiple_of: Some(f.name.clone()),
                });
            }
        }
    }
    let first = eliminate_with(target, facts, is_unknown, signs, deadline, false)?;
    if first.target.is_zero() || first.contradiction.is_some() || first.timed_out {
        return Ok(first);
    }
    let used: Vec<&str> = first.steps.iter().map(|s| s.fact.as_str()).collect();
    let mut rest: Vec<Fact> = Vec::new();
    // Only facts free of unknowns (relations among the parameters, such as a given
    // `g = 9.81`) may determine a parameter: solving a law of motion for `g` would
    // divide by quantities nobody declared nonzero.
    for f in facts.iter().filter(|f| !used.contains(&f.name.as_str())) {
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
    let any_symbol = |a: AtomId| atom::sym_name(a).is_some();
    let second = eliminate_with(&first.target, &rest, &any_symbol, signs, deadline, false)?;
    if !second.target.is_zero() {
        return Ok(first);
    }
    let mut steps = first.steps;
    steps.extend(second.steps);
    Ok(Elimination { steps, ..second })
}

fn eliminate_with(
    target: &Rat,
    facts: &[Fact],
    is_unknown: &dyn Fn(AtomId) -> bool,
    signs: &Assumptions,
    deadline: Option<Instant>,
    strict: bool,
) -> Result<Elimination, NormError> {
    let mut conditional = false;
    let mut target = target.clone();
    let mut facts: Vec<Fact> = facts.to_vec();
    let mut steps = Vec::new();
    let mut contradiction = None;
    let mut timed_out = false;
    loop {
        if deadline.is_some_and(|d| Instant::now() > d) {
            timed_out = true;
            break;
        }
        // Content order, not id order: the same file is checked the same way in every run.
        // An unknown inside another atom (`sqrt(I_O/m)`) counts: substituting its value
        // rebuilds that atom.
        let mut unknowns: Vec<AtomId> = target
            .atoms()
            .into_iter()
            .filter(|a| is_unknown(*a))
            .collect();
        for f in &facts {
            for a in f.value.atoms() {
                if is_unknown(a) && !unknowns.contains(&a) && depends_on(&target, a) {
                    unknowns.push(a);
                }
            }
        }
        unknowns.sort_by(|a, b| atom::cmp_atoms(*a, *b));
        if unknowns.is_empty() {
            break;
        }
        // The best (fact, unknown) pair: no division by a quantity of unknown sign if
        // possible, then the fact with fewest unknowns.
        let mut best: Option<((bool, usize), usize, AtomId, Solution)> = None;
        for u in &unknowns {
            for (i, f) in facts.iter().enumerate() {
                let n_unknowns = f.value.atoms().iter().filter(|a| is_unknown(**a)).count();
                if best.as_ref().is_some_and(|b| b.0 <= (false, n_unknowns)) {
                    continue;
                }
                if let Some(sol) = solve_for(&f.value, *u, signs)? {
                    let rank = (sol.divisor.is_some(), n_unknowns);
                    if strict && rank.0 {
                        continue;
                    }
                    if best.as_ref().is_none_or(|b| rank < b.0) {
                        best = Some((rank, i, *u, sol));
                    }
                }
            }
        }
        let Some((_, i, u, sol)) = best else {
            break;
        };
        conditional |= sol.divisor.is_some();
        let fact = facts.remove(i);
        target = subst_atom(&target, u, &sol.value, signs)?;
        let mut kept = Vec::with_capacity(facts.len());
        for f in facts {
            let v = match subst_atom(&f.value, u, &sol.value, signs) {
                Ok(v) => v,
                // The substitution makes this fact undefined: it cannot be used further.
                Err(NormError::DivisionByZero) => continue,
                Err(e) => return Err(e),
            };
            if v.is_zero() {
                continue;
            }
            if contradiction.is_none()
                && !conditional
                && !v.atoms().iter().any(|a| is_unknown(*a))
                && signs.rat(&v).is_nonzero()
            {
                contradiction = Some(f.name.clone());
            }
            kept.push(Fact {
                value: v,
                name: f.name,
            });
        }
        facts = kept;
        steps.push(Step {
            unknown: u,
            value: sol.value,
            fact: fact.name,
            divisor: sol.divisor,
        });
    }
    let mut stuck = Vec::new();
    unknowns_within(&target, is_unknown, &mut stuck);
    stuck.sort_by(|a, b| atom::cmp_atoms(*a, *b));
    stuck.dedup();
    Ok(Elimination {
        target,
        steps,
        contradiction,
        stuck,
        timed_out,
        multiple_of: None,
    })
}

/// A fact that gives `u` only through `u^n` (n ≥ 2) while `u` is not declared positive
/// or nonnegative, so that no principal root could be taken: its name and `n`.
pub fn power_only(facts: &[Fact], u: AtomId, signs: &Assumptions) -> Option<(String, u32)> {
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
        match &*atom::get(a) {
            Atom::Sym(_) | Atom::Pi | Atom::Moment(..) => {}
            Atom::Sqrt(p) | Atom::Root(p, _) | Atom::Abs(p) => poly(p, out),
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

struct Solution {
    value: Rat,
    divisor: Option<Rat>,
}

/// Solves `f = 0` for `u` when `f` is linear in `u`, or (for a positive unknown)
/// involves `u` only as `u^n`.
fn solve_for(f: &Rat, u: AtomId, signs: &Assumptions) -> Result<Option<Solution>, NormError> {
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
    let lead = Rat::poly(lead)?;
    let rest = Rat::poly(rest)?;
    let divisor =
        (!signs.rat(&lead).is_nonzero() && lead.as_constant().is_none()).then(|| lead.clone());
    let base = rest.neg().div(&lead)?;
    let value = if deg == 1 {
        base
    } else {
        // u^n = base with u > 0 (or ≥ 0): the principal root.
        match signs.declared(u) {
            Sign::Pos | Sign::NonNeg => func::root(&base, deg, signs)?,
            _ => return Ok(None),
        }
    };
    Ok(Some(Solution { value, divisor }))
}

/// `target` with every unknown the facts determine replaced, and then every parameter
/// that a fact free of unknowns fixes (a given `g = 9.81`): the value of a side.
pub fn reduce_fully(
    target: &Rat,
    facts: &[Fact],
    is_unknown: &dyn Fn(AtomId) -> bool,
    signs: &Assumptions,
    deadline: Option<Instant>,
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
    let any_symbol = |a: AtomId| atom::sym_name(a).is_some();
    Ok(eliminate_with(&first.target, &rest, &any_symbol, signs, deadline, true)?.target)
}

/// Whether `d` is zero by the facts, shown by eliminating atoms only with coefficients
/// that are provably nonzero (so the conclusion holds without side conditions).
pub fn zero_by_facts(d: &Rat, facts: &[Fact], signs: &Assumptions) -> bool {
    if d.is_zero() {
        return true;
    }
    let any_atom = |a: AtomId| !matches!(&*atom::get(a), crate::normal::Atom::Pi);
    eliminate_with(d, facts, &any_atom, signs, None, true).is_ok_and(|e| e.target.is_zero())
}

/// A fact that the others make false (a nonzero quantity equal to zero), found by
/// eliminating atoms with provably nonzero coefficients only.
pub fn contradiction(facts: &[Fact], signs: &Assumptions) -> Option<String> {
    let mut fs: Vec<Fact> = facts.to_vec();
    for _ in 0..=facts.len() {
        if let Some(f) = fs.iter().find(|f| signs.rat(&f.value).is_nonzero()) {
            return Some(f.name.clone());
        }
        let mut pick = None;
        'outer: for (i, f) in fs.iter().enumerate() {
            let mut atoms = f.value.num().atoms();
            atoms.sort_by(|a, b| atom::cmp_atoms(*a, *b));
            for u in atoms {
                if matches!(&*atom::get(u), crate::normal::Atom::Pi) {
                    continue;
                }
                if let Ok(Some(sol)) = solve_for(&f.value, u, signs) {
                    if sol.divisor.is_none() {
                        pick = Some((i, u, sol.value));
                        break 'outer;
                    }
                }
            }
        }
        let (i, u, value) = pick?;
        fs.remove(i);
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
    }
    None
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
    atom::sym_name(a).unwrap_or_else(|| "?".into())
}
