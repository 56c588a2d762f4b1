//! Why a linearization, an equilibrium search or a modal analysis has no
//! answer, with the time and the configuration it was asked about.

use nalgebra::{RealField, SVector};

use crate::error::Row;
use crate::error::{ConstraintLevel, IntegrationError};

/// Why [`linearize`](super::linearize), [`equilibrium`](super::equilibrium)
/// or [`modes`](super::modes) gave no result.
///
/// ```
/// use lagrange::models::DoublePendulum;
/// use lagrange_runtime::analysis::{modes, AnalysisError};
/// use lagrange_runtime::nalgebra::Vector2;
///
/// // A swinging-out configuration is no equilibrium: no modes there.
/// let pendulum = DoublePendulum::unit();
/// let err = modes(&pendulum, 0.0, &Vector2::new(0.3, 0.0)).unwrap_err();
/// assert!(matches!(err, AnalysisError::NotAnEquilibrium { .. }));
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum AnalysisError<S: RealField + Copy, const N: usize> {
    /// Evaluating the model failed: a singular or indefinite mass matrix,
    /// a NaN in `M`, `f` or the Jacobians, with `t` and the state, as an
    /// integrator would report it.
    #[error(transparent)]
    Model(#[from] IntegrationError<S, N>),

    /// [`linearize`](super::linearize) or
    /// [`linearize_with_inputs`](super::linearize_with_inputs) was asked
    /// for a model with holonomic constraints. Their `A` is in the model's
    /// `N` coordinates, which are not independent on `φ(t, q) = 0`:
    /// linearizing them as if they were free would be wrong. Use
    /// [`linearize_on_manifold`](super::linearize_on_manifold), in
    /// independent coordinates; inputs on the manifold are not supported
    /// yet.
    #[error(
        "the model has holonomic constraints at t = {t:?} (q = {}): its coordinates are not \
         independent; use `linearize_on_manifold` (`linearize_on_manifold_with_inputs` with inputs)",
        Row(.q)
    )]
    Constrained {
        /// Time asked about.
        t: S,
        /// Configuration asked about.
        q: SVector<S, N>,
    },

    /// The model has constraints on its velocities (rolling, a knife edge:
    /// [`Holonomic::has_velocity_constraints`](crate::model::constraints::Holonomic::has_velocity_constraints)).
    /// The analyses on the constraint manifold reduce the coordinates by
    /// the constraints' position level, which such a row does not have: not
    /// supported yet. (Integrating such a model is.)
    #[error(
        "the model has constraints on its velocities (at t = {t:?}, q = {}): the analyses on the \
         constraint manifold need every constraint on the positions, and velocity constraints are \
         not supported there yet",
        Row(.q)
    )]
    VelocityConstraints {
        /// Time asked about.
        t: S,
        /// Configuration asked about.
        q: SVector<S, N>,
    },

    /// [`linearize_steady_motion`](super::linearize_steady_motion) was
    /// asked about a motion that is not steady in a kept state: its rate
    /// (a kept coordinate's velocity, a kept velocity's acceleration) is
    /// not zero there.
    #[error(
        "the motion at t = {t:?} (q = {}, q̇ = {}) is not steady in `{state}`: its rate is {rate:?}",
        Row(.q), Row(.qdot)
    )]
    NotSteady {
        /// Time asked about.
        t: S,
        /// Configuration asked about.
        q: SVector<S, N>,
        /// Velocities asked about.
        qdot: SVector<S, N>,
        /// The kept state that moves.
        state: String,
        /// Its rate.
        rate: S,
    },

    /// [`linearize_steady_motion`](super::linearize_steady_motion) cannot
    /// reduce the motion to the states kept: one is not a coordinate, they
    /// are not independent on the motions the constraints allow, or their
    /// rates depend on states left out.
    #[error("the small motions cannot be reduced to the states kept: {reason}")]
    NotReducible {
        /// What fails.
        reason: String,
    },

    /// A constrained model was asked about a state off its constraints:
    /// `φ(t, q)` (or, for a linearization, `φ̇ = G q̇ + ∂φ/∂t`) is beyond
    /// `√ε` relative (see
    /// [`linearize_on_manifold`](super::linearize_on_manifold)). Project
    /// it first, or search with [`equilibrium`](super::equilibrium), which
    /// projects its guess.
    #[error(
        "the state at t = {t:?} (q = {}, q̇ = {}) is off the constraints: {level} residual \
         of constraint `{constraint}` is {residual:?}",
        Row(.q), Row(.qdot)
    )]
    OffConstraints {
        /// Time asked about.
        t: S,
        /// Configuration asked about.
        q: SVector<S, N>,
        /// Velocities asked about (zero for a question about rest).
        qdot: SVector<S, N>,
        /// The constraint found off, by name.
        constraint: &'static str,
        /// Position (`φ`) or velocity (`φ̇`).
        level: ConstraintLevel,
        /// Its `φ_i` or `φ̇_i`.
        residual: S,
    },

    /// The Newton iteration for an equilibrium did not converge: it ran out
    /// of iterations, or its iterate left the finite numbers. `q` is the
    /// last finite iterate and `residual` the forcing `f(t, q, 0)` there.
    #[error(
        "no equilibrium found from the guess: Newton stopped after {iterations} iterations \
         at t = {t:?} with q = {} and residual forcing f(t, q, 0) = {}; try another guess",
        Row(.q), Row(.residual)
    )]
    NotConverged {
        /// Time of the search.
        t: S,
        /// The last finite iterate.
        q: SVector<S, N>,
        /// `f(t, q, 0)` at that iterate; for a constrained model the part
        /// the constraints do not hold, `f − Gᵀ λ`.
        residual: SVector<S, N>,
        /// Iterations done.
        iterations: usize,
    },

    /// `∂f/∂q` at rest (for a constrained model, its tangent part
    /// `−K_z`, see [`modes`](super::modes)) is singular at `q`: some displacement changes no
    /// force to first order (a neutral direction: a cyclic coordinate, a
    /// free body, a force that does not depend on position), so Newton's
    /// step is not determined. If `residual` is not zero, a constant force
    /// along that direction means there may be no equilibrium at all.
    #[error(
        "∂f/∂q is singular at t = {t:?}, q = {} (residual forcing {}): a neutral direction \
         (a cyclic coordinate, a free body or a position-independent force) leaves the \
         equilibrium undetermined, or there is none",
        Row(.q), Row(.residual)
    )]
    SingularStiffness {
        /// Time of the evaluation.
        t: S,
        /// Configuration where `∂f/∂q` was singular.
        q: SVector<S, N>,
        /// `f(t, q, 0)` there; for a constrained model the part the
        /// constraints do not hold, `f − Gᵀ λ`.
        residual: SVector<S, N>,
    },

    /// Modes were asked for at a configuration that is not an equilibrium:
    /// the forcing at rest is beyond the tolerance
    /// ([`is_equilibrium`](super::is_equilibrium)), so small motions about
    /// it are not oscillations about `q`. Find one with
    /// [`equilibrium`](super::equilibrium) first.
    #[error(
        "t = {t:?}, q = {} is not an equilibrium: the forcing at rest is f(t, q, 0) = {}; \
         find one with `equilibrium` first",
        Row(.q), Row(.residual)
    )]
    NotAnEquilibrium {
        /// Time asked about.
        t: S,
        /// Configuration asked about.
        q: SVector<S, N>,
        /// `f(t, q, 0)` there; for a constrained model the part the
        /// constraints do not hold, `f − Gᵀ λ`.
        residual: SVector<S, N>,
    },

    /// The stiffness `K = −∂f/∂q` is not symmetric beyond the error of its
    /// evaluation: position-dependent forces that are not the gradient of a
    /// potential (follower or circulatory forces). Such a system has no
    /// real modes (it can flutter); study the eigenvalues of the
    /// [`Linearization`](super::Linearization)'s state matrix instead.
    #[error(
        "the stiffness −∂f/∂q at t = {t:?}, q = {} is not symmetric (relative asymmetry \
         {asymmetry:?}): the forces are not conservative, so there are no real modes; use \
         the eigenvalues of the linearization instead",
        Row(.q)
    )]
    NonConservative {
        /// Time asked about.
        t: S,
        /// Configuration asked about.
        q: SVector<S, N>,
        /// `max |K − Kᵀ| / max |K|`.
        asymmetry: S,
    },

    /// The model's `∂f/∂u` has a NaN or infinite entry at this state.
    #[error(
        "the input Jacobian ∂f/∂u is NaN or infinite at t = {t:?} (q = {}, q̇ = {})",
        Row(.q), Row(.qdot)
    )]
    NonFiniteInputJacobian {
        /// Time of the evaluation.
        t: S,
        /// Generalized coordinates.
        q: SVector<S, N>,
        /// Generalized velocities.
        qdot: SVector<S, N>,
    },
}

/// [`AnalysisError::VelocityConstraints`] for a model with constraints on
/// its velocities, at `(t, q)`.
pub(crate) fn refuse_velocity_constraints<L, const N: usize>(
    model: &L,
    t: L::Scalar,
    q: &SVector<L::Scalar, N>,
) -> Result<(), AnalysisError<L::Scalar, N>>
where
    L: crate::model::Lagrangian<N>,
{
    if crate::model::constraints::has_velocity_constraints(model) {
        return Err(AnalysisError::VelocityConstraints { t, q: *q });
    }
    Ok(())
}
