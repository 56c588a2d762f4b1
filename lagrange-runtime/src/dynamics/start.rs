//! The start of a constrained run: the settings checked, and `(q0, q̇0)`
//! accepted, projected or refused (see
//! [the module](super#initial-conditions)).

use crate::model::settings::ConstraintSettings;
use nalgebra::{RealField, SVector};

use super::projection::{
    position_tolerance, project_position, project_velocity, velocity_tolerance, worst_violation,
};
use crate::error::{ConstraintLevel, IntegrationError, InvalidInput, NonFiniteValue};
use crate::model::constraints::{Holonomic, Visitor};
use crate::model::settings::{Drift, InitialConditions};
use crate::trajectory::Stats;

/// The consistent initial state of a constrained run, the corrections
/// recorded in [`Stats`].
pub(crate) struct StartOnManifold<'a, S, const N: usize> {
    pub(crate) t0: S,
    pub(crate) q0: SVector<S, N>,
    pub(crate) qdot0: SVector<S, N>,
    pub(crate) stats: &'a mut Stats,
}

impl<S: RealField + Copy, const N: usize> Visitor<S, N> for StartOnManifold<'_, S, N> {
    type Output = Result<(SVector<S, N>, SVector<S, N>), IntegrationError<S, N>>;

    fn visit<H, const C: usize>(self, model: &H, settings: ConstraintSettings<S>) -> Self::Output
    where
        H: Holonomic<N, C, Scalar = S> + ?Sized,
    {
        let Self {
            t0: t,
            q0,
            qdot0,
            stats,
        } = self;
        if let Drift::Baumgarte { alpha, beta } = settings.drift {
            let valid = |x: S| x.is_finite() && x >= S::zero();
            if !(valid(alpha) && valid(beta)) {
                return Err(InvalidInput::InvalidBaumgarte { alpha, beta }.into());
            }
        }
        let non_finite = |q, qdot| IntegrationError::NonFiniteState {
            t,
            q,
            qdot,
            value: NonFiniteValue::Constraints,
        };
        let reject = |i: usize, level, residual, tolerance: SVector<S, C>| {
            let constraint = H::CONSTRAINTS[i];
            let tolerance = tolerance[i];
            Err(InvalidInput::InconsistentInitialConditions {
                constraint,
                level,
                residual,
                tolerance,
            }
            .into())
        };

        let phi = model.constraints(t, &q0);
        let g = model.constraint_jacobian(t, &q0);
        if !phi.iter().chain(g.iter()).all(|x| x.is_finite()) {
            return Err(non_finite(q0, qdot0));
        }
        let tolerance = position_tolerance(&g, &q0);
        let q = match worst_violation(&phi, &tolerance) {
            None => q0,
            Some(i) if settings.initial == InitialConditions::Reject => {
                return reject(i, ConstraintLevel::Position, phi[i], tolerance);
            }
            Some(_) => project_position(model, t, &q0, &qdot0, stats)?,
        };

        let g = model.constraint_jacobian(t, &q);
        let phidot = model.constraint_velocities(t, &q, &qdot0);
        if !crate::linalg::all_finite(phidot.as_slice()) {
            return Err(non_finite(q, qdot0));
        }
        let tolerance = velocity_tolerance(model, t, &q, &g, &qdot0);
        let qdot = match worst_violation(&phidot, &tolerance) {
            None => qdot0,
            Some(i) if settings.initial == InitialConditions::Reject => {
                return reject(i, ConstraintLevel::Velocity, phidot[i], tolerance);
            }
            Some(_) => project_velocity(model, t, &q, &qdot0)?.0,
        };
        let size = |x: SVector<S, N>| nalgebra::try_convert(x.amax()).unwrap_or(f64::NAN);
        stats.initial_position_correction = size(q - q0);
        stats.initial_velocity_correction = size(qdot - qdot0);
        Ok((q, qdot))
    }
}
