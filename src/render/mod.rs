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
mod pieces;
mod solution;
mod steps;
mod text;
pub mod web;

/// How much work a worked solution shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Detail {
    /// The file's own steps, as written.
    #[default]
    Written,
    /// The file's steps with the work it skipped filled in from the checker's own
    /// computation: integrals evaluated stage by stage, the unknowns a step was verified
    /// with solved and substituted (`rigor latex --steps`).
    Steps,
}

#[cfg(test)]
mod tests;
