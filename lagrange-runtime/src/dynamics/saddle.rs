//! `q̈` and `λ` of a constrained model: the saddle-point solve of
//! `linalg/schur.rs` on the model's `M`, `f`, `G` and `γ`, with the
//! run's Baumgarte terms, errors at `(t, q, q̇)`.

use crate::linalg::all_finite;
use nalgebra::{ComplexField, RealField, SMatrix, SVector};

use super::mass_error;
use crate::error::{IntegrationError, NonFiniteValue};
use crate::linalg::mass::{SolveError, accepted_cholesky, factor_mass_matrix};
use crate::linalg::schur::{SaddleError, by_cholesky, regularized, solve_saddle};
use crate::model::constraints::{Holonomic, Visitor};
use crate::model::settings::ConstraintSettings;

/// A failed saddle-point solve as the integrators report it, at
/// `(t, q, q̇)`.
pub(crate) fn saddle_error<S: RealField + Copy, const N: usize>(
    error: SaddleError,
    t: S,
    q: &SVector<S, N>,
    qdot: &SVector<S, N>,
) -> IntegrationError<S, N> {
    RhsError::from(error).at(t, q, qdot)
}

/// Why a constrained right-hand side failed, before the state is
/// attached ([`RhsError::at`]). The solve's hot path returns this small
/// error, not [`IntegrationError`]: a `Result` with the large error's
/// layout copied `q̈` out piece by piece along the error's fields, whose
/// overlapping loads and stores stalled store forwarding for about a
/// fifth of the Cartesian pendulum's right-hand side.
#[derive(Clone, Copy)]
pub(crate) enum RhsError {
    /// Solving with `M` failed.
    Mass(SolveError),
    /// A value of the model's evaluation is not finite.
    NonFinite(NonFiniteValue),
    /// `G M⁻¹ Gᵀ` is singular or numerically so.
    Singular,
}

impl From<SaddleError> for RhsError {
    fn from(error: SaddleError) -> Self {
        match error {
            SaddleError::Mass(error) => Self::Mass(error),
            SaddleError::Singular => Self::Singular,
        }
    }
}

impl RhsError {
    /// The error as the integrators report it, at `(t, q, q̇)`. Out of
    /// line and cold: it is off every hot path.
    #[cold]
    #[inline(never)]
    pub(crate) fn at<S: RealField + Copy, const N: usize>(
        self,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> IntegrationError<S, N> {
        match self {
            Self::Mass(error) => mass_error(error, t, q, qdot),
            Self::NonFinite(value) => IntegrationError::NonFiniteState {
                t,
                q: *q,
                qdot: *qdot,
                value,
            },
            Self::Singular => IntegrationError::SingularConstraints {
                t,
                q: *q,
                qdot: *qdot,
            },
        }
    }
}

/// `(q̈, λ)` of `model` at `(t, q, q̇)`: one right-hand side. With
/// `baumgarte = Some((2α, β²))`, the bias carries the Baumgarte terms
/// `2α φ̇ + β² φ` of the run's drift control.
#[allow(clippy::type_complexity)]
pub(crate) fn constrained_accelerations<H, const N: usize, const C: usize>(
    model: &H,
    t: H::Scalar,
    q: &SVector<H::Scalar, N>,
    qdot: &SVector<H::Scalar, N>,
    baumgarte: Option<(H::Scalar, H::Scalar)>,
) -> Result<(SVector<H::Scalar, N>, SVector<H::Scalar, C>), IntegrationError<H::Scalar, N>>
where
    H: Holonomic<N, C> + ?Sized,
{
    let finite = |v: &SVector<H::Scalar, N>| all_finite(v.as_slice());
    if !(t.is_finite() && finite(q) && finite(qdot)) {
        return Err(IntegrationError::NonFiniteState {
            t,
            q: *q,
            qdot: *qdot,
            value: NonFiniteValue::State,
        });
    }
    solve_constrained(model, t, q, qdot, baumgarte).map_err(|error| error.at(t, q, qdot))
}

/// [`constrained_accelerations`] at a state already checked finite, its
/// error without the state.
#[allow(clippy::type_complexity)]
#[inline]
fn solve_constrained<H, const N: usize, const C: usize>(
    model: &H,
    t: H::Scalar,
    q: &SVector<H::Scalar, N>,
    qdot: &SVector<H::Scalar, N>,
    baumgarte: Option<(H::Scalar, H::Scalar)>,
) -> Result<(SVector<H::Scalar, N>, SVector<H::Scalar, C>), RhsError>
where
    H: Holonomic<N, C> + ?Sized,
{
    let (m, f, g, mut gamma) = model.constrained_system(t, q, qdot);
    if let Some((two_alpha, beta2)) = baumgarte {
        let phi = model.constraints(t, q);
        let phidot = model.constraint_velocities(t, q, qdot);
        gamma += phidot * two_alpha + phi * beta2;
    }
    if model.mass_regular_on_constraints_only() {
        return regularized_accelerations((m, f, g, gamma));
    }
    // The common case, with no enum around `L` or the result: what
    // `checked` does where `M` takes Cholesky and `S` is accepted.
    if let Some(ldlt) = accepted_cholesky(&m) {
        if all_finite(f.as_slice()) && all_finite(g.as_slice()) && all_finite(gamma.as_slice()) {
            if let Some(solution) = by_cholesky(&ldlt, &f, &g, &gamma) {
                return Ok(solution);
            }
        }
    }
    checked((m, f, g, gamma))
}

/// `M`, `f`, `G` and `γ` of one right-hand side, as the model returns them.
type System<S, const N: usize, const C: usize> = (
    SMatrix<S, N, N>,
    SVector<S, N>,
    SMatrix<S, C, N>,
    SVector<S, C>,
);

/// The saddle-point solve of [`solve_constrained`] with each of its checks
/// in turn: the fallbacks (LU, the solve through `M⁻¹ Gᵀ`) and the
/// errors, with whom they blame. Where the fast path declined, this
/// factors `M` again, to the same bits.
#[cold]
#[inline(never)]
fn checked<S: RealField + Copy, const N: usize, const C: usize>(
    (m, f, g, gamma): System<S, N, C>,
) -> Result<(SVector<S, N>, SVector<S, C>), RhsError> {
    let mass = factor_mass_matrix(&m).map_err(RhsError::Mass)?;
    finite_forcing_and_constraints(&f, &g, &gamma)?;
    Ok(solve_saddle(&mass, &f, &g, &gamma)?)
}

/// `f`, then `G` and `γ`, checked finite, each blamed for itself.
fn finite_forcing_and_constraints<S: RealField + Copy, const N: usize, const C: usize>(
    f: &SVector<S, N>,
    g: &SMatrix<S, C, N>,
    gamma: &SVector<S, C>,
) -> Result<(), RhsError> {
    if !all_finite(f.as_slice()) {
        return Err(RhsError::NonFinite(NonFiniteValue::Forcing));
    }
    if !(all_finite(g.as_slice()) && all_finite(gamma.as_slice())) {
        return Err(RhsError::NonFinite(NonFiniteValue::Constraints));
    }
    Ok(())
}

/// The saddle-point solve of a model whose `M` is regular only on the
/// constraints ([`Holonomic::mass_regular_on_constraints_only`]): with
/// `M + k GᵀG` and `f − k Gᵀγ`, the same `(q̈, λ)`. Each input is checked
/// before they are mixed, so that a non-finite value is still blamed on
/// what produced it; a configuration where even `M + k GᵀG` is singular
/// is [`SingularMassMatrix`](IntegrationError::SingularMassMatrix) there.
fn regularized_accelerations<S: RealField + Copy, const N: usize, const C: usize>(
    (m, f, g, gamma): System<S, N, C>,
) -> Result<(SVector<S, N>, SVector<S, C>), RhsError> {
    if !all_finite(m.as_slice()) {
        return Err(RhsError::Mass(SolveError::NonFiniteMassMatrix));
    }
    finite_forcing_and_constraints(&f, &g, &gamma)?;
    let (m, k) = regularized(&m, &g);
    let f = f - g.transpose() * (gamma * k);
    let mass = factor_mass_matrix(&m).map_err(RhsError::Mass)?;
    Ok(solve_saddle(&mass, &f, &g, &gamma)?)
}

/// `q̈` of a constrained model, for [`acceleration`](super::acceleration).
pub(crate) struct Accelerations<'a, S, const N: usize> {
    pub(crate) t: S,
    pub(crate) q: &'a SVector<S, N>,
    pub(crate) qdot: &'a SVector<S, N>,
}

impl<S: RealField + Copy, const N: usize> Visitor<S, N> for Accelerations<'_, S, N> {
    /// The error without the state: [`acceleration`](super::acceleration)
    /// attaches it off the hot path ([`RhsError::at`]).
    type Output = Result<SVector<S, N>, RhsError>;

    fn visit<H, const C: usize>(self, model: &H, settings: ConstraintSettings<S>) -> Self::Output
    where
        H: Holonomic<N, C, Scalar = S> + ?Sized,
    {
        // `acceleration`, its one caller, has checked the state.
        let baumgarte = settings.baumgarte();
        solve_constrained(model, self.t, self.q, self.qdot, baumgarte).map(|(qddot, _)| qddot)
    }
}

/// The multipliers of a constrained model: [`multipliers`](Multipliers::multipliers)
/// for every [`Holonomic`] model (in the prelude).
pub trait Multipliers<const N: usize, const C: usize>: Holonomic<N, C> {
    /// The multipliers `λ` of the constrained motion through `(t, q, q̇)`:
    /// the constraint force on the coordinates is `−Gᵀ λ` (see
    /// [the module](crate::constraints#multipliers) for their units). They
    /// use `γ` itself, not a Baumgarte-modified bias: the forces of the
    /// exact constrained motion.
    fn multipliers(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> Result<SVector<Self::Scalar, C>, IntegrationError<Self::Scalar, N>> {
        constrained_accelerations(self, t, q, qdot, None).map(|(_, lambda)| lambda)
    }
}

impl<H: Holonomic<N, C> + ?Sized, const N: usize, const C: usize> Multipliers<N, C> for H {}
