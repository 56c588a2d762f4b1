//! What the implicit methods keep over long runs: no energy drift on a
//! model with a configuration-dependent mass matrix, time reversibility,
//! and quadratic invariants to round-off. RK4, which keeps none of them,
//! runs alongside to show that each test can fail.

use crate::models::{CartPole, stages};
use lagrange::Method;
use lagrange::models::Kepler;
use lagrange_runtime::Sample;
use lagrange_runtime::nalgebra::Vector2;
use lagrange_runtime::prelude::*;

/// The pendulum released from 1.2 rad while the cart is pushed: a large,
/// nonlinear swing with period ≈ 1.5.
fn start() -> (Vector2<f64>, Vector2<f64>) {
    (Vector2::new(0.0, 1.2), Vector2::new(0.3, 0.0))
}

/// Least-squares slope of `y` against `t`.
fn slope(t: &[f64], y: &[f64]) -> f64 {
    let n = t.len() as f64;
    let (t_mean, y_mean) = (t.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let covariance: f64 = t
        .iter()
        .zip(y)
        .map(|(t, y)| (t - t_mean) * (y - y_mean))
        .sum();
    let variance: f64 = t.iter().map(|t| (t - t_mean).powi(2)).sum();
    covariance / variance
}

/// `(energy drift over the run, largest |energy error|)` of `trajectory`,
/// the drift being the fitted slope of `E(t) − E(0)` times the duration.
fn drift_and_size(model: &CartPole, trajectory: &Trajectory<f64, 2>) -> (f64, f64) {
    let (q0, qdot0) = start();
    let e0 = model.energy(0.0, &q0, &qdot0);
    let errors: Vec<f64> = trajectory
        .iter()
        .map(|s| model.energy(s.t, &s.q, &s.qdot) - e0)
        .collect();
    let times = trajectory.times();
    let duration = times[times.len() - 1] - times[0];
    let size = errors.iter().fold(0.0, |m: f64, e| m.max(e.abs()));
    (slope(times, &errors) * duration, size)
}

#[test]
fn cart_pole_energy_has_no_drift_over_a_hundred_thousand_steps() {
    // M(θ) makes the Hamiltonian non-separable, and in (q, q̇) these methods
    // are not symplectic for it (see the integrators module docs); what they
    // are is reversible, and this model is reversible and integrable, where
    // reversible methods have no energy drift (Hairer, Lubich & Wanner,
    // Geometric Numerical Integration, ch. XI). This is the measurement.
    let model = CartPole::new(true);
    let (q0, qdot0) = start();
    let h = 0.05;
    // 1e5 steps, 5000 time units, ~3300 swings; a sample every 10 steps.
    let times: Vec<f64> = (1..=10_000).map(|i| 10.0 * h * i as f64).collect();
    for method in Method::GAUSS {
        let trajectory = method
            .with_step(h)
            .integrate(&model, 0.0, q0, qdot0, &times)
            .unwrap();
        let (drift, size) = drift_and_size(&model, &trajectory);
        // A bounded error of period P and size A has a fitted slope of at
        // most ~12 A P / T² (T the duration), i.e. a drift of 12 A / 3300 ≈
        // 0.004 A over these ~3300 periods; a linear drift gives ~A.
        // (Observed: ≤ 2e-4 A for all three.)
        assert!(
            drift.abs() < 0.01 * size,
            "{method:?}: energy drift {drift:e} with errors up to {size:e}"
        );
        // And the errors are the method's O(h^{2s}) size: midpoint 3e-2,
        // Gauss-2 2e-4, Gauss-3 4e-6 observed (of |E| ≈ 3.5). Round-off
        // piling up over 1e5 steps would show as drift, not size.
        let expected = [4e-2, 3e-4, 5e-6][stages(method) - 1];
        assert!(size < expected, "{method:?}: energy error {size:e}");
    }

    // RK4 at the same step loses energy steadily: its fitted drift is the
    // whole error (observed −0.98 of it, ΔE reaching −1.9).
    let trajectory = Rk4::new(h)
        .integrate(&model, 0.0, q0, qdot0, &times)
        .unwrap();
    let (drift, size) = drift_and_size(&model, &trajectory);
    assert!(drift < -0.5 * size, "RK4: drift {drift:e}, errors {size:e}");
}

#[test]
fn flipping_the_velocities_retraces_the_cart_pole_to_round_off() {
    // T is quadratic in q̇ and nothing depends on t, so (q, q̇) ↦ (q, −q̇)
    // reverses the motion; a symmetric method inherits this exactly
    // (Hairer, Lubich & Wanner, Thm. V.1.5). Forward n steps, flip, forward
    // n steps again: back at the start, flipped, up to the stage equations'
    // residual (10 ε of |y| ≤ 5, ~1e-14 per step) accumulated over 2000
    // steps (≤ 2e-11 if it all added up) and grown by the oscillator's
    // phase shear over 100 time units (≲ 30×): ≤ 1e-9. Observed ≤ 4e-11.
    let model = CartPole::new(true);
    let (q0, qdot0) = start();
    let (h, t_end) = (0.05, 50.0);
    let there_and_back = |forward: &dyn Fn(Vector2<f64>, Vector2<f64>) -> Sample<f64, 2>| {
        let there = forward(q0, qdot0);
        let back = forward(there.q, -there.qdot);
        (back.q - q0).amax().max((back.qdot + qdot0).amax())
    };
    for method in Method::GAUSS {
        let miss = there_and_back(&|q, qdot| {
            let trajectory = method
                .with_step(h)
                .integrate(&model, 0.0, q, qdot, &[t_end])
                .unwrap();
            trajectory.last().unwrap()
        });
        assert!(miss < 1e-9, "{method:?}: back to {miss:e} from the start");
    }
    let miss = there_and_back(&|q, qdot| {
        let trajectory = Rk4::new(h)
            .integrate(&model, 0.0, q, qdot, &[t_end])
            .unwrap();
        trajectory.last().unwrap()
    });
    // RK4 is not symmetric: its O(h⁴) errors add up instead of cancelling.
    assert!(miss > 1e-3, "RK4 came back to {miss:e}");
}

#[test]
fn kepler_angular_momentum_is_conserved_to_round_off() {
    // In Cartesian coordinates M = I and the angular momentum x ẏ − y ẋ is a
    // quadratic invariant of (q, q̇); Gauss methods conserve every one
    // (b_i a_ij + b_j a_ji = b_i b_j). The stage equations hold to 10 ε of
    // |y| ≤ 2 per step, which moves L by ≲ 1e-14; over 1e4 steps that is
    // ≤ 1e-10 even if it all added up. Observed ≤ 3e-12.
    // Without exact Jacobians: the methods difference the acceleration.
    let model = Kepler::new(1.0).without_jacobians();
    let (q0, qdot0) = model.model().pericentre(0.6);
    let l0 = Kepler::angular_momentum(&q0, &qdot0);
    // 200 steps per orbit, 50 orbits; fast through perihelion.
    let h = 2.0 * std::f64::consts::PI / 200.0;
    let times: Vec<f64> = (1..=1000).map(|i| 10.0 * h * i as f64).collect();
    let worst = |trajectory: &Trajectory<f64, 2>| {
        trajectory
            .iter()
            .map(|s| (Kepler::angular_momentum(&s.q, &s.qdot) - l0).abs())
            .fold(0.0, f64::max)
    };
    for method in Method::GAUSS {
        let trajectory = method
            .with_step(h)
            .integrate(&model, 0.0, q0, qdot0, &times)
            .unwrap();
        let change = worst(&trajectory);
        assert!(change < 1e-10, "{method:?}: L changed by {change:e}");
    }
    // RK4 changes it by its truncation error (observed 2e-5).
    let trajectory = Rk4::new(h)
        .integrate(&model, 0.0, q0, qdot0, &times)
        .unwrap();
    assert!(worst(&trajectory) > 1e-7);
}
