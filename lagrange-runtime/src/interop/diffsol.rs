//! A model as an ODE problem of the `diffsol` crate (feature `diffsol`).
//!
//! [`problem`] builds diffsol's `OdeSolverProblem` for the state
//! `y = (q, q̇)` (nalgebra matrices, the same nalgebra as this crate):
//! the right-hand side `(q̇, q̈)` with `q̈` from
//! [`acceleration`](crate::dynamics::acceleration()), and the Jacobian-vector
//! product `J v` with `J = [[0, I], [∂q̈/∂q, ∂q̈/∂q̇]]` from
//! [`acceleration_jacobians`]:
//! exact for a model with `#[lagrange(jacobians)]`, central differences
//! otherwise. Any of diffsol's solvers (BDF, SDIRK, Tsit45) then runs it.
//!
//! diffsol's closures cannot fail: where the model cannot be evaluated
//! they return NaN, which diffsol's error control rejects.
//!
//! ```
//! # #[cfg(feature = "diffsol")] {
//! use diffsol::{MatrixCommon, NalgebraLU, OdeSolverMethod};
//! use lagrange_runtime::interop::diffsol::problem;
//! use lagrange_runtime::nalgebra::{SMatrix, SVector, Vector1};
//! use lagrange_runtime::Lagrangian;
//!
//! /// A unit spring: `x(t) = cos t`.
//! struct Spring;
//! impl Lagrangian<1> for Spring {
//!     type Scalar = f64;
//!     const COORDINATES: [&'static str; 1] = ["x"];
//!     fn mass_matrix(&self, _t: f64, _q: &SVector<f64, 1>) -> SMatrix<f64, 1, 1> {
//!         SMatrix::<f64, 1, 1>::new(1.0)
//!     }
//!     fn forcing(&self, _t: f64, q: &SVector<f64, 1>, _qd: &SVector<f64, 1>) -> SVector<f64, 1> {
//!         -q
//!     }
//!     fn kinetic_energy(&self, _t: f64, _q: &SVector<f64, 1>, qd: &SVector<f64, 1>) -> f64 {
//!         0.5 * qd[0] * qd[0]
//!     }
//!     fn potential_energy(&self, _t: f64, q: &SVector<f64, 1>) -> f64 {
//!         0.5 * q[0] * q[0]
//!     }
//! }
//!
//! let spring = Spring;
//! let ode = problem(&spring, 0.0, Vector1::new(1.0), Vector1::new(0.0), 1e-10, 1e-10).unwrap();
//! let mut bdf = ode.bdf::<NalgebraLU<f64>>().unwrap();
//! let (ys, _) = bdf.solve_dense(&[1.0]).unwrap();
//! // Row 0 is x, column 0 the first (only) time asked for.
//! assert!((ys.inner()[(0, 0)] - 1f64.cos()).abs() < 1e-7);
//! # }
//! ```

use diffsol::{
    DiffsolError, NalgebraContext, NalgebraMat, NalgebraVec, OdeBuilder, OdeEquationsImplicit,
    OdeSolverProblem,
};
use nalgebra::SVector;

use crate::dynamics::acceleration;
use crate::dynamics::acceleration_jacobians;
use crate::model::Lagrangian;
use crate::trajectory::Stats;

/// The state `(q, q̇)` from diffsol's slice.
fn split<const N: usize>(y: &[f64]) -> (SVector<f64, N>, SVector<f64, N>) {
    (
        SVector::from_fn(|i, _| y[i]),
        SVector::from_fn(|i, _| y[N + i]),
    )
}

/// `model` from `(t0, q0, q̇0)` as a diffsol problem on `y = (q, q̇)`, with
/// relative tolerance `rtol` and absolute tolerance `atol` for every
/// component.
pub fn problem<'a, M, const N: usize>(
    model: &'a M,
    t0: f64,
    q0: SVector<f64, N>,
    qdot0: SVector<f64, N>,
    rtol: f64,
    atol: f64,
) -> Result<
    OdeSolverProblem<
        impl OdeEquationsImplicit<
            M = NalgebraMat<f64>,
            V = NalgebraVec<f64>,
            T = f64,
            C = NalgebraContext,
        > + 'a,
    >,
    DiffsolError,
>
where
    M: Lagrangian<N, Scalar = f64>,
{
    let rhs = move |y: &[f64], _p: &[f64], t: f64, dy: &mut [f64]| {
        let (q, qdot) = split::<N>(y);
        match acceleration(model, t, &q, &qdot) {
            Ok(qddot) => {
                dy[..N].copy_from_slice(qdot.as_slice());
                dy[N..].copy_from_slice(qddot.as_slice());
            }
            Err(_) => dy.fill(f64::NAN),
        }
    };
    let jacobian_times = move |y: &[f64], _p: &[f64], t: f64, v: &[f64], jv: &mut [f64]| {
        let (q, qdot) = split::<N>(y);
        let (vq, vqdot) = split::<N>(v);
        let blocks = acceleration(model, t, &q, &qdot).and_then(|qddot| {
            acceleration_jacobians(model, t, &q, &qdot, &qddot, &mut Stats::default())
        });
        match blocks {
            Ok((dq, dqdot)) => {
                jv[..N].copy_from_slice(vqdot.as_slice());
                jv[N..].copy_from_slice((dq * vq + dqdot * vqdot).as_slice());
            }
            Err(_) => jv.fill(f64::NAN),
        }
    };
    let init = move |_p: &[f64], _t: f64, y: &mut [f64]| {
        y[..N].copy_from_slice(q0.as_slice());
        y[N..].copy_from_slice(qdot0.as_slice());
    };
    OdeBuilder::<NalgebraMat<f64>>::new()
        .t0(t0)
        .rtol(rtol)
        .atol([atol])
        .rhs_implicit(rhs, jacobian_times)
        .init(init, 2 * N)
        .build()
}
