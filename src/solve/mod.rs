//! Exact solution of linear systems whose coefficients are normal forms.

pub mod linear;
mod packed;
mod quotients;

pub use linear::{solve, LinearError};
