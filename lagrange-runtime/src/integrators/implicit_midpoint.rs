//! The implicit midpoint rule: the one-stage Gauss method.

use nalgebra::{DMatrix, DVector, RealField};

use super::StepMethod;
use super::implicit_rk::{self, Settings, StageSolver, Tableau};
use crate::driver::fixed::FixedWalk;
use crate::error::InvalidInput;

/// The implicit midpoint rule with a fixed step `h`:
/// `y_{n+1} = y_n + h F(t_n + h/2, (y_n + y_{n+1}) / 2)`.
///
/// Order 2, symmetric, A-stable, and conserving every quadratic invariant of
/// `(q, q̇)`: the simplest method whose energy does not drift on long runs
/// (what "symplectic" does and does not mean here is in the
/// [crate documentation](crate#implicit-methods-symmetric-and-when-symplectic)).
/// It is the one-stage [`GaussLegendre`](super::GaussLegendre) method and
/// shares its solver: each step solves for the stage increment
/// `Z = (y_{n+1} − y_n) / 2` by simplified Newton, with the Jacobian of `q̈`
/// at the step start (exact when the model provides
/// [`residual_jacobians`](crate::model::Lagrangian::residual_jacobians), forward
/// differences otherwise), one LU factorization per step, and a starting
/// guess extrapolated from the previous step. Iterations stop when the
/// correction is below `10 ε` of the state's size; a step whose iteration
/// diverges, or has not converged after
/// [`max_iterations`](Self::max_iterations), is
/// [`NewtonDivergence`](crate::error::IntegrationError::NewtonDivergence).
///
/// ```
/// use lagrange_runtime::ImplicitMidpoint;
///
/// let midpoint = ImplicitMidpoint::new(1e-2).max_iterations(10);
/// # let _: ImplicitMidpoint<f64> = midpoint;
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImplicitMidpoint<S> {
    settings: Settings<S>,
}

impl<S: RealField + Copy> ImplicitMidpoint<S> {
    /// The midpoint rule with step `h`, a budget of 10 000 000 steps and 20
    /// Newton iterations per step.
    ///
    /// `h` is checked when integrating: it must be positive and finite.
    pub fn new(h: S) -> Self {
        Self {
            settings: Settings::new(h),
        }
    }

    /// The step budget; exceeding it is
    /// [`TooManySteps`](crate::error::IntegrationError::TooManySteps): at once,
    /// before any step, when the interval to the next sample alone needs
    /// more steps of `h` (the step is never lengthened to fit).
    pub fn max_steps(mut self, max_steps: usize) -> Self {
        self.settings.max_steps = max_steps;
        self
    }

    /// Newton iterations allowed per step before
    /// [`NewtonDivergence`](crate::error::IntegrationError::NewtonDivergence); at
    /// least 1, zero being
    /// [`NoNewtonIterations`](crate::error::InvalidInput::NoNewtonIterations).
    pub fn max_iterations(mut self, max_iterations: usize) -> Self {
        self.settings.max_iterations = max_iterations;
        self
    }

    /// The step size.
    pub fn step_size(&self) -> S {
        self.settings.h
    }

    /// `a = ½`, `b = 1`, `c = ½`, hence `d = bᵀ A⁻¹ = 2`.
    pub(crate) fn tableau(&self) -> Tableau<S> {
        let half: S = nalgebra::convert(0.5);
        Tableau {
            a: DMatrix::from_element(1, 1, half),
            b: DVector::from_element(1, S::one()),
            c: DVector::from_element(1, half),
            d: DVector::from_element(1, S::one() + S::one()),
        }
    }
}

impl<S: RealField + Copy> StepMethod<S> for ImplicitMidpoint<S> {
    type Walker<const N: usize> = FixedWalk<S, StageSolver<S, N>>;

    fn walker<const N: usize>(&self) -> Result<Self::Walker<N>, InvalidInput<S>> {
        implicit_rk::walker("ImplicitMidpoint", self.tableau(), self.settings)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrators::implicit_rk::tests::assert_collocation_conditions;

    #[test]
    fn midpoint_tableau_is_one_stage_gauss() {
        assert_collocation_conditions(&ImplicitMidpoint::new(0.1).tableau());
    }
}
