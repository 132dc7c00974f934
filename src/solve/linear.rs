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
    // Two exact methods, one result (the canonical x_i): fraction-free Gauss–Jordan is
    // cheap when the minors stay small (the chain of rods), Cramer's rule (one Bareiss
    // determinant per numerator) when they grow (dense or banded matrices, where
    // Gauss–Jordan multiplies large minors by one another). The determinant and the
    // first and last numerators (whose costs differ most in structured systems) price
    // Cramer's rule in term products; Gauss–Jordan runs within that budget, else
    // Cramer's rule finishes the work. Either way nothing is guessed: both are exact.
    let mut work = Work::new(u128::MAX);
    let det = determinant(columns(&m, n, None), &mut work)?.ok_or(Limit::Terms)?;
    if det.is_zero() {
        return Err(LinearError::Singular);
    }
    let before = work.done;
    let first = determinant(columns(&m, n, Some(0)), &mut work)?.ok_or(Limit::Terms)?;
    let last = if n > 1 {
        Some(determinant(columns(&m, n, Some(n - 1)), &mut work)?.ok_or(Limit::Terms)?)
    } else {
        None
    };
    let probes = if n > 1 { 2 } else { 1 };
    let budget = (work.done - before).saturating_mul(n as u128) / probes;
    // A Gauss–Jordan that hits a resource limit (its products of large minors) also
    // leaves the work to Cramer's rule, which stays within smaller products.
    let (nums, det) = match gauss_jordan(&mut m.clone(), n, &mut Work::new(budget)) {
        Ok(Some(solved)) => solved,
        Err(LinearError::Singular) => return Err(LinearError::Singular),
        Ok(None) | Err(_) => {
            let mut nums = vec![first];
            for i in 1..n.saturating_sub(1) {
                let d = determinant(columns(&m, n, Some(i)), &mut work)?;
                nums.push(d.ok_or(Limit::Terms)?);
            }
            nums.extend(last);
            (nums, det)
        }
    };
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

/// Term products spent, against a budget.
struct Work {
    done: u128,
    budget: u128,
}

impl Work {
    fn new(budget: u128) -> Work {
        Work { done: 0, budget }
    }

    /// Counts the term products of `a · b`; false once over budget.
    fn charge(&mut self, a: &Poly, b: &Poly) -> bool {
        let cost = (a.len() as u128).saturating_mul(b.len() as u128);
        self.done = self.done.saturating_add(cost);
        self.done <= self.budget
    }
}

/// The matrix `A` (the first `n` columns of `m`), with column `i` replaced by the
/// right-hand side (column `n`) when `i` is given.
fn columns(m: &[Vec<Poly>], n: usize, i: Option<usize>) -> Vec<Vec<Poly>> {
    m.iter()
        .map(|r| {
            (0..n)
                .map(|j| {
                    if Some(j) == i {
                        r[n].clone()
                    } else {
                        r[j].clone()
                    }
                })
                .collect()
        })
        .collect()
}

/// The row (from `k` down) with the shortest nonzero entry in column `k`.
fn pivot_row(m: &[Vec<Poly>], k: usize) -> Option<usize> {
    (k..m.len())
        .filter(|&r| !m[r][k].is_zero())
        .min_by_key(|&r| m[r][k].len())
}

/// `(a·b − c·d) / prev`, exact by Bareiss's theorem.
fn bareiss_entry(
    a: &Poly,
    b: &Poly,
    c: &Poly,
    d: &Poly,
    prev: &Poly,
    work: &mut Work,
) -> Result<Option<Poly>, LinearError> {
    if !work.charge(a, b) || !work.charge(c, d) {
        return Ok(None);
    }
    let t = if c.is_zero() || d.is_zero() {
        a.mul(b)?
    } else {
        a.mul(b)?.sub(&c.mul(d)?)
    };
    Ok(Some(div_exact(&t, prev)?.ok_or(Limit::Terms)?))
}

/// The determinant by Bareiss elimination (the sign of the row swaps included);
/// zero for a singular matrix, `None` over budget.
fn determinant(mut m: Vec<Vec<Poly>>, work: &mut Work) -> Result<Option<Poly>, LinearError> {
    let n = m.len();
    let mut prev = Poly::one();
    let mut negate = false;
    for k in 0..n {
        let Some(p) = pivot_row(&m, k) else {
            return Ok(Some(Poly::zero()));
        };
        if p != k {
            m.swap(k, p);
            negate = !negate;
        }
        for i in k + 1..n {
            for j in k + 1..n {
                let Some(e) = bareiss_entry(&m[k][k], &m[i][j], &m[i][k], &m[k][j], &prev, work)?
                else {
                    return Ok(None);
                };
                m[i][j] = e;
            }
            m[i][k] = Poly::zero();
        }
        prev = m[k][k].clone();
    }
    Ok(Some(if negate { prev.neg() } else { prev }))
}

/// Fraction-free Gauss–Jordan on `[A | b]`: every step eliminates above the pivot
/// too, every entry stays a minor, and the last column ends as the numerators over
/// the last pivot. `None` over budget.
#[allow(clippy::type_complexity)]
fn gauss_jordan(
    m: &mut [Vec<Poly>],
    n: usize,
    work: &mut Work,
) -> Result<Option<(Vec<Poly>, Poly)>, LinearError> {
    let mut prev = Poly::one();
    for k in 0..n {
        let p = pivot_row(m, k).ok_or(LinearError::Singular)?;
        m.swap(k, p);
        for i in (0..n).filter(|&i| i != k) {
            for j in k + 1..=n {
                let Some(e) = bareiss_entry(&m[k][k], &m[i][j], &m[i][k], &m[k][j], &prev, work)?
                else {
                    return Ok(None);
                };
                m[i][j] = e;
            }
            m[i][k] = Poly::zero();
        }
        prev = m[k][k].clone();
    }
    // Every diagonal entry is now the last pivot.
    Ok(Some((m.iter().map(|r| r[n].clone()).collect(), prev)))
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
