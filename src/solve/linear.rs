//! Fraction-free (Bareiss) elimination over polynomials, fraction-free back
//! substitution, and gcd-reduced results: `x_i = num_i / det`, each in lowest terms.

use crate::normal::gcd::{div_exact, gcd};
use crate::normal::mono::Mono;
use crate::normal::{Limit, NormError, Poly, Rat, Q};
use num_traits::One;
use std::fmt;

/// Why a system could not be solved.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum LinearError {
    /// The matrix is singular (its determinant is the zero polynomial).
    Singular,
    /// The matrix is not square or the right-hand side has the wrong length.
    Shape,
    /// A normal-form error (limits).
    Norm(NormError),
}

impl From<NormError> for LinearError {
    fn from(e: NormError) -> LinearError {
        LinearError::Norm(e)
    }
}

impl From<Limit> for LinearError {
    fn from(e: Limit) -> LinearError {
        LinearError::Norm(e.into())
    }
}

impl fmt::Display for LinearError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LinearError::Singular => f.write_str("the system is singular"),
            LinearError::Shape => f.write_str("the matrix is not square"),
            LinearError::Norm(e) => write!(f, "{e}"),
        }
    }
}

/// Solves `A x = b` exactly. Rows with rational-function entries are first scaled to
/// polynomials by their common denominator.
pub fn solve(a: &[Vec<Rat>], b: &[Rat]) -> Result<Vec<Rat>, LinearError> {
    let n = a.len();
    if b.len() != n || a.iter().any(|r| r.len() != n) {
        return Err(LinearError::Shape);
    }
    // The augmented matrix over polynomials.
    let mut m: Vec<Vec<Poly>> = Vec::with_capacity(n);
    for (row, rhs) in a.iter().zip(b) {
        let mut den = Poly::one();
        for e in row.iter().chain(std::iter::once(rhs)) {
            if !e.den().is_one() {
                let g = gcd(&den, e.den())?;
                let q = div_exact(e.den(), &g)?.ok_or(Limit::Terms)?;
                den = den.mul(&q)?;
            }
        }
        let mut out = Vec::with_capacity(n + 1);
        for e in row.iter().chain(std::iter::once(rhs)) {
            let q = div_exact(&den, e.den())?.ok_or(Limit::Terms)?;
            out.push(e.num().mul(&q)?);
        }
        m.push(out);
    }
    // Integer coefficients: Bareiss then stays over ℤ, where the word-size fast paths
    // of the coefficient arithmetic apply.
    for row in m.iter_mut() {
        let mut l = num_bigint::BigInt::one();
        for e in row.iter() {
            for (_, q) in e.terms() {
                if !q.denom().is_one() {
                    l = num_integer::Integer::lcm(&l, q.denom());
                }
            }
        }
        if !l.is_one() {
            let l = Q::from_integer(l);
            for e in row.iter_mut() {
                *e = e.scale(&l);
            }
        }
    }
    // Monomial factors common to a row (right-hand side included) do not change the
    // solution; one common to column j is moved into the unknown (x_j = y_j / c_j).
    // Both shrink the determinant and spare the final gcds (the chain of rods has
    // l_i l_j in every entry).
    for row in m.iter_mut() {
        let c = row_content(row.iter());
        if !c.is_one() {
            for e in row.iter_mut() {
                *e = e.div_mono(&c).ok_or(Limit::Exponent)?;
            }
        }
    }
    let mut col_factor = Vec::with_capacity(n);
    for j in 0..n {
        let c = row_content(m.iter().filter_map(|r| r.get(j)));
        if !c.is_one() {
            for r in m.iter_mut() {
                if let Some(e) = r.get_mut(j) {
                    *e = e.div_mono(&c).ok_or(Limit::Exponent)?;
                }
            }
        }
        col_factor.push(c);
    }
    // Bareiss: after step k, every entry below and right of the pivot is a minor.
    let mut prev = Poly::one();
    for k in 0..n {
        let Some(p) = (k..n).min_by_key(|&r| {
            let e = &m[r][k];
            if e.is_zero() {
                usize::MAX
            } else {
                e.len()
            }
        }) else {
            return Err(LinearError::Singular);
        };
        if m[p][k].is_zero() {
            return Err(LinearError::Singular);
        }
        m.swap(k, p);
        for i in k + 1..n {
            for j in k + 1..=n {
                let t = m[k][k].mul(&m[i][j])?.sub(&m[i][k].mul(&m[k][j])?);
                m[i][j] = div_exact(&t, &prev)?.ok_or(Limit::Terms)?;
            }
            m[i][k] = Poly::zero();
        }
        prev = m[k][k].clone();
    }
    // det = last pivot; num_i = (b'_i·det − Σ_{j>i} a'_ij num_j) / a'_ii, exact.
    let det = prev;
    let mut nums: Vec<Poly> = vec![Poly::zero(); n];
    for i in (0..n).rev() {
        let mut t = m[i][n].mul(&det)?;
        for j in i + 1..n {
            t = t.sub(&m[i][j].mul(&nums[j])?);
        }
        nums[i] = div_exact(&t, &m[i][i])?.ok_or(Limit::Terms)?;
    }
    let mut out = Vec::with_capacity(n);
    for (num, c) in nums.into_iter().zip(col_factor) {
        let y = Rat::new(num, det.clone())?;
        out.push(if c.is_one() {
            y
        } else {
            y.div(&Rat::poly(Poly::term(c, Q::one()))?)?
        });
    }
    Ok(out)
}

/// The greatest monomial dividing every nonzero polynomial of `entries`.
fn row_content<'a>(entries: impl Iterator<Item = &'a Poly>) -> Mono {
    let mut g: Option<Mono> = None;
    for e in entries.filter(|e| !e.is_zero()) {
        let c = e.mono_content();
        g = Some(match g {
            None => c,
            Some(g) => g.gcd(&c),
        });
        if g.as_ref().is_some_and(Mono::is_one) {
            break;
        }
    }
    g.unwrap_or_else(Mono::one)
}
