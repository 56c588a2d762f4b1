//! The derivatives the analyses share: exact from the model's residual
//! Jacobians, else central differences.

use nalgebra::{ComplexField, RealField, SMatrix, SVector};

use super::{AnalysisError, Derivatives};
use crate::error::{IntegrationError, NonFiniteValue};
use crate::model::Lagrangian;
use crate::model::constraints::is_constrained;

/// The central-difference step for a variable of size `x`:
/// `ε^(1/3) max(1, |x|)`, which balances the truncation error `h² |F'''| / 6`
/// against the rounding error `ε |F| / h`, leaving `≈ ε^(2/3)` relative.
pub(super) fn central_step<S: RealField + Copy>(x: S) -> S {
    let third: S = nalgebra::convert(1.0 / 3.0);
    S::default_epsilon().powf(third) * S::one().max(x.abs())
}

/// How much an entry of a derivative may be off, relative to the largest
/// entry: rounding for exact ones (`100 N ε`, the evaluation of a sum of
/// `N` products with some cancellation), `100 ε^(2/3)` for central
/// differences (their error estimate, with the derivatives of order three
/// of the model at most a hundred times its second).
pub(super) fn relative_noise<S: RealField + Copy>(derivatives: Derivatives, n: usize) -> S {
    let eps = S::default_epsilon();
    let hundred: S = nalgebra::convert(100.0);
    match derivatives {
        Derivatives::Exact => hundred * nalgebra::convert::<f64, S>(n.max(1) as f64) * eps,
        Derivatives::CentralDifferences => hundred * eps.powf(nalgebra::convert(2.0 / 3.0)),
        Derivatives::Extrapolated => hundred * eps.powf(nalgebra::convert(0.8)),
    }
}

/// Refuses a constrained model, whose analyses are not implemented.
pub(super) fn refuse_constrained<L: Lagrangian<N>, const N: usize>(
    model: &L,
    t: L::Scalar,
    q: &SVector<L::Scalar, N>,
) -> Result<(), AnalysisError<L::Scalar, N>> {
    if is_constrained(model) {
        Err(AnalysisError::Constrained { t, q: *q })
    } else {
        Ok(())
    }
}

/// `f(t, q, 0)` and `∂f/∂q` at rest: `−∂r/∂q` at `(q, q̇ = 0, q̈ = 0)` when
/// the model has exact Jacobians, else central differences of `f`
/// (`2 N` evaluations of the forcing).
#[allow(clippy::type_complexity)]
pub(super) fn forcing_at_rest<L: Lagrangian<N>, const N: usize>(
    model: &L,
    t: L::Scalar,
    q: &SVector<L::Scalar, N>,
) -> Result<
    (SVector<L::Scalar, N>, SMatrix<L::Scalar, N, N>, Derivatives),
    AnalysisError<L::Scalar, N>,
> {
    let zero = SVector::<L::Scalar, N>::zeros();
    let non_finite = |q: &SVector<L::Scalar, N>, value| IntegrationError::NonFiniteState {
        t,
        q: *q,
        qdot: zero,
        value,
    };
    if !t.is_finite() || q.iter().any(|x| !x.is_finite()) {
        return Err(non_finite(q, NonFiniteValue::State).into());
    }
    let f = model.forcing(t, q, &zero);
    if f.iter().any(|x| !x.is_finite()) {
        return Err(non_finite(q, NonFiniteValue::Forcing).into());
    }
    let (jacobian, derivatives) = match model.residual_jacobians(t, q, &zero, &zero) {
        Some((dr_dq, _)) => (-dr_dq, Derivatives::Exact),
        None => {
            let mut jacobian = SMatrix::<L::Scalar, N, N>::zeros();
            for k in 0..N {
                let (plus, minus) = shifted(q, k);
                let fp = model.forcing(t, &plus, &zero);
                let fm = model.forcing(t, &minus, &zero);
                jacobian.set_column(k, &((fp - fm) / (plus[k] - minus[k])));
            }
            (jacobian, Derivatives::CentralDifferences)
        }
    };
    if jacobian.iter().any(|x| !x.is_finite()) {
        return Err(non_finite(q, NonFiniteValue::Jacobian).into());
    }
    Ok((f, jacobian, derivatives))
}

/// `x` moved by `± central_step(x[k])` in component `k`; the steps actually
/// taken are `plus[k] − x[k]` and `x[k] − minus[k]`, exactly representable.
pub(super) fn shifted<S: RealField + Copy, const N: usize>(
    x: &SVector<S, N>,
    k: usize,
) -> (SVector<S, N>, SVector<S, N>) {
    let h = central_step(x[k]);
    let (mut plus, mut minus) = (*x, *x);
    plus[k] += h;
    minus[k] -= h;
    (plus, minus)
}

/// `√ε`: the default relative tolerance of an equilibrium, the accuracy
/// to which a point found by another method (a long run damped to rest,
/// say) usually is one.
pub(super) fn sqrt_epsilon<S: RealField + Copy>() -> S {
    S::default_epsilon().sqrt()
}
