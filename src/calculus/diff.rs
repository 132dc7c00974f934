//! Exact derivatives of normal forms: product, quotient and chain rules through every atom.

use crate::normal::atom::{self, Atom, AtomId};
use crate::normal::subst::atom_depends_on;
use crate::normal::{func, trig, Assumptions, NormError, Poly, Rat, Q};
use foldhash::{HashMap, HashMapExt};

/// With respect to what a derivative is taken.
pub struct Wrt<'a> {
    /// The variable.
    pub var: AtomId,
    /// For `d/dt`: the base names of `time` symbols, whose derivative adds a prime.
    pub time: Option<&'a dyn Fn(&str) -> bool>,
}

/// `d r / d var`.
pub fn diff(r: &Rat, wrt: &Wrt<'_>, s: &Assumptions) -> Result<Rat, NormError> {
    let mut memo = HashMap::new();
    diff_rat(r, wrt, s, &mut memo)
}

fn diff_rat(
    r: &Rat,
    w: &Wrt<'_>,
    s: &Assumptions,
    memo: &mut HashMap<AtomId, Rat>,
) -> Result<Rat, NormError> {
    let dn = diff_poly(r.num(), w, s, memo)?;
    if r.den().is_one() {
        return Ok(dn);
    }
    let dd = diff_poly(r.den(), w, s, memo)?;
    let n = Rat::poly(r.num().clone())?;
    let d = Rat::poly(r.den().clone())?;
    // (n/d)' = (n' d − n d') / d²
    dn.mul(&d)?.sub(&n.mul(&dd)?)?.div(&d.mul(&d)?)
}

fn diff_poly(
    p: &Poly,
    w: &Wrt<'_>,
    s: &Assumptions,
    memo: &mut HashMap<AtomId, Rat>,
) -> Result<Rat, NormError> {
    let mut out = Rat::zero();
    for a in p.atoms() {
        let da = diff_atom(a, w, s, memo)?;
        if da.is_zero() {
            continue;
        }
        let partial = Rat::poly(p.deriv_atom(a))?;
        out = out.add(&partial.mul(&da)?)?;
    }
    Ok(out)
}

fn diff_atom(
    a: AtomId,
    w: &Wrt<'_>,
    s: &Assumptions,
    memo: &mut HashMap<AtomId, Rat>,
) -> Result<Rat, NormError> {
    if let Some(v) = memo.get(&a) {
        return Ok(v.clone());
    }
    let v = diff_atom_uncached(a, w, s, memo)?;
    memo.insert(a, v.clone());
    Ok(v)
}

fn diff_atom_uncached(
    a: AtomId,
    w: &Wrt<'_>,
    s: &Assumptions,
    memo: &mut HashMap<AtomId, Rat>,
) -> Result<Rat, NormError> {
    if a == w.var {
        return Ok(Rat::one());
    }
    let at = atom::get(a);
    if let Atom::Sym(name) = at {
        if let Some(is_time) = w.time {
            let base = name.trim_end_matches('\'');
            if is_time(base) {
                return Ok(Rat::atom(atom::sym(&format!("{name}'"))));
            }
        }
        return Ok(Rat::zero());
    }
    if w.time.is_none() && !atom_depends_on(a, w.var) {
        return Ok(Rat::zero());
    }
    let two = Q::from_integer(2.into());
    Ok(match at {
        Atom::Sym(_) | Atom::Pi | Atom::Moment(..) => Rat::zero(),
        // d/dv x(u) = x'(u) · du/dv
        Atom::At(name, u) => {
            let du = diff_rat(u, w, s, memo)?;
            if du.is_zero() {
                return Ok(du);
            }
            Rat::atom(atom::at(&format!("{name}'"), u)).mul(&du)?
        }
        Atom::Sqrt(p) => {
            let dp = diff_poly(p, w, s, memo)?;
            if dp.is_zero() {
                return Ok(dp);
            }
            dp.div(&Rat::atom(a).scale(&two))?
        }
        Atom::Root(p, n) => {
            let dp = diff_poly(p, w, s, memo)?;
            if dp.is_zero() {
                return Ok(dp);
            }
            let n = i64::from(*n);
            dp.div(&Rat::atom(a).powi(n - 1)?.scale(&Q::from_integer(n.into())))?
        }
        // A kept factor is its sum.
        Atom::Factor(p) => diff_poly(p, w, s, memo)?,
        Atom::Abs(p) => {
            let dp = diff_poly(p, w, s, memo)?;
            if dp.is_zero() {
                return Ok(dp);
            }
            // |p|' = |p|/p · p'
            Rat::atom(a).mul(&dp)?.div(&Rat::poly(p.clone())?)?
        }
        Atom::Sin(u) => {
            let du = diff_rat(u, w, s, memo)?;
            if du.is_zero() {
                return Ok(du);
            }
            trig::cos(u)?.mul(&du)?
        }
        Atom::Cos(u) => {
            let du = diff_rat(u, w, s, memo)?;
            if du.is_zero() {
                return Ok(du);
            }
            trig::sin(u)?.neg().mul(&du)?
        }
        Atom::Exp(u) => {
            let du = diff_rat(u, w, s, memo)?;
            Rat::atom(a).mul(&du)?
        }
        Atom::Ln(u) => {
            let du = diff_rat(u, w, s, memo)?;
            if du.is_zero() {
                return Ok(du);
            }
            du.div(u)?
        }
        Atom::Pow(b, e) => {
            // (b^e)' = b^e (e' ln b + e b'/b)
            let db = diff_rat(b, w, s, memo)?;
            let de = diff_rat(e, w, s, memo)?;
            if db.is_zero() && de.is_zero() {
                return Ok(Rat::zero());
            }
            let mut inner = e.mul(&db)?.div(b)?;
            if !de.is_zero() {
                inner = inner.add(&de.mul(&func::ln(b, s)?)?)?;
            }
            Rat::atom(a).mul(&inner)?
        }
    })
}

/// The `n`-th derivative.
pub fn diff_n(r: &Rat, wrt: &Wrt<'_>, n: u32, s: &Assumptions) -> Result<Rat, NormError> {
    let mut cur = r.clone();
    for _ in 0..n {
        if cur.is_zero() {
            break;
        }
        cur = diff(&cur, wrt, s)?;
    }
    Ok(cur)
}
