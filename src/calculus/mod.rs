//! Calculus on normal forms: derivatives, exact integrals, and integrals over bodies.

pub mod body;
pub mod diff;
pub mod integrate;
pub mod time;

pub use body::Body;
pub use diff::{diff, diff_n, Wrt};
pub use integrate::{antiderivative, antiderivative_owned, between_bounds, definite, IntError};
pub use time::{at_instant, time_antiderivative};
