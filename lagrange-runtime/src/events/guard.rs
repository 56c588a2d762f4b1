//! The Zeno guard: events that accumulate in finite time.
//!
//! A bouncing ball with restitution `e < 1` bounces infinitely often before
//! `t∞ = t₁ (1 + 2e / (1 − e))`, its gaps shrinking geometrically. No
//! integration gets past `t∞` by locating bounces, and long before it the
//! gaps fall to the rounding of `t`, where the located times, and the
//! velocities reversed at them, are noise. The guard stops such a run once
//! the gaps have become too short to resolve: three in a row shorter than
//! the minimum separation. One short gap alone is no accumulation (two
//! different events may cross close together); three in a row is.

use nalgebra::RealField;

/// How many gaps in a row below the minimum separation make a Zeno run.
pub(crate) const RUN: usize = 3;

/// The time of the last event and how many short gaps led to it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ZenoGuard<S> {
    last: Option<S>,
    short: usize,
}

/// A Zeno run: `gaps` gaps in a row shorter than `min_separation`, the last
/// one `gap`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ZenoRun<S> {
    pub(crate) gaps: usize,
    pub(crate) gap: S,
}

impl<S: RealField + Copy> ZenoGuard<S> {
    pub(crate) fn new() -> Self {
        Self {
            last: None,
            short: 0,
        }
    }

    /// An event at `t`: `Some` when it ends a Zeno run.
    pub(crate) fn check(&mut self, t: S, min_separation: S) -> Option<ZenoRun<S>> {
        let gap = self.last.replace(t).map(|last| t - last)?;
        if gap < min_separation {
            self.short += 1;
        } else {
            self.short = 0;
        }
        (self.short >= RUN).then_some(ZenoRun {
            gaps: self.short,
            gap,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn three_short_gaps_in_a_row_are_a_zeno_run() {
        let mut guard = ZenoGuard::<f64>::new();
        // Gaps 1, 0.1 (short), 1 (resets the run), then 0.1, 0.01, 0.001.
        let times = [0.0, 1.0, 1.1, 2.1, 2.2, 2.21];
        for t in times {
            assert_eq!(guard.check(t, 0.5), None, "at {t}");
        }
        let run = guard.check(2.211, 0.5).unwrap();
        assert_eq!(run.gaps, 3);
        assert!((run.gap - 0.001).abs() < 1e-12);
    }

    #[test]
    fn a_zero_separation_never_fires() {
        let mut guard = ZenoGuard::<f64>::new();
        for _ in 0..10 {
            assert_eq!(guard.check(1.0, 0.0), None);
        }
    }
}
