//! Time integrators, one per file, all behind [`Integrator`].
//!
//! Each integrator advances the first-order system `y = (q, q̇)`,
//! `ẏ = (q̇, q̈)` with `q̈` from [`acceleration`], and records the state at
//! the requested sample times only.
//!
//! Shared rules, so that methods can be swapped without surprises:
//!
//! - Input is validated before the first step: non-finite `t0`, `q0`, `q̇0`
//!   or model parameters, and sample times that are not finite, decrease, or
//!   precede `t0` are [`InvalidInput`].
//! - Integration runs forward from `t0` to the last sample time. Samples
//!   equal to `t0` are the initial state, unchanged.
//! - A failure returns the samples computed so far in [`Failure`].

mod dopri5;
mod lu;
mod radau5;
mod rk4;
mod second_order;

pub use dopri5::Dopri5;
pub use radau5::Radau5;
pub use rk4::Rk4;

use nalgebra::{ComplexField, RealField, SVector};

use crate::solve::acceleration;
use crate::{
    Failure, IntegrationError, IntegrationResult, InvalidInput, Lagrangian, Stats, Trajectory,
};

/// A method that integrates a [`Lagrangian`] model and samples it at
/// requested times.
///
/// `S` is the model's scalar type; the integrator's own settings (step size,
/// tolerances) use it too, so `f32` models get `f32` tolerances.
///
/// ```
/// use lagrange_runtime::prelude::*;
/// use lagrange_runtime::nalgebra::{SMatrix, SVector, Vector1};
///
/// struct FreeFall;
///
/// impl Lagrangian<1> for FreeFall {
///     type Scalar = f64;
///     const COORDINATES: [&'static str; 1] = ["z"];
///     fn mass_matrix(&self, _t: f64, _q: &SVector<f64, 1>) -> SMatrix<f64, 1, 1> {
///         SMatrix::<f64, 1, 1>::new(1.0)
///     }
///     fn forcing(&self, _t: f64, _q: &SVector<f64, 1>, _qd: &SVector<f64, 1>) -> SVector<f64, 1> {
///         Vector1::new(-9.81)
///     }
///     fn kinetic_energy(&self, _t: f64, _q: &SVector<f64, 1>, qd: &SVector<f64, 1>) -> f64 {
///         0.5 * qd[0] * qd[0]
///     }
///     fn potential_energy(&self, _t: f64, q: &SVector<f64, 1>) -> f64 {
///         9.81 * q[0]
///     }
/// }
///
/// /// Any method will do: the caller picks it.
/// fn height_after_one_second(method: &impl Integrator<f64>) -> f64 {
///     let trajectory = method
///         .integrate(&FreeFall, 0.0, Vector1::new(0.0), Vector1::new(0.0), &[1.0])
///         .unwrap();
///     trajectory.last().unwrap().q[0]
/// }
///
/// // z(1) = -g/2; both methods are exact for a quadratic.
/// assert!((height_after_one_second(&Rk4::new(0.1)) + 4.905).abs() < 1e-12);
/// assert!((height_after_one_second(&Dopri5::new()) + 4.905).abs() < 1e-12);
/// ```
pub trait Integrator<S: RealField + Copy> {
    /// Integrates `model` from `(t0, q0, q̇0)` and returns the state at each
    /// of `times` (non-decreasing, none before `t0`).
    fn integrate<L, const N: usize>(
        &self,
        model: &L,
        t0: S,
        q0: SVector<S, N>,
        qdot0: SVector<S, N>,
        times: &[S],
    ) -> IntegrationResult<S, N>
    where
        L: Lagrangian<N, Scalar = S>;
}

/// The one call: integrates `model` with [`Dopri5`] at its default
/// tolerances and returns the state at each of `times`.
///
/// ```
/// use lagrange_runtime::integrate;
/// # use lagrange_runtime::Lagrangian;
/// # use lagrange_runtime::nalgebra::{SMatrix, SVector, Vector1};
/// # struct Spring;
/// # impl Lagrangian<1> for Spring {
/// #     type Scalar = f64;
/// #     const COORDINATES: [&'static str; 1] = ["x"];
/// #     fn mass_matrix(&self, _t: f64, _q: &SVector<f64, 1>) -> SMatrix<f64, 1, 1> {
/// #         SMatrix::<f64, 1, 1>::new(1.0)
/// #     }
/// #     fn forcing(&self, _t: f64, q: &SVector<f64, 1>, _qd: &SVector<f64, 1>) -> SVector<f64, 1> {
/// #         -q
/// #     }
/// #     fn kinetic_energy(&self, _t: f64, _q: &SVector<f64, 1>, qd: &SVector<f64, 1>) -> f64 {
/// #         0.5 * qd[0] * qd[0]
/// #     }
/// #     fn potential_energy(&self, _t: f64, q: &SVector<f64, 1>) -> f64 {
/// #         0.5 * q[0] * q[0]
/// #     }
/// # }
///
/// // A unit spring released from x = 1: x(t) = cos t.
/// let times = [0.5, 1.0, 1.5];
/// let trajectory = integrate(&Spring, 0.0, Vector1::new(1.0), Vector1::new(0.0), &times)?;
/// for sample in &trajectory {
///     assert!((sample.q[0] - sample.t.cos()).abs() < 1e-7);
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn integrate<L: Lagrangian<N>, const N: usize>(
    model: &L,
    t0: L::Scalar,
    q0: SVector<L::Scalar, N>,
    qdot0: SVector<L::Scalar, N>,
    times: &[L::Scalar],
) -> IntegrationResult<L::Scalar, N> {
    Dopri5::new().integrate(model, t0, q0, qdot0, times)
}

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

/// A failure before any work: empty trajectory.
pub(crate) fn invalid<S: RealField + Copy, const N: usize>(
    invalid: InvalidInput<S>,
) -> Box<Failure<S, N>> {
    Failure::boxed(invalid.into(), Trajectory::with_capacity(0))
}

fn validate<L: Lagrangian<N>, const N: usize>(
    model: &L,
    t0: L::Scalar,
    q0: &SVector<L::Scalar, N>,
    qdot0: &SVector<L::Scalar, N>,
    times: &[L::Scalar],
) -> Result<(), InvalidInput<L::Scalar>> {
    if !t0.is_finite() {
        return Err(InvalidInput::NonFiniteStartTime { t0 });
    }
    if !model.parameters_are_finite() {
        return Err(InvalidInput::NonFiniteParameters);
    }
    for (i, coordinate) in L::COORDINATES.into_iter().enumerate() {
        if !q0[i].is_finite() {
            let value = q0[i];
            return Err(InvalidInput::NonFiniteInitialPosition { coordinate, value });
        }
        if !qdot0[i].is_finite() {
            let value = qdot0[i];
            return Err(InvalidInput::NonFiniteInitialVelocity { coordinate, value });
        }
    }
    for (index, &time) in times.iter().enumerate() {
        if !time.is_finite() {
            return Err(InvalidInput::NonFiniteSampleTime { index, time });
        }
        if time < t0 {
            return Err(InvalidInput::SampleBeforeStart { index, time, t0 });
        }
        if let Some(&previous) = index.checked_sub(1).and_then(|i| times.get(i)) {
            if time < previous {
                return Err(InvalidInput::UnsortedSampleTimes {
                    index,
                    previous,
                    time,
                });
            }
        }
    }
    Ok(())
}
