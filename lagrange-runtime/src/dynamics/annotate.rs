//! The constraint forces and residuals along a trajectory.

use nalgebra::SVector;

use super::saddle::Multipliers;
use crate::error::IntegrationError;
use crate::model::constraints::Holonomic;
use crate::trajectory::Trajectory;

/// A sample of a constrained model's trajectory with what the constraints
/// do there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConstrainedSample<S, const N: usize, const C: usize> {
    /// The sample time.
    pub t: S,
    /// Generalized coordinates at `t`.
    pub q: SVector<S, N>,
    /// Generalized velocities at `t`.
    pub qdot: SVector<S, N>,
    /// The multipliers `λ`: the constraint force on the coordinates is
    /// `−Gᵀ λ` ([`Multipliers::multipliers`]).
    pub multipliers: SVector<S, C>,
    /// `φ(t, q)`: how far the sample is off the constraints.
    pub residual: SVector<S, C>,
    /// `φ̇(t, q, q̇)`: how far its velocity is off them.
    pub velocity_residual: SVector<S, C>,
}

/// Every sample of `trajectory` with its multipliers and residuals: one
/// saddle-point solve each. Fails where a solve does (a sample at a dead
/// centre, say), with that sample's time and state.
///
/// ```text
/// let run = Dop853::new().integrate(&pendulum, 0.0, q0, v0, &times)?;
/// for s in constraints::annotate(&pendulum, &run)? {
///     let tension = 2.0 * l * s.multipliers[0]; // φ = x² + y² − l²
/// }
/// ```
///
/// (Compiled and run on `lagrange::models::CartesianPendulum`.)
#[allow(clippy::type_complexity)]
pub fn annotate<H, const N: usize, const C: usize>(
    model: &H,
    trajectory: &Trajectory<H::Scalar, N>,
) -> Result<Vec<ConstrainedSample<H::Scalar, N, C>>, IntegrationError<H::Scalar, N>>
where
    H: Holonomic<N, C> + ?Sized,
{
    trajectory
        .iter()
        .map(|s| {
            Ok(ConstrainedSample {
                t: s.t,
                q: s.q,
                qdot: s.qdot,
                multipliers: model.multipliers(s.t, &s.q, &s.qdot)?,
                residual: model.constraints(s.t, &s.q),
                velocity_residual: model.constraint_velocities(s.t, &s.q, &s.qdot),
            })
        })
        .collect()
}
