//! Implicit midpoint and Gauss–Legendre on a model whose mass matrix depends
//! on the configuration (a pendulum on a free cart): observed orders, exact
//! against finite-difference Jacobians, the work they count, and sample
//! times hit exactly.

use crate::models::{CartPole, CoupledOscillator, max_error, stages};
use lagrange::Method;
use lagrange_runtime::Stats;
use lagrange_runtime::dynamics::acceleration;
use lagrange_runtime::dynamics::acceleration_jacobians;
use lagrange_runtime::nalgebra::Vector2;
use lagrange_runtime::prelude::*;

/// The pendulum released from 1.2 rad while the cart is pushed: a large,
/// nonlinear swing, with both coordinates moving.
fn start() -> (Vector2<f64>, Vector2<f64>) {
    (Vector2::new(0.0, 1.2), Vector2::new(0.3, 0.0))
}

/// Max-norm distance between two states `(q, q̇)`.
fn distance(a: (Vector2<f64>, Vector2<f64>), b: (Vector2<f64>, Vector2<f64>)) -> f64 {
    (a.0 - b.0).amax().max((a.1 - b.1).amax())
}

#[test]
fn observed_orders_are_two_four_and_six_on_a_cart_pole() {
    let model = CartPole::new(true);
    let (q0, qdot0) = start();
    let t_end = 2.0; // about 1.3 swings
    let reference = Dopri5::new()
        .rtol(1e-14)
        .atol(1e-14)
        .integrate(&model, 0.0, q0, qdot0, &[t_end])
        .unwrap()
        .last()
        .unwrap();
    // Largest steps in the asymptotic regime, found by halving: above them
    // the h^{p+1} term still moves the observed order by more than 0.1.
    for (method, h0) in [
        (Method::ImplicitMidpoint, 0.02),
        (Method::GaussLegendre2, 0.025),
        (Method::GaussLegendre3, 0.04),
    ] {
        let errors: Vec<f64> = [h0, h0 / 2.0, h0 / 4.0]
            .iter()
            .map(|&h| {
                let end = method
                    .with_step(h)
                    .integrate(&model, 0.0, q0, qdot0, &[t_end])
                    .unwrap()
                    .last()
                    .unwrap();
                distance((end.q, end.qdot), (reference.q, reference.qdot))
            })
            .collect();
        for pair in errors.windows(2) {
            let order = (pair[0] / pair[1]).log2();
            // The smallest error here is Gauss-3's ~4e-12 (midpoint 1e-4,
            // Gauss-2 1e-9), ≥ 300× the reference's error and the round-off
            // of 200 steps (both ~1e-14), which thus move the observed
            // order by < 0.01; the next term of the error expansion moves it
            // by < 0.05 at these steps. An order one lower or higher is off
            // by 1.
            assert!(
                (order - method.order() as f64).abs() < 0.2,
                "{method:?}: observed order {order}, errors {errors:?}"
            );
        }
    }
}

#[test]
fn cart_pole_exact_jacobians_match_finite_differences() {
    // The hand-derived residual Jacobians of the test model, checked before
    // the next test relies on them.
    let (exact, differenced) = (CartPole::new(true), CartPole::new(false));
    for (q, qdot) in [
        start(),
        (Vector2::new(0.3, -2.0), Vector2::new(-1.0, 4.0)),
        (Vector2::new(-5.0, 0.1), Vector2::new(2.0, -0.5)),
    ] {
        let mut stats = Stats::default();
        let qddot = acceleration(&exact, 0.0, &q, &qdot).unwrap();
        let (jq, jv) = acceleration_jacobians(&exact, 0.0, &q, &qdot, &qddot, &mut stats).unwrap();
        let (dq, dv) =
            acceleration_jacobians(&differenced, 0.0, &q, &qdot, &qddot, &mut stats).unwrap();
        // Forward differences with step √ε ≈ 1.5e-8 are off by ~√ε times
        // the second derivatives of q̈ (≲ 100 here): ≲ 1e-6. A wrong term
        // of the hand derivation is off by O(1).
        assert!((jq - dq).amax() < 1e-5, "∂q̈/∂q: {jq} vs {dq}");
        assert!((jv - dv).amax() < 1e-5, "∂q̈/∂q̇: {jv} vs {dv}");
        // Exact Jacobians cost no right-hand sides, differences 2 N = 4.
        assert_eq!(stats.rhs_evals, 4);
    }
}

#[test]
fn exact_jacobians_give_the_finite_difference_trajectory_without_its_evaluations() {
    let (q0, qdot0) = start();
    let times: Vec<f64> = (1..=100).map(|i| 0.5 * i as f64).collect();
    let h = 0.05;
    for method in Method::GAUSS {
        let exact = method
            .with_step(h)
            .integrate(&CartPole::new(true), 0.0, q0, qdot0, &times)
            .unwrap();
        let differenced = method
            .with_step(h)
            .integrate(&CartPole::new(false), 0.0, q0, qdot0, &times)
            .unwrap();
        // Both solve the same stage equations to 10 ε of |y| ≤ 5 per step;
        // only Newton's path there differs. So they differ by ~1e-14 per
        // step, growing at most linearly over 1000 steps with the
        // oscillator's phase error: ≲ 1e-10 (observed ≤ 1e-12).
        let gap = exact
            .iter()
            .zip(&differenced)
            .map(|(a, b)| distance((a.q, a.qdot), (b.q, b.qdot)))
            .fold(0.0, f64::max);
        assert!(gap < 1e-10, "{method:?}: trajectories differ by {gap:e}");

        // The work, exactly: each Jacobian needs q̈ at its point (one
        // right-hand side) and, without exact Jacobians, 2 N = 4 more; each
        // Newton iteration evaluates the s stages and solves once.
        let s = stages(method);
        for (stats, per_jacobian) in [(exact.stats(), 1), (differenced.stats(), 5)] {
            assert_eq!(stats.steps_accepted, 1000);
            assert!(stats.jacobian_evals >= stats.steps_accepted);
            assert_eq!(stats.linear_solves, stats.newton_iterations);
            assert_eq!(
                stats.rhs_evals,
                s * stats.newton_iterations + per_jacobian * stats.jacobian_evals,
                "{method:?}: {stats:?}"
            );
        }
    }
}

#[test]
fn newton_needs_a_few_iterations_per_step_from_the_extrapolated_guess() {
    // At h = 0.01 the simplified-Newton contraction rate is ~h² |J'| ≈ 0.01
    // and the extrapolated guess is O(h^{s+1}) off, so reaching 10 ε takes
    // about four iterations. A convergence test stricter than round-off, or
    // a guess that ignores the previous step, would show here as ~2× more.
    let (q0, qdot0) = start();
    for method in Method::GAUSS {
        let stats = method
            .with_step(0.01)
            .integrate(&CartPole::new(true), 0.0, q0, qdot0, &[10.0])
            .unwrap()
            .stats();
        let per_step = stats.newton_iterations as f64 / stats.steps_accepted as f64;
        assert!(per_step < 5.0, "{method:?}: {per_step} iterations per step");
    }
}

/// The coupled oscillator's start and frequency for the linear tests.
const OMEGA: f64 = 2.0;

fn oscillator_start() -> (Vector2<f64>, Vector2<f64>) {
    (Vector2::new(1.0, -0.5), Vector2::new(0.3, 0.8))
}

/// The error of an `s`-stage Gauss method after `steps` steps on
/// `q̈ = −ω² q`, where it is pure phase error: its stability function is the
/// (s, s) Padé approximant of `e^z`, so `|R(i h ω)| = 1` (no amplitude
/// error) and each step lags by `(s!)² / ((2s)! (2s+1)!) (h ω)^{2s+1}` rad
/// (1/12 for the midpoint rule, 1/720 for Gauss-2). A phase lag `δ` moves
/// the state by `δ` times its amplitude, at most `A = max_k ω √(q₀ₖ² +
/// (q̇₀ₖ/ω)²)` (the velocity of the larger mode).
fn phase_error(method: Method, h: f64, steps: usize) -> f64 {
    let s = stages(method) as i32;
    let factorial = |n: i32| (1..=n).map(f64::from).product::<f64>();
    let lag_per_step = factorial(s).powi(2) / (factorial(2 * s) * factorial(2 * s + 1))
        * (h * OMEGA).powi(2 * s + 1);
    let (q0, qdot0) = oscillator_start();
    let amplitude = (0..2)
        .map(|k| OMEGA * (q0[k].powi(2) + (qdot0[k] / OMEGA).powi(2)).sqrt())
        .fold(0.0, f64::max);
    steps as f64 * lag_per_step * amplitude
}

#[test]
fn linear_oscillator_error_is_the_gauss_phase_error() {
    let model = CoupledOscillator { omega: OMEGA };
    let (q0, qdot0) = oscillator_start();
    let times: Vec<f64> = (1..=20).map(|i| 0.5 * i as f64).collect();
    for method in Method::GAUSS {
        let trajectory = method
            .with_step(0.1)
            .integrate(&model, 0.0, q0, qdot0, &times)
            .unwrap();
        let error = max_error(&model, &trajectory, q0, qdot0);
        let predicted = phase_error(method, 0.1, 100);
        // The largest error is at the end, where the lag is largest; it
        // falls short of the prediction by the sampling missing the peak of
        // the oscillating error (≤ 1 − cos(ω · 0.25) at worst, ~5% seen)
        // and the next term of the lag, (hω)² = 4% of it. A wrong tableau
        // changes R(z) and misses by a factor, not by percents.
        let ratio = error / predicted;
        assert!(
            (0.8..1.05).contains(&ratio),
            "{method:?}: error {error:e}, predicted {predicted:e}"
        );
        // Linear, and the differenced Jacobian is exact to √ε: the first
        // iteration lands on the solution, the second confirms it.
        assert_eq!(trajectory.stats().newton_iterations, 200, "{method:?}");
    }
}

#[test]
fn single_precision_works_with_the_implicit_methods() {
    let model = CoupledOscillator { omega: 2.0f32 };
    let (q0, qdot0) = oscillator_start();
    let (q0, qdot0) = (q0.cast::<f32>(), qdot0.cast::<f32>());
    let times: Vec<f32> = (1..=20).map(|i| 0.5 * i as f32).collect();
    for method in Method::GAUSS {
        let trajectory = method
            .with_step(0.01f32)
            .integrate(&model, 0.0, q0, qdot0, &times)
            .unwrap();
        let error = f64::from(max_error(&model, &trajectory, q0, qdot0));
        // Phase error as in f64 (1.3e-3 for the midpoint rule, below 1e-8
        // for Gauss), plus rounding: Newton stops within 10 ε_f32 ≈ 1.2e-6
        // of |y| ≈ 2 per step, a random walk over 1000 steps of ~8e-5.
        let bound = 1.05 * phase_error(method, 0.01, 1000) + 1e-4;
        assert!(
            error < bound,
            "{method:?}: f32 error {error:e} above {bound:e}"
        );
    }
}

#[test]
fn sample_times_are_hit_exactly_and_start_samples_are_the_initial_state() {
    let model = CoupledOscillator { omega: OMEGA };
    let (q0, qdot0) = oscillator_start();
    let times = [0.0, 0.0, 0.013, 0.5, 0.5, 1.0];
    let every_half: Vec<f64> = (1..=20).map(|i| 0.5 * i as f64).collect();
    for method in Method::GAUSS {
        let trajectory = method
            .with_step(0.1)
            .integrate(&model, 0.0, q0, qdot0, &times)
            .unwrap();
        assert_eq!(trajectory.times(), &times);
        for sample in trajectory.iter().take(2) {
            assert_eq!((sample.q, sample.qdot), (q0, qdot0));
        }
        assert_eq!(trajectory.get(3), trajectory.get(4));

        // Spacing a multiple of h: every step is exactly h, no slivers.
        let trajectory = method
            .with_step(0.1)
            .integrate(&model, 0.0, q0, qdot0, &every_half)
            .unwrap();
        assert_eq!(trajectory.stats().steps_accepted, 100);
    }
}
