//! rigor: an exact derivation and proof checker.

pub mod syntax;
