//! Whom to blame for a non-finite value: the inputs a model evaluates
//! with at that state (a controller's NaN), or the value itself.

use nalgebra::{RealField, SVector};

use crate::error::{IntegrationError, NonFiniteValue};
use crate::model::Lagrangian;
use crate::model::inputs::{Inputs, Visitor};

/// The input that explains a non-finite evaluation at `(t, q, q̇)`:
/// [`NonFiniteValue::Inputs`](NonFiniteValue::Inputs) when the
/// inputs the model evaluates with there (its controller's) are not
/// finite, else `value`.
pub(crate) fn blame<L: Lagrangian<N>, const N: usize>(
    model: &L,
    value: NonFiniteValue,
    t: L::Scalar,
    q: &SVector<L::Scalar, N>,
    qdot: &SVector<L::Scalar, N>,
) -> NonFiniteValue {
    use NonFiniteValue as V;
    struct Finite<'a, S, const N: usize> {
        t: S,
        q: &'a SVector<S, N>,
        qdot: &'a SVector<S, N>,
    }
    impl<S: RealField + Copy, const N: usize> Visitor<S, N> for Finite<'_, S, N> {
        type Output = bool;
        fn visit<A, const K: usize>(self, model: &A) -> bool
        where
            A: Inputs<N, K, Scalar = S> + ?Sized,
        {
            let u = model.inputs_at(self.t, self.q, self.qdot);
            crate::linalg::all_finite(u.as_slice())
        }
    }
    match value {
        V::Forcing | V::LagrangianGradient | V::NonconservativeForces | V::Jacobian
            if model.visit_inputs(Finite { t, q, qdot }) == Some(false) =>
        {
            V::Inputs
        }
        _ => value,
    }
}

/// An error of an evaluation at a state, with a non-finite value blamed on
/// the inputs where they are to blame (see [`blame`]).
pub(crate) fn blame_error<L: Lagrangian<N>, const N: usize>(
    model: &L,
    error: IntegrationError<L::Scalar, N>,
) -> IntegrationError<L::Scalar, N> {
    match error {
        IntegrationError::NonFiniteState { t, q, qdot, value } => {
            let value = blame(model, value, t, &q, &qdot);
            IntegrationError::NonFiniteState { t, q, qdot, value }
        }
        error => error,
    }
}
