//! Substitution: replacing atoms by normal forms, rebuilding the atoms that contain them.

use super::atom::{self, Atom, AtomId};
use super::func;
use super::mono::Mono;
use super::poly::{Poly, Q};
use super::rat::Rat;
use super::sign::Assumptions;
use super::trig;
use super::NormError;
use foldhash::{HashMap, HashMapExt};
use std::borrow::Cow;

/// Replaces atoms: `map(a)` gives the new value of atom `a` (or `None` to keep it,
/// in which case atoms inside its arguments are still replaced).
pub struct Subst<'a> {
    map: &'a dyn Fn(AtomId) -> Option<Rat>,
    signs: &'a Assumptions,
    memo: HashMap<AtomId, Option<Rat>>,
}

impl<'a> Subst<'a> {
    /// A substitution.
    pub fn new(map: &'a dyn Fn(AtomId) -> Option<Rat>, signs: &'a Assumptions) -> Subst<'a> {
        Subst {
            map,
            signs,
            memo: HashMap::new(),
        }
    }

    /// The new value of atom `a`, `None` if unchanged.
    fn atom(&mut self, a: AtomId) -> Result<Option<Rat>, NormError> {
        if let Some(v) = self.memo.get(&a) {
            return Ok(v.clone());
        }
        let v = match (self.map)(a) {
            Some(v) => Some(v),
            None => self.rebuild(a)?,
        };
        self.memo.insert(a, v.clone());
        Ok(v)
    }

    fn rebuild(&mut self, a: AtomId) -> Result<Option<Rat>, NormError> {
        let at = atom::get(a);
        let s = self.signs;
        Ok(match at {
            Atom::Sym(_) | Atom::Pi | Atom::Moment(..) => None,
            Atom::At(name, u) => self.rat_changed(u)?.map(|v| Rat::atom(atom::at(name, &v))),
            Atom::Sqrt(p) => self
                .poly_changed(p)?
                .map(|v| func::sqrt(&v, s))
                .transpose()?,
            Atom::Root(p, n) => self
                .poly_changed(p)?
                .map(|v| func::root(&v, *n, s))
                .transpose()?,
            Atom::Abs(p) => self
                .poly_changed(p)?
                .map(|v| func::abs(&v, s))
                .transpose()?,
            Atom::Factor(p) => self
                .poly_changed(p)?
                .map(|v| super::power::refactor(&v))
                .transpose()?,
            Atom::Sin(u) => self.rat_changed(u)?.map(|v| trig::sin(&v)).transpose()?,
            Atom::Cos(u) => self.rat_changed(u)?.map(|v| trig::cos(&v)).transpose()?,
            Atom::Exp(u) => self.rat_changed(u)?.map(|v| func::exp(&v)).transpose()?,
            Atom::Ln(u) => self.rat_changed(u)?.map(|v| func::ln(&v, s)).transpose()?,
            Atom::Pow(b, e) => {
                let nb = self.rat_changed(b)?;
                let ne = self.rat_changed(e)?;
                if nb.is_none() && ne.is_none() {
                    None
                } else {
                    let b = nb.unwrap_or_else(|| b.clone());
                    let e = ne.unwrap_or_else(|| e.clone());
                    Some(func::pow(&b, &e, s)?)
                }
            }
        })
    }

    fn poly_changed(&mut self, p: &Poly) -> Result<Option<Rat>, NormError> {
        let mut changed = false;
        for a in p.atoms() {
            if self.atom(a)?.is_some() {
                changed = true;
            }
        }
        if !changed {
            return Ok(None);
        }
        self.poly(p).map(Some)
    }

    fn rat_changed(&mut self, r: &Rat) -> Result<Option<Rat>, NormError> {
        let n = self.poly_changed(r.num())?;
        let d = self.poly_changed(r.den())?;
        if n.is_none() && d.is_none() {
            return Ok(None);
        }
        let n = match n {
            Some(n) => n,
            None => Rat::poly(r.num().clone())?,
        };
        let d = match d {
            Some(d) => d,
            None => Rat::poly(r.den().clone())?,
        };
        n.div(&d).map(Some)
    }

    /// The polynomial with every atom replaced, as one rational function.
    pub fn poly(&mut self, p: &Poly) -> Result<Rat, NormError> {
        let atoms = p.atoms();
        let mut vals: HashMap<AtomId, Rat> = HashMap::new();
        for a in &atoms {
            if let Some(v) = self.atom(*a)? {
                vals.insert(*a, v);
            }
        }
        if vals.is_empty() {
            return Rat::poly(p.clone());
        }
        // Common denominator: Π q_a^{D_a}, D_a the top exponent of a.
        let mut top: HashMap<AtomId, u32> = HashMap::new();
        for (m, _) in p.terms() {
            for &(a, e) in m.pairs() {
                if vals.contains_key(&a) {
                    let t = top.entry(a).or_insert(0);
                    *t = (*t).max(e);
                }
            }
        }
        // Powers of the new values, shared by the terms; a one-term value (`x → a`,
        // `x → 0`) is folded into the term's monomial and coefficient directly.
        let mut powers: HashMap<(AtomId, u32, bool), Poly> = HashMap::new();
        let mut acc: Vec<(Mono, Q)> = Vec::with_capacity(p.len());
        'terms: for (m, q) in p.terms() {
            let mut keep = Vec::new();
            let mut coeff = q.clone();
            let mut factors: Vec<(AtomId, u32, bool)> = Vec::new();
            let mut wanted: Vec<(AtomId, u32, bool)> = Vec::new();
            for &(a, e) in m.pairs() {
                if vals.contains_key(&a) {
                    wanted.push((a, e, false));
                } else {
                    keep.push((a, e));
                }
            }
            for (a, d) in &top {
                let e = m.exp(*a);
                if *d > e && vals.get(a).is_some_and(|v| !v.den().is_one()) {
                    wanted.push((*a, d - e, true));
                }
            }
            for (a, e, den) in wanted {
                let Some(v) = vals.get(&a) else { continue };
                let base = if den { v.den() } else { v.num() };
                match base.terms() {
                    [] => continue 'terms,
                    [(vm, vq)] => {
                        coeff = super::qops::mul(&coeff, &super::poly::pow_q_checked(vq, e)?);
                        let vm = vm.pow(e).ok_or(super::Limit::Exponent)?;
                        keep.extend_from_slice(vm.pairs());
                    }
                    _ => {
                        if let std::collections::hash_map::Entry::Vacant(slot) =
                            powers.entry((a, e, den))
                        {
                            slot.insert(base.pow(u64::from(e))?);
                        }
                        factors.push((a, e, den));
                    }
                }
            }
            let keep = Mono::from_pairs(keep).ok_or(super::Limit::Exponent)?;
            let mut t = Poly::term(keep, coeff);
            for k in &factors {
                if let Some(f) = powers.get(k) {
                    t = t.mul(f)?;
                }
            }
            acc.extend(t.terms().iter().cloned());
            if acc.len() > super::poly::max_terms().saturating_mul(4) {
                acc = Poly::from_terms(acc).terms().to_vec();
                if acc.len() > super::poly::max_terms() {
                    return Err(super::Limit::terms().into());
                }
            }
        }
        let num = Poly::from_terms(acc);
        let mut den = Poly::one();
        for (a, d) in &top {
            if let Some(v) = vals.get(a) {
                if !v.den().is_one() {
                    den = den.mul(&v.den().pow(u64::from(*d))?)?;
                }
            }
        }
        Rat::new(num, den)
    }

    /// The rational function with every atom replaced.
    pub fn rat(&mut self, r: &Rat) -> Result<Rat, NormError> {
        let n = self.poly(r.num())?;
        if r.den().is_one() {
            return Ok(n);
        }
        let d = self.poly(r.den())?;
        n.div(&d)
    }
}

/// `r` rebuilt under the signs `s`: every atom that contains the symbol `x` is formed
/// again, so rules that the signs now allow (`abs(x) = x` for `x > 0`) fire. Used when a
/// result computed for a bound variable of unknown sign is read as the free symbol.
pub fn rebuild_under(r: &Rat, x: AtomId, s: &Assumptions) -> Result<Rat, NormError> {
    if !r.atoms().iter().any(|a| *a != x && atom_depends_on(*a, x)) {
        return Ok(r.clone());
    }
    // Through a placeholder no input can name: both passes rebuild every atom holding x.
    let tmp = atom::sym("\u{1}rebuild");
    let there = |a: AtomId| (a == x).then(|| Rat::atom(tmp));
    let back = |a: AtomId| (a == tmp).then(|| Rat::atom(x));
    let mid = Subst::new(&there, s).rat(r)?;
    Subst::new(&back, s).rat(&mid)
}

/// `r` with atom `x` replaced by `v`.
pub fn subst_atom(r: &Rat, x: AtomId, v: &Rat, s: &Assumptions) -> Result<Rat, NormError> {
    subst_atom_cow(Cow::Borrowed(r), x, v, s)
}

/// [`subst_atom`] of a value the caller gives up: renaming a symbol to another (a
/// bound of integration, say) reuses its terms instead of copying them.
pub fn subst_atom_owned(r: Rat, x: AtomId, v: &Rat, s: &Assumptions) -> Result<Rat, NormError> {
    subst_atom_cow(Cow::Owned(r), x, v, s)
}

fn subst_atom_cow(
    mut r: Cow<'_, Rat>,
    x: AtomId,
    v: &Rat,
    s: &Assumptions,
) -> Result<Rat, NormError> {
    let atoms = r.atoms();
    // Whether `x` occurs only as itself, never inside another atom's arguments.
    let only_itself = atoms.iter().all(|&b| b == x || !atom_depends_on(b, x));
    if only_itself && atoms.binary_search(&x).is_err() {
        return Ok(r.into_owned());
    }
    if only_itself {
        let to = v.as_atom().filter(|&a| Rat::renames_symbol(x, a, &atoms));
        if let Some(a) = to {
            match r.into_owned().into_renamed_symbol(x, a, &atoms) {
                Ok(renamed) => return Ok(renamed),
                Err(back) => r = Cow::Owned(back),
            }
        }
        if let Some(out) = monomial_value(&r, x, v)? {
            return Ok(out);
        }
    }
    subst_atom_general(&r, x, v, s)
}

/// [`subst_atom`] by the general substitution.
fn subst_atom_general(r: &Rat, x: AtomId, v: &Rat, s: &Assumptions) -> Result<Rat, NormError> {
    let f = |a: AtomId| (a == x).then(|| v.clone());
    Subst::new(&f, s).rat(r)
}

/// The exact special case of [`subst_atom`] where `x` occurs in `r` only as itself and
/// its value is `0` or one term `c·m`: each term `q·m'·x^e` becomes `q·c^e·m'·m^e`
/// (terms with `x` vanish for `0`), with no hashing and no common denominator. `None`
/// when the case does not apply (a value with a denominator or several terms, or `x` in
/// the denominator of `r`).
fn monomial_value(r: &Rat, x: AtomId, v: &Rat) -> Result<Option<Rat>, NormError> {
    if !v.den().is_one() || r.den().contains(x) {
        return Ok(None);
    }
    let value = match v.num().terms() {
        [] => None,
        [(m, c)] => Some((m, c)),
        _ => return Ok(None),
    };
    let mut acc: Vec<(Mono, Q)> = Vec::with_capacity(r.num().len());
    // Powers of the value's coefficient and monomial, by exponent (exponents repeat).
    let mut powers: std::collections::BTreeMap<u32, (Q, Mono)> = Default::default();
    for (m, q) in r.num().terms() {
        let (rest, e) = m.split(x);
        if e == 0 {
            acc.push((rest, q.clone()));
            continue;
        }
        let Some((vm, vc)) = value else { continue };
        let (c, pm) = match powers.entry(e) {
            std::collections::btree_map::Entry::Occupied(o) => o.into_mut(),
            std::collections::btree_map::Entry::Vacant(slot) => slot.insert((
                super::poly::pow_q_checked(vc, e)?,
                vm.pow(e).ok_or(super::Limit::Exponent)?,
            )),
        };
        let t = rest.mul(pm).ok_or(super::Limit::Exponent)?;
        acc.push((t, super::qops::mul(q, c)));
    }
    let num = Poly::from_terms(acc);
    if num.len() > super::poly::max_terms() {
        return Err(super::Limit::terms().into());
    }
    if r.den().is_one() {
        return Rat::poly(num).map(Some);
    }
    Rat::new(num, r.den().clone()).map(Some)
}

/// Whether `r` depends on atom `x`, also inside the arguments of other atoms.
pub fn depends_on(r: &Rat, x: AtomId) -> bool {
    r.atoms().iter().any(|a| atom_depends_on(*a, x))
}

/// Whether atom `a` is or contains atom `x`.
pub fn atom_depends_on(a: AtomId, x: AtomId) -> bool {
    if a == x {
        return true;
    }
    let at = atom::get(a);
    let p = |p: &Poly| p.atoms().iter().any(|b| atom_depends_on(*b, x));
    let r = |r: &Rat| depends_on(r, x);
    match at {
        Atom::Sym(_) | Atom::Pi | Atom::Moment(..) => false,
        Atom::Sqrt(q) | Atom::Root(q, _) | Atom::Abs(q) | Atom::Factor(q) => p(q),
        Atom::Sin(u) | Atom::Cos(u) | Atom::Exp(u) | Atom::Ln(u) => r(u),
        Atom::Pow(b, e) => r(b) || r(e),
        Atom::At(_, u) => r(u),
    }
}

/// Every atom inside atom `a` (its arguments, recursively), `a` excluded.
pub fn atoms_within(a: AtomId) -> Vec<AtomId> {
    let mut out = Vec::new();
    let mut todo = vec![a];
    while let Some(b) = todo.pop() {
        let at = atom::get(b);
        let push_rat = |r: &Rat, todo: &mut Vec<AtomId>| {
            for x in r.atoms() {
                todo.push(x);
            }
        };
        match at {
            Atom::Sym(_) | Atom::Pi | Atom::Moment(..) => {}
            Atom::Sqrt(q) | Atom::Root(q, _) | Atom::Abs(q) | Atom::Factor(q) => {
                todo.extend(q.atoms())
            }
            Atom::Sin(u) | Atom::Cos(u) | Atom::Exp(u) | Atom::Ln(u) | Atom::At(_, u) => {
                push_rat(u, &mut todo)
            }
            Atom::Pow(x, e) => {
                push_rat(x, &mut todo);
                push_rat(e, &mut todo);
            }
        }
        if b != a && !out.contains(&b) {
            out.push(b);
        }
        if out.len() > 100_000 {
            break;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::normal::atom::sym;
    use num_bigint::BigInt;
    use proptest::prelude::*;

    /// The general path: the substitution by [`Subst`], with no special case.
    fn general(r: &Rat, x: AtomId, v: &Rat) -> Result<Rat, NormError> {
        let s = Assumptions::new();
        let f = |a: AtomId| (a == x).then(|| v.clone());
        Subst::new(&f, &s).rat(r)
    }

    use crate::normal::poly::from_exponents as poly_of;

    fn terms(atoms: usize) -> impl Strategy<Value = Vec<(Vec<u32>, i64, i64)>> {
        proptest::collection::vec(
            (proptest::collection::vec(0u32..4, atoms), -6i64..7, 1i64..4),
            0..7,
        )
    }

    proptest! {
        /// Substituting `0`, a fresh symbol, a symbol already present, a constant or a
        /// term `c·m` for `x` gives the general path's value, for polynomials and for
        /// fractions whose denominator is free of `x`.
        #[test]
        fn monomial_values_agree_with_the_general_substitution(
            num in terms(3),
            den in terms(2),
            value in (0usize..5, proptest::collection::vec(0u32..3, 3), -5i64..6, 1i64..4),
        ) {
            let (x, y, b, c) = (sym("x"), sym("y"), sym("b"), sym("c"));
            let num = poly_of(&[x, y, b], &num);
            let den = poly_of(&[y, b], &den);
            let Ok(r) = Rat::new(num, if den.is_zero() { Poly::one() } else { den }) else {
                return Ok(());
            };
            let (kind, es, n, d) = value;
            let v = match kind {
                0 => Rat::zero(),
                1 => Rat::atom(c),
                2 => Rat::atom(b),
                3 => Rat::constant(Q::new(BigInt::from(n), BigInt::from(d))),
                _ => Rat::poly(poly_of(&[y, b, c], &[(es, n, d)])).unwrap_or_else(|_| Rat::zero()),
            };
            let fast = subst_atom(&r, x, &v, &Assumptions::new());
            prop_assert_eq!(fast, general(&r, x, &v));
        }
    }

    proptest! {
        /// Renaming `x` to a fresh symbol whose id lies beyond other atoms', upward or
        /// downward, borrowed or given up, gives the general path's value.
        #[test]
        fn renaming_agrees_with_the_general_substitution(
            num in terms(3),
            den in terms(3),
            upward in any::<bool>(),
        ) {
            // Interned in this order, so their ids are in this order too.
            let [lo, p, x, q, hi] = ["lo", "p", "x", "q", "hi"]
                .map(|n| sym(&format!("subst_rename_test_{n}")));
            prop_assert!(lo < p && p < x && x < q && q < hi);
            let num = poly_of(&[p, x, q], &num);
            let den = poly_of(&[p, x, q], &den);
            let Ok(r) = Rat::new(num, if den.is_zero() { Poly::one() } else { den }) else {
                return Ok(());
            };
            let v = Rat::atom(if upward { hi } else { lo });
            let expected = general(&r, x, &v);
            let s = Assumptions::new();
            prop_assert_eq!(&subst_atom(&r, x, &v, &s), &expected);
            prop_assert_eq!(&subst_atom_owned(r, x, &v, &s), &expected);
        }
    }

    #[test]
    fn a_symbol_inside_another_atom_takes_the_general_path() {
        let (x, y) = (sym("x"), sym("y"));
        let s = Assumptions::new();
        let root =
            crate::normal::func::sqrt(&Rat::atom(x).add(&Rat::atom(y)).unwrap(), &s).unwrap();
        let r = root.add(&Rat::atom(x)).unwrap();
        let at_zero = subst_atom(&r, x, &Rat::zero(), &s).unwrap();
        assert_eq!(
            at_zero,
            crate::normal::func::sqrt(&Rat::atom(y), &s).unwrap()
        );
        assert_eq!(at_zero, general(&r, x, &Rat::zero()).unwrap());
    }
}
