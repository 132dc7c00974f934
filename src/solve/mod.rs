//! Exact solution of linear systems whose coefficients are normal forms.

pub mod linear;

pub use linear::{solve, LinearError};
