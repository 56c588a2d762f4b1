//! Models with holonomic constraints on every method: the Cartesian
//! pendulum against the pendulum in its angle, the multiplier as the rod's
//! tension, drift with and without control, initial conditions, dead
//! centres, and the constrained variational step.

mod accuracy;
mod drift;
mod singular;
mod start;
mod variational;

use crate::models::CartesianPendulum;
use lagrange::models::Pendulum;
use lagrange_runtime::nalgebra::{Vector1, Vector2};
use lagrange_runtime::prelude::*;

/// The pendulum released at 1 rad (a swing of period ≈ 2.3 s).
const THETA0: f64 = 1.0;

fn pendulum() -> CartesianPendulum<f64> {
    CartesianPendulum::unit()
}

/// The Cartesian start for `θ = 1`, `θ̇ = 0`.
fn start() -> (Vector2<f64>, Vector2<f64>) {
    pendulum().state(THETA0, 0.0)
}

/// Every `dt` up to `end`.
fn every(dt: f64, end: f64) -> Vec<f64> {
    let n = (end / dt).round() as usize;
    (1..=n).map(|i| dt * i as f64).collect()
}

/// `(θ, θ̇)` of the same pendulum in its angle, `θ̈ = −(g/l) sin θ`, by
/// Dop853 at `1e-13`: its own error, ~1e-12 over a few swings, is below
/// every bound it is compared with.
fn angle_reference(times: &[f64]) -> Trajectory<f64, 1> {
    let model = Pendulum::new(1.0, 1.0, 9.81);
    let (q0, qdot0) = (Vector1::new(THETA0), Vector1::new(0.0));
    Dop853::new()
        .rtol(1e-13)
        .atol(1e-13)
        .integrate(&model, 0.0, q0, qdot0, times)
        .unwrap()
}

/// Largest `|θ − θ_ref|` over the samples.
fn angle_error(run: &Trajectory<f64, 2>, reference: &Trajectory<f64, 1>) -> f64 {
    let model = pendulum();
    assert_eq!(run.times(), reference.times());
    run.iter().zip(reference).fold(0.0, |worst, (s, r)| {
        let (theta, _) = model.angle(&s.q, &s.qdot);
        worst.max((theta - r.q[0]).abs())
    })
}
