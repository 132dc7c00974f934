//! Square linear systems over polynomials by Cramer's rule, one fraction-free (Bareiss)
//! determinant per numerator, and gcd-reduced results: `x_i = num_i / det`, each in
//! lowest terms.
//!
//! The checker does not use this solver (it eliminates fact by fact, `check/elimination.rs`);
//! it is the library's solver and the one the benchmarks time.

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
    if n == 0 {
        return Ok(Vec::new());
    }
    // The augmented matrix over polynomials.
    let mut m: Vec<Vec<Poly>> = Vec::with_capacity(n);
    for (row, rhs) in a.iter().zip(b) {
        let mut den = Poly::one();
        for e in row.iter().chain(std::iter::once(rhs)) {
            if !e.den().is_one() {
                let g = gcd(&den, e.den())?;
                let q = div_exact(e.den(), &g)?.ok_or(Limit::terms())?;
                den = den.mul(&q)?;
            }
        }
        let mut out = Vec::with_capacity(n + 1);
        for e in row.iter().chain(std::iter::once(rhs)) {
            let q = div_exact(&den, e.den())?.ok_or(Limit::terms())?;
            out.push(e.num().mul(&q)?);
        }
        m.push(out);
    }
    // Integer coefficients: Bareiss then stays over ℤ, where the word-size fast paths
    // of the coefficient arithmetic apply.
    for row in m.iter_mut() {
        let mut l = num_bigint::BigInt::one();
        for e in row.iter().filter(|e| !e.is_zero()) {
            // The content's denominator is the lcm of the coefficients' denominators.
            l = num_integer::Integer::lcm(&l, e.content().denom());
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
    // Cramer's rule, x_i = det(A with column i replaced by b) / det(A), with one
    // fraction-free (Bareiss) elimination per determinant. Every intermediate entry is
    // a minor, never a minor times a whole numerator as in back substitution or the
    // upper half of Gauss–Jordan.
    let det = determinant(columns(&m, n, None))?;
    if det.is_zero() {
        return Err(LinearError::Singular);
    }
    let nums = (0..n)
        .map(|i| determinant(columns(&m, n, Some(i))))
        .collect::<Result<Vec<Poly>, LinearError>>()?;
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

/// The matrix `A` (the first `n` columns of `m`) or, for the numerator of `x_i`, `A`
/// without column `i` and with the right-hand side (column `n`) appended last, and the
/// sign that makes its determinant `det(A with column i replaced by b)`. The
/// right-hand side is usually the least structured column: eliminated last, it leaves
/// the elimination of the others as cheap as in `det A`.
fn columns(m: &[Vec<Poly>], n: usize, i: Option<usize>) -> (Vec<Vec<Poly>>, bool) {
    let keep: Vec<usize> = match i {
        None => (0..n).collect(),
        Some(i) => (0..n)
            .filter(|&j| j != i)
            .chain(std::iter::once(n))
            .collect(),
    };
    let rows = m
        .iter()
        .map(|r| keep.iter().map(|&j| r[j].clone()).collect())
        .collect();
    // Moving column i to the end is n − 1 − i adjacent swaps.
    (rows, i.is_some_and(|i| (n - 1 - i) % 2 == 1))
}

/// The row (from `k` down) with the shortest nonzero entry in column `k`.
fn pivot_row(m: &[Vec<Poly>], k: usize) -> Option<usize> {
    (k..m.len())
        .filter(|&r| !m[r][k].is_zero())
        .min_by_key(|&r| m[r][k].len())
}

/// `(a·b − c·d) / prev`, exact by Bareiss's theorem.
fn bareiss_entry(a: &Poly, b: &Poly, c: &Poly, d: &Poly, prev: &Poly) -> Result<Poly, LinearError> {
    let t = if c.is_zero() || d.is_zero() {
        a.mul(b)?
    } else {
        a.mul(b)?.sub_owned(c.mul(d)?)
    };
    Ok(div_exact(&t, prev)?.ok_or(Limit::terms())?)
}

/// The determinant by Bareiss elimination, negated when `negate` (the sign of the row
/// swaps included); zero for a singular matrix.
fn determinant((mut m, negate): (Vec<Vec<Poly>>, bool)) -> Result<Poly, LinearError> {
    let n = m.len();
    let mut prev = Poly::one();
    let mut negate = negate;
    for k in 0..n {
        let Some(p) = pivot_row(&m, k) else {
            return Ok(Poly::zero());
        };
        if p != k {
            m.swap(k, p);
            negate = !negate;
        }
        for i in k + 1..n {
            for j in k + 1..n {
                m[i][j] = bareiss_entry(&m[k][k], &m[i][j], &m[i][k], &m[k][j], &prev)?;
            }
            m[i][k] = Poly::zero();
        }
        prev = m[k][k].clone();
    }
    Ok(if negate { prev.neg() } else { prev })
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
