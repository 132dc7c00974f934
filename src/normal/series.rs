//! Power series in one fresh atom `ε`, truncated after order `n`, with exact
//! coefficients: the small-quantity approximations of FORMAT.md §3 (`small theta`).
//! Series of sin, cos, exp, ln, square and other roots, and quotients are exact Taylor
//! series with rational coefficients.

use super::atom::{self, Atom, AtomId};
use super::poly::{Poly, Q};
use super::rat::Rat;
use super::sign::{Assumptions, Sign};
use super::subst::atom_depends_on;
use super::{func, trig, NormError};
use foldhash::{HashMap, HashMapExt};
use num_bigint::BigInt;
use num_traits::{One, Zero};

/// Why a series could not be formed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SeriesError {
    /// A function with no Taylor series at the point (`abs(θ)`, `sqrt(θ²)`, a symbol at
    /// an instant that depends on the small quantity); the text names it.
    NotAnalytic(String),
    /// The normal form failed.
    Norm(NormError),
}

impl From<NormError> for SeriesError {
    fn from(e: NormError) -> SeriesError {
        SeriesError::Norm(e)
    }
}

/// Coefficients `c₀ … cₙ` of a series in `ε`.
type Coeffs = Vec<Rat>;

struct Ctx<'a> {
    eps: AtomId,
    n: usize,
    signs: &'a Assumptions,
    memo: HashMap<AtomId, Coeffs>,
}

/// The coefficients `c₀ … cₙ` of `r` as a power series in the atom `eps`.
pub fn series(
    r: &Rat,
    eps: AtomId,
    n: usize,
    signs: &Assumptions,
) -> Result<Vec<Rat>, SeriesError> {
    let mut cx = Ctx {
        eps,
        n,
        signs,
        memo: HashMap::new(),
    };
    cx.rat(r)
}

fn q(n: i64, d: i64) -> Q {
    Q::new(BigInt::from(n), BigInt::from(d))
}

impl Ctx<'_> {
    fn constant(&self, r: Rat) -> Coeffs {
        let mut c = vec![Rat::zero(); self.n + 1];
        c[0] = r;
        c
    }

    fn add(&self, a: &Coeffs, b: &Coeffs) -> Result<Coeffs, SeriesError> {
        a.iter().zip(b).map(|(x, y)| Ok(x.add(y)?)).collect()
    }

    fn mul(&self, a: &Coeffs, b: &Coeffs) -> Result<Coeffs, SeriesError> {
        let mut out = vec![Rat::zero(); self.n + 1];
        for (i, x) in a.iter().enumerate() {
            if x.is_zero() {
                continue;
            }
            for (j, y) in b.iter().enumerate().take(self.n + 1 - i) {
                if !y.is_zero() {
                    out[i + j] = out[i + j].add(&x.mul(y)?)?;
                }
            }
        }
        Ok(out)
    }

    fn scale(&self, a: &Coeffs, k: &Rat) -> Result<Coeffs, SeriesError> {
        a.iter().map(|x| Ok(x.mul(k)?)).collect()
    }

    /// `Σ coef[k] δ^k` for a `δ` with no constant term.
    fn compose(&self, coef: &[Q], delta: &Coeffs) -> Result<Coeffs, SeriesError> {
        let mut out = self.constant(Rat::zero());
        let mut power = self.constant(Rat::one());
        for c in coef.iter().take(self.n + 1) {
            if !c.is_zero() {
                out = self.add(&out, &self.scale(&power, &Rat::constant(c.clone()))?)?;
            }
            power = self.mul(&power, delta)?;
        }
        Ok(out)
    }

    /// The value at ε = 0 and the rest.
    fn split(&self, a: &Coeffs) -> (Rat, Coeffs) {
        let mut d = a.clone();
        let c0 = std::mem::replace(&mut d[0], Rat::zero());
        (c0, d)
    }

    fn rat(&mut self, r: &Rat) -> Result<Coeffs, SeriesError> {
        let num = self.poly(r.num())?;
        if r.den().is_one() {
            return Ok(num);
        }
        let den = self.poly(r.den())?;
        if !den[0].is_zero() {
            let inv = self.inverse(&den)?;
            return self.mul(&num, &inv);
        }
        self.quotient_at_zero(r, &den)
    }

    /// `num/den` for a denominator whose series starts at `ε^k`, `k ≥ 1` (`sin θ/θ`):
    /// both to order `n + k`, where the numerator's first `k` coefficients must vanish
    /// too (else it is a pole), and the quotient of the series shifted by `k`.
    fn quotient_at_zero(&mut self, r: &Rat, den: &Coeffs) -> Result<Coeffs, SeriesError> {
        let pole = || SeriesError::NotAnalytic("a quotient by a small quantity".into());
        // A leading coefficient counts only where it is nonzero after a second look.
        let k = den
            .iter()
            .position(|c| !super::settle(c, self.signs).is_zero())
            .ok_or_else(pole)?;
        let mut wide = Ctx {
            eps: self.eps,
            n: self.n + k,
            signs: self.signs,
            memo: HashMap::new(),
        };
        let num = wide.poly(r.num())?;
        let den = wide.poly(r.den())?;
        if num.iter().take(k).any(|c| !c.is_zero()) || den.iter().take(k).any(|c| !c.is_zero()) {
            return Err(pole());
        }
        let (num, den) = (num[k..].to_vec(), den[k..].to_vec());
        let inv = self.inverse(&den)?;
        self.mul(&num, &inv)
    }

    /// `1/a`, for `a` whose value at ε = 0 is not zero.
    fn inverse(&self, a: &Coeffs) -> Result<Coeffs, SeriesError> {
        let (c0, d) = self.split(a);
        if c0.is_zero() {
            return Err(SeriesError::NotAnalytic(
                "a quotient by a small quantity".into(),
            ));
        }
        let z = self.scale(&d, &Rat::one().div(&c0)?)?;
        // 1/(1 + z) = Σ (−z)^k
        let coef: Vec<Q> = (0..=self.n)
            .map(|k| if k % 2 == 0 { Q::one() } else { -Q::one() })
            .collect();
        let s = self.compose(&coef, &z)?;
        self.scale(&s, &Rat::one().div(&c0)?)
    }

    fn poly(&mut self, p: &Poly) -> Result<Coeffs, SeriesError> {
        let mut out = self.constant(Rat::zero());
        for (m, c) in p.terms() {
            let mut t = self.constant(Rat::constant(c.clone()));
            for &(a, e) in m.pairs() {
                let s = self.atom(a)?;
                t = self.mul(&t, &self.power(&s, e)?)?;
            }
            out = self.add(&out, &t)?;
        }
        Ok(out)
    }

    /// `s^e`, truncated (a series without constant term vanishes past order n).
    fn power(&self, s: &Coeffs, e: u32) -> Result<Coeffs, SeriesError> {
        if s[0].is_zero() && e as usize > self.n {
            return Ok(self.constant(Rat::zero()));
        }
        if s.iter().skip(1).all(Rat::is_zero) {
            return Ok(self.constant(s[0].powi(i64::from(e))?));
        }
        if e > 10_000 {
            return Err(SeriesError::NotAnalytic(
                "a power too large to expand".into(),
            ));
        }
        let mut out = self.constant(Rat::one());
        for _ in 0..e {
            out = self.mul(&out, s)?;
        }
        Ok(out)
    }

    fn atom(&mut self, a: AtomId) -> Result<Coeffs, SeriesError> {
        if let Some(c) = self.memo.get(&a) {
            return Ok(c.clone());
        }
        let c = self.atom_uncached(a)?;
        self.memo.insert(a, c.clone());
        Ok(c)
    }

    fn atom_uncached(&mut self, a: AtomId) -> Result<Coeffs, SeriesError> {
        if a == self.eps {
            let mut c = self.constant(Rat::zero());
            if self.n >= 1 {
                c[1] = Rat::one();
            }
            return Ok(c);
        }
        if !atom_depends_on(a, self.eps) {
            return Ok(self.constant(Rat::atom(a)));
        }
        let at = atom::get(a);
        let fact = |k: usize| -> Q { (1..=k).fold(Q::one(), |f, i| f * q(i as i64, 1)) };
        match at {
            Atom::Sin(u) | Atom::Cos(u) => {
                let whole = self.rat(u)?;
                let (u0, d) = self.split(&whole);
                let cos_c: Vec<Q> = (0..=self.n)
                    .map(|k| match k % 4 {
                        0 => Q::one() / fact(k),
                        2 => -Q::one() / fact(k),
                        _ => Q::zero(),
                    })
                    .collect();
                let sin_c: Vec<Q> = (0..=self.n)
                    .map(|k| match k % 4 {
                        1 => Q::one() / fact(k),
                        3 => -Q::one() / fact(k),
                        _ => Q::zero(),
                    })
                    .collect();
                let (cd, sd) = (self.compose(&cos_c, &d)?, self.compose(&sin_c, &d)?);
                let (s0, c0) = (trig::sin(&u0)?, trig::cos(&u0)?);
                if matches!(at, Atom::Sin(_)) {
                    self.add(&self.scale(&cd, &s0)?, &self.scale(&sd, &c0)?)
                } else {
                    self.add(&self.scale(&cd, &c0)?, &self.scale(&sd, &s0.neg())?)
                }
            }
            Atom::Exp(u) => {
                let whole = self.rat(u)?;
                let (u0, d) = self.split(&whole);
                let c: Vec<Q> = (0..=self.n).map(|k| Q::one() / fact(k)).collect();
                let s = self.compose(&c, &d)?;
                self.scale(&s, &func::exp(&u0)?)
            }
            Atom::Ln(u) => {
                let whole = self.rat(u)?;
                let (u0, d) = self.split(&whole);
                if u0.is_zero() {
                    return Err(SeriesError::NotAnalytic("ln of a small quantity".into()));
                }
                let z = self.scale(&d, &Rat::one().div(&u0)?)?;
                let c: Vec<Q> = (0..=self.n)
                    .map(|k| match k {
                        0 => Q::zero(),
                        k if k % 2 == 1 => q(1, k as i64),
                        k => q(-1, k as i64),
                    })
                    .collect();
                let s = self.compose(&c, &z)?;
                self.add(&s, &self.constant(func::ln(&u0, self.signs)?))
            }
            Atom::Sqrt(p) => self.root(p, 2),
            Atom::Root(p, m) => self.root(p, *m),
            Atom::Factor(p) => self.poly(p),
            Atom::Abs(p) => {
                let s = self.poly(p)?;
                match self.signs.rat(&s[0]) {
                    Sign::Pos => Ok(s),
                    Sign::Neg => s.iter().map(|x| Ok(x.neg())).collect(),
                    _ => Err(SeriesError::NotAnalytic(format!(
                        "abs({}) near a point where its sign is not known",
                        super::print::plain(&Rat::poly(p.clone())?)
                    ))),
                }
            }
            Atom::Pow(b, e) => {
                let lnb = func::ln(b, self.signs)?;
                let arg = e.mul(&lnb)?;
                let ex = func::exp(&arg)?;
                self.rat(&ex)
            }
            _ => Err(SeriesError::NotAnalytic(super::print::atom_plain(at))),
        }
    }

    /// `p^(1/m)` as `p₀^(1/m) (1 + z)^(1/m)`.
    fn root(&mut self, p: &Poly, m: u32) -> Result<Coeffs, SeriesError> {
        let whole = self.poly(p)?;
        let (p0, d) = self.split(&whole);
        if p0.is_zero() {
            return Err(SeriesError::NotAnalytic(
                "a root of a small quantity".into(),
            ));
        }
        let z = self.scale(&d, &Rat::one().div(&p0)?)?;
        let alpha = q(1, i64::from(m));
        let mut c = Vec::with_capacity(self.n + 1);
        let mut binom = Q::one();
        for k in 0..=self.n {
            c.push(binom.clone());
            binom = binom * (&alpha - q(k as i64, 1)) / q(k as i64 + 1, 1);
        }
        let s = self.compose(&c, &z)?;
        self.scale(&s, &func::root(&p0, m, self.signs)?)
    }
}
