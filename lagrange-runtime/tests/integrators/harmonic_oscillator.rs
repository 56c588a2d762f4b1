//! Accuracy on a problem with an exact solution: a coupled harmonic
//! oscillator (`M` full, `q̈ = -ω² q`), in `f64` and `f32`.

use crate::models::{CoupledOscillator, max_error};
use lagrange_runtime::nalgebra::Vector2;
use lagrange_runtime::prelude::*;

const OMEGA: f64 = 2.0;

fn start() -> (Vector2<f64>, Vector2<f64>) {
    (Vector2::new(1.0, -0.5), Vector2::new(0.3, 0.8))
}

/// Every 0.5 up to t = 10: a bit over three periods.
fn every_half_second() -> Vec<f64> {
    (1..=20).map(|i| 0.5 * i as f64).collect()
}

#[test]
fn rk4_global_error_falls_as_h_to_the_fourth() {
    let model = CoupledOscillator { omega: OMEGA };
    let (q0, qdot0) = start();
    let times = every_half_second();
    let errors: Vec<f64> = [0.1, 0.05, 0.025, 0.0125]
        .iter()
        .map(|&h| {
            let trajectory = Rk4::new(h)
                .integrate(&model, 0.0, q0, qdot0, &times)
                .unwrap();
            max_error(&model, &trajectory, q0, qdot0)
        })
        .collect();
    for pair in errors.windows(2) {
        let order = (pair[0] / pair[1]).log2();
        // Global error C h⁴ + O(h⁵): the observed order approaches 4 from the
        // h⁵ term (≈ 3.98 at h = 0.1), and rounding (~1e-14) is far below the
        // smallest error here (~1e-7), so ±0.2 has room for the first but not
        // for an order-3 method.
        assert!(
            (order - 4.0).abs() < 0.2,
            "observed order {order}, errors {errors:?}"
        );
    }
}

#[test]
fn rk4_steps_are_exactly_h_when_samples_are_multiples_of_it() {
    let model = CoupledOscillator { omega: OMEGA };
    let (q0, qdot0) = start();
    let trajectory = Rk4::new(0.1)
        .integrate(&model, 0.0, q0, qdot0, &every_half_second())
        .unwrap();
    // 10 / 0.1 steps, four evaluations each; a spurious sliver step per
    // sample (from 0.5 / 0.1 rounding to 5.000…01) would show up here.
    assert_eq!(trajectory.stats().steps_accepted, 100);
    assert_eq!(trajectory.stats().rhs_evals, 400);
    assert_eq!(trajectory.times(), every_half_second().as_slice());
}

#[test]
fn fixed_steps_take_one_step_per_sample_spaced_h_apart_even_late_in_a_run() {
    let model = CoupledOscillator { omega: OMEGA };
    let (q0, qdot0) = start();
    // i · 0.01 carries rounding of a few ulps of t, ~1e-14 at t = 100: a
    // thousand times an ulp of h. Forgiving only ulps of h would give most
    // intervals a second, sliver step.
    let times: Vec<f64> = (1..=10_000).map(|i| 0.01 * i as f64).collect();
    let trajectory = Rk4::new(0.01)
        .integrate(&model, 0.0, q0, qdot0, &times)
        .unwrap();
    assert_eq!(trajectory.stats().steps_accepted, 10_000);
}

#[test]
fn dopri5_error_is_a_small_multiple_of_the_tolerance() {
    let model = CoupledOscillator { omega: OMEGA };
    let (q0, qdot0) = start();
    let tol = 1e-10;
    let trajectory = Dopri5::new()
        .rtol(tol)
        .atol(tol)
        .integrate(&model, 0.0, q0, qdot0, &every_half_second())
        .unwrap();
    let error = max_error(&model, &trajectory, q0, qdot0);
    // Each step's estimated local error is ≤ tol · (1 + |y|) ≤ 3.2 tol, and a
    // harmonic oscillator neither damps nor amplifies errors, so they add up:
    // ~500 steps could give 1.6e-7 at worst. In practice DOPRI5 propagates the
    // fifth-order solution, whose error is far below the fourth-order
    // estimate, and lands near 10 tol over three periods (Hairer's
    // "tolerance proportionality"). 100 tol fails a controller that accepts
    // steps 2-3× too large, or a stage coefficient off.
    assert!(error < 100.0 * tol, "error {error:e} at tol {tol:e}");
}

#[test]
fn dopri5_error_falls_in_proportion_to_the_tolerance() {
    let model = CoupledOscillator { omega: OMEGA };
    let (q0, qdot0) = start();
    let errors: Vec<f64> = [1e-6, 1e-8, 1e-10, 1e-12]
        .iter()
        .map(|&tol| {
            let trajectory = Dopri5::new()
                .rtol(tol)
                .atol(tol)
                .integrate(&model, 0.0, q0, qdot0, &every_half_second())
                .unwrap();
            max_error(&model, &trajectory, q0, qdot0)
        })
        .collect();
    for pair in errors.windows(2) {
        // Steps scale as tol^(1/5) and the fifth-order error as h⁵, so the
        // error should fall ~100× per 100× in tolerance; 30× allows for the
        // step-count rounding of short runs.
        assert!(pair[0] / pair[1] > 30.0, "errors {errors:?}");
    }
}

#[test]
fn dense_output_between_steps_is_as_accurate_as_the_steps() {
    let model = CoupledOscillator { omega: OMEGA };
    let (q0, qdot0) = start();
    let dopri5 = Dopri5::new().rtol(1e-10).atol(1e-10);
    // t = 1 ends the last step exactly, so its error is the steps' own.
    let at_step_end = dopri5.integrate(&model, 0.0, q0, qdot0, &[1.0]).unwrap();
    let step_error = max_error(&model, &at_step_end, q0, qdot0);
    // 1001 samples, almost all strictly inside steps (~50 steps).
    let dense_times: Vec<f64> = (0..=1000).map(|i| 0.001 * i as f64).collect();
    let dense = dopri5
        .integrate(&model, 0.0, q0, qdot0, &dense_times)
        .unwrap();
    let dense_error = max_error(&model, &dense, q0, qdot0);
    // The continuous extension is fourth order, so between step ends it adds
    // an O(h⁵) error of the size of one local error, at most about the
    // global error here: ≤ 2×. A third-order (cubic Hermite) interpolant
    // would add O(h⁴), ~1e-8 at these steps.
    assert!(
        dense_error <= 2.0 * step_error,
        "dense {dense_error:e} vs step ends {step_error:e}"
    );
}

#[test]
fn dense_sampling_does_not_change_the_steps_or_the_final_state() {
    let model = CoupledOscillator { omega: OMEGA };
    let (q0, qdot0) = start();
    let dopri5 = Dopri5::new().rtol(1e-9).atol(1e-9);
    let sparse = dopri5.integrate(&model, 0.0, q0, qdot0, &[10.0]).unwrap();
    let dense_times: Vec<f64> = (1..=10_000).map(|i| 0.001 * i as f64).collect();
    let dense = dopri5
        .integrate(&model, 0.0, q0, qdot0, &dense_times)
        .unwrap();
    assert_eq!(dense.len(), 10_000);
    assert_eq!(sparse.stats(), dense.stats());
    assert_eq!(sparse.last(), dense.last());
}

#[test]
fn dopri5_reuses_its_last_stage_for_six_evaluations_per_step() {
    let model = CoupledOscillator { omega: OMEGA };
    let (q0, qdot0) = start();
    let trajectory = Dopri5::new()
        .integrate(&model, 0.0, q0, qdot0, &every_half_second())
        .unwrap();
    let stats = trajectory.stats();
    // Two evaluations for the start (f(t0) and hinit's Euler probe), then
    // six per attempted step: the seventh stage is the next step's first.
    let attempts = stats.steps_accepted + stats.steps_rejected;
    assert_eq!(stats.rhs_evals, 2 + 6 * attempts);
}

#[test]
fn samples_at_the_start_time_are_the_initial_state() {
    let model = CoupledOscillator { omega: OMEGA };
    let (q0, qdot0) = start();
    let times = [0.0, 0.0, 1.0, 1.0];
    for trajectory in [
        Dopri5::new().integrate(&model, 0.0, q0, qdot0, &times),
        Dop853::new().integrate(&model, 0.0, q0, qdot0, &times),
        Rk4::new(0.1).integrate(&model, 0.0, q0, qdot0, &times),
        ExplicitEuler::new(0.1).integrate(&model, 0.0, q0, qdot0, &times),
        SymplecticEuler::new(0.1).integrate(&model, 0.0, q0, qdot0, &times),
    ] {
        let trajectory = trajectory.unwrap();
        assert_eq!(trajectory.times(), &times);
        for sample in trajectory.iter().take(2) {
            assert_eq!((sample.q, sample.qdot), (q0, qdot0));
        }
        assert_eq!(trajectory.get(2), trajectory.get(3));
    }
}

#[test]
fn no_sample_times_means_no_work() {
    let model = CoupledOscillator { omega: OMEGA };
    let (q0, qdot0) = start();
    for trajectory in [
        integrate(&model, 0.0, q0, qdot0, &[]),
        Dop853::new().integrate(&model, 0.0, q0, qdot0, &[]),
    ] {
        let trajectory = trajectory.unwrap();
        assert!(trajectory.is_empty());
        assert_eq!(trajectory.stats().rhs_evals, 0);
    }
}

#[test]
fn single_precision_oscillator_works_with_rk4_and_dopri5() {
    let model = CoupledOscillator { omega: 2.0f32 };
    let (q0, qdot0) = (Vector2::new(1.0f32, -0.5), Vector2::new(0.3f32, 0.8));
    let times: Vec<f32> = (1..=20).map(|i| 0.5 * i as f32).collect();

    let rk4 = Rk4::new(0.01f32)
        .integrate(&model, 0.0, q0, qdot0, &times)
        .unwrap();
    let rk4_error = max_error(&model, &rk4, q0, qdot0);
    // Truncation is negligible (~1e-10 at h = 0.01); rounding dominates:
    // ~ε_f32 |y| ≈ 2e-7 per step, 1000 steps of mostly cancelling rounding.
    // Linear accumulation would be 2e-4; a random walk √1000 · 2e-7 ≈ 7e-6.
    assert!(rk4_error < 3e-5, "f32 RK4 error {rk4_error:e}");

    let tol = 1e-5f32;
    let dopri5 = Dopri5::new()
        .rtol(tol)
        .atol(tol)
        .integrate(&model, 0.0, q0, qdot0, &times)
        .unwrap();
    let dopri5_error = max_error(&model, &dopri5, q0, qdot0);
    // Same argument as in f64: a small multiple of tol (≈ 10 tol observed).
    assert!(
        dopri5_error < 100.0 * tol,
        "f32 DOPRI5 error {dopri5_error:e}"
    );
}
