//! Rational functions in atoms: the normal form. Canonical by construction.
//!
//! A [`Rat`] is `num / den` with both polynomials reduced by the atoms' rules
//! (`sqrt(a)² = a`, `cos² = 1 − sin²`, merged exponentials), square roots
//! rationalised out of the denominator, the gcd cancelled, and the denominator
//! monic. Every constructor goes through [`Rat::new`].

use super::gcd::{div_exact, gcd};
use super::poly::{Poly, Q};
use super::reduce::{rationalise, reduce};
use super::{Limit, NormError};
use num_traits::{One, Zero};

/// `a / b` for a divisor known to divide exactly.
fn exact(a: &Poly, b: &Poly) -> Result<Poly, NormError> {
    div_exact(a, b)?.ok_or(NormError::Limit(Limit::terms()))
}

/// `p` reduced by the atoms' rules; moved, not copied, when none of its atoms has one.
fn reduced(p: Poly) -> Result<Poly, NormError> {
    if p.len() <= 1 && p.terms().first().is_none_or(|t| t.0.is_one()) {
        return Ok(p);
    }
    let free = super::atom::rules(&p.atoms())
        .iter()
        .all(|r| *r == super::atom::Rule::Free);
    if free {
        return Ok(p);
    }
    reduce(&p)
}

/// A normal form: a reduced rational function over ℚ in atoms.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Rat {
    num: Poly,
    den: Poly,
}

impl Rat {
    /// The canonical form of `num / den`. Fails when `den` is zero.
    pub fn new(num: Poly, den: Poly) -> Result<Rat, NormError> {
        let den = reduced(den)?;
        if den.is_zero() {
            return Err(NormError::DivisionByZero);
        }
        let num = reduced(num)?;
        if num.is_zero() {
            return Ok(Rat::zero());
        }
        if let Some(c) = den.as_constant() {
            if c.is_one() {
                return Ok(Rat { num, den });
            }
            return Ok(Rat {
                num: num.scale(&c.recip()),
                den: Poly::one(),
            });
        }
        let (num, den) = rationalise(num, den)?;
        if den.is_zero() {
            return Err(NormError::DivisionByZero);
        }
        Self::cancel(num, den).map_err(NormError::from)
    }

    /// Cancels the gcd and makes the denominator monic.
    fn cancel(num: Poly, den: Poly) -> Result<Rat, Limit> {
        if num.is_zero() {
            return Ok(Rat::zero());
        }
        if let Some(c) = den.as_constant() {
            return Ok(Rat {
                num: num.scale(&c.recip()),
                den: Poly::one(),
            });
        }
        let g = gcd(&num, &den)?;
        let (num, den) = if g.is_one() {
            (num, den)
        } else {
            (
                div_exact(&num, &g)?.unwrap_or(num),
                div_exact(&den, &g)?.unwrap_or(den),
            )
        };
        let lc = den.lead().map(|t| t.1.clone()).unwrap_or_else(Q::one);
        let inv = lc.recip();
        Ok(Rat {
            num: num.into_scaled(&inv),
            den: den.into_scaled(&inv),
        })
    }

    /// `num / den` as given, for a caller that has established what [`Rat::new`] would
    /// otherwise establish: no atom of either carries a rewrite rule (so neither needs
    /// reducing and nothing is rationalised), `num` and `den` are coprime, `den` is
    /// monic, and `den` is `1` when `num` is zero. The solver's quotients, which share
    /// one determinant, prove coprimality once for all of them (`solve::quotients`).
    /// Debug builds check every condition, the gcd included.
    pub(crate) fn from_coprime(num: Poly, den: Poly) -> Rat {
        debug_assert!(
            den.lead().is_some_and(|t| t.1.is_one()),
            "monic denominator"
        );
        debug_assert!(!num.is_zero() || den.is_one(), "zero is 0/1");
        debug_assert!(
            {
                let mut ids = num.atoms();
                ids.extend(den.atoms());
                super::atom::rules(&ids)
                    .iter()
                    .all(|r| *r == super::atom::Rule::Free)
            },
            "atoms without rules"
        );
        debug_assert!(
            // (A gcd refused by a limit shows nothing either way.)
            num.is_zero() || !matches!(gcd(&num, &den), Ok(g) if !g.is_one()),
            "coprime"
        );
        Rat { num, den }
    }

    /// A polynomial as a rational function (reduced).
    pub fn poly(p: Poly) -> Result<Rat, NormError> {
        Ok(Rat {
            num: reduced(p)?,
            den: Poly::one(),
        })
    }

    /// 0.
    pub fn zero() -> Rat {
        Rat {
            num: Poly::zero(),
            den: Poly::one(),
        }
    }

    /// 1.
    pub fn one() -> Rat {
        Rat::constant(Q::one())
    }

    /// A rational number.
    pub fn constant(q: Q) -> Rat {
        Rat {
            num: Poly::constant(q),
            den: Poly::one(),
        }
    }

    /// An integer.
    pub fn int(n: i64) -> Rat {
        Rat::constant(Q::from_integer(n.into()))
    }

    /// An atom.
    pub fn atom(a: super::atom::AtomId) -> Rat {
        Rat {
            num: Poly::atom(a),
            den: Poly::one(),
        }
    }

    /// The numerator and the denominator, given up.
    pub fn into_parts(self) -> (Poly, Poly) {
        (self.num, self.den)
    }

    /// The numerator.
    pub fn num(&self) -> &Poly {
        &self.num
    }

    /// The denominator (monic; `1` for polynomials).
    pub fn den(&self) -> &Poly {
        &self.den
    }

    /// Whether this is 0.
    pub fn is_zero(&self) -> bool {
        self.num.is_zero()
    }

    /// The value, if a rational number.
    pub fn as_constant(&self) -> Option<Q> {
        if self.den.is_one() {
            self.num.as_constant()
        } else {
            None
        }
    }

    /// The polynomial, if the denominator is 1.
    pub fn as_poly(&self) -> Option<&Poly> {
        self.den.is_one().then_some(&self.num)
    }

    /// Whether this is the atom `a` exactly.
    pub fn as_atom(&self) -> Option<super::atom::AtomId> {
        if self.den.is_one() {
            self.num.as_atom()
        } else {
            None
        }
    }

    /// The sum.
    pub fn add(&self, o: &Rat) -> Result<Rat, NormError> {
        if self.is_zero() {
            return Ok(o.clone());
        }
        if o.is_zero() {
            return Ok(self.clone());
        }
        if self.den == o.den {
            let num = self.num.add(&o.num);
            if self.den.is_one() {
                return Ok(Rat {
                    num,
                    den: Poly::one(),
                });
            }
            return Rat::cancel(num, self.den.clone()).map_err(NormError::from);
        }
        if self.free() && o.free() {
            // Henrici: with g = gcd(b, d), a/b + c/d = (a·d' + c·b') / (g·b'·d'), and only
            // g can share a factor with that numerator.
            let (b, d) = (&self.den, &o.den);
            let g = gcd(b, d)?;
            let (b1, d1) = if g.is_one() {
                (b.clone(), d.clone())
            } else {
                (exact(b, &g)?, exact(d, &g)?)
            };
            let num = self.num.mul(&d1)?.add(&o.num.mul(&b1)?);
            if num.is_zero() {
                return Ok(Rat::zero());
            }
            let den = b1.mul(&d1)?;
            if g.is_one() {
                return Ok(Rat::monic(num, den));
            }
            let h = gcd(&num, &g)?;
            let (num, g) = if h.is_one() {
                (num, g)
            } else {
                (exact(&num, &h)?, exact(&g, &h)?)
            };
            return Ok(Rat::monic(num, den.mul(&g)?));
        }
        let num = self.num.mul(&o.den)?.add(&o.num.mul(&self.den)?);
        let den = self.den.mul(&o.den)?;
        Rat::new(num, den)
    }

    /// Whether no atom of `self` carries a rewrite rule, so products of its parts need no
    /// reduction and cancellation can work factor by factor.
    fn free(&self) -> bool {
        let mut ids = self.num.atoms();
        ids.extend(self.den.atoms());
        super::atom::rules(&ids)
            .iter()
            .all(|r| *r == super::atom::Rule::Free)
    }

    /// `num/den` already in lowest terms: only the denominator is made monic.
    fn monic(num: Poly, den: Poly) -> Rat {
        let lc = den.lead().map(|t| t.1.clone()).unwrap_or_else(Q::one);
        if lc.is_one() {
            return Rat { num, den };
        }
        let inv = lc.recip();
        Rat {
            num: num.scale(&inv),
            den: den.scale(&inv),
        }
    }

    /// `self` with symbol `x` renamed to symbol `a`, when `a` does not occur in it (not
    /// even inside another atom) and `x` occurs only as itself: renaming is then a ring
    /// isomorphism, so the fraction stays reduced and needs no gcd.
    pub fn rename_symbol(&self, x: super::atom::AtomId, a: super::atom::AtomId) -> Option<Rat> {
        self.clone().into_renamed_symbol(x, a, &self.atoms()).ok()
    }

    /// Whether renaming `x` to `a` in a value whose atoms are `atoms` is a ring
    /// isomorphism: both are symbols, `a` occurs nowhere, not even inside another atom
    /// (`sqrt(a)` would relate to `a`), and `x` occurs only as itself.
    pub(crate) fn renames_symbol(
        x: super::atom::AtomId,
        a: super::atom::AtomId,
        atoms: &[super::atom::AtomId],
    ) -> bool {
        use super::atom::{self, Atom};
        use super::subst::atom_depends_on;
        let symbol = |id| matches!(atom::get(id), Atom::Sym(_));
        symbol(x)
            && symbol(a)
            && !atoms.iter().any(|&b| atom_depends_on(b, a))
            && !atoms.iter().any(|&b| b != x && atom_depends_on(b, x))
    }

    /// [`Rat::rename_symbol`] of a value the caller gives up, with `atoms`, the value of
    /// `self.atoms()`, given: the terms are renamed where they are, with no copy.
    /// `Err(self)`, unchanged, when the renaming is not an isomorphism.
    pub(crate) fn into_renamed_symbol(
        mut self,
        x: super::atom::AtomId,
        a: super::atom::AtomId,
        atoms: &[super::atom::AtomId],
    ) -> Result<Rat, Rat> {
        if !Rat::renames_symbol(x, a, atoms) || self.contains(a) {
            return Err(self);
        }
        // `a` occurs in neither polynomial, so both renamings take place.
        let renamed = self.num.rename(x, a) & self.den.rename(x, a);
        debug_assert!(renamed);
        Ok(Rat::monic(self.num, self.den))
    }

    /// `(a/b)·(c/d)` for reduced fractions of rule-free atoms: cancel `gcd(a, d)` and
    /// `gcd(c, b)`; the result is in lowest terms.
    fn mul_free(a: &Poly, b: &Poly, c: &Poly, d: &Poly) -> Result<Rat, NormError> {
        if b.is_one() && d.is_one() {
            // Two polynomials: nothing to cancel, no copies of the factors.
            return Ok(Rat {
                num: a.mul(c)?,
                den: Poly::one(),
            });
        }
        let g1 = gcd(a, d)?;
        let g2 = gcd(c, b)?;
        let (a, d) = if g1.is_one() {
            (a.clone(), d.clone())
        } else {
            (exact(a, &g1)?, exact(d, &g1)?)
        };
        let (c, b) = if g2.is_one() {
            (c.clone(), b.clone())
        } else {
            (exact(c, &g2)?, exact(b, &g2)?)
        };
        Ok(Rat::monic(a.mul(&c)?, b.mul(&d)?))
    }

    /// The negation.
    pub fn neg(&self) -> Rat {
        Rat {
            num: self.num.neg(),
            den: self.den.clone(),
        }
    }

    /// The difference.
    pub fn sub(&self, o: &Rat) -> Result<Rat, NormError> {
        if o.is_zero() {
            return Ok(self.clone());
        }
        self.add(&o.neg())
    }

    /// The product.
    pub fn mul(&self, o: &Rat) -> Result<Rat, NormError> {
        if self.is_zero() || o.is_zero() {
            return Ok(Rat::zero());
        }
        if let Some(c) = o.as_constant() {
            return Ok(self.scale(&c));
        }
        if let Some(c) = self.as_constant() {
            return Ok(o.scale(&c));
        }
        if self.free() && o.free() {
            return Rat::mul_free(&self.num, &self.den, &o.num, &o.den);
        }
        Rat::new(self.num.mul(&o.num)?, self.den.mul(&o.den)?)
    }

    /// `q · self`.
    pub fn scale(&self, q: &Q) -> Rat {
        if q.is_zero() {
            return Rat::zero();
        }
        Rat {
            num: self.num.scale(q),
            den: self.den.clone(),
        }
    }

    /// The quotient; `DivisionByZero` when `o` is zero.
    pub fn div(&self, o: &Rat) -> Result<Rat, NormError> {
        if o.is_zero() {
            return Err(NormError::DivisionByZero);
        }
        if let Some(c) = o.as_constant() {
            return Ok(self.scale(&c.recip()));
        }
        if self.free() && o.free() {
            return Rat::mul_free(&self.num, &self.den, &o.den, &o.num);
        }
        Rat::new(self.num.mul(&o.den)?, self.den.mul(&o.num)?)
    }

    /// The reciprocal.
    pub fn recip(&self) -> Result<Rat, NormError> {
        Rat::one().div(self)
    }

    /// `self^k` for an integer `k` (negative: the reciprocal's power).
    pub fn powi(&self, k: i64) -> Result<Rat, NormError> {
        if k == 0 {
            if self.is_zero() {
                return Err(NormError::ZeroToZero);
            }
            return Ok(Rat::one());
        }
        let base = if k < 0 { self.recip()? } else { self.clone() };
        let e = k.unsigned_abs();
        if base.num.len() <= 1 && base.den.len() <= 1 {
            // Monomials: no expansion, exponents multiply (x^(10^9) is one term).
            return Rat::new(base.num.pow(e)?, base.den.pow(e)?);
        }
        if base.free() {
            // No atom rewrites: powers of coprime polynomials stay coprime and a monic
            // denominator stays monic, so the powers are already in lowest terms.
            return Ok(Rat::monic(base.num.pow(e)?, base.den.pow(e)?));
        }
        // Powers of sums: square and multiply, reducing as we go.
        if !super::poly::pow_fits(base.num.len().max(base.den.len()), e) {
            return Err(Limit::terms().into());
        }
        let mut result = Rat::one();
        let mut b = base;
        let mut e = e;
        while e > 0 {
            if e & 1 == 1 {
                result = result.mul(&b)?;
            }
            e >>= 1;
            if e > 0 {
                b = b.mul(&b)?;
            }
        }
        Ok(result)
    }

    /// All atoms in numerator and denominator.
    pub fn atoms(&self) -> Vec<super::atom::AtomId> {
        let mut v = self.num.atoms();
        v.extend(self.den.atoms());
        v.sort_unstable();
        v.dedup();
        v
    }

    /// Whether atom `a` occurs.
    pub fn contains(&self, a: super::atom::AtomId) -> bool {
        self.num.contains(a) || self.den.contains(a)
    }
}
