//! The explicit (forward) Euler method with a fixed step.

use nalgebra::{RealField, SVector};

use super::{StepMethod, lane_step};
use crate::driver::fixed::{FixedStep, FixedWalk};
use crate::driver::{Recorder, check_step_size};
use crate::error::{IntegrationError, InvalidInput};
use crate::model::Lagrangian;
use crate::trajectory::State;

/// Explicit Euler with a fixed step `h`: one right-hand side per step,
/// global error `O(h)`, no error control.
///
/// The baseline the other methods are measured against, and rarely the
/// right choice: on an undamped oscillator it multiplies the energy by
/// `1 + h² ω²` every step, so a long run spirals outwards. Use it to check a
/// model cheaply, or as the reference point of a convergence study;
/// [`SymplecticEuler`](crate::integrators::SymplecticEuler) costs the same and does not
/// drift, [`Rk4`](crate::integrators::Rk4) and [`Dopri5`](crate::integrators::Dopri5) are far more
/// accurate per evaluation.
///
/// Sample times are hit exactly, as with [`Rk4`](crate::integrators::Rk4): each interval
/// between consecutive sample times is cut into the fewest equal steps no
/// longer than `h`.
///
/// ```
/// use lagrange_runtime::ExplicitEuler;
///
/// let euler = ExplicitEuler::new(1e-4).max_steps(1_000_000);
/// # let _: ExplicitEuler<f64> = euler;
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExplicitEuler<S> {
    h: S,
    max_steps: usize,
}

impl<S: RealField + Copy> ExplicitEuler<S> {
    /// Explicit Euler with step `h` and a budget of 10 000 000 steps.
    ///
    /// `h` is checked when integrating: it must be positive and finite.
    pub fn new(h: S) -> Self {
        Self {
            h,
            max_steps: 10_000_000,
        }
    }

    /// The step budget; exceeding it is
    /// [`TooManySteps`](IntegrationError::TooManySteps), so a step size that
    /// is far too small fails instead of running for hours: at once, before
    /// any step, when the interval to the next sample alone needs more steps
    /// of `h` (the step is never lengthened to fit).
    pub fn max_steps(mut self, max_steps: usize) -> Self {
        self.max_steps = max_steps;
        self
    }

    /// The step size.
    pub fn step_size(&self) -> S {
        self.h
    }
}

impl<S: RealField + Copy> StepMethod<S> for ExplicitEuler<S> {
    type Walker<const N: usize> = FixedWalk<S, EulerStep>;

    fn walker<const N: usize>(&self) -> Result<Self::Walker<N>, InvalidInput<S>> {
        check_step_size(self.h)?;
        Ok(FixedWalk::new(EulerStep, self.h, self.max_steps))
    }
}

/// [`euler_step`] as the fixed-step loop takes it.
#[doc(hidden)]
pub struct EulerStep;

impl<S: RealField + Copy, const N: usize> FixedStep<S, N> for EulerStep {
    fn step<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        rec: &mut Recorder<'_, S, N>,
        model: &L,
        t: S,
        (q, qdot): (&SVector<S, N>, &SVector<S, N>),
        h: S,
    ) -> Result<State<S, N>, IntegrationError<S, N>> {
        euler_step(rec, model, t, q, qdot, h)
    }
}

/// `q ← q + h q̇`, `q̇ ← q̇ + h q̈`, both from the state at `t`.
pub(crate) fn euler_step<L: Lagrangian<N>, const N: usize>(
    rec: &mut Recorder<'_, L::Scalar, N>,
    model: &L,
    t: L::Scalar,
    q: &SVector<L::Scalar, N>,
    qdot: &SVector<L::Scalar, N>,
    h: L::Scalar,
) -> Result<State<L::Scalar, N>, IntegrationError<L::Scalar, N>> {
    euler(t, (q, qdot), h, |t, q, qdot| rec.rhs(model, t, q, qdot))
}

// The step on scalars (`V = S`) or SIMD lanes of them.
lane_step!(ExplicitEuler, fn euler(t, q, qdot, h, a) {
    let qddot = a(t, q, qdot)?;
    let h = V::splat(h);
    Ok((q + qdot * h, qdot + qddot * h))
});
