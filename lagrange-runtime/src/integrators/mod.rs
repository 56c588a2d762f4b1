//! Time integrators, one per file or folder, all behind [`Integrator`].
//!
//! Each integrator advances the first-order system `y = (q, q̇)`,
//! `ẏ = (q̇, q̈)` with `q̈` from [`acceleration`](crate::dynamics::acceleration),
//! and records the state at the requested sample times only.
//! [`Variational`] is the exception: it advances `(q, p)` by the discrete
//! Euler–Lagrange equations of the Lagrangian itself, and converts to
//! `(q, q̇)` at the boundaries.
//!
//! Shared rules, so that methods can be swapped without surprises:
//!
//! - Input is validated before the first step: non-finite `t0`, `q0`, `q̇0`
//!   or model parameters, and sample times that are not finite, decrease, or
//!   precede `t0` are [`InvalidInput`](crate::error::InvalidInput).
//! - Integration runs forward from `t0` to the last sample time. Samples
//!   equal to `t0` are the initial state, unchanged.
//! - A failure returns the samples computed so far in
//!   [`Failure`](crate::error::Failure).
//! - What was asked is never changed quietly. A fixed step `h` is never
//!   lengthened: each interval between sample times is cut into the fewest
//!   equal steps no longer than `h` (up to 8 ulps of `t` forgiven to the
//!   rounding of the sample times), and an interval that alone needs more
//!   steps than `max_steps` is
//!   [`TooManySteps`](crate::error::IntegrationError::TooManySteps) before its
//!   first step. Tolerances are used as given: `rtol` below `10 ε`, a
//!   non-positive `atol`, a non-finite or non-positive `h` and
//!   `max_iterations = 0` are [`InvalidInput`](crate::error::InvalidInput), and
//!   loose tolerances are honoured (where one is too loose to keep
//!   [`Dopri5`] or [`Dop853`] within its stability region, they stop with
//!   [`Unstable`](crate::error::IntegrationError::Unstable), as a fixed step beyond
//!   its limit does; [`Radau5`], L-stable, needs no such guard).
//! - A mass matrix that is not positive definite, a kinetic energy negative
//!   for some velocities, is a modelling error:
//!   [`IndefiniteMassMatrix`](crate::error::IntegrationError::IndefiniteMassMatrix)
//!   where it is first met, at the first state for a model indefinite
//!   everywhere.
//!
//! Fixed-step methods supply one step to a shared driver that lands on the
//! sample times and watches for growth; the explicit adaptive ones supply
//! their stages, error estimate and dense output to a shared step loop with
//! the same growth guard; all adaptive methods share Hairer's initial step
//! guess and the tolerance checks. Which method
//! to choose, and what the implicit ones conserve, is in the
//! [crate documentation](crate#choosing-a-method).

mod dop853;
mod dopri5;
mod euler;
mod gauss_legendre;
mod implicit_midpoint;
mod implicit_rk;
mod radau5;
mod rk4;
mod stages;
mod symplectic_euler;
mod variational;

pub use dop853::Dop853;
pub use dopri5::Dopri5;
pub use euler::ExplicitEuler;
pub use gauss_legendre::GaussLegendre;
pub use implicit_midpoint::ImplicitMidpoint;
pub use radau5::Radau5;
pub use rk4::Rk4;
pub use symplectic_euler::SymplecticEuler;
pub use variational::Variational;

// What a `Stepper` drives: the explicit methods' steps and pairs.
pub(crate) use dop853::{Pair as Dop853Pair, CONTROL as DOP853_CONTROL};
pub(crate) use dopri5::{Pair as Dopri5Pair, CONTROL as DOPRI5_CONTROL};
pub(crate) use euler::euler_step;
pub(crate) use implicit_rk::StageSolver;
pub(crate) use rk4::rk4_step;
pub(crate) use symplectic_euler::symplectic_step;

use nalgebra::{RealField, SVector};

use crate::error::IntegrationResult;
use crate::events::Events;
use crate::model::Lagrangian;

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
        L: Lagrangian<N, Scalar = S>,
    {
        self.integrate_with_events(model, t0, q0, qdot0, times, &Events::new())
    }

    /// [`integrate`](Integrator::integrate), watching `events`: each
    /// crossing located, recorded in
    /// [`Trajectory::events`](crate::trajectory::Trajectory::events), and acted on
    /// (stop, or reset and restart; see [`events`](crate::events)). With
    /// no events it is `integrate`, to the bit.
    fn integrate_with_events<L, const N: usize>(
        &self,
        model: &L,
        t0: S,
        q0: SVector<S, N>,
        qdot0: SVector<S, N>,
        times: &[S],
        events: &Events<'_, S, N>,
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
