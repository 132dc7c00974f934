//! Greatest common divisors and exact division of multivariate polynomials over ℚ.
//!
//! The gcd is the recursive primitive polynomial remainder sequence: view both
//! polynomials in their highest common atom, split off contents, and run the
//! pseudo-remainder sequence on primitive parts. Atoms are treated as
//! independent variables; a common factor found that way is a common factor
//! in any quotient ring too, so cancelling it is always valid.

use super::atom::AtomId;
use super::mono::Mono;
use super::poly::{Poly, Q};
use super::Limit;
use num_traits::One;

/// `a / b` when `b` divides `a` exactly, else `None`.
pub fn div_exact(a: &Poly, b: &Poly) -> Result<Option<Poly>, Limit> {
    if b.is_zero() {
        return Ok(None);
    }
    if let Some(c) = b.as_constant() {
        return Ok(Some(a.scale(&c.recip())));
    }
    let Some((mb, cb)) = b.lead().cloned() else {
        return Ok(None);
    };
    let cb_inv = cb.recip();
    let mut q_terms: Vec<(Mono, Q)> = Vec::new();
    let mut r = a.clone();
    let mut steps = 0usize;
    while let Some((mr, cr)) = r.lead().cloned() {
        let Some(m) = mr.div(&mb) else {
            return Ok(None);
        };
        let c = &cr * &cb_inv;
        r = r.sub(&b.mul_term(&m, &c)?);
        q_terms.push((m, c));
        steps += 1;
        if steps > super::poly::max_terms() {
            return Err(Limit::Terms);
        }
    }
    Ok(Some(Poly::from_terms(q_terms)))
}

/// The monic greatest common divisor (`gcd(0, 0) = 0`).
pub fn gcd(a: &Poly, b: &Poly) -> Result<Poly, Limit> {
    if a.is_zero() {
        return Ok(b.monic());
    }
    if b.is_zero() {
        return Ok(a.monic());
    }
    if a.as_constant().is_some() || b.as_constant().is_some() {
        return Ok(Poly::one());
    }
    if a == b {
        return Ok(a.monic());
    }
    let (ma, mb) = (a.mono_content(), b.mono_content());
    let gm = ma.gcd(&mb);
    let a1 = a.div_mono(&ma).unwrap_or_else(|| a.clone());
    let b1 = b.div_mono(&mb).unwrap_or_else(|| b.clone());
    let g = gcd_nomono(&a1, &b1)?;
    Ok(g.mul_term(&gm, &Q::one())?.monic())
}

fn gcd_nomono(a: &Poly, b: &Poly) -> Result<Poly, Limit> {
    if a.as_constant().is_some() || b.as_constant().is_some() {
        return Ok(Poly::one());
    }
    if a.len() == 1 || b.len() == 1 {
        // One side is a monomial with no monomial factor in common: only constants remain.
        return Ok(Poly::one());
    }
    let aa = a.atoms();
    let ba = b.atoms();
    // An atom in only one of them: the gcd divides that one's content in it.
    if let Some(v) = aa.iter().rev().find(|v| ba.binary_search(v).is_err()) {
        let c = content_in(a, *v)?;
        return gcd(&c, b);
    }
    if let Some(v) = ba.iter().rev().find(|v| aa.binary_search(v).is_err()) {
        let c = content_in(b, *v)?;
        return gcd(a, &c);
    }
    let Some(&v) = aa.last() else {
        return Ok(Poly::one());
    };
    let ca = content_in(a, v)?;
    let cb = content_in(b, v)?;
    let gc = gcd(&ca, &cb)?;
    let mut p = div_exact(a, &ca)?.unwrap_or_else(|| a.clone());
    let mut q = div_exact(b, &cb)?.unwrap_or_else(|| b.clone());
    if p.degree_in(v) < q.degree_in(v) {
        std::mem::swap(&mut p, &mut q);
    }
    loop {
        let r = prem(&p, &q, v)?;
        if r.is_zero() {
            break;
        }
        if r.degree_in(v) == 0 {
            q = Poly::one();
            break;
        }
        p = q;
        q = primitive_in(&r, v)?;
    }
    let g = primitive_in(&q, v)?;
    gc.mul(&g)
}

/// The gcd of the coefficients of `p` viewed as a polynomial in `v`.
pub fn content_in(p: &Poly, v: AtomId) -> Result<Poly, Limit> {
    let coeffs = p.coeffs_in(v);
    let mut g = Poly::zero();
    for (_, c) in &coeffs {
        g = gcd(&g, c)?;
        if g.is_one() {
            break;
        }
    }
    Ok(g)
}

/// `p` divided by its content in `v`.
pub fn primitive_in(p: &Poly, v: AtomId) -> Result<Poly, Limit> {
    let c = content_in(p, v)?;
    Ok(div_exact(p, &c)?.unwrap_or_else(|| p.clone()).primitive())
}

/// The pseudo-remainder of `a` by `b` in `v`, scaled to integer content 1.
fn prem(a: &Poly, b: &Poly, v: AtomId) -> Result<Poly, Limit> {
    let db = b.degree_in(v);
    let bc = b.coeffs_in(v);
    let lc_b = bc.last().map(|c| c.1.clone()).unwrap_or_else(Poly::one);
    let mut r = a.clone();
    let mut guard = 0u32;
    while !r.is_zero() {
        let dr = r.degree_in(v);
        if dr < db {
            break;
        }
        let rc = r.coeffs_in(v);
        let lc_r = rc.last().map(|c| c.1.clone()).unwrap_or_else(Poly::zero);
        let shift = Poly::term(Mono::atom(v, dr - db), Q::one());
        r = lc_b.mul(&r)?.sub(&lc_r.mul(&shift)?.mul(b)?);
        r = r.primitive();
        guard += 1;
        if guard > dr.saturating_add(2) * 4 + 64 {
            return Err(Limit::Terms);
        }
    }
    Ok(r)
}
