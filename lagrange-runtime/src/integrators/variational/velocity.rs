//! Velocities from momenta: the variational integrator carries `(q, p)`
//! and hands out `(q, q̇)`.

use nalgebra::{RealField, SVector};

use super::lacks;
use crate::driver::Recorder;
use crate::error::{IntegrationError, NonFiniteValue};
use crate::linalg::all_finite;
use crate::linalg::mass::{SolveError, solve_mass_matrix};
use crate::model::Lagrangian;
use crate::trajectory::Stats;

/// `q̇ = M(t, q)⁻¹ (p − ∂L/∂q̇(t, q, 0))`: the velocity with momenta `p`,
/// for a Lagrangian quadratic in `q̇`.
///
/// Errors report the last midpoint velocity as `q̇`, the integrator's best
/// knowledge of it (within `O(h)`).
pub(super) fn velocity<L: Lagrangian<N>, const N: usize>(
    stats: &mut Stats,
    model: &L,
    t: L::Scalar,
    q: &SVector<L::Scalar, N>,
    p: &SVector<L::Scalar, N>,
    velocities: &VelocityHistory<L::Scalar, N>,
) -> Result<SVector<L::Scalar, N>, IntegrationError<L::Scalar, N>> {
    stats.rhs_evals += 1;
    let near = velocities.latest();
    let non_finite = |value| IntegrationError::NonFiniteState {
        t,
        q: *q,
        qdot: near,
        value,
    };
    if !all_finite(q.as_slice()) {
        return Err(non_finite(NonFiniteValue::State));
    }
    if !all_finite(p.as_slice()) {
        return Err(non_finite(NonFiniteValue::Momentum));
    }
    let offset = model
        .momentum(t, q, &SVector::zeros())
        .ok_or_else(|| lacks("momentum"))?;
    if !all_finite(offset.as_slice()) {
        return Err(non_finite(NonFiniteValue::Momentum));
    }
    let mut m = model.mass_matrix(t, q);
    if let Some(k) = velocities.augment {
        let metric = super::augmented::Metric { k, t, q };
        if let Some(added) = model.visit_constraints(metric) {
            m += added;
        }
    }
    solve_mass_matrix(&m, &(p - offset)).map_err(|err| match err {
        SolveError::NonFiniteMassMatrix => non_finite(NonFiniteValue::MassMatrix),
        SolveError::NonFiniteForcing => non_finite(NonFiniteValue::Momentum),
        SolveError::Singular => IntegrationError::SingularMassMatrix {
            t,
            q: *q,
            qdot: near,
        },
        SolveError::Indefinite => IntegrationError::IndefiniteMassMatrix {
            t,
            q: *q,
            qdot: near,
        },
    })
}

/// `error` at `(t, q, p)`, with `q̇` converted from `p` for the report; if
/// even that conversion fails, its own error instead.
pub(super) fn with_velocity<L: Lagrangian<N>, const N: usize>(
    rec: &mut Recorder<'_, L::Scalar, N>,
    model: &L,
    (t, q, p): (L::Scalar, SVector<L::Scalar, N>, SVector<L::Scalar, N>),
    velocities: &VelocityHistory<L::Scalar, N>,
    error: impl FnOnce(SVector<L::Scalar, N>) -> IntegrationError<L::Scalar, N>,
) -> IntegrationError<L::Scalar, N> {
    match velocity(&mut rec.stats, model, t, &q, &p, velocities) {
        Ok(qdot) => error(qdot),
        Err(other) => other,
    }
}

/// The two latest midpoint velocities (the first is `q̇_0` at `t_0`), for the
/// predictor.
pub(super) struct VelocityHistory<S, const N: usize> {
    older: Option<(S, SVector<S, N>)>,
    newer: (S, SVector<S, N>),
    /// `k` of the augmented Lagrangian (`augmented.rs`), for a model whose
    /// `M` is regular only with its constraints: the run's Legendre
    /// transform is then `p = (M + k GᵀG) q̇ + ∂L/∂q̇(q, 0)`.
    pub(super) augment: Option<S>,
}

impl<S: RealField + Copy, const N: usize> VelocityHistory<S, N> {
    pub(super) fn new(t0: S, qdot0: SVector<S, N>, augment: Option<S>) -> Self {
        Self {
            older: None,
            newer: (t0, qdot0),
            augment,
        }
    }

    pub(super) fn push(&mut self, t: S, v: SVector<S, N>) {
        self.older = Some(self.newer);
        self.newer = (t, v);
    }

    pub(super) fn latest(&self) -> SVector<S, N> {
        self.newer.1
    }

    /// The midpoint velocity at `t`, extrapolated linearly from the last two:
    /// `O(h²)` accurate for free, where `q̇_k` (the classic predictor
    /// `q_{k+1} ≈ q_k + h q̇_k`) would cost a solve with `M` and be only
    /// `O(h)` accurate.
    pub(super) fn predict(&self, t: S) -> SVector<S, N> {
        let (t_b, v_b) = self.newer;
        match self.older {
            Some((t_a, v_a)) => v_b + (v_b - v_a) * ((t - t_b) / (t_b - t_a)),
            None => v_b,
        }
    }
}
