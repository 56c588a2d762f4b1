//! Radau IIA of order 5: adaptive, implicit, L-stable, for stiff models.
//!
//! Follows Hairer's RADAU5 (Hairer & Wanner, *Solving Ordinary Differential
//! Equations II*, §IV.8, and the Fortran code `radau5.f`): simplified Newton
//! on the stage system transformed by the eigenvectors of `A⁻¹` (one real and
//! one complex linear system per iteration instead of one three times the
//! size), the embedded error estimate with its refinement on a first or
//! rejected step, Gustafsson's predictive step-size controller, Jacobian and
//! LU reuse, and the collocation polynomial as dense output.
//!
//! One change of form, not of method: the linear systems use the
//! second-order structure of `y = (q, q̇)`, as RADAU5 does with its option
//! `M1 = M2 = N`. With `J = [[0, I], [∂q̈/∂q, ∂q̈/∂q̇]]`, the first block row
//! of `(γ I − J) x = b` gives `x_q` from `x_q̇`, so each system is `N × N`:
//! an eighth of the factorization work of the `2N × 2N` one.
//!
//! The files follow RADAU5's subroutines: `walk.rs` the step loop
//! (`RADCOR`, resumable), `work.rs` the workspace, `newton.rs` the Jacobians, factorizations and the
//! Newton iteration, `estimate.rs` the error estimate (`ESTRAD`),
//! `dense.rs` acceptance and the collocation polynomial (`CONTR5`),
//! `coefficients.rs` the method's constants.

use nalgebra::RealField;

use super::StepMethod;
use crate::driver::{check_tolerances, default_tolerance};
use crate::error::InvalidInput;
use walk::Radau5Walk;

mod coefficients;
mod dense;
mod estimate;
mod newton;
mod walk;
mod work;

/// Radau IIA of order 5 with adaptive steps (three stages, L-stable,
/// stiffly accurate): the method for stiff models, where a hard spring or a
/// strong damper would hold an explicit method to steps far below the time
/// scale of the motion of interest.
///
/// Each step solves the implicit stage equations by simplified Newton with
/// the Jacobians of
/// [`acceleration_jacobians`](crate::dynamics::acceleration_jacobians):
/// exact when the model provides [`Lagrangian::residual_jacobians`](crate::Lagrangian::residual_jacobians), forward
/// differences (`2N` extra right-hand sides) otherwise. The costs, all counted in
/// [`Stats`](crate::trajectory::Stats):
///
/// - per Newton iteration: three right-hand sides and one solve of the
///   transformed system (a real and a complex `N × N` triangular solve);
/// - per accepted step: one right-hand side at the new state, one solve for
///   the error estimate (two, and one more right-hand side, when a first or
///   retried step fails the plain estimate);
/// - per new step size: one real and one complex `N × N` LU, `O(N³)`;
/// - per Jacobian: one evaluation, kept across steps while Newton contracts
///   fast (rate below 0.001). When the step size would change by less than
///   20 %, the step size and the LU factors are kept too.
///
/// All vectors and matrices (`O(N²)`) are allocated once per call to
/// [`integrate`](crate::Integrator::integrate); steps allocate nothing.
///
/// **Tolerances** are the user's, as for [`Dopri5`](crate::integrators::Dopri5). The
/// error estimate is of order three while the solution is of order five, so
/// RADAU5 controls the local error against `rtol' = 0.1 rtol^(2/3)` (and
/// `atol' = atol rtol'/rtol`), and so do we: the global error then grows
/// like `rtol^(5/6)`, about `rtol` at `1e-4` and `10 rtol` at `1e-10` on a
/// harmonic oscillator over five periods.
///
/// **Sample times** never shorten a step: between steps the state comes
/// from the collocation polynomial, so dense sampling changes neither the
/// steps nor the final state. That polynomial has order three only: its
/// error is of the size of the local error, `rtol'`, above `rtol` at tight
/// tolerances (≈ 100 `rtol` observed at `1e-10`).
///
/// **Stiff components** are damped, not resolved: a vibration much faster
/// than the steps decays in a few steps (L-stability). That is the point
/// for a hard spring whose vibration does not matter; when it does, tighten
/// the tolerance until the steps resolve it, or use `Dopri5`.
///
/// **Failures**: a stage where the model cannot be evaluated, a Newton
/// iteration that diverges or converges too slowly, or a singular iteration
/// matrix reject the step and retry with a smaller one; if `h` underflows
/// the error reported is the last model failure, else
/// [`StepSizeUnderflow`](crate::error::IntegrationError::StepSizeUnderflow). The
/// derivative and the Jacobians at an accepted state are needed to go on,
/// so a model failure there is reported at once.
///
/// ```
/// use lagrange_runtime::prelude::*;
/// use lagrange_runtime::nalgebra::{SMatrix, SVector, Vector1};
///
/// /// A unit mass on a unit spring in honey: `ẍ = −x − c ẋ`.
/// struct Honey { c: f64 }
/// # impl Lagrangian<1> for Honey {
/// #     type Scalar = f64;
/// #     const COORDINATES: [&'static str; 1] = ["x"];
/// #     fn mass_matrix(&self, _t: f64, _q: &SVector<f64, 1>) -> SMatrix<f64, 1, 1> {
/// #         SMatrix::<f64, 1, 1>::new(1.0)
/// #     }
/// #     fn forcing(&self, _t: f64, q: &SVector<f64, 1>, qd: &SVector<f64, 1>) -> SVector<f64, 1> {
/// #         Vector1::new(-q[0] - self.c * qd[0])
/// #     }
/// #     fn kinetic_energy(&self, _t: f64, _q: &SVector<f64, 1>, qd: &SVector<f64, 1>) -> f64 {
/// #         0.5 * qd[0] * qd[0]
/// #     }
/// #     fn potential_energy(&self, _t: f64, q: &SVector<f64, 1>) -> f64 {
/// #         0.5 * q[0] * q[0]
/// #     }
/// # }
///
/// // With c = 1000 the mass creeps back as e^(−t/c), but the velocity
/// // relaxes as e^(−c t): explicit methods need h < 3/c for stability.
/// let honey = Honey { c: 1000.0 };
/// let (x0, v0) = (Vector1::new(1.0), Vector1::new(0.0));
/// let radau = Radau5::new().rtol(1e-6).atol(1e-9);
/// let slow = radau.integrate(&honey, 0.0, x0, v0, &[10.0])?;
/// let fast = Dopri5::new().rtol(1e-6).atol(1e-9).integrate(&honey, 0.0, x0, v0, &[10.0])?;
/// assert!(100 * slow.stats().rhs_evals < fast.stats().rhs_evals);
///
/// // Both agree with the creep (x = e^(−t/c) up to O(1/c²) terms).
/// let creep = (-10.0f64 / 1000.0).exp();
/// assert!((slow.last().unwrap().q[0] - creep).abs() < 1e-5);
/// assert!((fast.last().unwrap().q[0] - creep).abs() < 1e-5);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Radau5<S> {
    rtol: S,
    atol: S,
    max_steps: usize,
}

impl<S: RealField + Copy> Radau5<S> {
    /// Defaults as for [`Dopri5`](crate::integrators::Dopri5): `rtol = atol = 1e-8`,
    /// raised to `100 ε` for scalar types with fewer digits, and RADAU5's
    /// budget of 100 000 steps.
    pub fn new() -> Self {
        let tol = default_tolerance::<S>();
        Self {
            rtol: tol,
            atol: tol,
            max_steps: 100_000,
        }
    }

    /// Relative tolerance; must be at least `10 ε`, and has no upper bound:
    /// a loose one is honoured as asked (see [`Radau5`] for the tolerance
    /// the local error is then held to).
    pub fn rtol(mut self, rtol: S) -> Self {
        self.rtol = rtol;
        self
    }

    /// Absolute tolerance, the error scale for components near zero; must be
    /// positive.
    pub fn atol(mut self, atol: S) -> Self {
        self.atol = atol;
        self
    }

    /// The step budget, counting every attempt (rejected ones too), so that
    /// every call ends.
    pub fn max_steps(mut self, max_steps: usize) -> Self {
        self.max_steps = max_steps;
        self
    }
}

impl<S: RealField + Copy> Default for Radau5<S> {
    fn default() -> Self {
        Self::new()
    }
}

/// RADAU5's controller and Newton constants.
const SAFETY: f64 = 0.9;
/// `h_new / h ≥ 1 / FAC_L`.
const FAC_L: f64 = 5.0;
/// `h_new / h ≤ 1 / FAC_R`.
const FAC_R: f64 = 0.125;
/// Newton contraction rate below which the Jacobian is kept.
const THETA_REUSE: f64 = 0.001;
/// Keep `h` (and the LU factors) when `h_new / h` falls in this range.
const KEEP_H: (f64, f64) = (1.0, 1.2);
/// Newton iterations per step before the step is retried smaller.
const MAX_NEWTON: usize = 7;
/// Smallest error norm: keeps the Gustafsson ratio finite.
const ERR_FLOOR: f64 = 1e-10;

impl<S: RealField + Copy> StepMethod<S> for Radau5<S> {
    type Walker<const N: usize> = Radau5Walk<S, N>;

    /// The workspace, `O(N²)`, allocated once per run or stepper.
    fn walker<const N: usize>(&self) -> Result<Self::Walker<N>, InvalidInput<S>> {
        check_tolerances(self.rtol, self.atol)?;
        Ok(Radau5Walk::new(self))
    }
}
