//! Back onto the constraints: the rounding-level tolerances, the
//! projections of `q` onto `φ = 0` and of `q̇` onto `φ̇ = 0` in the metric of
//! `M`, and the drift control every integrator applies after a step.

use crate::dynamics::saddle::saddle_error;
use crate::model::settings::ConstraintSettings;
use nalgebra::{ComplexField, RealField, SMatrix, SVector};

use crate::dynamics::mass_error;
use crate::error::{IntegrationError, NonFiniteValue};
use crate::linalg::all_finite;
use crate::linalg::mass::{MassFactor, factor_mass_matrix};
use crate::linalg::schur::{Schur, regularized};
use crate::model::constraints::{Holonomic, Visitor};
use crate::trajectory::Stats;

/// Newton iterations a position projection may take. From the end of a
/// step (`|φ|` the size of the local error) one or two reach rounding; an
/// initial state far off the constraints may take several, converging
/// quadratically once close.
const MAX_ITERATIONS: usize = 16;

/// How many rounding errors a residual may hold and still count as zero.
const ROUNDING: f64 = 100.0;

/// What rounding alone leaves in `φ_i`: `100 ε ‖G_i‖₁ ‖q‖∞`, the size of
/// the terms `φ_i` sums (for `φ` homogeneous in `q`, `G q` is a multiple of
/// them), so the same whatever the constraint's units.
pub(crate) fn position_tolerance<S: RealField + Copy, const N: usize, const C: usize>(
    g: &SMatrix<S, C, N>,
    q: &SVector<S, N>,
) -> SVector<S, C> {
    let scale = rounding::<S>() * q.amax();
    SVector::from_fn(|i, _| g.row(i).lp_norm(1) * scale)
}

/// What rounding alone leaves in `φ̇_i = G_i q̇ + ∂φ_i/∂t`:
/// `100 ε (‖G_i‖₁ ‖q̇‖∞ + |∂φ_i/∂t|)`.
pub(crate) fn velocity_tolerance<H, const N: usize, const C: usize>(
    model: &H,
    t: H::Scalar,
    q: &SVector<H::Scalar, N>,
    g: &SMatrix<H::Scalar, C, N>,
    qdot: &SVector<H::Scalar, N>,
) -> SVector<H::Scalar, C>
where
    H: Holonomic<N, C> + ?Sized,
{
    let rounding = rounding::<H::Scalar>();
    let explicit = model.constraint_velocities(t, q, &SVector::zeros());
    SVector::from_fn(|i, _| rounding * (g.row(i).lp_norm(1) * qdot.amax() + explicit[i].abs()))
}

/// `100 ε`.
fn rounding<S: RealField + Copy>() -> S {
    nalgebra::convert::<f64, S>(ROUNDING) * S::default_epsilon()
}

/// The index and value of the constraint furthest beyond its tolerance,
/// if any is.
pub(crate) fn worst_violation<S: RealField + Copy, const C: usize>(
    residual: &SVector<S, C>,
    tolerance: &SVector<S, C>,
) -> Option<usize> {
    (0..C)
        .filter(|&i| !residual[i].is_finite() || residual[i].abs() > tolerance[i])
        .max_by(|&i, &j| {
            let (a, b) = (residual[i].abs(), residual[j].abs());
            a.partial_cmp(&b).unwrap_or(core::cmp::Ordering::Greater)
        })
}

/// `q` moved onto `φ(t, q) = 0` by Newton's method on the projection
/// orthogonal in the metric of `M` (at the point given, fixed):
/// `Δq = −M⁻¹ G(q)ᵀ (G M⁻¹ Gᵀ)⁻¹ φ(q)`, `G` refreshed each iteration so
/// that it converges quadratically, at least once and then until every
/// `|φ_i|` is at rounding level ([`position_tolerance`], a bound, not the
/// aim: one iteration from a step's drift lands far below it). `q̇` is
/// only reported in errors.
pub(crate) fn project_position<H, const N: usize, const C: usize>(
    model: &H,
    t: H::Scalar,
    q: &SVector<H::Scalar, N>,
    qdot: &SVector<H::Scalar, N>,
    stats: &mut Stats,
) -> Result<SVector<H::Scalar, N>, IntegrationError<H::Scalar, N>>
where
    H: Holonomic<N, C> + ?Sized,
{
    let (mass, _) = projection_metric(model, t, q, qdot)?;
    let mut q = *q;
    let mut iterations = 0;
    loop {
        let phi = model.constraints(t, &q);
        let g = model.constraint_jacobian(t, &q);
        if !all_finite(q.as_slice()) {
            let (qdot, value) = (*qdot, NonFiniteValue::State);
            return Err(IntegrationError::NonFiniteState { t, q, qdot, value });
        }
        if !(all_finite(phi.as_slice()) && all_finite(g.as_slice())) {
            let (qdot, value) = (*qdot, NonFiniteValue::Constraints);
            return Err(IntegrationError::NonFiniteState { t, q, qdot, value });
        }
        // At least one iteration: a step's drift below the tolerance would
        // otherwise stay and add up over the run, where one Newton step
        // takes it to rounding (quadratically) for the price of one solve.
        let worst = worst_violation(&phi, &position_tolerance(&g, &q));
        let Some(worst) = worst.or((iterations == 0).then_some(0)) else {
            let after = &mut stats.projected_position_residual;
            *after = after.max(to_f64(phi.amax()));
            return Ok(q);
        };
        if iterations == MAX_ITERATIONS {
            return Err(IntegrationError::ProjectionFailed {
                t,
                constraint: H::CONSTRAINTS[worst],
                residual: phi[worst],
                iterations,
                q,
                qdot: *qdot,
            });
        }
        let schur = Schur::new(&mass, &g).map_err(|e| saddle_error(e, t, &q, qdot))?;
        let (delta, _) = schur
            .correction(&phi)
            .map_err(|e| saddle_error(e, t, &q, qdot))?;
        q += delta;
        iterations += 1;
        stats.projection_iterations += 1;
    }
}

/// `q̇` moved onto `φ̇ = 0` at `(t, q)`, orthogonally in the metric of `M`:
/// `q̇ − M⁻¹Gᵀ μ` with `μ = (G M⁻¹ Gᵀ)⁻¹ φ̇`; exact in one step, `φ̇` being
/// linear in `q̇`. Returns the new `q̇` and `μ`, the impulse `Gᵀ μ` taken
/// off the momenta.
#[allow(clippy::type_complexity)]
pub(crate) fn project_velocity<H, const N: usize, const C: usize>(
    model: &H,
    t: H::Scalar,
    q: &SVector<H::Scalar, N>,
    qdot: &SVector<H::Scalar, N>,
) -> Result<(SVector<H::Scalar, N>, SVector<H::Scalar, C>), IntegrationError<H::Scalar, N>>
where
    H: Holonomic<N, C> + ?Sized,
{
    let (mass, k) = projection_metric(model, t, q, qdot)?;
    let g = model.constraint_jacobian(t, q);
    let phidot = model.constraint_velocities(t, q, qdot);
    if !(all_finite(g.as_slice()) && all_finite(phidot.as_slice())) {
        let (q, qdot, value) = (*q, *qdot, NonFiniteValue::Constraints);
        return Err(IntegrationError::NonFiniteState { t, q, qdot, value });
    }
    let schur = Schur::new(&mass, &g).map_err(|e| saddle_error(e, t, q, qdot))?;
    let (delta, mu) = schur
        .correction(&phidot)
        .map_err(|e| saddle_error(e, t, q, qdot))?;
    // In the metric `M + k GᵀG` the change of momentum `M Δq̇` is
    // `−Gᵀ (μ + k G Δq̇) = −Gᵀ (μ − k φ̇)`: the impulse of the constraints.
    let mu = match k {
        Some(k) => mu - phidot * k,
        None => mu,
    };
    Ok((qdot + delta, mu))
}

/// The metric of the projections at `(t, q)`, factored: `M`, or `M + k GᵀG`
/// and `k` for a model whose `M` is regular only on the constraints
/// ([`Holonomic::mass_regular_on_constraints_only`]); on the velocities the
/// constraints allow the two agree.
#[allow(clippy::type_complexity)]
fn projection_metric<H, const N: usize, const C: usize>(
    model: &H,
    t: H::Scalar,
    q: &SVector<H::Scalar, N>,
    qdot: &SVector<H::Scalar, N>,
) -> Result<(MassFactor<H::Scalar, N>, Option<H::Scalar>), IntegrationError<H::Scalar, N>>
where
    H: Holonomic<N, C> + ?Sized,
{
    let m = model.mass_matrix(t, q);
    if !model.mass_regular_on_constraints_only() {
        let mass = factor_mass_matrix(&m).map_err(|e| mass_error(e, t, q, qdot))?;
        return Ok((mass, None));
    }
    let g = model.constraint_jacobian(t, q);
    if !all_finite(g.as_slice()) {
        let (q, qdot, value) = (*q, *qdot, NonFiniteValue::Constraints);
        return Err(IntegrationError::NonFiniteState { t, q, qdot, value });
    }
    let (m, k) = regularized(&m, &g);
    let mass = factor_mass_matrix(&m).map_err(|e| mass_error(e, t, q, qdot))?;
    Ok((mass, Some(k)))
}

/// `q` then `q̇` projected.
#[allow(clippy::type_complexity)]
pub(crate) fn project<H, const N: usize, const C: usize>(
    model: &H,
    t: H::Scalar,
    q: &SVector<H::Scalar, N>,
    qdot: &SVector<H::Scalar, N>,
    stats: &mut Stats,
) -> Result<(SVector<H::Scalar, N>, SVector<H::Scalar, N>), IntegrationError<H::Scalar, N>>
where
    H: Holonomic<N, C> + ?Sized,
{
    let q = project_position(model, t, q, qdot, stats)?;
    let (qdot, _) = project_velocity(model, t, &q, qdot)?;
    Ok((q, qdot))
}

fn to_f64<S: RealField + Copy>(x: S) -> f64 {
    nalgebra::try_convert(x).unwrap_or(f64::NAN)
}

/// Drift control at the end of an accepted step: the residuals recorded in
/// [`Stats`], then the state projected if the model's
/// [`Drift`](super::Drift) says so.
pub(crate) struct DriftControl<'a, S, const N: usize> {
    pub(crate) t: S,
    pub(crate) q: SVector<S, N>,
    pub(crate) qdot: SVector<S, N>,
    pub(crate) stats: &'a mut Stats,
    /// Whether to project at all (`false`: only record the residuals).
    pub(crate) project: bool,
}

impl<S: RealField + Copy, const N: usize> Visitor<S, N> for DriftControl<'_, S, N> {
    type Output = Result<(SVector<S, N>, SVector<S, N>), IntegrationError<S, N>>;

    fn visit<H, const C: usize>(self, model: &H, settings: ConstraintSettings<S>) -> Self::Output
    where
        H: Holonomic<N, C, Scalar = S> + ?Sized,
    {
        let Self {
            t,
            q,
            qdot,
            stats,
            project: may_project,
        } = self;
        if !(all_finite(q.as_slice()) && all_finite(qdot.as_slice())) {
            let value = NonFiniteValue::State;
            return Err(IntegrationError::NonFiniteState { t, q, qdot, value });
        }
        let phi = model.constraints(t, &q);
        let phidot = model.constraint_velocities(t, &q, &qdot);
        if !(all_finite(phi.as_slice()) && all_finite(phidot.as_slice())) {
            let value = NonFiniteValue::Constraints;
            return Err(IntegrationError::NonFiniteState { t, q, qdot, value });
        }
        stats.max_position_residual = stats.max_position_residual.max(to_f64(phi.amax()));
        stats.max_velocity_residual = stats.max_velocity_residual.max(to_f64(phidot.amax()));
        if may_project && settings.projects() {
            project(model, t, &q, &qdot, stats)
        } else {
            Ok((q, qdot))
        }
    }
}

/// A sample from dense output, projected if the model's drift control
/// projects (steps' ends are projected already).
pub(crate) struct ProjectSample<'a, S, const N: usize> {
    pub(crate) t: S,
    pub(crate) q: SVector<S, N>,
    pub(crate) qdot: SVector<S, N>,
    pub(crate) stats: &'a mut Stats,
}

impl<S: RealField + Copy, const N: usize> Visitor<S, N> for ProjectSample<'_, S, N> {
    type Output = Result<(SVector<S, N>, SVector<S, N>), IntegrationError<S, N>>;

    fn visit<H, const C: usize>(self, model: &H, settings: ConstraintSettings<S>) -> Self::Output
    where
        H: Holonomic<N, C, Scalar = S> + ?Sized,
    {
        let Self { t, q, qdot, stats } = self;
        if settings.projects() {
            project(model, t, &q, &qdot, stats)
        } else {
            Ok((q, qdot))
        }
    }
}

/// [`project_velocity`] reached from generic code: the projected `q̇` and
/// the impulse `Gᵀ μ` it took off the momenta (`M Δq̇ = −Gᵀ μ`).
pub(crate) struct VelocityProjection<'a, S, const N: usize> {
    pub(crate) t: S,
    pub(crate) q: &'a SVector<S, N>,
    pub(crate) qdot: &'a SVector<S, N>,
}

impl<S: RealField + Copy, const N: usize> Visitor<S, N> for VelocityProjection<'_, S, N> {
    type Output = Result<(SVector<S, N>, SVector<S, N>), IntegrationError<S, N>>;

    fn visit<H, const C: usize>(self, model: &H, _: ConstraintSettings<S>) -> Self::Output
    where
        H: Holonomic<N, C, Scalar = S> + ?Sized,
    {
        let (qdot, mu) = project_velocity(model, self.t, self.q, self.qdot)?;
        let g = model.constraint_jacobian(self.t, self.q);
        Ok((qdot, g.transpose() * mu))
    }
}
