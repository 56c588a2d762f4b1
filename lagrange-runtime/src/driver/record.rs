//! Sample recording: where a run keeps the samples it has passed and counts
//! its work, so that a success and a [`Failure`] hand back the same
//! trajectory.

use nalgebra::{RealField, SVector};

use crate::trajectory::State;

use super::validate::{invalid, validate};
use crate::dynamics::acceleration;
use crate::dynamics::projection::{DriftControl, ProjectSample};
use crate::dynamics::start::StartOnManifold;
use crate::error::{Failure, IntegrationError, NonFiniteValue};
use crate::events::Watch;
use crate::model::Lagrangian;
use crate::trajectory::{Stats, Trajectory};

/// Records samples as an integrator passes them and counts its work; owns
/// the trajectory that a success or a [`Failure`] hands back.
pub struct Recorder<'a, S: RealField + Copy, const N: usize> {
    times: &'a [S],
    next: usize,
    pub(super) trajectory: Trajectory<S, N>,
    pub(crate) stats: Stats,
    /// The events watched, if any (`driver/events.rs`).
    pub(super) watch: Option<Watch<'a, S, N>>,
    /// Whether the model has constraints, so that a model in minimal
    /// coordinates skips the drift control's call after every step.
    constrained: bool,
}

impl<'a, S: RealField + Copy, const N: usize> Recorder<'a, S, N> {
    /// Validates the call, brings a constrained model's initial state onto
    /// its constraints (or refuses it, as the model's settings say; see
    /// [`constraints`](crate::constraints#initial-conditions)) and records
    /// the samples at `t0`. Integration starts from the state returned:
    /// `(q0, q̇0)` as given for a model in minimal coordinates.
    #[allow(clippy::type_complexity)]
    pub(crate) fn start<L: Lagrangian<N, Scalar = S>>(
        model: &L,
        t0: S,
        q0: &SVector<S, N>,
        qdot0: &SVector<S, N>,
        times: &'a [S],
    ) -> Result<(Self, State<S, N>), Box<Failure<S, N>>> {
        validate(model, t0, q0, qdot0, times).map_err(invalid)?;
        let mut recorder = Self {
            times,
            next: 0,
            trajectory: Trajectory::with_capacity(times.len()),
            stats: Stats::default(),
            watch: None,
            constrained: false,
        };
        let (q0, qdot0) = match model.visit_constraints(StartOnManifold {
            t0,
            q0: *q0,
            qdot0: *qdot0,
            stats: &mut recorder.stats,
        }) {
            None => (*q0, *qdot0),
            Some(Ok(start)) => {
                recorder.constrained = true;
                start
            }
            Some(Err(error)) => return Err(recorder.fail(error)),
        };
        while recorder.pending() == Some(t0) {
            recorder.record(t0, q0, qdot0);
        }
        Ok((recorder, (q0, qdot0)))
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
    pub(crate) fn rhs<E: Evaluate<S, N> + ?Sized>(
        &mut self,
        model: &E,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> Result<SVector<S, N>, IntegrationError<S, N>> {
        self.stats.rhs_evals += 1;
        model.qddot(t, q, qdot)
    }

    /// The end of an accepted step of a constrained model: its residuals
    /// recorded, then the state projected if its drift control says so.
    /// `(q, q̇)` unchanged for a model in minimal coordinates.
    pub(crate) fn control_drift<E: Evaluate<S, N> + ?Sized>(
        &mut self,
        model: &E,
        t: S,
        q: SVector<S, N>,
        qdot: SVector<S, N>,
    ) -> Result<State<S, N>, IntegrationError<S, N>> {
        if !self.constrained {
            return Ok((q, qdot));
        }
        model.drift(&mut self.stats, t, q, qdot)
    }

    /// The residuals of a constrained model's state, recorded without any
    /// drift control (for a method whose equations keep the constraints).
    pub(crate) fn record_residuals<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        model: &L,
        t: S,
        q: SVector<S, N>,
        qdot: SVector<S, N>,
    ) -> Result<(), IntegrationError<S, N>> {
        let stats = &mut self.stats;
        let control = DriftControl {
            t,
            q,
            qdot,
            stats,
            project: false,
        };
        model.visit_constraints(control).unwrap_or(Ok((q, qdot)))?;
        Ok(())
    }

    /// Records a sample from dense output, projected onto the constraints
    /// if the model's drift control projects.
    pub(crate) fn record_dense(
        &mut self,
        model: &dyn Evaluate<S, N>,
        t: S,
        q: SVector<S, N>,
        qdot: SVector<S, N>,
    ) -> Result<(), IntegrationError<S, N>> {
        let (q, qdot) = self.project_sample(model, t, q, qdot)?;
        self.record(t, q, qdot);
        Ok(())
    }

    /// A state from dense output projected onto the constraints as a
    /// sample is ([`record_dense`](Self::record_dense)), not recorded.
    /// A non-finite one (the interpolant overflowed between two finite
    /// states) is an error, never a sample.
    pub(crate) fn project_sample(
        &mut self,
        model: &dyn Evaluate<S, N>,
        t: S,
        q: SVector<S, N>,
        qdot: SVector<S, N>,
    ) -> Result<State<S, N>, IntegrationError<S, N>> {
        if !finite_state(&q, &qdot) {
            return Err(IntegrationError::NonFiniteState {
                t,
                q,
                qdot,
                value: NonFiniteValue::DenseOutput,
            });
        }
        model.project(&mut self.stats, t, q, qdot)
    }

    pub(crate) fn finish(mut self) -> Trajectory<S, N> {
        self.trajectory.set_stats(self.stats);
        self.trajectory
    }

    pub(crate) fn fail(self, error: IntegrationError<S, N>) -> Box<Failure<S, N>> {
        Failure::boxed(error, self.finish())
    }
}

/// Whether every component of `q` and `q̇` is finite.
pub(crate) fn finite_state<S: RealField + Copy, const N: usize>(
    q: &SVector<S, N>,
    qdot: &SVector<S, N>,
) -> bool {
    q.iter().chain(qdot.iter()).all(|x| x.is_finite())
}

/// What the run loops ask of a model (its accelerations, the drift control
/// after a step, the projection of a sample), object-safe: a loop that
/// takes the model as `&dyn Evaluate` is compiled once per scalar and
/// size, not once per model and method. The steps themselves, where the
/// model is evaluated several times a step, keep the model's own type.
pub(crate) trait Evaluate<S: RealField + Copy, const N: usize> {
    /// `q̈` at `(t, q, q̇)` (not counted: [`Recorder::rhs`] counts).
    fn qddot(
        &self,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> Result<SVector<S, N>, IntegrationError<S, N>>;

    /// [`Recorder::control_drift`].
    fn drift(
        &self,
        stats: &mut Stats,
        t: S,
        q: SVector<S, N>,
        qdot: SVector<S, N>,
    ) -> Result<State<S, N>, IntegrationError<S, N>>;

    /// A state from an interpolant brought onto the constraints, as the
    /// model's drift control says (unchanged in minimal coordinates): what
    /// sampling and event location need of a model.
    fn project(
        &self,
        stats: &mut Stats,
        t: S,
        q: SVector<S, N>,
        qdot: SVector<S, N>,
    ) -> Result<State<S, N>, IntegrationError<S, N>>;
}

impl<S: RealField + Copy, L: Lagrangian<N, Scalar = S>, const N: usize> Evaluate<S, N> for L {
    fn qddot(
        &self,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> Result<SVector<S, N>, IntegrationError<S, N>> {
        acceleration(self, t, q, qdot)
    }

    fn drift(
        &self,
        stats: &mut Stats,
        t: S,
        q: SVector<S, N>,
        qdot: SVector<S, N>,
    ) -> Result<State<S, N>, IntegrationError<S, N>> {
        let control = DriftControl {
            t,
            q,
            qdot,
            stats,
            project: true,
        };
        self.visit_constraints(control).unwrap_or(Ok((q, qdot)))
    }

    fn project(
        &self,
        stats: &mut Stats,
        t: S,
        q: SVector<S, N>,
        qdot: SVector<S, N>,
    ) -> Result<State<S, N>, IntegrationError<S, N>> {
        let sample = ProjectSample { t, q, qdot, stats };
        self.visit_constraints(sample).unwrap_or(Ok((q, qdot)))
    }
}
