//! Sample recording: where a run keeps the samples it has passed and counts
//! its work, so that a success and a [`Failure`] hand back the same
//! trajectory.

use nalgebra::{RealField, SVector};

use super::validate::{invalid, validate};
use crate::solve::acceleration;
use crate::{Failure, IntegrationError, Lagrangian, Stats, Trajectory};

/// Records samples as an integrator passes them and counts its work; owns
/// the trajectory that a success or a [`Failure`] hands back.
pub(crate) struct Recorder<'a, S: RealField + Copy, const N: usize> {
    times: &'a [S],
    next: usize,
    trajectory: Trajectory<S, N>,
    pub(crate) stats: Stats,
}

impl<'a, S: RealField + Copy, const N: usize> Recorder<'a, S, N> {
    /// Validates the call and records the samples at `t0`.
    pub(crate) fn start<L: Lagrangian<N, Scalar = S>>(
        model: &L,
        t0: S,
        q0: &SVector<S, N>,
        qdot0: &SVector<S, N>,
        times: &'a [S],
    ) -> Result<Self, Box<Failure<S, N>>> {
        validate(model, t0, q0, qdot0, times).map_err(invalid)?;
        let mut recorder = Self {
            times,
            next: 0,
            trajectory: Trajectory::with_capacity(times.len()),
            stats: Stats::default(),
        };
        while recorder.pending() == Some(t0) {
            recorder.record(t0, *q0, *qdot0);
        }
        Ok(recorder)
    }

    /// The next sample time not yet recorded.
    pub(crate) fn pending(&self) -> Option<S> {
        self.times.get(self.next).copied()
    }

    /// The last sample time, where integration ends.
    pub(crate) fn end(&self) -> Option<S> {
        self.times.last().copied()
    }

    pub(crate) fn record(&mut self, t: S, q: SVector<S, N>, qdot: SVector<S, N>) {
        self.trajectory.push(t, q, qdot);
        self.next += 1;
    }

    /// One counted right-hand side evaluation.
    pub(crate) fn rhs<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        model: &L,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> Result<SVector<S, N>, IntegrationError<S, N>> {
        self.stats.rhs_evals += 1;
        acceleration(model, t, q, qdot)
    }

    pub(crate) fn finish(mut self) -> Trajectory<S, N> {
        self.trajectory.set_stats(self.stats);
        self.trajectory
    }

    pub(crate) fn fail(self, error: IntegrationError<S, N>) -> Box<Failure<S, N>> {
        Failure::boxed(error, self.finish())
    }
}

/// `(q, q̇)`, as a one-step method returns it.
pub(crate) type State<S, const N: usize> = (SVector<S, N>, SVector<S, N>);
