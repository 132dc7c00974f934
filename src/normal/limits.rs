//! The limits of the engine's work on the current thread: the size limits ([`Limits`]:
//! terms of a polynomial, digits of a number) and the deadline of the current claim.
//!
//! They are thread-local, installed for a stretch of work by a guard ([`install`],
//! [`until`]) that restores the previous values when dropped, also while unwinding from
//! a panic: `check_source` installs its [`crate::check::Options::limits`] for the whole
//! check and each claim's deadline around the claim, so two checks on two threads with
//! different limits do not see each other's. Work outside any guard runs with
//! [`Limits::DEFAULT`], the command line's defaults.

use super::Limit;
use crate::clock::Deadline;
use std::cell::Cell;
use std::marker::PhantomData;

/// The size limits of the exact engine.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// The largest number of terms any intermediate polynomial may have.
    pub max_terms: usize,
    /// The largest number of decimal digits a number produced by a power may have (kept
    /// in bits, so about this many digits).
    pub max_digits: u64,
}

impl Limits {
    /// The defaults, the same for the library, the browser and the command line.
    pub const DEFAULT: Limits = Limits {
        max_terms: 200_000,
        max_digits: 120_000,
    };

    /// The digit limit in bits (10/3 bits a digit, as the size checks count).
    pub fn max_bits(&self) -> u64 {
        self.max_digits.saturating_mul(10) / 3
    }
}

impl Default for Limits {
    fn default() -> Limits {
        Limits::DEFAULT
    }
}

thread_local! {
    static LIMITS: Cell<Limits> = const { Cell::new(Limits::DEFAULT) };
    static DEADLINE: Cell<Option<Deadline>> = const { Cell::new(None) };
}

/// Restores this thread's previous [`Limits`] when dropped (see [`install`]).
#[must_use = "the limits hold only while the guard lives"]
pub struct LimitsGuard {
    previous: Limits,
    /// The guard restores a thread-local: it stays on its thread.
    _thread: PhantomData<*const ()>,
}

impl Drop for LimitsGuard {
    fn drop(&mut self) {
        LIMITS.with(|c| c.set(self.previous));
    }
}

/// Makes `limits` this thread's limits until the guard is dropped.
pub fn install(limits: Limits) -> LimitsGuard {
    LimitsGuard {
        previous: LIMITS.with(|c| c.replace(limits)),
        _thread: PhantomData,
    }
}

/// This thread's limits.
pub fn current() -> Limits {
    LIMITS.with(Cell::get)
}

/// Restores this thread's previous deadline when dropped (see [`until`]).
#[must_use = "the deadline holds only while the guard lives"]
pub struct DeadlineGuard {
    previous: Option<Deadline>,
    _thread: PhantomData<*const ()>,
}

impl Drop for DeadlineGuard {
    fn drop(&mut self) {
        DEADLINE.with(|c| c.set(self.previous));
    }
}

/// Makes `deadline` (or none) the deadline of the work on this thread until the guard is
/// dropped; long operations check it and fail with [`Limit::Time`].
pub fn until(deadline: Option<Deadline>) -> DeadlineGuard {
    DeadlineGuard {
        previous: DEADLINE.with(|c| c.replace(deadline)),
        _thread: PhantomData,
    }
}

/// Fails with [`Limit::Time`] once this thread's deadline has passed.
pub fn check_deadline() -> Result<(), Limit> {
    match DEADLINE.with(Cell::get) {
        Some(d) if d.passed() => Err(Limit::Time),
        _ => Ok(()),
    }
}

/// This thread's limit on the number of terms.
pub fn max_terms() -> usize {
    current().max_terms
}

/// This thread's limit on the size of a number, in bits.
pub fn max_bits() -> u64 {
    current().max_bits()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_guard_restores_the_previous_limits_also_on_panic() {
        let small = Limits {
            max_terms: 10,
            max_digits: 5,
        };
        {
            let _g = install(small);
            assert_eq!(current(), small);
            {
                let _h = install(Limits::DEFAULT);
                assert_eq!(current(), Limits::DEFAULT);
            }
            assert_eq!(current(), small);
        }
        assert_eq!(current(), Limits::DEFAULT);
        let r = std::panic::catch_unwind(|| {
            let _g = install(small);
            panic!("inside");
        });
        assert!(r.is_err());
        assert_eq!(current(), Limits::DEFAULT);
    }
}
