//! Text to syntax tree: nom parsers for expressions (FORMAT.md §1) and derivation files (§2).

pub mod ast;
pub mod error;
pub mod expr;
pub mod file;
pub mod latex;
pub mod print;

mod chain;
mod lex;
mod prec;
mod stmt;

#[cfg(test)]
mod tests;

pub use error::{ParseOptions, SyntaxError, SyntaxErrorKind};
pub use expr::{parse_chain, parse_expr};
pub use file::parse_file;
