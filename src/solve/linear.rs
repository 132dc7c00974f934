//! Square linear systems over polynomials by Cramer's rule with fraction-free (Bareiss)
//! determinants, and gcd-reduced results: `x_i = num_i / det`, each in lowest terms. On
//! packed polynomials one elimination of `[A | b]` serves every numerator
//! (`packed_determinants`).
//!
//! The checker does not use this solver (it eliminates fact by fact, `check/elimination.rs`);
//! it is the library's solver and the one the benchmarks time.

use super::{packed, quotients};
use crate::normal::gcd::{div_exact, gcd};
use crate::normal::mono::Mono;
use crate::normal::{atom, AtomId, Limit, NormError, Poly, Rat, Q};
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
    // The unknowns in the order of elimination: the given one or its reverse (which
    // keeps a band a band), whichever eliminates the columns with fewer terms first.
    let reverse = eliminate_reversed(&m, n);
    if reverse {
        for row in m.iter_mut() {
            row[..n].reverse();
        }
        col_factor.reverse();
    }
    // Cramer's rule, x_i = det(A with column i replaced by b) / det(A), with one
    // fraction-free (Bareiss) elimination per determinant. Every intermediate entry is
    // a minor, never a minor times a whole numerator as in back substitution or the
    // upper half of Gauss–Jordan.
    let (det, nums) = match packed_determinants(&m, n) {
        Some((ring, det, nums)) => (ring.unpack(&det), Numerators::Packed(Box::new(ring), nums)),
        None => {
            let det = determinant(columns(&m, n, None))?;
            if det.is_zero() {
                return Err(LinearError::Singular);
            }
            let nums = (0..n)
                .map(|i| determinant(columns(&m, n, Some(i))))
                .collect::<Result<Vec<Poly>, LinearError>>()?;
            (det, Numerators::General(nums))
        }
    };
    if det.is_zero() {
        return Err(LinearError::Singular);
    }
    let mut out = quotients_of(&det, &nums, &col_factor, rule_free(&m))?;
    if reverse {
        out.reverse();
    }
    Ok(out)
}

/// Cramer's numerators, packed (with their ring) or as polynomials.
enum Numerators {
    Packed(Box<packed::Ring>, Vec<packed::P>),
    General(Vec<Poly>),
}

/// `x_i = y_i / c_i = num_i / (det · c_i)`, one canonical form each: from one proof
/// about `det` when the atoms have no rules (`free`) and it is shown
/// ([`quotients::Denominator`]), else one `Rat::new` (one gcd) each.
fn quotients_of(
    det: &Poly,
    nums: &Numerators,
    col_factor: &[Mono],
    free: bool,
) -> Result<Vec<Rat>, LinearError> {
    let shared = if free {
        quotients::Denominator::new(det)?
    } else {
        None
    };
    let mut out = Vec::with_capacity(col_factor.len());
    for (k, c) in col_factor.iter().enumerate() {
        if let (Some(d), Numerators::Packed(ring, ps)) = (&shared, nums) {
            if let Some(x) = d.quotient_packed(ring, ps.get(k).ok_or(LinearError::Shape)?, c)? {
                out.push(x);
                continue;
            }
        }
        let num = match nums {
            Numerators::Packed(ring, ps) => ring.unpack(ps.get(k).ok_or(LinearError::Shape)?),
            Numerators::General(ps) => ps.get(k).ok_or(LinearError::Shape)?.clone(),
        };
        if let Some(d) = &shared {
            out.push(d.quotient(num, c)?);
            continue;
        }
        let den = if c.is_one() {
            det.clone()
        } else {
            det.mul_term(c, &Q::one())?
        };
        out.push(Rat::new(num, den)?);
    }
    Ok(out)
}

/// Whether eliminating the columns of `A` (the first `n` of `m`) from the last to the
/// first puts the columns with more terms later than the given order does. Bareiss's
/// entries are minors on the columns eliminated so far, and each numerator's last
/// steps multiply them: the chain of rods, whose first column holds every mass and
/// its last one mass, does 40 % fewer term products at n = 8 reversed. A band (or any
/// order whose weights are symmetric) stays as it is.
fn eliminate_reversed(m: &[Vec<Poly>], n: usize) -> bool {
    let weight = |j: usize| -> usize { m.iter().filter_map(|r| r.get(j)).map(Poly::len).sum() };
    // Σ position × weight: larger when the heavy columns come late.
    let (mut given, mut reversed) = (0usize, 0usize);
    for j in 0..n {
        let w = weight(j);
        given = given.saturating_add(j.saturating_mul(w));
        reversed = reversed.saturating_add((n - 1 - j).saturating_mul(w));
    }
    reversed > given
}

/// The matrix `A` (the first `n` columns of `m`) or, for the numerator of `x_i`, `A`
/// without column `i` and with the right-hand side (column `n`) appended last, and the
/// sign that makes its determinant `det(A with column i replaced by b)`. The
/// right-hand side is usually the least structured column: eliminated last, it leaves
/// the elimination of the others as cheap as in `det A`.
fn columns<T: Clone>(m: &[Vec<T>], n: usize, i: Option<usize>) -> (Vec<Vec<T>>, bool) {
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

/// `det A` and Cramer's numerators on packed integer polynomials ([`packed`]), `None`
/// when the matrix does not pack or an entry outgrows the packed form (the general
/// path then runs). A singular `A` gives a zero determinant.
///
/// One elimination of `[A | b]` serves them all. After it, `U x = b'` with `U` upper
/// triangular and `D = U_{n−1,n−1}`, and each numerator can be had in one of two exact
/// ways:
///
/// - by fraction-free back substitution, `num_i = (b'_i·D − Σ_{j>i} U_ij·num_j) / U_ii`;
/// - by continuing the elimination: after `k` steps, an entry of column `j` depends only
///   on the columns before `k` and on column `j`, so the state of the rows from `k` on,
///   without column `k`, is the state the elimination for the numerator of `x_k`
///   (columns `0..k`, then those after `k`, then `b`) reaches after its own `k` steps;
///   that numerator takes it from there.
///
/// Neither is always cheaper: back substitution multiplies whole numerators by the
/// entries of `U`, which are small in the first rows and large in the last of a generic
/// matrix, and on the chain of rods continuing builds entries far larger than the
/// elimination's own. Back substitution's work (term products, and the division's) is
/// known from the sizes at hand before it is done; the continued elimination's is not,
/// but it is forecast from the rows done ([`Forecast`]). So each numerator, from the
/// last, is continued within a budget (back substitution's work when the forecast says
/// continuing is cheaper, a sixteenth of it otherwise), and got by back substitution
/// when the budget runs out. Both give the same polynomial.
fn packed_determinants(
    m: &[Vec<Poly>],
    n: usize,
) -> Option<(packed::Ring, packed::P, Vec<packed::P>)> {
    packed_determinants_by(m, n, Way::Cheaper)
}

/// How [`packed_determinants_by`] gets each numerator: the tests take each way alone.
#[derive(Clone, Copy, Debug)]
enum Way {
    /// The continued elimination within the budget [`Forecast`] gives it, else back
    /// substitution.
    Cheaper,
    /// Back substitution (the continued elimination gets no budget).
    #[cfg(test)]
    Back,
    /// The continued elimination, whatever it costs.
    #[cfg(test)]
    Continued,
    /// The continued elimination within back substitution's work, else back
    /// substitution, whatever the forecast: the choice before there was one.
    #[cfg(test)]
    WithinBack,
}

/// [`packed_determinants`], each numerator got `way`.
fn packed_determinants_by(
    m: &[Vec<Poly>],
    n: usize,
    way: Way,
) -> Option<(packed::Ring, packed::P, Vec<packed::P>)> {
    let ring = packed::Ring::new(m)?;
    let mut m = m
        .iter()
        .map(|r| r.iter().map(|e| ring.pack(e)).collect::<Option<Vec<_>>>())
        .collect::<Option<Vec<_>>>()?;
    let mut prev: packed::P = vec![(0, 1)];
    let mut negate = false;
    // Where the elimination for numerator k would start, the rows from k on as they
    // were before step k: the pivot row stays in `m`, and the entries step k replaces in
    // the others are kept here (rows after the pivot's swap), with the sign.
    let mut replaced: Vec<(Vec<Vec<packed::P>>, bool)> = Vec::with_capacity(n);
    // What the forward elimination has left of an unlimited budget: its work, after.
    let mut forward = u64::MAX;
    for k in 0..n {
        // The numerator of x_k: moving column k past the n − 1 − k after it.
        let mut sign = negate != ((n - 1 - k) % 2 == 1);
        let Some(p) = pivot_row(&m, k, |e: &packed::P| e.len()) else {
            return Some((ring, Vec::new(), Vec::new()));
        };
        if p != k {
            m.swap(k, p);
            negate = !negate;
            sign = !sign;
        }
        let mut old = Vec::with_capacity(n - 1 - k);
        bareiss_step_packed(&ring, &mut m, k, &prev, &mut forward, Some(&mut old))?;
        replaced.push((old, sign));
        prev = m.get(k)?.get(k)?.clone();
    }
    // Numerators as back substitution gives them: of `U x = b'`, whose determinant is
    // `prev`, the Cramer numerators negated when the rows were swapped an odd number of
    // times. Continued eliminations give Cramer's: `frame` converts either way.
    let frame = |mut p: packed::P| -> Option<packed::P> {
        if negate {
            for t in &mut p {
                t.1 = t.1.checked_neg()?;
            }
        }
        Some(p)
    };
    let size = |p: &packed::P| p.len() as u64;
    let mut forecast = Forecast::new(u64::MAX - forward);
    let mut nums: Vec<packed::P> = vec![Vec::new(); n];
    for i in (0..n).rev() {
        let row = m.get(i)?;
        let (b, u) = (row.get(n)?, row.get(i)?);
        if i + 1 == n {
            nums[i] = b.clone();
            continue;
        }
        // Back substitution's work, known before it is done: its term products, and for
        // the exact division one product per term of the quotient (a numerator, about
        // the determinant's size) and of the divisor.
        let mut back = size(b).saturating_mul(size(&prev));
        for j in i + 1..n {
            back = back.saturating_add(size(row.get(j)?).saturating_mul(size(nums.get(j)?)));
        }
        if u.len() > 1 {
            back = back.saturating_add(size(&prev).saturating_mul(size(u)));
        }
        // The continued elimination, whose work is not known before, may spend as much;
        // past that, back substitution. Each numerator costs at most twice the cheaper.
        let (old, sign) = replaced.get(i)?;
        let rows: Vec<&[packed::P]> = std::iter::once(row.as_slice())
            .chain(old.iter().map(Vec::as_slice))
            .collect();
        let last = match i {
            0 => &vec![(0, 1)],
            _ => m.get(i - 1)?.get(i - 1)?,
        };
        let expected = forecast.next(i);
        let given = match way {
            Way::Cheaper => forecast.budget(expected, back),
            #[cfg(test)]
            Way::Back => 0,
            #[cfg(test)]
            Way::Continued => u64::MAX,
            #[cfg(test)]
            Way::WithinBack => back,
        };
        let mut budget = given;
        let got = numerator_packed(&ring, &rows, i + 1, *sign, last, &mut budget)?;
        forecast.record(expected, given - budget, got.is_some());
        #[cfg(test)]
        tests::WORK.with(|w| {
            let fallback = if got.is_some() { 0 } else { back };
            w.set(w.get() + (given - budget) + fallback);
        });
        nums[i] = match got {
            Some(num) => frame(num)?,
            None => {
                let rest: Vec<(&packed::P, &packed::P)> = (i + 1..n)
                    .map(|j| Some((row.get(j)?, nums.get(j)?)))
                    .collect::<Option<_>>()?;
                ring.back_substitute(b, &prev, &rest, u)?
            }
        };
    }
    let nums = nums.into_iter().map(frame).collect::<Option<Vec<_>>>()?;
    Some((ring, frame(prev)?, nums))
}

/// The work of each numerator's continued elimination (term products, as
/// [`budgeted_entry`] counts them), forecast before it is done.
///
/// From the last row up, each continued elimination is larger than the one before and
/// of the same kind (a determinant of minors one order lower), and their work grows
/// about geometrically: on the chain of rods, about twice per row, while back
/// substitution's grows by 1.4. The next is forecast from the last two by their ratio
/// (at least 1). The numerator of `x_0` continues nothing: it eliminates the original
/// entries, as the forward elimination did, whose work forecasts it.
///
/// A forecast only spends the budget: a continued elimination forecast to cost no more
/// than back substitution gets as much work as back substitution takes (at most about
/// twice the cheaper way when the forecast is wrong), and one forecast to cost more gets
/// a sixteenth of it, which finds the cheap ones the forecast missed at a small cost
/// (at most about seventeen times the cheaper way).
struct Forecast {
    /// The work of the forward elimination, which forecasts row 0's.
    forward: u64,
    /// The work of the last two rows' continued eliminations, the latest first: as
    /// measured when they ran to the end, else what is known of it (what they spent
    /// before the budget ran out, or the forecast when that is more).
    last: [Option<u64>; 2],
}

impl Forecast {
    fn new(forward: u64) -> Forecast {
        Forecast {
            forward,
            last: [None, None],
        }
    }

    /// The work forecast for row `i`'s continued elimination (0: none known, try it).
    fn next(&self, i: usize) -> u64 {
        if i == 0 {
            return self.forward;
        }
        match self.last {
            [Some(c1), Some(c2)] if c2 > 0 && c1 > c2 => {
                u64::try_from(u128::from(c1) * u128::from(c1) / u128::from(c2)).unwrap_or(u64::MAX)
            }
            [Some(c1), _] => c1,
            [None, _] => 0,
        }
    }

    /// The budget of a continued elimination forecast to cost `expected`, where back
    /// substitution costs `back`.
    fn budget(&self, expected: u64, back: u64) -> u64 {
        if expected <= back {
            back
        } else {
            back / 16
        }
    }

    /// What row's continued elimination turned out: `spent` of a budget, to the end
    /// (`done`) or not.
    fn record(&mut self, expected: u64, spent: u64, done: bool) {
        let cost = if done { spent } else { spent.max(expected) };
        self.last = [Some(cost), self.last[0]];
    }
}

/// Step `k` of Bareiss elimination on packed polynomials: every entry right of and
/// below the pivot `(k, k)` becomes `(pivot·e − left·up) / prev`; column `k` below the
/// pivot becomes zero, each within `budget` ([`budgeted_entry`]); `Some(false)` when
/// the budget does not cover the next entry. The entries replaced are pushed to
/// `replaced` when given, a row each (full width, empty where nothing was replaced).
fn bareiss_step_packed(
    ring: &packed::Ring,
    m: &mut [Vec<packed::P>],
    k: usize,
    prev: &packed::P,
    budget: &mut u64,
    mut replaced: Option<&mut Vec<Vec<packed::P>>>,
) -> Option<bool> {
    let (top, below) = m.split_at_mut(k + 1);
    let pivot_row = top.last()?;
    for row in below {
        let mut old = Vec::new();
        if replaced.is_some() {
            old.resize_with(row.len(), Vec::new);
        }
        for j in k + 1..row.len() {
            let entry = (&pivot_row[k], &row[j], &row[k], &pivot_row[j]);
            let Some(e) = budgeted_entry(ring, entry, prev, budget)? else {
                return Some(false);
            };
            let was = std::mem::replace(&mut row[j], e);
            if let Some(slot) = old.get_mut(j) {
                *slot = was;
            }
        }
        row[k] = Vec::new();
        if let Some(kept) = replaced.as_deref_mut() {
            kept.push(old);
        }
    }
    Some(true)
}

/// One Bareiss entry `(a·b − c·d) / prev` within `budget`, whose work is counted as
/// `packed_determinants` counts back substitution's: the term products, taken before
/// they are made (`Some(None)`, with nothing spent, when the budget does not cover
/// them), and for a divisor of several terms, its terms times the quotient's, taken
/// after (down to zero).
fn budgeted_entry(
    ring: &packed::Ring,
    (a, b, c, d): (&packed::P, &packed::P, &packed::P, &packed::P),
    prev: &packed::P,
    budget: &mut u64,
) -> Option<Option<packed::P>> {
    let size = |p: &packed::P| p.len() as u64;
    let products = size(a)
        .saturating_mul(size(b))
        .saturating_add(size(c).saturating_mul(size(d)));
    let Some(left) = budget.checked_sub(products) else {
        return Some(None);
    };
    let e = ring.bareiss_entry(a, b, c, d, prev)?;
    *budget = if prev.len() > 1 {
        left.saturating_sub(size(&e).saturating_mul(size(prev)))
    } else {
        left
    };
    Some(Some(e))
}

/// The determinant of `rows` from column `first` on (the rest of `[A | b]` after `k`
/// steps, without column `k`), negated when `negate`, continuing an elimination whose
/// last pivot was `prev`. Its first step reads the shared state and writes a matrix of
/// its own (every entry it keeps is new: nothing is copied), [`determinant_packed`]
/// takes the others.
fn numerator_packed(
    ring: &packed::Ring,
    rows: &[&[packed::P]],
    first: usize,
    negate: bool,
    prev: &packed::P,
    budget: &mut u64,
) -> Option<Option<packed::P>> {
    let len = |r: &[packed::P]| r.get(first).map_or(0, Vec::len);
    let Some(p) = (0..rows.len())
        .filter(|&r| len(rows[r]) > 0)
        .min_by_key(|&r| len(rows[r]))
    else {
        return Some(Some(Vec::new()));
    };
    // The rows in the order a swap of rows 0 and p leaves them.
    let mut order: Vec<usize> = (0..rows.len()).collect();
    order.swap(0, p);
    let pivot = rows.get(p)?;
    let mut m = Vec::with_capacity(rows.len() - 1);
    for &r in order.get(1..)? {
        let row = rows.get(r)?;
        let mut out = Vec::with_capacity(row.len().saturating_sub(first + 1));
        for j in first + 1..row.len() {
            let entry = (&pivot[first], &row[j], &row[first], &pivot[j]);
            let Some(e) = budgeted_entry(ring, entry, prev, budget)? else {
                return Some(None);
            };
            out.push(e);
        }
        m.push(out);
    }
    determinant_packed(
        ring,
        (m, negate != (p != 0)),
        pivot.get(first)?.clone(),
        budget,
    )
}

/// [`determinant`] on packed polynomials, continuing an elimination whose last pivot
/// was `prev` (`1` for a fresh one), within `budget` (`Some(None)` past it).
fn determinant_packed(
    ring: &packed::Ring,
    (mut m, negate): (Vec<Vec<packed::P>>, bool),
    mut prev: packed::P,
    budget: &mut u64,
) -> Option<Option<packed::P>> {
    let n = m.len();
    let mut negate = negate;
    for k in 0..n {
        let Some(p) = pivot_row(&m, k, |e: &packed::P| e.len()) else {
            return Some(Some(Vec::new()));
        };
        if p != k {
            m.swap(k, p);
            negate = !negate;
        }
        if !bareiss_step_packed(ring, &mut m, k, &prev, budget, None)? {
            return Some(None);
        }
        prev = std::mem::take(&mut m[k][k]);
    }
    if negate {
        for t in &mut prev {
            t.1 = t.1.checked_neg()?;
        }
    }
    Some(Some(prev))
}

/// The row (from `k` down) with the shortest nonzero entry in column `k` (`len`: the
/// number of terms, 0 for zero).
fn pivot_row<T>(m: &[Vec<T>], k: usize, len: impl Fn(&T) -> usize) -> Option<usize> {
    (k..m.len())
        .filter(|&r| len(&m[r][k]) > 0)
        .min_by_key(|&r| len(&m[r][k]))
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
        let Some(p) = pivot_row(&m, k, Poly::len) else {
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

/// Whether no atom of the matrix carries a rewrite rule (its products need no
/// reduction, and [`quotients`] applies).
fn rule_free(m: &[Vec<Poly>]) -> bool {
    let mut ids: Vec<AtomId> = m.iter().flatten().flat_map(Poly::atoms).collect();
    ids.sort_unstable();
    ids.dedup();
    atom::rules(&ids).iter().all(|r| *r == atom::Rule::Free)
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

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::normal::AtomId;
    use num_bigint::BigInt;
    use proptest::prelude::*;

    /// The tests' atom `i`: a symbol of its own, interned after atoms `0..i`, so that ids
    /// follow the indices in every run. A bare `AtomId::from_index(i)` would be whatever
    /// atom the test process happened to intern `i`-th (it varies with the order the
    /// tests run in, and it may carry a rewrite rule, which `solve` looks at).
    pub(in crate::solve) fn var(i: u32) -> AtomId {
        let name = |k: u32| format!("solve_test_x{k}");
        for k in 0..i {
            atom::sym(&name(k));
        }
        atom::sym(&name(i))
    }

    /// A small polynomial from `(atom, exponent)` lists and integer coefficients
    /// (atoms [`var`] 0–3, so products of entries share atoms and cancel).
    pub(in crate::solve) fn poly(terms: &[(Vec<(u32, u32)>, i64)]) -> Poly {
        Poly::from_terms(
            terms
                .iter()
                .filter_map(|(m, c)| {
                    let m = m.iter().map(|&(a, e)| (var(a), e));
                    Some((
                        Mono::from_pairs(m.collect())?,
                        Q::from_integer(BigInt::from(*c)),
                    ))
                })
                .collect(),
        )
    }

    fn any_poly() -> impl Strategy<Value = Poly> {
        let term = (
            proptest::collection::vec((0u32..4, 1u32..3), 0..3),
            -4i64..=4,
        );
        proptest::collection::vec(term, 0..4).prop_map(|t| poly(&t))
    }

    fn any_matrix() -> impl Strategy<Value = Vec<Vec<Poly>>> {
        any_matrix_up_to(4)
    }

    /// An augmented matrix `[A | b]` with `A` at most `max` × `max`.
    fn any_matrix_up_to(max: usize) -> impl Strategy<Value = Vec<Vec<Poly>>> {
        (1usize..=max).prop_flat_map(|n| {
            proptest::collection::vec(proptest::collection::vec(any_poly(), n + 1), n)
        })
    }

    thread_local! {
        /// The work (term products) the numerators of the last packed solve on this
        /// thread took: continued eliminations, and back substitutions where used.
        pub(super) static WORK: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
    }

    /// The chain of rods of `n` links (WORKLOADS.md's W3.chain, lengths 1), six times
    /// its mass matrix (integer coefficients) with the generalized forces on the right,
    /// its columns in the order `solve` eliminates them.
    fn chain_of_rods(n: u32) -> Vec<Vec<Poly>> {
        let mass = |k: u32, c: i64| (vec![(k, 1)], c);
        let mut m: Vec<Vec<Poly>> = (0..n)
            .map(|i| {
                let mut row: Vec<Poly> = (0..n)
                    .map(|j| {
                        let (k, own) = if i == j { (i, 2) } else { (i.max(j), 3) };
                        let mut t = vec![mass(k, own)];
                        t.extend((k + 1..n).map(|h| mass(h, 6)));
                        poly(&t)
                    })
                    .collect();
                row.push(poly(&[(vec![(n + i, 1)], 1)]));
                row
            })
            .collect();
        if eliminate_reversed(&m, n as usize) {
            for row in m.iter_mut() {
                row[..n as usize].reverse();
            }
        }
        m
    }

    /// On the chain of rods the forecast takes less work for the numerators than either
    /// way alone (continuing wins in some rows, back substitution in others), and less
    /// than trying every continued elimination within back substitution's work.
    #[test]
    fn the_forecast_takes_less_work_than_either_way_alone() {
        let m = chain_of_rods(7);
        let work = |way: Way| {
            WORK.with(|w| w.set(0));
            assert!(packed_determinants_by(&m, 7, way).is_some(), "{way:?}");
            WORK.with(|w| w.get())
        };
        let cheaper = work(Way::Cheaper);
        for way in [Way::Back, Way::Continued, Way::WithinBack] {
            let other = work(way);
            assert!(cheaper < other, "forecast {cheaper}, {way:?} {other}");
        }
    }

    /// Cramer's numerators and `det A` by the general (unpacked) path.
    fn general(m: &[Vec<Poly>]) -> Result<(Poly, Vec<Poly>), LinearError> {
        let n = m.len();
        let det = determinant(columns(m, n, None))?;
        let nums = (0..n)
            .map(|i| determinant(columns(m, n, Some(i))))
            .collect::<Result<Vec<Poly>, LinearError>>()?;
        Ok((det, nums))
    }

    /// The forecast grows by the ratio of the last two rows' work (at least 1), takes
    /// what a row that ran out of budget is known to cost, forecasts row 0 by the
    /// forward elimination, and gives a continued elimination forecast dearer than back
    /// substitution only a sixteenth of its work.
    #[test]
    fn forecast_extrapolates_the_work_of_the_rows_done() {
        let mut f = Forecast::new(2142);
        assert_eq!(f.next(6), 0, "nothing known: try it");
        assert_eq!(f.budget(0, 638), 638);
        assert_eq!(f.budget(638, 638), 638, "no dearer: the whole budget");
        f.record(0, 382, true);
        assert_eq!(f.next(5), 382);
        f.record(382, 1304, true);
        // 1304 · 1304 / 382
        assert_eq!(f.next(4), 4451);
        assert_eq!(f.budget(4451, 2510), 156);
        // Ran out of its sixteenth: known to cost at least the forecast.
        f.record(4451, 150, false);
        assert_eq!(f.next(3), 4451 * 4451 / 1304);
        assert_eq!(f.next(0), 2142);
        // Work that fell: the next is forecast as the last, not lower.
        let mut f = Forecast::new(0);
        f.record(0, 900, true);
        f.record(900, 300, true);
        assert_eq!(f.next(1), 300);
        // Ran out of a budget larger than its forecast: at least what it spent.
        f.record(100, 700, false);
        assert_eq!(f.next(1), 700 * 700 / 300);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        /// The packed determinants are the general path's, term for term, whichever way
        /// the numerators are got (back substitution, continued elimination, the cheaper).
        #[test]
        fn packed_agrees_with_general(m in any_matrix()) {
            let n = m.len();
            let Ok((det, nums)) = general(&m) else {
                return Err(TestCaseError::fail("the general path failed on a small matrix"));
            };
            for way in [Way::Cheaper, Way::Back, Way::Continued, Way::WithinBack] {
                let Some((ring, pdet, pnums)) = packed_determinants_by(&m, n, way) else {
                    return Err(TestCaseError::fail(format!("small integer matrices pack ({way:?})")));
                };
                let pnums: Vec<Poly> = pnums.iter().map(|p| ring.unpack(p)).collect();
                prop_assert_eq!(&ring.unpack(&pdet), &det, "{:?}", way);
                if !det.is_zero() {
                    prop_assert_eq!(&pnums, &nums, "{:?}", way);
                }
            }
        }

    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]

        /// The solution satisfies every equation of the system (exactly, by
        /// substitution), and a singular matrix is reported as such. Systems up to 2 × 2:
        /// on some 3 × 3 draws (about one in fifty runs of the test) the gcds that bring
        /// the quotients to lowest terms, when the determinant is not shown irreducible,
        /// run for minutes (recursive PRS on coefficients that grow); the packed and
        /// general determinants are compared up to 4 × 4 above, and the workloads'
        /// systems up to 8 × 8 are solved and checked in `tests/it/workloads.rs`.
        #[test]
        fn solution_satisfies_the_system(m in any_matrix_up_to(2)) {
            let n = m.len();
            let rat = |p: &Poly| Rat::poly(p.clone()).unwrap_or_else(|_| Rat::zero());
            let a: Vec<Vec<Rat>> = m.iter().map(|r| r[..n].iter().map(rat).collect()).collect();
            let b: Vec<Rat> = m.iter().map(|r| rat(&r[n])).collect();
            let Ok((det, _)) = general(&m) else {
                return Err(TestCaseError::fail("the general path failed on a small matrix"));
            };
            match solve(&a, &b) {
                Err(LinearError::Singular) => prop_assert!(det.is_zero()),
                Err(e) => return Err(TestCaseError::fail(format!("{e}"))),
                Ok(x) => {
                    prop_assert!(!det.is_zero());
                    prop_assert_eq!(x.len(), n);
                    // Σ_j a_ij·p_j/q_j = b_i, multiplied through by Π_k q_k: polynomial
                    // products and sums only (adding the quotients as rational functions
                    // takes multivariate gcds, which can run for minutes on some draws).
                    let fail = |e: Limit| TestCaseError::fail(format!("{e}"));
                    // The product of the denominators of the unknowns but `skip`.
                    let dens = |skip: Option<usize>| {
                        x.iter()
                            .enumerate()
                            .filter(|(k, _)| Some(*k) != skip)
                            .try_fold(Poly::one(), |d, (_, xk)| d.mul(xk.den()))
                            .map_err(fail)
                    };
                    let all = dens(None)?;
                    for (row, rhs) in a.iter().zip(&b) {
                        prop_assert!(rhs.den().is_one() && row.iter().all(|c| c.den().is_one()));
                        let mut lhs = Poly::zero();
                        for (j, (c, xj)) in row.iter().map(Rat::num).zip(&x).enumerate() {
                            let others = dens(Some(j))?;
                            let term = c.mul(xj.num()).and_then(|t| t.mul(&others));
                            lhs = lhs.add(&term.map_err(fail)?);
                        }
                        prop_assert_eq!(lhs, rhs.num().mul(&all).map_err(fail)?);
                    }
                }
            }
        }
    }

    /// A system with rational coefficients whose rows and columns carry monomial
    /// factors (random, some of them the same atom), and now and then a zero row or a
    /// zero column: `(A, b)`.
    fn any_scaled_system() -> impl Strategy<Value = (Vec<Vec<Rat>>, Vec<Rat>)> {
        let mono = proptest::collection::vec((0u32..4, 1u32..2), 0..2);
        // n ≤ 2: the reference's gcds (recursive PRS on unreduced Cramer quotients)
        // stay fast on every draw.
        (1usize..=2).prop_flat_map(move |n| {
            (
                proptest::collection::vec(proptest::collection::vec(any_poly(), n + 1), n),
                proptest::collection::vec(1i64..=3, n),
                proptest::collection::vec(mono.clone(), n),
                proptest::collection::vec(mono.clone(), n),
                proptest::option::weighted(0.15, (0..n, any::<bool>())),
            )
                .prop_map(|(m, dens, rows, cols, zero)| {
                    let n = m.len();
                    let factor = |pairs: &[(u32, u32)]| poly(&[(pairs.to_vec(), 1)]);
                    let rat = |p: Poly, d: i64| {
                        Rat::poly(p)
                            .and_then(|r| r.div(&Rat::int(d)))
                            .unwrap_or_else(|_| Rat::zero())
                    };
                    let mut a = vec![vec![Rat::zero(); n]; n];
                    let mut b = Vec::with_capacity(n);
                    for (i, row) in m.iter().enumerate() {
                        let ri = factor(&rows[i]);
                        for j in 0..n {
                            let e = row[j].mul(&ri).and_then(|e| e.mul(&factor(&cols[j])));
                            a[i][j] = rat(e.unwrap_or_else(|_| Poly::zero()), dens[(i + j) % n]);
                        }
                        b.push(rat(
                            row[n].mul(&ri).unwrap_or_else(|_| Poly::zero()),
                            dens[i],
                        ));
                    }
                    match zero {
                        Some((k, true)) => a[k].iter_mut().for_each(|e| *e = Rat::zero()),
                        Some((k, false)) => a.iter_mut().for_each(|r| r[k] = Rat::zero()),
                        None => {}
                    }
                    (a, b)
                })
        })
    }

    /// Cramer's rule on the system as given, with none of the solver's shortcuts (no
    /// contents taken out, no reordering, no packing): each row times the product of
    /// its denominators, the general Bareiss determinants, one `Rat::new` per unknown.
    fn plain_cramer(a: &[Vec<Rat>], b: &[Rat]) -> Result<Vec<Rat>, LinearError> {
        let n = a.len();
        let mut m = Vec::with_capacity(n);
        for (row, rhs) in a.iter().zip(b) {
            let all: Vec<&Rat> = row.iter().chain(std::iter::once(rhs)).collect();
            let mut den = Poly::one();
            for e in &all {
                den = den.mul(e.den())?;
            }
            let mut out = Vec::with_capacity(n + 1);
            for e in &all {
                let q = div_exact(&den, e.den())?.ok_or(Limit::terms())?;
                out.push(e.num().mul(&q)?);
            }
            m.push(out);
        }
        let det = determinant(columns(&m, n, None))?;
        if det.is_zero() {
            return Err(LinearError::Singular);
        }
        (0..n)
            .map(|i| {
                Ok(Rat::new(
                    determinant(columns(&m, n, Some(i)))?,
                    det.clone(),
                )?)
            })
            .collect()
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]

        /// The solver (contents taken out of rows and columns, columns perhaps
        /// reversed, packed elimination, denominators shifted by the column factors)
        /// gives the canonical forms plain Cramer's rule gives, and calls the same
        /// systems singular.
        #[test]
        fn solver_agrees_with_plain_cramer((a, b) in any_scaled_system()) {
            let want = plain_cramer(&a, &b);
            let got = solve(&a, &b);
            match (&want, &got) {
                (Err(LinearError::Singular), Err(LinearError::Singular)) => {}
                (Ok(w), Ok(g)) => prop_assert_eq!(w, g),
                _ => return Err(TestCaseError::fail(format!("{want:?} vs {got:?}"))),
            }
        }
    }

    /// The chain of rods' shape (the first column the heaviest) is eliminated from
    /// its last column; a band, whose weights are symmetric, is left as it is.
    #[test]
    fn heavy_first_columns_are_eliminated_last() {
        let x = |i: u32| poly(&[(vec![(i, 1)], 1)]);
        let sum = |k: u32| poly(&(k..4).map(|i| (vec![(i, 1)], 1)).collect::<Vec<_>>());
        let chain: Vec<Vec<Poly>> = (0..3u32)
            .map(|i| (0..3u32).map(|j| sum(i.max(j))).chain([x(3)]).collect())
            .collect();
        assert!(eliminate_reversed(&chain, 3));
        let band: Vec<Vec<Poly>> = (0..3usize)
            .map(|i| {
                (0..3usize)
                    .map(|j| {
                        if i.abs_diff(j) <= 1 {
                            sum(1)
                        } else {
                            Poly::zero()
                        }
                    })
                    .chain([x(0)])
                    .collect()
            })
            .collect();
        assert!(!eliminate_reversed(&band, 3));
    }

    /// Coefficients beyond `i128` leave the packed path (the general one answers).
    #[test]
    fn huge_coefficients_fall_back() {
        let big = Poly::constant(Q::from_integer(BigInt::from(i128::MAX) * 4));
        let x = Poly::atom(var(0));
        let m = vec![
            vec![big.clone(), x.clone(), Poly::one()],
            vec![x, big, Poly::one()],
        ];
        assert!(packed_determinants(&m, 2).is_none());
        let (det, nums) = general(&m).unwrap_or_else(|e| panic!("{e}"));
        assert!(!det.is_zero());
        assert_eq!(nums.len(), 2);
    }
}
