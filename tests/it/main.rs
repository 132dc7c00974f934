//! rigor's integration tests: one binary, one module per feature.

mod calculus;
mod check;
mod cli;
mod equiv;
mod fuzz;
mod hostile;
mod normal;
mod props;
mod workloads;
