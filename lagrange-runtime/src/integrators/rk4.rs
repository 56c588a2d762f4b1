//! The classic fourth-order Runge–Kutta method with a fixed step.

use nalgebra::{RealField, SVector};

use super::{StepMethod, lane_step};
use crate::driver::fixed::{FixedStep, FixedWalk};
use crate::driver::{Recorder, check_step_size};
use crate::error::{IntegrationError, InvalidInput};
use crate::model::Lagrangian;
use crate::trajectory::State;

/// Classic RK4 with a fixed step `h`: four right-hand sides per step,
/// global error `O(h⁴)`, no error control.
///
/// Sample times are hit exactly, not interpolated: each interval between
/// consecutive sample times is cut into the fewest equal steps no longer than
/// `h`. When the sample spacing is a multiple of `h`, every step is exactly
/// `h`.
///
/// ```
/// use lagrange_runtime::Rk4;
///
/// let rk4 = Rk4::new(1e-3).max_steps(1_000_000);
/// # let _: Rk4<f64> = rk4;
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rk4<S> {
    h: S,
    max_steps: usize,
}

impl<S: RealField + Copy> Rk4<S> {
    /// RK4 with step `h` and a budget of 10 000 000 steps.
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

impl<S: RealField + Copy> StepMethod<S> for Rk4<S> {
    type Walker<const N: usize> = FixedWalk<S, Rk4Step>;

    fn walker<const N: usize>(&self) -> Result<Self::Walker<N>, InvalidInput<S>> {
        check_step_size(self.h)?;
        Ok(FixedWalk::new(Rk4Step, self.h, self.max_steps))
    }
}

/// [`rk4_step`] as the fixed-step loop takes it.
#[doc(hidden)]
pub struct Rk4Step;

impl<S: RealField + Copy, const N: usize> FixedStep<S, N> for Rk4Step {
    fn step<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        rec: &mut Recorder<'_, S, N>,
        model: &L,
        t: S,
        (q, qdot): (&SVector<S, N>, &SVector<S, N>),
        h: S,
    ) -> Result<State<S, N>, IntegrationError<S, N>> {
        rk4_step(rec, model, t, q, qdot, h)
    }
}

/// One RK4 step for `y = (q, q̇)`, `ẏ = (q̇, q̈)`.
pub(crate) fn rk4_step<L: Lagrangian<N>, const N: usize>(
    rec: &mut Recorder<'_, L::Scalar, N>,
    model: &L,
    t: L::Scalar,
    q: &SVector<L::Scalar, N>,
    qdot: &SVector<L::Scalar, N>,
    h: L::Scalar,
) -> Result<State<L::Scalar, N>, IntegrationError<L::Scalar, N>> {
    rk4(t, (q, qdot), h, |t, q, qdot| rec.rhs(model, t, q, qdot))
}

// The step on scalars (`V = S`) or SIMD lanes of them: the coefficients
// computed in `S`, then the same arithmetic on every lane.
lane_step!(Rk4, fn rk4(t, q, qdot, h, a) {
    let two: S = nalgebra::convert(2.0);
    let (half, sixth) = (h / two, h / nalgebra::convert(6.0));
    let lanes = V::splat;
    let (two_v, half_v, h_v, sixth_v) = (lanes(two), lanes(half), lanes(h), lanes(sixth));

    let (v1, a1) = (*qdot, a(t, q, qdot)?);
    let (q2, v2) = (q + v1 * half_v, qdot + a1 * half_v);
    let a2 = a(t + half, &q2, &v2)?;
    let (q3, v3) = (q + v2 * half_v, qdot + a2 * half_v);
    let a3 = a(t + half, &q3, &v3)?;
    let (q4, v4) = (q + v3 * h_v, qdot + a3 * h_v);
    let a4 = a(t + h, &q4, &v4)?;

    let q_next = q + (v1 + (v2 + v3) * two_v + v4) * sixth_v;
    let qdot_next = qdot + (a1 + (a2 + a3) * two_v + a4) * sixth_v;
    Ok((q_next, qdot_next))
});
