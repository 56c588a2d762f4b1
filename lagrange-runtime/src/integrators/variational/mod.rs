//! The midpoint-rule variational integrator: the discrete Euler–Lagrange
//! equations of the model's own Lagrangian, with forces by the discrete
//! Lagrange–d'Alembert principle.
//!
//! # The discrete equations
//!
//! The action over one step of length `h` is approximated by the midpoint
//! rule, `L_d(q_k, q_{k+1}) = h L(t̄, q̄, v̄)` with `t̄ = t_k + h/2`,
//! `q̄ = (q_k + q_{k+1})/2` and `v̄ = (q_{k+1} − q_k)/h`, so
//!
//! ```text
//! D1 L_d = (h/2) ∂L/∂q − ∂L/∂q̇,    D2 L_d = (h/2) ∂L/∂q + ∂L/∂q̇    (at t̄, q̄, v̄)
//! ```
//!
//! and the forces enter as `f_d⁻ = f_d⁺ = (h/2) Q(t̄, q̄, v̄)`. Stationarity of
//! the discrete action with forces, `D2 L_d(q_{k−1}, q_k) + f_d⁺ + D1 L_d(q_k,
//! q_{k+1}) + f_d⁻ = 0`, written with the discrete momenta `p_k = −D1 L_d −
//! f_d⁻` and `p_{k+1} = D2 L_d + f_d⁺`, is a one-step map `(q_k, p_k) ↦
//! (q_{k+1}, p_{k+1})`:
//!
//! ```text
//! r(v̄) = p_k + (h/2) (∂L/∂q + Q) − ∂L/∂q̇ = 0,        q_{k+1} = q_k + h v̄,
//! p_{k+1} = ∂L/∂q̇ + (h/2) (∂L/∂q + Q) = p_k + h (∂L/∂q + Q).
//! ```
//!
//! Its continuous limit is `ṗ = ∂L/∂q + Q`, the Euler–Lagrange equations with
//! the forces of [`Lagrangian::nonconservative_forces`].

use nalgebra::{RealField, SVector};

use super::StepMethod;
use crate::driver::{Recorder, check_step_size};
use crate::error::{IntegrationError, InvalidInput};
use crate::model::Lagrangian;
use velocity::{VelocityHistory, with_velocity};
use walk::VariationalWalk;

mod augmented;
mod constrained;
mod newton;
mod rattle;
mod velocity;
mod walk;

/// The midpoint-rule variational integrator with a fixed step `h`: second
/// order, symplectic, and it conserves the momentum of every symmetry of the
/// Lagrangian (the discrete Noether theorem).
///
/// It integrates the Lagrangian itself rather than `M q̈ = f`, so it needs the
/// model's [`momentum`](Lagrangian::momentum) `∂L/∂q̇`,
/// [`lagrangian_gradient`](Lagrangian::lagrangian_gradient) `∂L/∂q` and
/// [`nonconservative_forces`](Lagrangian::nonconservative_forces) `Q`; models
/// from `lagrangian!` provide all three, and a model without one is refused
/// with [`ModelLacks`](InvalidInput::ModelLacks) before any work.
///
/// # What it conserves, and why
///
/// - **Momenta of symmetries, exactly.** If `L` is invariant under a
///   translation or rotation of the coordinates, so is `L_d`, since the
///   midpoint and the difference quotient transform like `q` and `q̇`. The
///   discrete Noether theorem then makes the discrete momentum map an exact
///   invariant of the discrete flow, not an `O(h²)` approximation. For a
///   cyclic coordinate (`∂L/∂q_i ≡ 0`, `Q_i = 0`) the update
///   `p_{k+1} = p_k + h (∂L/∂q + Q)` leaves `p_i` untouched: it is kept bit
///   for bit, whatever the Newton tolerance. Other symmetries (a rotation in
///   Cartesian coordinates) are kept to the Newton tolerance and rounding.
/// - **Energy, without drift.** The map `(q_k, p_k) ↦ (q_{k+1}, p_{k+1})` is
///   symplectic, so for a conservative, autonomous model the energy error
///   stays bounded, `O(h²)`, over very long times instead of growing like
///   Runge–Kutta's. That argument assumes the same `h` every step: keep the
///   sample spacing a multiple of `h`.
/// - **Forces, to second order.** With [`nonconservative_forces`](Lagrangian::nonconservative_forces),
///   the momenta change by the impulse of `Q` at the midpoint, so a damped
///   system loses energy at the right rate to `O(h²)`.
///
/// # Constrained models
///
/// A model with [constraints](crate::constraints) is stepped by the
/// constrained discrete Euler–Lagrange equations (RATTLE, see
/// `constrained.rs`): symplectic on the constraint manifold, with `φ = 0`
/// and `φ̇ = 0` at every step by construction, so the model's
/// [`Drift`](crate::constraints::Drift) setting does not apply. Each step
/// costs an outer iteration on the multipliers (3 to 4 on the Cartesian
/// pendulum at `h = 0.01`), each one unconstrained solve as below, plus
/// one velocity projection.
///
/// A model whose `M` is singular by itself and regular only with its
/// constraints (a rigid body in unit quaternions,
/// [`Holonomic::mass_regular_on_constraints_only`](crate::model::constraints::Holonomic::mass_regular_on_constraints_only))
/// is stepped as the Lagrangian `L + (k/2)|φ̇|²` (`augmented.rs`): equal to
/// `L` on the constrained motion, with every symmetry `L` and `φ` share,
/// and the regular mass matrix `M + k GᵀG` (`k` fixed at the start). For a
/// constraint quadratic in `q` such as `|q| = 1` the steps are RATTLE's for
/// `L` itself. Constraints on the velocities are refused
/// ([`VelocityConstraints`](InvalidInput::VelocityConstraints)): RATTLE
/// imposes every constraint on the next position.
///
/// # Cost
///
/// One step solves `r(v̄) = 0` for the midpoint velocity `v̄` by Newton's
/// method (see [`max_iterations`](Variational::max_iterations)): one
/// residual at the predictor, one `N × N` Jacobian `∂r/∂v̄` by forward
/// differences of `r` (`N` residuals), then usually two or three iterations
/// of one `N × N` LU solve and one residual each (the last residual, at the
/// solution, also gives `p_{k+1}`). A residual is one call each of
/// `momentum`, `lagrangian_gradient` and `nonconservative_forces`;
/// [`Stats::rhs_evals`](crate::trajectory::Stats::rhs_evals) counts residuals, plus
/// the conversions between `q̇` and `p` at the start and at each sample
/// time. Nothing is allocated.
///
/// # Steps, samples and velocities
///
/// Sample times are hit exactly: as in [`Rk4`](crate::integrators::Rk4), each interval
/// between consecutive sample times is cut into the fewest equal steps no
/// longer than `h`. A step of another length is still a symplectic,
/// momentum-conserving map of `(q, p)`, so this costs nothing but the
/// constant-`h` energy argument above.
///
/// The state handed in and out is `(q, q̇)`: `p_0 = ∂L/∂q̇(t_0, q_0, q̇_0)`,
/// and at each sample `q̇ = M(t, q)⁻¹ (p − ∂L/∂q̇(t, q, 0))`, exact for any
/// Lagrangian quadratic in `q̇` (those `lagrangian!` derives: `M = ∂²T/∂q̇²`);
/// `M + k GᵀG` in place of `M` for a model stepped as `L + (k/2)|φ̇|²`.
///
/// ```
/// use lagrange_runtime::Variational;
///
/// let variational = Variational::new(1e-2).max_iterations(8).max_steps(1_000_000);
/// assert_eq!(variational.step_size(), 1e-2);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Variational<S> {
    h: S,
    max_steps: usize,
    max_iterations: usize,
}

impl<S: RealField + Copy> Variational<S> {
    /// The variational integrator with step `h`, a budget of 10 000 000 steps
    /// and 10 Newton iterations per step.
    ///
    /// `h` is checked when integrating: it must be positive and finite.
    pub fn new(h: S) -> Self {
        Self {
            h,
            max_steps: 10_000_000,
            max_iterations: 10,
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

    /// Newton iterations allowed per step, at least 1 (zero is refused when
    /// integrating, as
    /// [`NoNewtonIterations`](InvalidInput::NoNewtonIterations)); running out is
    /// [`NewtonDivergence`](IntegrationError::NewtonDivergence). A smooth
    /// problem at a sensible `h` needs two or three, so running out means `h`
    /// is too large for the nonlinearity, or the discrete equations have no
    /// solution at this `h` at all.
    pub fn max_iterations(mut self, max_iterations: usize) -> Self {
        self.max_iterations = max_iterations;
        self
    }

    /// The step size.
    pub fn step_size(&self) -> S {
        self.h
    }
}

impl<S: RealField + Copy> StepMethod<S> for Variational<S> {
    type Walker<const N: usize> = VariationalWalk<S, N>;

    fn walker<const N: usize>(&self) -> Result<Self::Walker<N>, InvalidInput<S>> {
        check_step_size(self.h)?;
        if self.max_iterations == 0 {
            let method = "Variational";
            return Err(InvalidInput::NoNewtonIterations { method });
        }
        Ok(VariationalWalk::new(*self))
    }
}

/// [`TooManySteps`](IntegrationError::TooManySteps) at `(t, q, p)`.
fn out_of_budget<L: Lagrangian<N>, const N: usize>(
    rec: &mut Recorder<'_, L::Scalar, N>,
    model: &L,
    (t, q, p): (L::Scalar, SVector<L::Scalar, N>, SVector<L::Scalar, N>),
    velocities: &VelocityHistory<L::Scalar, N>,
    max_steps: usize,
) -> IntegrationError<L::Scalar, N> {
    let budget = |qdot| IntegrationError::TooManySteps {
        t,
        max_steps,
        q,
        qdot,
    };
    with_velocity(rec, model, (t, q, p), velocities, budget)
}

fn lacks<S: RealField + Copy>(needs: &'static str) -> InvalidInput<S> {
    InvalidInput::ModelLacks {
        method: "Variational",
        needs,
    }
}

fn epsilon<S: RealField>() -> S {
    S::default_epsilon()
}
