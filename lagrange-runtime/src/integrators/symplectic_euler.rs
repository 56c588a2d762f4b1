//! Semi-implicit (symplectic) Euler with a fixed step.

use nalgebra::{RealField, SVector};

use super::{StepMethod, lane_step};
use crate::driver::fixed::{FixedStep, FixedWalk};
use crate::driver::{Recorder, check_step_size};
use crate::error::{IntegrationError, InvalidInput};
use crate::model::Lagrangian;
use crate::trajectory::State;

/// Semi-implicit Euler with a fixed step `h`: the velocity first, then the
/// position with the *new* velocity,
///
/// ```text
/// q̇ₙ₊₁ = q̇ₙ + h q̈(tₙ, qₙ, q̇ₙ)
/// qₙ₊₁ = qₙ + h q̇ₙ₊₁
/// ```
///
/// One right-hand side per step, global error `O(h)`, explicit: the
/// "implicit" in the name only refers to using `q̇ₙ₊₁` in the position
/// update.
///
/// **Symplectic only for separable Hamiltonians**: a constant mass matrix
/// and forces that do not depend on `q̇`. Then the map is symplectic, and
/// the energy error stays bounded, `O(h)`, over arbitrarily many steps
/// instead of drifting: an oscillator keeps its amplitude where
/// [`ExplicitEuler`](crate::integrators::ExplicitEuler) spirals outwards. With a
/// configuration-dependent `M(q)` (a double pendulum) or velocity-dependent
/// forces (damping, gyroscopic terms) that guarantee is gone and it is merely
/// a cheap first-order method. Games and real-time simulations use it for
/// its stability on stiff-ish oscillators at one evaluation per step; for
/// accuracy, use [`Rk4`](crate::integrators::Rk4) or an adaptive method.
///
/// Sample times are hit exactly, as with [`Rk4`](crate::integrators::Rk4): each interval
/// between consecutive sample times is cut into the fewest equal steps no
/// longer than `h`.
///
/// ```
/// use lagrange_runtime::SymplecticEuler;
///
/// let game_loop = SymplecticEuler::new(1.0 / 60.0);
/// # let _: SymplecticEuler<f64> = game_loop;
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SymplecticEuler<S> {
    h: S,
    max_steps: usize,
}

impl<S: RealField + Copy> SymplecticEuler<S> {
    /// Symplectic Euler with step `h` and a budget of 10 000 000 steps.
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

impl<S: RealField + Copy> StepMethod<S> for SymplecticEuler<S> {
    type Walker<const N: usize> = FixedWalk<S, SymplecticStep>;

    fn walker<const N: usize>(&self) -> Result<Self::Walker<N>, InvalidInput<S>> {
        check_step_size(self.h)?;
        Ok(FixedWalk::new(SymplecticStep, self.h, self.max_steps))
    }
}

/// [`symplectic_step`] as the fixed-step loop takes it.
#[doc(hidden)]
pub struct SymplecticStep;

impl<S: RealField + Copy, const N: usize> FixedStep<S, N> for SymplecticStep {
    fn step<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        rec: &mut Recorder<'_, S, N>,
        model: &L,
        t: S,
        (q, qdot): (&SVector<S, N>, &SVector<S, N>),
        h: S,
    ) -> Result<State<S, N>, IntegrationError<S, N>> {
        symplectic_step(rec, model, t, q, qdot, h)
    }
}

/// The kick `q̇ ← q̇ + h q̈(t, q, q̇)`, then the drift `q ← q + h q̇`.
pub(crate) fn symplectic_step<L: Lagrangian<N>, const N: usize>(
    rec: &mut Recorder<'_, L::Scalar, N>,
    model: &L,
    t: L::Scalar,
    q: &SVector<L::Scalar, N>,
    qdot: &SVector<L::Scalar, N>,
    h: L::Scalar,
) -> Result<State<L::Scalar, N>, IntegrationError<L::Scalar, N>> {
    symplectic(t, (q, qdot), h, |t, q, qdot| rec.rhs(model, t, q, qdot))
}

// The step on scalars (`V = S`) or SIMD lanes of them.
lane_step!(SymplecticEuler, fn symplectic(t, q, qdot, h, a) {
    let h_v = V::splat(h);
    let qdot_next = qdot + a(t, q, qdot)? * h_v;
    Ok((q + qdot_next * h_v, qdot_next))
});
