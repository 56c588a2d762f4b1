//! The methods the scenarios run, by name.

use super::{H, TOL, model};
use lagrange::IntegrationResult;
use lagrange::nalgebra::Vector2;
use lagrange::prelude::*;

/// The methods, by name: three adaptive at `TOL`, four fixed-step at `h`.
#[derive(Debug, Clone, Copy)]
pub(super) enum Method {
    Dopri5,
    Dop853,
    Radau5,
    Rk4(f64),
    Midpoint(f64),
    Gauss2(f64),
    Variational(f64),
}

use Method::*;

pub(super) const ALL: [Method; 7] = [
    Dopri5,
    Dop853,
    Radau5,
    Rk4(H),
    Midpoint(H),
    Gauss2(H),
    Variational(H),
];

impl Method {
    pub(super) fn run(
        self,
        q0: Vector2<f64>,
        v0: Vector2<f64>,
        times: &[f64],
    ) -> IntegrationResult<f64, 2> {
        let model = model();
        match self {
            Dopri5 => lagrange::Dopri5::new()
                .rtol(TOL)
                .atol(TOL)
                .max_steps(1_000_000)
                .integrate(&model, 0.0, q0, v0, times),
            Dop853 => lagrange::Dop853::new()
                .rtol(TOL)
                .atol(TOL)
                .max_steps(1_000_000)
                .integrate(&model, 0.0, q0, v0, times),
            Radau5 => lagrange::Radau5::new()
                .rtol(TOL)
                .atol(TOL)
                .max_steps(1_000_000)
                .integrate(&model, 0.0, q0, v0, times),
            Rk4(h) => lagrange::Rk4::new(h).integrate(&model, 0.0, q0, v0, times),
            Midpoint(h) => ImplicitMidpoint::new(h).integrate(&model, 0.0, q0, v0, times),
            Gauss2(h) => GaussLegendre::two_stage(h).integrate(&model, 0.0, q0, v0, times),
            Variational(h) => lagrange::Variational::new(h).integrate(&model, 0.0, q0, v0, times),
        }
    }

    pub(super) fn adaptive(self) -> bool {
        matches!(self, Dopri5 | Dop853 | Radau5)
    }

    /// The order of a fixed-step method, and the method at half its step.
    pub(super) fn refined(self) -> Option<(i32, Method)> {
        match self {
            Rk4(h) => Some((4, Rk4(h / 2.0))),
            Midpoint(h) => Some((2, Midpoint(h / 2.0))),
            Gauss2(h) => Some((4, Gauss2(h / 2.0))),
            Variational(h) => Some((2, Variational(h / 2.0))),
            _ => None,
        }
    }

    /// The global error an adaptive method's tolerance allows per unit of
    /// the flow's perturbation growth and the state's scale: `100 tol` for
    /// Dormand–Prince (as in the reference tests), `100 tol^(5/6)` for
    /// Radau5 (its documented global error law).
    pub(super) fn allowance(self) -> f64 {
        match self {
            Radau5 => 100.0 * TOL.powf(5.0 / 6.0),
            _ => 100.0 * TOL,
        }
    }
}
