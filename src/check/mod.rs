//! The checker: walks a derivation in order, keeps declarations and facts, and checks
//! every link of every claim (FORMAT.md §3). It never fails: every outcome, errors
//! included, is recorded in a [`FileReport`]. One entry, [`check_source`], pure: imports
//! come through a [`Resolver`].
//!
//! | file | owns |
//! |---|---|
//! | `entry.rs` | [`check_source`], [`Options`] (with the engine's limits), [`Resolver`] and [`ImportError`], imports' cycles and cache |
//! | `walk.rs` | the walk over a file: statements, scope, bodies, givens, constraints |
//! | `claims.rs` | claims: `where`, each link in turn, the facts a claim adds |
//! | `imports.rs` | `use … with …`: imported claims instantiated, with their conditions |
//! | `step.rs` | deciding one link: identity, elimination with the facts, the verdict |
//! | `conditions.rs` | side conditions of a link: assumed, settled, or failing it |
//! | `explain.rs` | a link that fails: refutation (only where the facts allow), or why not |
//! | `confirm.rs` | the guard: both sides as written, evaluated independently at points |
//! | `dims.rs` | units: the `units` statement and the dimensions of every relation |
//! | `coefficients.rs` | `by [..] comparing coefficients of theta`: linear equations in a motion |
//! | `terms.rs` | the one term, as written, whose sign, factor or power explains a failure |
//! | `relations.rs` | `!=`, `<`, `<=`, `>`, `>=` and `~=` links |
//! | `signs.rs` | signs of differences and divisors, values against declared signs |
//! | `elimination.rs` | elimination of unknowns, contradictions, zero divisors |
//! | `scope.rs`, `report.rs` | declarations; the results as data |

mod claims;
mod coefficients;
mod conditions;
mod confirm;
mod dims;
pub mod elimination;
mod entry;
mod explain;
mod imports;
mod parameters;
mod reading;
mod relations;
pub mod report;
mod roots;
pub mod scope;
mod signs;
mod step;
mod terms;
mod walk;
mod witness;
mod zeros;

pub(crate) use entry::normalise;
pub use entry::{check_source, Exports, ImportError, MemoryResolver, Options, Resolver, Source};
pub use report::{ClaimReport, FileReport, Justification, LinkReport, Status};
pub use signs::interval;
