//! Time budgets with a clock that is passed in: the library reads no clock of its own,
//! so it runs where there is none (`wasm32-unknown-unknown`, where
//! `std::time::Instant::now` panics). The command line passes [`system`].

use std::time::Duration;

/// A monotonic clock: the time elapsed since some fixed origin.
pub type Clock = fn() -> Duration;

/// The operating system's monotonic clock, where there is one.
pub fn system() -> Option<Clock> {
    #[cfg(not(target_family = "wasm"))]
    {
        Some(since_start)
    }
    #[cfg(target_family = "wasm")]
    {
        None
    }
}

#[cfg(not(target_family = "wasm"))]
fn since_start() -> Duration {
    use std::sync::OnceLock;
    use std::time::Instant;
    static START: OnceLock<Instant> = OnceLock::new();
    START.get_or_init(Instant::now).elapsed()
}

/// A point in time on a clock, after which work stops.
#[derive(Clone, Copy, Debug)]
pub struct Deadline {
    at: Duration,
    clock: Clock,
}

impl Deadline {
    /// `budget` from now on `clock`, or no deadline without a clock.
    pub fn after(budget: Duration, clock: Option<Clock>) -> Option<Deadline> {
        let clock = clock?;
        Some(Deadline {
            at: clock().saturating_add(budget),
            clock,
        })
    }

    /// Whether the deadline has passed.
    pub fn passed(&self) -> bool {
        (self.clock)() > self.at
    }

    /// The time left before the deadline (zero once it has passed).
    pub fn remaining(&self) -> Duration {
        self.at.saturating_sub((self.clock)())
    }
}
