//! Bodies: concrete mass distributions integrated exactly, and abstract bodies whose
//! integrals expand into moments `∫ xⁱ yʲ dm`.

use super::integrate::{definite, IntError};
use crate::normal::atom::{self, Atom, AtomId};
use crate::normal::subst::atom_depends_on;
use crate::normal::{Assumptions, Poly, Rat};

/// A body declared with `body`.
#[derive(Clone, Debug)]
pub enum Body {
    /// `dm = ρ dx dy …` over a region, coordinates outermost first.
    Concrete {
        /// The density ρ (the mass element without its differentials).
        density: Rat,
        /// `(coordinate, from, to)`, outermost first.
        ranges: Vec<(AtomId, Rat, Rat)>,
    },
    /// `mass m, coordinates x y, centred`.
    Abstract {
        /// The body's name (it names its moments).
        name: String,
        /// The total mass.
        mass: Rat,
        /// The coordinates, in order.
        coords: Vec<(String, AtomId)>,
        /// Whether the first moments vanish.
        centred: bool,
    },
}

impl Body {
    /// The coordinates of the body.
    pub fn coords(&self) -> Vec<AtomId> {
        match self {
            Body::Concrete { ranges, .. } => ranges.iter().map(|r| r.0).collect(),
            Body::Abstract { coords, .. } => coords.iter().map(|c| c.1).collect(),
        }
    }

    /// `∫ f dm` over the body.
    pub fn integrate(&self, f: &Rat, s: &Assumptions) -> Result<Rat, IntError> {
        match self {
            Body::Concrete { density, ranges } => {
                let mut g = f.mul(density)?;
                for (v, lo, hi) in ranges.iter().rev() {
                    g = definite(&g, *v, lo, hi, s)?;
                }
                Ok(g)
            }
            Body::Abstract {
                name,
                mass,
                coords,
                centred,
            } => {
                let ids: Vec<AtomId> = coords.iter().map(|c| c.1).collect();
                let not_poly = || {
                    IntError::Unsupported(format!(
                        "over the abstract body {name}, the integrand must be a polynomial in its coordinates"
                    ))
                };
                if ids.iter().any(|c| f.den().contains(*c)) {
                    return Err(not_poly());
                }
                let den = Rat::poly(f.den().clone())?;
                let mut total = Rat::zero();
                for (m, q) in f.num().terms() {
                    let mut exps = vec![0u32; ids.len()];
                    let mut rest = Vec::new();
                    for &(a, e) in m.pairs() {
                        if let Some(i) = ids.iter().position(|c| *c == a) {
                            if let Some(slot) = exps.get_mut(i) {
                                *slot = e;
                            }
                        } else if ids.iter().any(|c| atom_depends_on(a, *c)) {
                            return Err(not_poly());
                        } else {
                            rest.push((a, e));
                        }
                    }
                    let coeff = crate::normal::mono::Mono::from_pairs(rest)
                        .ok_or(crate::normal::Limit::Exponent)?;
                    let coeff = Rat::poly(Poly::term(coeff, q.clone()))?;
                    let total_deg: u32 = exps.iter().sum();
                    let moment = if total_deg == 0 {
                        mass.clone()
                    } else if *centred && total_deg == 1 {
                        Rat::zero()
                    } else {
                        let named = coords
                            .iter()
                            .zip(exps.iter())
                            .map(|(c, e)| (c.0.clone(), *e))
                            .collect();
                        Rat::atom(atom::intern(Atom::Moment(name.clone(), named)))
                    };
                    total = total.add(&coeff.mul(&moment)?)?;
                }
                Ok(total.div(&den)?)
            }
        }
    }
}
