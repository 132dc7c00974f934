//! Text to syntax tree: nom parsers for expressions (FORMAT.md §1) and derivation files (§2).

pub mod ast;
