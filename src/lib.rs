//! rigor: an exact derivation and proof checker for engineering-dynamics course material.
//!
//! The pipeline, in reading order:
//!
//! text → [`syntax`] (nom parsers, spans) → [`lower`] → [`normal`] (exact normal form,
//! no spans) with [`calculus`] → [`decide`] (equal / not equal / undecided) →
//! [`check`] (verdicts and diagnostics as data) → [`render`] (terminal, JSON, LaTeX, Markdown).
//!
//! ```
//! use rigor::{decide::{decide, Verdict}, normal::Assumptions, syntax};
//! let opts = syntax::ParseOptions::default();
//! let a = syntax::parse_expr("m L^2/12 + m (L/2)^2", &opts).unwrap();
//! let b = syntax::parse_expr("m L^2/3", &opts).unwrap();
//! let env = rigor::lower::Env::default();
//! let (a, b) = (rigor::lower::lower(&a, &env).unwrap(), rigor::lower::lower(&b, &env).unwrap());
//! assert!(matches!(decide(&a, &b, &Assumptions::new()), Verdict::Equal));
//! ```
#![warn(missing_docs)]

pub mod calculus;
pub mod check;
pub mod clock;
pub mod decide;
pub mod diag;
pub mod files;
pub mod guard;
pub mod interval;
pub mod lint;
pub mod lower;
#[cfg(not(target_arch = "wasm32"))]
pub mod lsp;
pub mod mark;
pub mod normal;
pub mod render;
pub mod solve;
pub mod syntax;
pub mod units;

pub use check::{check_source, FileReport, MemoryResolver, Options, Resolver};
