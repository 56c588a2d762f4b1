//! Gauss–Legendre collocation with two or three stages: orders 4 and 6.

use nalgebra::{DMatrix, DVector, RealField};

use super::StepMethod;
use super::implicit_rk::{self, Settings, StageSolver, Tableau};
use crate::driver::fixed::FixedWalk;
use crate::error::InvalidInput;

/// The `s`-stage Gauss–Legendre method with a fixed step `h`: collocation at
/// the Gauss nodes, order `2 s` (the highest of any `s`-stage Runge–Kutta
/// method), symmetric, A-stable, and conserving every quadratic invariant of
/// `(q, q̇)`.
///
/// For long runs where energy must not drift, and for accuracy per step when
/// a step is expensive. Each step solves a nonlinear system of dimension
/// `2 N s` by simplified Newton (see [`ImplicitMidpoint`](super::ImplicitMidpoint),
/// which shares the solver); what "symplectic" does and does not mean here is
/// in the [crate documentation](crate#implicit-methods-symmetric-and-when-symplectic).
///
/// ```
/// use lagrange_runtime::prelude::*;
/// use lagrange_runtime::nalgebra::{SMatrix, SVector, Vector1};
///
/// struct Pendulum;
///
/// impl Lagrangian<1> for Pendulum {
///     type Scalar = f64;
///     const COORDINATES: [&'static str; 1] = ["theta"];
///     fn mass_matrix(&self, _t: f64, _q: &SVector<f64, 1>) -> SMatrix<f64, 1, 1> {
///         SMatrix::<f64, 1, 1>::new(1.0)
///     }
///     fn forcing(&self, _t: f64, q: &SVector<f64, 1>, _qd: &SVector<f64, 1>) -> SVector<f64, 1> {
///         Vector1::new(-q[0].sin())
///     }
///     fn kinetic_energy(&self, _t: f64, _q: &SVector<f64, 1>, qd: &SVector<f64, 1>) -> f64 {
///         0.5 * qd[0] * qd[0]
///     }
///     fn potential_energy(&self, _t: f64, q: &SVector<f64, 1>) -> f64 {
///         -q[0].cos()
///     }
/// }
///
/// // A large swing (2 rad) for 1000 time units, about 120 periods of 8.3,
/// // at 17 steps per period.
/// let (q0, qdot0) = (Vector1::new(2.0), Vector1::new(0.0));
/// let times: Vec<f64> = (1..=1000).map(|i| i as f64).collect();
/// let e0 = Pendulum.energy(0.0, &q0, &qdot0);
/// let energy_error = |trajectory: &Trajectory<f64, 1>| {
///     trajectory
///         .iter()
///         .map(|s| (Pendulum.energy(s.t, &s.q, &s.qdot) - e0).abs())
///         .fold(0.0, f64::max)
/// };
///
/// // Gauss-3 keeps its O(h⁶) energy error (about 2e-6) to the end...
/// let gauss = GaussLegendre::three_stage(0.5).integrate(&Pendulum, 0.0, q0, qdot0, &times)?;
/// assert!(energy_error(&gauss) < 1e-5);
///
/// // ...while RK4's accumulates: it has lost 0.27 of |E| = 0.42 by the end.
/// let rk4 = Rk4::new(0.5).integrate(&Pendulum, 0.0, q0, qdot0, &times)?;
/// assert!(energy_error(&rk4) > 0.1);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GaussLegendre<S> {
    stages: Stages,
    settings: Settings<S>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Stages {
    Two,
    Three,
}

impl<S: RealField + Copy> GaussLegendre<S> {
    /// Two stages, order 4: nodes `½ ∓ √3/6`.
    ///
    /// `h` is checked when integrating: it must be positive and finite.
    pub fn two_stage(h: S) -> Self {
        Self {
            stages: Stages::Two,
            settings: Settings::new(h),
        }
    }

    /// Three stages, order 6: nodes `½ − √15/10`, `½`, `½ + √15/10`.
    ///
    /// `h` is checked when integrating: it must be positive and finite.
    pub fn three_stage(h: S) -> Self {
        Self {
            stages: Stages::Three,
            settings: Settings::new(h),
        }
    }

    /// The step budget (default 10 000 000); exceeding it is
    /// [`TooManySteps`](crate::error::IntegrationError::TooManySteps): at once,
    /// before any step, when the interval to the next sample alone needs
    /// more steps of `h` (the step is never lengthened to fit).
    pub fn max_steps(mut self, max_steps: usize) -> Self {
        self.settings.max_steps = max_steps;
        self
    }

    /// Newton iterations allowed per step (default 20) before
    /// [`NewtonDivergence`](crate::error::IntegrationError::NewtonDivergence); at
    /// least 1, zero being
    /// [`NoNewtonIterations`](crate::error::InvalidInput::NoNewtonIterations). From
    /// the extrapolated starting guess a step at a sensible `h` needs a few.
    pub fn max_iterations(mut self, max_iterations: usize) -> Self {
        self.settings.max_iterations = max_iterations;
        self
    }

    /// The step size.
    pub fn step_size(&self) -> S {
        self.settings.h
    }

    /// The number of stages `s`.
    pub fn stages(&self) -> usize {
        match self.stages {
            Stages::Two => 2,
            Stages::Three => 3,
        }
    }

    /// The order `2 s`.
    pub fn order(&self) -> usize {
        2 * self.stages()
    }

    /// The exact Butcher tableau (Hairer, Nørsett & Wanner, *Solving ODEs I*,
    /// Table II.7.3–II.7.4), square roots taken in `S`, with `dᵀ = bᵀ A⁻¹`
    /// in closed form.
    pub(crate) fn tableau(&self) -> Tableau<S> {
        let r = |x: f64| -> S { nalgebra::convert(x) };
        match self.stages {
            Stages::Two => {
                let s3 = r(3.0).sqrt();
                let (quarter, w) = (r(0.25), s3 / r(6.0));
                Tableau {
                    a: DMatrix::from_row_slice(2, 2, &[quarter, quarter - w, quarter + w, quarter]),
                    b: DVector::from_column_slice(&[r(0.5), r(0.5)]),
                    c: DVector::from_column_slice(&[r(0.5) - w, r(0.5) + w]),
                    d: DVector::from_column_slice(&[-s3, s3]),
                }
            }
            Stages::Three => {
                let s15 = r(15.0).sqrt();
                let (a1, a2) = (r(5.0) / r(36.0), r(2.0) / r(9.0));
                let (w10, w15, w24, w30) =
                    (s15 / r(10.0), s15 / r(15.0), s15 / r(24.0), s15 / r(30.0));
                #[rustfmt::skip]
                let a = DMatrix::from_row_slice(3, 3, &[
                    a1,       a2 - w15, a1 - w30,
                    a1 + w24, a2,       a1 - w24,
                    a1 + w30, a2 + w15, a1,
                ]);
                let (b1, b2) = (r(5.0) / r(18.0), r(4.0) / r(9.0));
                let (d1, d2) = (r(5.0) / r(3.0), r(-4.0) / r(3.0));
                Tableau {
                    a,
                    b: DVector::from_column_slice(&[b1, b2, b1]),
                    c: DVector::from_column_slice(&[r(0.5) - w10, r(0.5), r(0.5) + w10]),
                    d: DVector::from_column_slice(&[d1, d2, d1]),
                }
            }
        }
    }
}

impl<S: RealField + Copy> StepMethod<S> for GaussLegendre<S> {
    type Walker<const N: usize> = FixedWalk<S, StageSolver<S, N>>;

    fn walker<const N: usize>(&self) -> Result<Self::Walker<N>, InvalidInput<S>> {
        implicit_rk::walker("GaussLegendre", self.tableau(), self.settings)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrators::implicit_rk::tests::assert_collocation_conditions;

    #[test]
    fn two_stage_tableau_satisfies_the_order_four_conditions() {
        assert_collocation_conditions(&GaussLegendre::two_stage(0.1).tableau());
    }

    #[test]
    fn three_stage_tableau_satisfies_the_order_six_conditions() {
        assert_collocation_conditions(&GaussLegendre::three_stage(0.1).tableau());
    }
}
