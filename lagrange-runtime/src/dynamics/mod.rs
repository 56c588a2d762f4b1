//! The dynamics of a model: `q̈` (and, with constraints, `λ`) at a state,
//! and whom to blame for a value that is not finite. Between the linear
//! algebra, which knows no models (`linalg/`), and the run loops
//! (`driver/`): every method's right-hand side is [`acceleration`].
//!
//! - `mod.rs`: [`acceleration`], constrained or not, its errors at
//!   `(t, q, q̇)`;
//! - `saddle.rs`: the constrained accelerations and multipliers
//!   ([`Multipliers`](saddle::Multipliers));
//! - `blame.rs`: a non-finite value blamed on the inputs where they are not
//!   finite at that state;
//! - `jacobian.rs`: [`acceleration_jacobians`], `∂q̈/∂q` and `∂q̈/∂q̇`;
//! - `projection.rs`: the constraints' rounding-level tolerances, the
//!   projections onto them and the drift control after a step;
//! - `start.rs`: a constrained run's initial state, projected or refused;
//! - `annotate.rs`: the multipliers and residuals of every sample.

use nalgebra::{ComplexField, RealField, SVector};

use crate::error::{IntegrationError, NonFiniteValue};
use crate::linalg::all_finite;
use crate::linalg::mass::{SolveError, solve_mass_matrix, solve_mass_matrix_in_place};
use crate::model::Lagrangian;
use saddle::Accelerations;

pub(crate) mod annotate;
pub(crate) mod blame;
mod jacobian;
pub(crate) mod projection;
pub(crate) mod saddle;
pub(crate) mod start;

pub use jacobian::acceleration_jacobians;

/// `q̈` of `model` in the state `(t, q, q̇)`: one right-hand side evaluation.
///
/// For a model with constraints (see [`constraints`](crate::constraints))
/// this is the saddle-point solve of `M q̈ + Gᵀ λ = f`, `G q̈ = −γ`; a
/// model in minimal coordinates solves `M q̈ = f` as ever, or solves it
/// itself ([`Lagrangian::accelerations`]). Errors carry `t`
/// and the state, as the integrators report them.
#[inline]
pub fn acceleration<L: Lagrangian<N>, const N: usize>(
    model: &L,
    t: L::Scalar,
    q: &SVector<L::Scalar, N>,
    qdot: &SVector<L::Scalar, N>,
) -> Result<SVector<L::Scalar, N>, IntegrationError<L::Scalar, N>> {
    let non_finite = |value| IntegrationError::NonFiniteState {
        t,
        q: *q,
        qdot: *qdot,
        value,
    };
    if !t.is_finite() || !all_finite(q.as_slice()) || !all_finite(qdot.as_slice()) {
        return Err(non_finite(NonFiniteValue::State));
    }
    if let Some(constrained) = model.visit_constraints(Accelerations { t, q, qdot }) {
        return constrained.map_err(|error| constrained_error(model, error, t, q, qdot));
    }
    if L::SOLVES_ACCELERATIONS {
        if let Some(accelerations) = model.accelerations(t, q, qdot) {
            return accelerations;
        }
    }
    // `M` factored where the model returned it; where Cholesky refuses it,
    // the same solve again on a fresh one (LU needs the `M` overwritten),
    // out of line: a second call of the model here would keep the
    // optimizer from inlining either into the step (issue 49: 15 % more
    // instructions per evaluation of the double pendulum).
    let mut mass_and_forcing = model.mass_matrix_and_forcing(t, q, qdot);
    let (m, f) = (&mut mass_and_forcing.0, &mass_and_forcing.1);
    let solved = match solve_mass_matrix_in_place(m, f) {
        Some(solved) => solved,
        None => solve_anew(model, t, q, qdot),
    };
    solved.map_err(|err| match err {
        // A controller's non-finite inputs show as a non-finite forcing.
        SolveError::NonFiniteForcing => {
            non_finite(blame::blame(model, NonFiniteValue::Forcing, t, q, qdot))
        }
        err => mass_error(err, t, q, qdot),
    })
}

/// `M q̈ = f` solved on a fresh `M` and `f`, where the in-place solve
/// handed them back (Cholesky refused `M` or its pivots): the rare case,
/// kept out of the hot path.
#[cold]
#[inline(never)]
fn solve_anew<L: Lagrangian<N>, const N: usize>(
    model: &L,
    t: L::Scalar,
    q: &SVector<L::Scalar, N>,
    qdot: &SVector<L::Scalar, N>,
) -> Result<SVector<L::Scalar, N>, SolveError> {
    let (m, f) = model.mass_matrix_and_forcing(t, q, qdot);
    solve_mass_matrix(&m, &f)
}

/// A constrained right-hand side's error as the integrators report it,
/// at `(t, q, q̇)`; a controller's non-finite inputs show as a non-finite
/// forcing, and are blamed. Cold, off the hot path with the
/// [`RhsError`](saddle::RhsError) it builds on.
#[cold]
#[inline(never)]
fn constrained_error<L: Lagrangian<N>, const N: usize>(
    model: &L,
    error: saddle::RhsError,
    t: L::Scalar,
    q: &SVector<L::Scalar, N>,
    qdot: &SVector<L::Scalar, N>,
) -> IntegrationError<L::Scalar, N> {
    blame::blame_error(model, error.at(t, q, qdot))
}

/// A failed solve with `M` as the integrators report it, at `(t, q, q̇)`.
pub(crate) fn mass_error<S: RealField + Copy, const N: usize>(
    err: SolveError,
    t: S,
    q: &SVector<S, N>,
    qdot: &SVector<S, N>,
) -> IntegrationError<S, N> {
    let (q, qdot) = (*q, *qdot);
    let non_finite = |value| IntegrationError::NonFiniteState { t, q, qdot, value };
    match err {
        SolveError::NonFiniteMassMatrix => non_finite(NonFiniteValue::MassMatrix),
        SolveError::NonFiniteForcing => non_finite(NonFiniteValue::Forcing),
        SolveError::Singular => IntegrationError::SingularMassMatrix { t, q, qdot },
        SolveError::Indefinite => IntegrationError::IndefiniteMassMatrix { t, q, qdot },
    }
}
