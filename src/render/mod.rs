//! Renderers of checker results: terminal text, JSON, GitHub annotations, and
//! worked solutions in LaTeX and Markdown, and the browser playground's answers (`web`).
//!
//! Everything here reads a [`FileReport`](crate::check::report::FileReport) and
//! the syntax tree it holds; nothing here decides truth. Expressions are printed
//! as written (never simplified) by [`expr`], which the two document renderers
//! share.

pub mod expr;
pub mod github;
pub mod human;
pub mod json;
pub mod latex;
pub mod lint;
pub mod mark;
pub mod markdown;
mod solution;
mod text;
pub mod web;

#[cfg(test)]
mod tests;
