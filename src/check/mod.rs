//! The checker: walks a derivation file in order, keeps declarations and facts, and
//! checks every link of every claim (FORMAT.md §3). It never fails: every outcome,
//! errors included, is recorded in a [`FileReport`].

mod link;
mod load;
pub mod report;
pub mod scope;
pub mod solve;

pub use load::{check_paths, check_source, Options};
pub use report::{cite, ClaimReport, FileReport, Justification, LinkReport, Status};
