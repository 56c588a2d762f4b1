//! Models that break, and inputs that are wrong: typed errors with the time
//! and state, the samples before the failure kept, never a NaN or a hang.
//!
//! Here, models that break down along the way; the inputs in `inputs.rs`;
//! methods that share a driver failing alike in `alike.rs`.

use crate::models::{BlowUp, ForcingBreaksDown, InertiaVanishes};
use lagrange_runtime::NonFiniteValue;
use lagrange_runtime::nalgebra::{Vector1, Vector2};
use lagrange_runtime::prelude::*;

mod alike;
mod inputs;

/// The Dopri5 retry (shrinking h by 5× after a failed stage) closes in on a
/// breakdown at `t*` until `h ≤ 10 ε t`, so the failing evaluation lies
/// within a few `10 ε t*` of it; 1e-12 leaves a factor of ~100.
const CLOSE_IN: f64 = 1e-12;

#[test]
fn vanishing_inertia_is_a_singular_mass_matrix_at_that_time() {
    let model = InertiaVanishes { t_s: 1.0 };
    let (q0, qdot0) = (Vector2::new(1.0, 1.0), Vector2::zeros());
    let times = [0.25, 0.5, 0.75, 1.5];
    let failure = Dopri5::new()
        .rtol(1e-10)
        .atol(1e-10)
        .integrate(&model, 0.0, q0, qdot0, &times)
        .unwrap_err();
    let IntegrationError::SingularMassMatrix { t, q, qdot } = failure.error else {
        panic!("expected a singular mass matrix, got {}", failure.error);
    };
    assert!(t >= 1.0 && t - 1.0 < CLOSE_IN, "t = {t}");
    // Both springs are x = cos t up to there; the global error at tol 1e-10
    // over one time unit is ~1e-10 (see harmonic_oscillator.rs).
    assert!((q - Vector2::repeat(t.cos())).amax() < 1e-8);
    assert!((qdot + Vector2::repeat(t.sin())).amax() < 1e-8);
    assert_eq!(failure.trajectory.times(), &times[..3]);
}

#[test]
fn rk4_reports_the_stage_where_the_mass_matrix_turned_singular() {
    let model = InertiaVanishes { t_s: 1.0 };
    let (q0, qdot0) = (Vector2::new(1.0, 1.0), Vector2::zeros());
    let times = [0.25, 0.5, 0.75, 1.5];
    let failure = Rk4::new(0.1)
        .integrate(&model, 0.0, q0, qdot0, &times)
        .unwrap_err();
    let IntegrationError::SingularMassMatrix { t, .. } = failure.error else {
        panic!("expected a singular mass matrix, got {}", failure.error);
    };
    // 0.75 → 1.5 in 8 steps of 0.09375: the step from 0.9375 has its last
    // stage at 1.03125, the first evaluation past t_s.
    assert_eq!(t, 1.03125);
    assert_eq!(failure.trajectory.len(), 3);
}

#[test]
fn nan_forcing_is_reported_where_it_starts() {
    let model = ForcingBreaksDown { t_star: 2.0 };
    let times = [1.0, 1.9, 3.0];
    let failure = Dopri5::new()
        .rtol(1e-10)
        .atol(1e-10)
        .integrate(&model, 0.0, Vector1::new(1.0), Vector1::zeros(), &times)
        .unwrap_err();
    let IntegrationError::NonFiniteState { t, q, value, .. } = failure.error else {
        panic!("expected a non-finite state, got {}", failure.error);
    };
    assert_eq!(value, NonFiniteValue::Forcing);
    assert!(t > 2.0 && t - 2.0 < 2.0 * CLOSE_IN, "t = {t}");
    // x = cos t before t*, to the global error (~1e-10 per time unit).
    assert!((q[0] - t.cos()).abs() < 1e-8);
    assert_eq!(failure.trajectory.times(), &times[..2]);
    for sample in &failure.trajectory {
        assert!(sample.q[0].is_finite() && sample.qdot[0].is_finite());
    }
}

#[test]
fn blow_up_in_finite_time_ends_in_step_size_underflow() {
    let failure = Dopri5::new()
        .rtol(1e-10)
        .atol(1e-10)
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
    // time (~1e-10 at tol 1e-10), so q ≈ 1 / (t_pole - t) ≥ 1 / 2e-9.
    assert!(q[0] > 5e8, "q = {}", q[0]);
    assert_eq!(failure.trajectory.times(), &[0.5]);
}

#[test]
fn messages_say_what_happened_when_and_in_which_state() {
    let model = InertiaVanishes { t_s: 1.0 };
    let failure = Rk4::new(0.1)
        .integrate(
            &model,
            0.0,
            Vector2::new(1.0, 1.0),
            Vector2::zeros(),
            &[0.5, 2.0],
        )
        .unwrap_err();
    let message = failure.to_string();
    assert!(
        message.starts_with("mass matrix is singular at t = 1.0 (q = [0.540"),
        "{message}"
    );
    // The last stage of the step 0.9 → 1.0 is at t = 1.0 = t_s, in the
    // state (cos 1, -sin 1) to RK4's error at h = 0.1 (~1e-4).
    assert!(message.contains("q̇ = [-0.841"), "{message}");
    assert!(message.ends_with("(1 sample kept)"), "{message}");

    let failure = Dopri5::new()
        .rtol(1e-20)
        .integrate(&model, 0.0, Vector2::zeros(), Vector2::zeros(), &[1.0])
        .unwrap_err();
    assert!(
        failure
            .to_string()
            .starts_with("invalid input: the relative tolerance rtol = 1e-20 must be"),
        "{failure}"
    );
}
