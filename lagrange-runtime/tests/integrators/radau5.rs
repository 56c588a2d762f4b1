//! Radau5, the implicit method: fifth order where the problem is smooth,
//! large steps where it is stiff, dense output between the steps, exact
//! Jacobians used when the model has them, and the same typed failures as
//! the explicit methods.

use crate::models::{
    BlowUp, CoupledOscillator, ElasticPendulum, ForcingBreaksDown, InertiaVanishes, StiffChain,
    assert_exhausted_budget_keeps_the_samples, max_error,
};
use lagrange_runtime::dynamics::acceleration_jacobians;
use lagrange_runtime::nalgebra::{SMatrix, SVector, Vector1, Vector2};
use lagrange_runtime::prelude::*;
use lagrange_runtime::{InvalidInput, NonFiniteValue, Stats};

const OMEGA: f64 = 2.0;

fn start() -> (Vector2<f64>, Vector2<f64>) {
    (Vector2::new(1.0, -0.5), Vector2::new(0.3, 0.8))
}

fn radau5(tol: f64) -> Radau5<f64> {
    Radau5::new().rtol(tol).atol(tol)
}

/// RADAU5 controls the local error against `0.1 tol^(2/3)` (see the docs of
/// `Radau5`): the size of one step's error, and of the dense output's.
fn local_tolerance(tol: f64) -> f64 {
    0.1 * tol.powf(2.0 / 3.0)
}

#[test]
fn error_falls_with_the_tolerance_at_fifth_order() {
    let model = CoupledOscillator { omega: OMEGA };
    let (q0, qdot0) = start();
    let tols = [1e-4, 1e-6, 1e-8, 1e-10];
    // Only t = 10, the end of the last step: the method's own error, not
    // the dense output's.
    let errors = tols.map(|tol| {
        let trajectory = radau5(tol)
            .integrate(&model, 0.0, q0, qdot0, &[10.0])
            .unwrap();
        max_error(&model, &trajectory, q0, qdot0)
    });
    for (tol, error) in tols.iter().zip(&errors) {
        // Steps follow h ∝ (0.1 tol^(2/3))^(1/4) and the global error of an
        // order-5 method h⁵, so error ≈ C tol^(5/6): the ratio error / tol
        // creeps up by 10× over six decades (observed 0.9 at 1e-4, 12 at
        // 1e-10, over five periods). 30 tol holds that with 2.5× to spare
        // and fails a controller that accepts steps 2× too large (32×).
        assert!(error < &(30.0 * tol), "error {error:e} at tol {tol:e}");
    }
    for pair in errors.windows(2) {
        // Per 100× in tolerance: 100^(5/6) ≈ 46× for order 5 (observed
        // 36-46×); an order-4 solution would give 100^(4/6) ≈ 22×.
        assert!(pair[0] / pair[1] > 30.0, "errors {errors:?}");
    }
}

#[test]
fn dense_output_between_steps_has_the_size_of_the_local_error() {
    let model = CoupledOscillator { omega: OMEGA };
    let (q0, qdot0) = start();
    // 1000 samples, almost all strictly inside steps (50-400 steps).
    let times: Vec<f64> = (1..=1000).map(|i| 0.01 * i as f64).collect();
    for tol in [1e-4, 1e-7, 1e-10] {
        let trajectory = radau5(tol)
            .integrate(&model, 0.0, q0, qdot0, &times)
            .unwrap();
        let error = max_error(&model, &trajectory, q0, qdot0);
        // The collocation polynomial has order 3, so between step ends it
        // adds an error of one local error, ≤ local_tolerance · (1 + |y|)
        // with |y| ≤ 2.1 here (observed 0.5-0.75 local_tolerance). Linear
        // interpolation would be off by h²ω²|y|/8 ≈ 3e-2 at tol 1e-4
        // (h ≈ 0.2), a wrong cubic coefficient by O(h²) or O(h³) too.
        let bound = 3.1 * local_tolerance(tol);
        assert!(error < bound, "dense error {error:e} at tol {tol:e}");
    }
}

#[test]
fn dense_sampling_does_not_change_the_steps_or_the_final_state() {
    let model = CoupledOscillator { omega: OMEGA };
    let (q0, qdot0) = start();
    let sparse = radau5(1e-8)
        .integrate(&model, 0.0, q0, qdot0, &[10.0])
        .unwrap();
    let dense_times: Vec<f64> = (1..=10_000).map(|i| 0.001 * i as f64).collect();
    let dense = radau5(1e-8)
        .integrate(&model, 0.0, q0, qdot0, &dense_times)
        .unwrap();
    assert_eq!(dense.len(), 10_000);
    assert_eq!(sparse.stats(), dense.stats());
    assert_eq!(sparse.last(), dense.last());
}

#[test]
fn linear_model_keeps_its_first_jacobian_for_the_whole_run() {
    let model = CoupledOscillator { omega: OMEGA };
    let (q0, qdot0) = start();
    let stats = radau5(1e-8)
        .integrate(&model, 0.0, q0, qdot0, &[10.0])
        .unwrap()
        .stats();
    // For a linear model the Jacobian never changes, so simplified Newton
    // converges at once (contraction ≈ 1e-8 from the finite differences,
    // far below the reuse threshold 1e-3) and no step is rejected: the one
    // Jacobian of the first step serves all ~200.
    assert!(stats.steps_accepted > 100);
    assert_eq!(stats.jacobian_evals, 1, "{stats:?}");
}

#[test]
fn every_evaluation_solve_and_iteration_is_counted() {
    let model = ElasticPendulum {
        exact_jacobians: true,
        ..ElasticPendulum::stiff()
    };
    let (q0, qdot0) = model.start();
    let stats = radau5(1e-7)
        .integrate(&model, 0.0, q0, qdot0, &[5.0])
        .unwrap()
        .stats();
    let Stats {
        steps_accepted: accepted,
        steps_rejected: rejected,
        newton_iterations: iterations,
        ..
    } = stats;
    // One at t0, three per Newton iteration, one at each new state but the
    // last; exact Jacobians cost none. The refined error estimate adds one
    // per first or rejected-then-retried step at most.
    let base = 1 + 3 * iterations + (accepted - 1);
    assert!(
        (base..=base + rejected + 1).contains(&stats.rhs_evals),
        "{stats:?}"
    );
    // One solve per iteration, one or two per error estimate.
    let solves = iterations + accepted;
    assert!(
        (solves..=solves + accepted + 2 * rejected).contains(&stats.linear_solves),
        "{stats:?}"
    );
    // The spring makes Newton work: several Jacobians, yet fewer than steps.
    assert!(stats.jacobian_evals > 1 && stats.jacobian_evals < accepted);
}

#[test]
fn single_precision_oscillator_works() {
    let model = CoupledOscillator { omega: 2.0f32 };
    let (q0, qdot0) = (Vector2::new(1.0f32, -0.5), Vector2::new(0.3f32, 0.8));
    let tol = 1e-4f32;
    let trajectory = Radau5::new()
        .rtol(tol)
        .atol(tol)
        .integrate(&model, 0.0, q0, qdot0, &[10.0])
        .unwrap();
    let error = max_error(&model, &trajectory, q0, qdot0);
    // As in f64 (0.9 tol at 1e-4): f32 rounding (1e-7 per step, ~50 steps)
    // is far below the tolerance.
    assert!(error < 3.0 * tol, "f32 error {error:e}");
}

// The stiff chain: a hard spring (K = 1e6) between two unit masses, a soft
// one (k = 1) to the wall, light dampers. Released from x₁ = x₂ = 1 at rest,
// the hard spring starts unstretched, so its 1414 rad/s vibration is barely
// excited (velocity amplitude ≈ 3.5e-4) and dies as e^(−10 t).

fn chain_times() -> Vec<f64> {
    (1..=20).map(|i| 0.5 * i as f64).collect()
}

#[test]
fn stiff_chain_takes_few_large_steps_and_tracks_the_slow_swing() {
    let chain = StiffChain::new();
    let (q0, qdot0) = (Vector2::new(1.0, 1.0), Vector2::zeros());
    let tol = 1e-6;
    let trajectory = radau5(tol)
        .integrate(&chain, 0.0, q0, qdot0, &chain_times())
        .unwrap();
    let stats = trajectory.stats();
    // Observed: 57 accepted, 3 rejected, 290 right-hand sides. An explicit
    // method is held to h < 3.3 / 1414 by stability alone: > 4000 steps.
    assert!(stats.steps_accepted < 200, "{stats:?}");
    for sample in trajectory.iter().filter(|s| s.t >= 1.0) {
        // From t = 1 on the vibration is below 2e-8: what remains is the
        // slow swing, and the exact solution is known. Observed error
        // 2.6e-6, the dense output's (local tolerance 1e-5, |y| ≤ 1, steps
        // ~0.2 long); 10 tol keeps ~4× margin. A method that damped the
        // swing, like implicit Euler losing (ωh)²/2 ≈ 0.8 % of the amplitude
        // per step at these steps, would be off by 1e-1.
        let (q, qdot) = chain.exact(sample.t, q0, qdot0);
        let error = (sample.q - q).amax().max((sample.qdot - qdot).amax());
        assert!(error < 10.0 * tol, "t = {}: error {error:e}", sample.t);
    }
}

#[test]
fn stiff_chain_costs_dopri5_two_hundred_times_more_evaluations() {
    let chain = StiffChain::new();
    let (q0, qdot0) = (Vector2::new(1.0, 1.0), Vector2::zeros());
    let tol = 1e-6;
    let implicit = radau5(tol)
        .integrate(&chain, 0.0, q0, qdot0, &chain_times())
        .unwrap()
        .stats();
    let explicit = Dopri5::new()
        .rtol(tol)
        .atol(tol)
        .integrate(&chain, 0.0, q0, qdot0, &chain_times())
        .unwrap()
        .stats();
    // Observed: Dopri5 57 818 right-hand sides (8 096 accepted and 1 540
    // rejected steps, all at its stability limit), Radau5 290 (including the
    // finite-difference Jacobians): a ratio of ~200. 50 leaves room for
    // controller details while failing any method that resolves the
    // vibration.
    let ratio = explicit.rhs_evals as f64 / implicit.rhs_evals as f64;
    assert!(ratio > 50.0, "ratio {ratio}: {explicit:?} vs {implicit:?}");
}

// The elastic pendulum: nonlinear, q-dependent mass matrix, spring 32× faster
// than the swing.

#[test]
fn hand_written_pendulum_jacobians_match_finite_differences() {
    let (exact, approximate) = (
        ElasticPendulum {
            exact_jacobians: true,
            ..ElasticPendulum::stiff()
        },
        ElasticPendulum::stiff(),
    );
    // A generic state, moving, so every term of the Jacobians matters.
    let (q, qdot) = (Vector2::new(1.05, 0.7), Vector2::new(-0.3, 1.2));
    let qddot = lagrange_runtime::dynamics::acceleration(&exact, 0.0, &q, &qdot).unwrap();
    let mut stats = Stats::default();
    let (eq, ev) = acceleration_jacobians(&exact, 0.0, &q, &qdot, &qddot, &mut stats).unwrap();
    let (aq, av) =
        acceleration_jacobians(&approximate, 0.0, &q, &qdot, &qddot, &mut stats).unwrap();
    // Forward differences with step √ε: truncation ≈ √ε |q̈''| and rounding
    // ≈ √ε |q̈|, relative to entries up to k = 1e4: 1e-8 · 1e4 = 1e-4 at worst.
    assert!((eq - aq).amax() < 1e-3, "{eq} vs {aq}");
    assert!((ev - av).amax() < 1e-3, "{ev} vs {av}");
    // Not vacuous: ∂θ̈/∂r, where q̈ enters, is of the order of g here.
    assert!(eq[(1, 0)].abs() > 1.0);
}

#[test]
fn exact_jacobians_give_the_same_answer_for_fewer_evaluations() {
    let times: Vec<f64> = (1..=10).map(|i| 0.5 * i as f64).collect();
    let run = |exact_jacobians| {
        let model = ElasticPendulum {
            exact_jacobians,
            ..ElasticPendulum::stiff()
        };
        let (q0, qdot0) = model.start();
        radau5(1e-7)
            .integrate(&model, 0.0, q0, qdot0, &times)
            .unwrap()
    };
    let (exact, differences) = (run(true), run(false));
    for (a, b) in exact.iter().zip(&differences) {
        // The Jacobians only steer Newton: both runs converge to the same
        // stages up to Newton's stopping test (≈ 1.5e-3 of the local
        // tolerance 2e-6), and here they even take the same steps. Were the
        // steps to differ, the gap would be the global error of either,
        // ≈ 1e-6 against a Dopri5 reference at 1e-13 — the bound.
        let gap = (a.q - b.q).amax().max((a.qdot - b.qdot).amax());
        assert!(gap < 1e-6, "t = {}: gap {gap:e}", a.t);
    }
    let (e, d) = (exact.stats(), differences.stats());
    // Differences cost 2N = 4 right-hand sides per Jacobian, and the
    // pendulum needs one on most steps (83 for 96 steps) against ~7
    // right-hand sides per step for Newton: observed 672 vs 1004 (−33 %).
    assert!(
        (e.rhs_evals as f64) < 0.8 * d.rhs_evals as f64,
        "{e:?} vs {d:?}"
    );
}

// Failures: the same typed errors as the explicit methods, the samples
// before them kept, never a hang.

/// Halving h after a failed stage closes in on a breakdown at t* until
/// h ≤ 10 ε t; the failing stage lies within h of it. 1e-12 leaves ~100×.
const CLOSE_IN: f64 = 1e-12;

#[test]
fn vanishing_inertia_is_a_singular_mass_matrix_at_that_time() {
    let model = InertiaVanishes { t_s: 1.0 };
    let (q0, qdot0) = (Vector2::new(1.0, 1.0), Vector2::zeros());
    let times = [0.25, 0.5, 0.75, 1.5];
    let failure = radau5(1e-10)
        .integrate(&model, 0.0, q0, qdot0, &times)
        .unwrap_err();
    let IntegrationError::SingularMassMatrix { t, .. } = failure.error else {
        panic!("expected a singular mass matrix, got {}", failure.error);
    };
    assert!(t >= 1.0 && t - 1.0 < CLOSE_IN, "t = {t}");
    assert_eq!(failure.trajectory.times(), &times[..3]);
    for sample in &failure.trajectory {
        // Both springs are x = cos t. The samples come from the dense
        // output, within 3.1 local tolerances (see the dense output test);
        // observed 4e-9.
        let exact = Vector2::repeat(sample.t.cos());
        assert!((sample.q - exact).amax() < 3.1 * local_tolerance(1e-10));
    }
}

#[test]
fn nan_forcing_is_reported_where_it_starts() {
    let model = ForcingBreaksDown { t_star: 2.0 };
    let times = [1.0, 1.9, 3.0];
    let failure = radau5(1e-10)
        .integrate(&model, 0.0, Vector1::new(1.0), Vector1::zeros(), &times)
        .unwrap_err();
    let IntegrationError::NonFiniteState { t, value, .. } = failure.error else {
        panic!("expected a non-finite state, got {}", failure.error);
    };
    assert_eq!(value, NonFiniteValue::Forcing);
    assert!(t > 2.0 && t - 2.0 < 2.0 * CLOSE_IN, "t = {t}");
    assert_eq!(failure.trajectory.times(), &times[..2]);
}

#[test]
fn exhausted_step_budget_keeps_the_samples_so_far() {
    assert_exhausted_budget_keeps_the_samples(10, |b| Radau5::new().max_steps(b));
}

#[test]
fn invalid_tolerances_are_refused_up_front() {
    let model = CoupledOscillator { omega: OMEGA };
    let (q0, qdot0) = start();
    for (settings, expected) in [
        (
            Radau5::new().rtol(1e-20),
            InvalidInput::InvalidRelativeTolerance {
                rtol: 1e-20,
                min: 10.0 * f64::EPSILON,
            },
        ),
        (
            Radau5::new().atol(0.0),
            InvalidInput::InvalidAbsoluteTolerance { atol: 0.0 },
        ),
        (
            Radau5::new().rtol(f64::NAN),
            InvalidInput::InvalidRelativeTolerance {
                rtol: f64::NAN,
                min: 10.0 * f64::EPSILON,
            },
        ),
    ] {
        let failure = settings
            .integrate(&model, 0.0, q0, qdot0, &[1.0])
            .unwrap_err();
        let IntegrationError::InvalidInput(invalid) = failure.error else {
            panic!("expected invalid input, got {}", failure.error);
        };
        // NaN ≠ NaN: compare the debug forms.
        assert_eq!(format!("{invalid:?}"), format!("{expected:?}"));
        assert_eq!(failure.trajectory.stats().rhs_evals, 0);
    }
}

#[test]
fn unreachable_absolute_tolerance_ends_in_a_clean_error_not_a_hang() {
    // y₂ = 1e-10 is asked to be right to rtol |y₂| + atol ≈ 1e-24, below
    // the rounding (~1e-16) that x's terms leave in its acceleration:
    // rounding alone fails Newton's test and the error test, so every step
    // is cut until h underflows (observed: 713 attempts, t ≈ 3e-296).
    // From exactly y₂ = 0 it would stay exactly 0, the solve of M q̈ = f
    // being exact there, and any atol would be met.
    let model = CoupledOscillator { omega: OMEGA };
    let (q0, qdot0) = (Vector2::new(1.0, 1e-10), Vector2::zeros());
    let failure = Radau5::new()
        .rtol(1e-14)
        .atol(1e-300)
        .integrate(&model, 0.0, q0, qdot0, &[1.0])
        .unwrap_err();
    assert!(
        matches!(failure.error, IntegrationError::StepSizeUnderflow { .. }),
        "{}",
        failure.error
    );
}

#[test]
fn blow_up_in_finite_time_ends_in_step_size_underflow() {
    let failure = radau5(1e-10)
        .integrate(
            &BlowUp,
            0.0,
            Vector1::new(1.0),
            Vector1::new(1.0),
            &[0.5, 2.0],
        )
        .unwrap_err();
    let IntegrationError::StepSizeUnderflow { t, h, q, .. } = failure.error else {
        panic!("expected step size underflow, got {}", failure.error);
    };
    // q = 1 / (1 - t): the steps shrink with 1 - t until h ≤ 10 ε t.
    assert!(t < 1.0 && 1.0 - t < 1e-9, "t = {t}");
    assert!(h <= 10.0 * f64::EPSILON * t);
    // The numerical pole is the exact one shifted by the global error in
    // time (~1e-9 at tol 1e-10, see the order test), so q ≈ 1 / (t_pole − t)
    // ≥ 1 / 2e-9. Observed: t = 1 − 4.5e-12, q = 5.9e12.
    assert!(q[0] > 5e8, "q = {}", q[0]);
    assert_eq!(failure.trajectory.times(), &[0.5]);
}

/// A unit spring whose exact residual Jacobians are NaN: a model bug that
/// no step size can fix.
struct NanJacobian;

impl Lagrangian<1> for NanJacobian {
    type Scalar = f64;
    const COORDINATES: [&'static str; 1] = ["x"];
    fn mass_matrix(&self, _t: f64, _q: &Vector1<f64>) -> SMatrix<f64, 1, 1> {
        SMatrix::<f64, 1, 1>::new(1.0)
    }
    fn forcing(&self, _t: f64, q: &Vector1<f64>, _qdot: &Vector1<f64>) -> Vector1<f64> {
        -q
    }
    fn kinetic_energy(&self, _t: f64, _q: &Vector1<f64>, qdot: &Vector1<f64>) -> f64 {
        0.5 * qdot[0] * qdot[0]
    }
    fn potential_energy(&self, _t: f64, q: &Vector1<f64>) -> f64 {
        0.5 * q[0] * q[0]
    }
    fn residual_jacobians(
        &self,
        _t: f64,
        _q: &SVector<f64, 1>,
        _qdot: &SVector<f64, 1>,
        _qddot: &SVector<f64, 1>,
    ) -> Option<(SMatrix<f64, 1, 1>, SMatrix<f64, 1, 1>)> {
        Some((SMatrix::repeat(f64::NAN), SMatrix::zeros()))
    }
}

#[test]
fn nan_jacobian_is_reported_at_once() {
    let failure = Radau5::new()
        .integrate(
            &NanJacobian,
            0.0,
            Vector1::new(1.0),
            Vector1::zeros(),
            &[0.0, 1.0],
        )
        .unwrap_err();
    assert!(
        matches!(
            failure.error,
            IntegrationError::NonFiniteState {
                t: 0.0,
                value: NonFiniteValue::Jacobian,
                ..
            }
        ),
        "{}",
        failure.error
    );
    assert_eq!(failure.trajectory.times(), &[0.0]);
    assert_eq!(failure.trajectory.stats().steps_accepted, 0);
}
