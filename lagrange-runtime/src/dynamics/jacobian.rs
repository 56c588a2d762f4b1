//! Jacobians of the acceleration `q̈(t, q, q̇)`, for implicit methods.
//!
//! From `r(t, q, q̇, q̈(t, q, q̇)) = 0`: `∂q̈/∂q = −M⁻¹ ∂r/∂q` and
//! `∂q̈/∂q̇ = −M⁻¹ ∂r/∂q̇`. With the model's exact residual Jacobians
//! (`#[lagrange(jacobians)]`) Newton converges quadratically; without them
//! they come from forward differences of `q̈`, `N` extra right-hand sides per
//! block, counted in [`Stats::rhs_evals`](crate::trajectory::Stats). A constrained
//! model always takes the differences: its `q̈` comes from the saddle-point
//! system, which the residual Jacobians do not describe.

use nalgebra::{ComplexField, RealField, SMatrix, SVector};

use super::acceleration;
use crate::error::{IntegrationError, NonFiniteValue};
use crate::linalg::mass::{SolveError, solve_mass_matrix};
use crate::model::Lagrangian;
use crate::model::constraints::is_constrained;
use crate::trajectory::Stats;

/// `(∂q̈/∂q, ∂q̈/∂q̇)` at `(t, q, q̇)`, where `qddot` is `q̈` there.
#[allow(clippy::type_complexity)]
pub fn acceleration_jacobians<L: Lagrangian<N>, const N: usize>(
    model: &L,
    t: L::Scalar,
    q: &SVector<L::Scalar, N>,
    qdot: &SVector<L::Scalar, N>,
    qddot: &SVector<L::Scalar, N>,
    stats: &mut Stats,
) -> Result<(SMatrix<L::Scalar, N, N>, SMatrix<L::Scalar, N, N>), IntegrationError<L::Scalar, N>> {
    stats.jacobian_evals += 1;
    // The residual Jacobians describe `M q̈ − f` alone; a constrained
    // model's `q̈` also depends on `q` and `q̇` through `G` and `γ`, so it
    // is differentiated numerically.
    let exact = if is_constrained(model) {
        None
    } else {
        model.residual_jacobians(t, q, qdot, qddot)
    };
    if let Some((jq, jv)) = exact {
        let m = model.mass_matrix(t, q);
        let mut out = [SMatrix::<L::Scalar, N, N>::zeros(); 2];
        for (block, j) in out.iter_mut().zip([jq, jv]) {
            for k in 0..N {
                let col = solve_mass_matrix(&m, &(-j.column(k).into_owned())).map_err(|err| {
                    let (q, qdot) = (*q, *qdot);
                    let non_finite = |value| IntegrationError::NonFiniteState { t, q, qdot, value };
                    match err {
                        SolveError::Singular => IntegrationError::SingularMassMatrix { t, q, qdot },
                        SolveError::Indefinite => {
                            IntegrationError::IndefiniteMassMatrix { t, q, qdot }
                        }
                        SolveError::NonFiniteMassMatrix => non_finite(NonFiniteValue::MassMatrix),
                        // The right-hand side here is the model's Jacobian.
                        SolveError::NonFiniteForcing => non_finite(NonFiniteValue::Jacobian),
                    }
                })?;
                block.set_column(k, &col);
            }
        }
        return Ok((out[0], out[1]));
    }
    // Forward differences, step √ε · max(1, |x|) per component.
    let one: L::Scalar = nalgebra::convert(1.0);
    let sqrt_eps = epsilon::<L::Scalar>().sqrt();
    let mut dq = SMatrix::<L::Scalar, N, N>::zeros();
    let mut dv = SMatrix::<L::Scalar, N, N>::zeros();
    for k in 0..N {
        let h = sqrt_eps * one.max(q[k].abs());
        let mut qp = *q;
        qp[k] += h;
        let h = qp[k] - q[k]; // the step actually taken, exactly representable
        stats.rhs_evals += 1;
        let a = acceleration(model, t, &qp, qdot)?;
        dq.set_column(k, &((a - qddot) / h));

        let hv = sqrt_eps * one.max(qdot[k].abs());
        let mut vp = *qdot;
        vp[k] += hv;
        let hv = vp[k] - qdot[k];
        stats.rhs_evals += 1;
        let a = acceleration(model, t, q, &vp)?;
        dv.set_column(k, &((a - qddot) / hv));
    }
    Ok((dq, dv))
}

fn epsilon<S: RealField>() -> S {
    S::default_epsilon()
}
