//! Checker fixtures.
