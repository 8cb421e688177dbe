//! `limit time` (SPEC 2.5) counts from the plan's start, set-up included:
//! building a lattice, a C-space, a graph. A plan fixes its [`Deadline`]
//! when it starts and every stage, set-up and search alike, asks the same
//! clock.

use std::time::{Duration, Instant};

use crate::contract::Limits;

/// Set-up loops ask the clock once per this many lattice configurations
/// (or grid cells): a few milliseconds of work at most between two looks.
pub const SETUP_CHECK_EVERY: usize = 1 << 14;

/// When a plan's `limit time` runs out (never, without one).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Deadline {
    at: Option<Instant>,
}

impl Deadline {
    /// The deadline of a plan starting now under `limits`.
    pub fn start(limits: &Limits) -> Self {
        Deadline {
            at: limits
                .time
                .map(|s| Instant::now() + Duration::from_secs_f64(s.clamp(0.0, 1e9))),
        }
    }

    /// No time limit.
    pub fn never() -> Self {
        Deadline { at: None }
    }

    /// Whether the time is up.
    pub fn passed(&self) -> bool {
        self.at.is_some_and(|d| Instant::now() >= d)
    }

    /// The instant it runs out, if any.
    pub fn instant(&self) -> Option<Instant> {
        self.at
    }

    /// `limits` with `time` replaced by the seconds left (at least 0), for
    /// a stage that counts `limit time` from its own start (the search
    /// core).
    pub fn remaining(&self, limits: Limits) -> Limits {
        Limits {
            time: self
                .at
                .map(|d| d.saturating_duration_since(Instant::now()).as_secs_f64()),
            ..limits
        }
    }
}

/// The note of a plan whose time ran out during its set-up.
pub fn setup_note(what: &str) -> String {
    format!(
        "the time limit was reached while {what}, before the search began (`limit time` counts the set-up)"
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_zero_limit_has_passed_and_none_never_does() {
        let zero = Limits {
            time: Some(0.0),
            ..Limits::default()
        };
        let d = Deadline::start(&zero);
        assert!(d.passed());
        assert_eq!(d.remaining(zero).time, Some(0.0));
        let none = Deadline::start(&Limits::default());
        assert!(!none.passed() && !Deadline::never().passed());
        assert_eq!(none.remaining(Limits::default()).time, None);
        let long = Limits {
            time: Some(3600.0),
            ..Limits::default()
        };
        let left = Deadline::start(&long).remaining(long).time.unwrap_or(0.0);
        assert!(left > 3000.0 && left <= 3600.0, "{left}");
    }
}
