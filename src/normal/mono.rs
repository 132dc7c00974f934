//! Monomials: products of atoms with positive integer exponents, in a lexicographic monomial order.

use super::atom::AtomId;
use std::cmp::Ordering;

/// A product `a₁^e₁ · a₂^e₂ ⋯`, atoms sorted by id, every exponent ≥ 1.
#[derive(Clone, Debug, PartialEq, Eq, Hash, Default)]
pub struct Mono(Vec<(AtomId, u32)>);

/// Largest exponent rigor represents; beyond it an operation is refused.
pub const MAX_EXPONENT: u64 = u32::MAX as u64;

impl Mono {
    /// The empty product, 1.
    pub fn one() -> Mono {
        Mono(Vec::new())
    }

    /// `a^e` (`e ≥ 1`).
    pub fn atom(a: AtomId, e: u32) -> Mono {
        if e == 0 {
            Mono::one()
        } else {
            Mono(vec![(a, e)])
        }
    }

    /// Builds a monomial from pairs in any order; zero exponents are dropped and repeats merged.
    /// Returns `None` if an exponent overflows.
    pub fn from_pairs(mut pairs: Vec<(AtomId, u32)>) -> Option<Mono> {
        pairs.sort_unstable_by_key(|p| p.0);
        let mut out: Vec<(AtomId, u32)> = Vec::with_capacity(pairs.len());
        for (a, e) in pairs {
            if e == 0 {
                continue;
            }
            match out.last_mut() {
                Some(last) if last.0 == a => last.1 = last.1.checked_add(e)?,
                _ => out.push((a, e)),
            }
        }
        Some(Mono(out))
    }

    /// A monomial from pairs already sorted by atom id, distinct, exponents ≥ 1.
    pub(crate) fn from_sorted_pairs(pairs: Vec<(AtomId, u32)>) -> Mono {
        debug_assert!(pairs.windows(2).all(|w| w[0].0 < w[1].0));
        debug_assert!(pairs.iter().all(|p| p.1 > 0));
        Mono(pairs)
    }

    /// The pairs, sorted by atom id.
    pub fn pairs(&self) -> &[(AtomId, u32)] {
        &self.0
    }

    /// Whether this is 1.
    pub fn is_one(&self) -> bool {
        self.0.is_empty()
    }

    /// Total degree (saturating).
    pub fn degree(&self) -> u64 {
        self.0.iter().map(|p| p.1 as u64).sum()
    }

    /// Exponent of `a`.
    pub fn exp(&self, a: AtomId) -> u32 {
        match self.0.binary_search_by_key(&a, |p| p.0) {
            Ok(i) => self.0.get(i).map_or(0, |p| p.1),
            Err(_) => 0,
        }
    }

    /// The product, `None` on exponent overflow.
    pub fn mul(&self, other: &Mono) -> Option<Mono> {
        let (a, b) = (&self.0, &other.0);
        let mut out = Vec::with_capacity(a.len() + b.len());
        let (mut i, mut j) = (0, 0);
        while i < a.len() && j < b.len() {
            let (x, y) = (a[i], b[j]);
            match x.0.cmp(&y.0) {
                Ordering::Less => {
                    out.push(x);
                    i += 1;
                }
                Ordering::Greater => {
                    out.push(y);
                    j += 1;
                }
                Ordering::Equal => {
                    out.push((x.0, x.1.checked_add(y.1)?));
                    i += 1;
                    j += 1;
                }
            }
        }
        out.extend_from_slice(&a[i..]);
        out.extend_from_slice(&b[j..]);
        Some(Mono(out))
    }

    /// `self^k`, `None` on overflow.
    pub fn pow(&self, k: u32) -> Option<Mono> {
        let mut out = Vec::with_capacity(self.0.len());
        for &(a, e) in &self.0 {
            out.push((a, e.checked_mul(k)?));
        }
        if k == 0 {
            out.clear();
        }
        Some(Mono(out))
    }

    /// `self / other` if `other` divides `self`.
    pub fn div(&self, other: &Mono) -> Option<Mono> {
        let mut out = Vec::with_capacity(self.0.len());
        let mut j = 0;
        let b = &other.0;
        for &(a, e) in &self.0 {
            if let Some(&(bb, be)) = b.get(j) {
                if bb < a {
                    return None;
                }
                if bb == a {
                    j += 1;
                    if be > e {
                        return None;
                    }
                    if be < e {
                        out.push((a, e - be));
                    }
                    continue;
                }
            }
            out.push((a, e));
        }
        if j < b.len() {
            return None;
        }
        Some(Mono(out))
    }

    /// The greatest common divisor of two monomials.
    pub fn gcd(&self, other: &Mono) -> Mono {
        // Both sorted by atom: one merge.
        let (a, b) = (&self.0, &other.0);
        let mut out = Vec::with_capacity(a.len().min(b.len()));
        let (mut i, mut j) = (0, 0);
        while let (Some(&(x, e)), Some(&(y, f))) = (a.get(i), b.get(j)) {
            match x.cmp(&y) {
                Ordering::Less => i += 1,
                Ordering::Greater => j += 1,
                Ordering::Equal => {
                    out.push((x, e.min(f)));
                    i += 1;
                    j += 1;
                }
            }
        }
        Mono(out)
    }

    /// This monomial with atom `a` removed, and the exponent it had.
    pub fn split(&self, a: AtomId) -> (Mono, u32) {
        let mut e = 0;
        let rest = self
            .0
            .iter()
            .filter(|p| {
                if p.0 == a {
                    e = p.1;
                    false
                } else {
                    true
                }
            })
            .copied()
            .collect();
        (Mono(rest), e)
    }

    /// `self · a` and the exponent `a` had in `self`; `None` on exponent overflow.
    pub fn times_atom(&self, a: AtomId) -> Option<(Mono, u32)> {
        let mut out = Vec::with_capacity(self.0.len() + 1);
        let mut had = None;
        for &(b, e) in &self.0 {
            if had.is_none() && b >= a {
                if b == a {
                    out.push((a, e.checked_add(1)?));
                    had = Some(e);
                    continue;
                }
                out.push((a, 1));
                had = Some(0);
            }
            out.push((b, e));
        }
        if had.is_none() {
            out.push((a, 1));
        }
        Some((Mono(out), had.unwrap_or(0)))
    }

    /// [`Mono::times_atom`] in place: `self` becomes `self · a`, and the exponent `a` had
    /// is returned; `None`, with `self` unchanged, on exponent overflow.
    pub(crate) fn mul_by_atom(&mut self, a: AtomId) -> Option<u32> {
        match self.0.binary_search_by_key(&a, |p| p.0) {
            Ok(i) => {
                let e = self.0[i].1;
                self.0[i].1 = e.checked_add(1)?;
                Some(e)
            }
            Err(i) => {
                self.0.insert(i, (a, 1));
                Some(0)
            }
        }
    }

    /// Atom `x` replaced by atom `a`, which does not occur in `self`, in place: the pairs
    /// between the two positions move up or down one place.
    pub(crate) fn rename(&mut self, x: AtomId, a: AtomId) {
        let Ok(i) = self.0.binary_search_by_key(&x, |p| p.0) else {
            return;
        };
        debug_assert!(self.0.binary_search_by_key(&a, |p| p.0).is_err());
        let e = self.0[i].1;
        // The first place whose atom is at least `a`, counted with `x` still at `i`.
        let j = self.0.partition_point(|p| p.0 < a);
        if j > i {
            self.0[i..j].rotate_left(1);
            self.0[j - 1] = (a, e);
        } else {
            self.0[j..=i].rotate_right(1);
            self.0[j] = (a, e);
        }
    }

    /// The highest atom id present.
    pub fn max_atom(&self) -> Option<AtomId> {
        self.0.last().map(|p| p.0)
    }
}

impl Ord for Mono {
    /// Lexicographic order in which atoms with higher ids are more significant.
    /// It is a monomial order: `1` is least and multiplication preserves it.
    fn cmp(&self, other: &Mono) -> Ordering {
        let (a, b) = (&self.0, &other.0);
        let (mut i, mut j) = (a.len(), b.len());
        while i > 0 && j > 0 {
            let (x, y) = (a[i - 1], b[j - 1]);
            match x.0.cmp(&y.0) {
                Ordering::Greater => return Ordering::Greater,
                Ordering::Less => return Ordering::Less,
                Ordering::Equal => match x.1.cmp(&y.1) {
                    Ordering::Equal => {
                        i -= 1;
                        j -= 1;
                    }
                    o => return o,
                },
            }
        }
        i.cmp(&j)
    }
}

impl PartialOrd for Mono {
    fn partial_cmp(&self, other: &Mono) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
