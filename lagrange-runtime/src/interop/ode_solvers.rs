//! A model as a first-order system for the `ode_solvers` crate (feature
//! `ode_solvers`).
//!
//! `ode_solvers` integrates `ẏ = F(t, y)` for a state vector of its own
//! nalgebra version; [`FirstOrder`] is that system for `y = (q, q̇)` of
//! length `2N`, `F = (q̇, q̈)` with `q̈` from
//! [`acceleration`](crate::dynamics::acceleration()). The state's length is
//! checked at compile time.
//!
//! `ode_solvers`' `System::system` cannot fail. Where the model cannot be
//! evaluated (a singular mass matrix, a NaN), `F` is NaN, the first such
//! error is kept ([`FirstOrder::error`]), and `solout` stops the
//! integration at the next accepted step.
//!
//! ```
//! # #[cfg(feature = "ode_solvers")] {
//! use lagrange_runtime::interop::ode_solvers::FirstOrder;
//! use lagrange_runtime::nalgebra::{SMatrix, SVector};
//! use lagrange_runtime::Lagrangian;
//! use ode_solvers::dop_shared::OutputType;
//! use ode_solvers::{Dopri5, Vector2};
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
//! // Their Dopri5 with Hairer's defaults and sparse output: the state
//! // after each accepted step, the last at t = 1. (Their dense output at
//! // exactly the end time returned a wrong state in our trials; use
//! // sparse output to read the final state.)
//! let (rtol, atol) = (1e-10, 1e-10);
//! let mut solver = Dopri5::from_param(
//!     FirstOrder::new(&Spring), 0.0, 1.0, 1.0, Vector2::new(1.0, 0.0), rtol, atol,
//!     0.9, 0.04, 0.2, 10.0, 1.0, 0.0, 100_000, 1000, OutputType::Sparse,
//! );
//! solver.integrate().unwrap();
//! assert_eq!(solver.x_out().last(), Some(&1.0));
//! let y = solver.y_out().last().unwrap();
//! // Global error of a 1e-10 local error control over a radian: ~1e-10.
//! assert!((y[0] - 1f64.cos()).abs() < 1e-8);
//! # }
//! ```

use core::cell::Cell;

use nalgebra::SVector;

use crate::dynamics::acceleration;
use crate::error::IntegrationError;
use crate::model::Lagrangian;

/// `model` as the first-order system `ẏ = (q̇, q̈)` on `y = (q, q̇)`.
pub struct FirstOrder<'a, M: Lagrangian<N>, const N: usize> {
    model: &'a M,
    error: Cell<Option<IntegrationError<M::Scalar, N>>>,
}

impl<'a, M: Lagrangian<N, Scalar = f64>, const N: usize> FirstOrder<'a, M, N> {
    /// The system of `model`.
    pub fn new(model: &'a M) -> Self {
        Self {
            model,
            error: Cell::new(None),
        }
    }

    /// The first evaluation that failed, with its time and state: why
    /// `ode_solvers` stopped early, or why its result holds NaN.
    pub fn error(&self) -> Option<IntegrationError<f64, N>> {
        let error = self.error.take();
        self.error.set(error.clone());
        error
    }
}

impl<M, const N: usize, const D: usize> ::ode_solvers::System<f64, ::ode_solvers::SVector<f64, D>>
    for FirstOrder<'_, M, N>
where
    M: Lagrangian<N, Scalar = f64>,
{
    fn system(
        &self,
        t: f64,
        y: &::ode_solvers::SVector<f64, D>,
        dy: &mut ::ode_solvers::SVector<f64, D>,
    ) {
        const {
            assert!(
                D == 2 * N,
                "the ode_solvers state must hold q and q̇: length 2N"
            )
        };
        let q = SVector::<f64, N>::from_fn(|i, _| y[i]);
        let qdot = SVector::<f64, N>::from_fn(|i, _| y[N + i]);
        match acceleration(self.model, t, &q, &qdot) {
            Ok(qddot) => {
                for i in 0..N {
                    dy[i] = qdot[i];
                    dy[N + i] = qddot[i];
                }
            }
            Err(error) => {
                dy.fill(f64::NAN);
                let first = self.error.take().unwrap_or(error);
                self.error.set(Some(first));
            }
        }
    }

    /// Stops the integration once an evaluation has failed.
    fn solout(
        &mut self,
        _t: f64,
        _y: &::ode_solvers::SVector<f64, D>,
        _dy: &::ode_solvers::SVector<f64, D>,
    ) -> bool {
        let failed = self.error.take();
        let stop = failed.is_some();
        self.error.set(failed);
        stop
    }
}
