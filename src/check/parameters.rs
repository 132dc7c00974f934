//! Parameters that facts free of unknowns fix (`I_G = m R^2/2`), solved for and
//! substituted before an elimination: used when the first elimination divided by a
//! quantity the facts make zero, and for a refutation's sides and counterexample.

use super::elimination::{apply_steps, finish, setup, Fact, Step};
use crate::normal::atom::{self, AtomId};
use crate::normal::{Assumptions, NormError, Rat};

/// The parameters that facts free of unknowns fix, substituted first in the target and in
/// every other fact: `I_G = m R^2/2` before a law that, solved alone for `x''`, divides
/// by `I_G - m R^2/2`. A fact is solved only for a symbol it holds to the first power
/// with a coefficient the signs make nonzero (no condition), preferring one in `zero`,
/// the divisor an elimination could not use. An elimination of the result's target and
/// facts goes after its steps: [`apply_steps`] replays them in order.
pub fn parameters_substituted(
    target: &Rat,
    facts: &[Fact],
    (is_unknown, zero): (&dyn Fn(AtomId) -> bool, &Rat),
    signs: &Assumptions,
) -> Result<(Vec<Step>, Rat, Vec<Fact>), NormError> {
    let in_zero = zero.atoms();
    let mut steps: Vec<Step> = Vec::new();
    let mut others: Vec<Fact> = Vec::new();
    for f in facts {
        let value = apply_steps(&f.value, &steps, signs)?;
        let atoms = value.atoms();
        let mut candidates: Vec<AtomId> = if atoms.iter().any(|a| is_unknown(*a)) {
            Vec::new()
        } else {
            atoms
                .iter()
                .copied()
                .filter(|a| atom::sym_str(*a).is_some())
                .collect()
        };
        candidates.sort_by(|a, b| {
            (!in_zero.contains(a))
                .cmp(&!in_zero.contains(b))
                .then_with(|| atom::cmp_atoms(*a, *b))
        });
        let mut solved = None;
        for q in candidates {
            match setup(&value, q, signs)? {
                Some(s) if s.deg == 1 && s.divisor.is_none() => {
                    solved = Some((q, finish(&s, signs)?.value));
                    break;
                }
                _ => {}
            }
        }
        match solved {
            Some((q, v)) => steps.push(Step {
                unknown: q,
                value: v,
                fact: f.name.clone(),
                divisor: None,
            }),
            None => others.push(Fact {
                value,
                name: f.name.clone(),
            }),
        }
    }
    // A fact met before a parameter was solved still holds that parameter.
    let others = others
        .into_iter()
        .filter_map(|f| {
            let value = apply_steps(&f.value, &steps, signs).ok()?;
            (!value.is_zero()).then_some(Fact {
                value,
                name: f.name,
            })
        })
        .collect();
    let target = apply_steps(target, &steps, signs)?;
    Ok((steps, target, others))
}
