//! Models that break, and inputs that are wrong: typed errors with the time
//! and state, the samples before the failure kept, never a NaN or a hang.

use crate::models::{
    assert_exhausted_budget_keeps_the_samples, BlowUp, CoupledOscillator, ForcingBreaksDown,
    InertiaVanishes,
};
use lagrange::models::Oscillator;
use lagrange_runtime::nalgebra::{SVector, Vector1, Vector2};
use lagrange_runtime::prelude::*;
use lagrange_runtime::{IntegrationResult, InvalidInput, NonFiniteValue};
use std::mem::discriminant;

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
fn exhausted_step_budget_keeps_the_samples_so_far() {
    assert_exhausted_budget_keeps_the_samples(10, |b| Dopri5::new().max_steps(b));

    let model = CoupledOscillator { omega: 2.0 };
    let (q0, qdot0) = (Vector2::new(1.0, 0.0), Vector2::zeros());
    let times = [0.1, 0.2, 0.3, 0.4, 100.0];
    let failure = Rk4::new(0.01_f64)
        .max_steps(25)
        .integrate(&model, 0.0, q0, qdot0, &times)
        .unwrap_err();
    let IntegrationError::TooManySteps { t, .. } = failure.error else {
        panic!("expected too many steps, got {}", failure.error);
    };
    assert!((t - 0.25).abs() < 1e-15, "t = {t}");
    assert_eq!(failure.trajectory.times(), &times[..2]);
}

#[test]
fn impossibly_tight_tolerance_is_refused_up_front() {
    let model = CoupledOscillator { omega: 2.0 };
    let (q0, qdot0) = (Vector2::new(1.0, 0.0), Vector2::zeros());
    let failure = Dopri5::new()
        .rtol(1e-20)
        .integrate(&model, 0.0, q0, qdot0, &[1.0])
        .unwrap_err();
    assert!(matches!(
        failure.error,
        IntegrationError::InvalidInput(InvalidInput::InvalidRelativeTolerance { rtol, .. })
            if rtol == 1e-20
    ));
    assert_eq!(failure.trajectory.stats().rhs_evals, 0);
}

#[test]
fn unreachable_absolute_tolerance_ends_in_a_clean_error_not_a_hang() {
    // y stays near rounding level (~1e-28) and atol = 1e-300 asks it to be
    // right to ~1e-42: steps of ~1e-11 manage that, so the run crawls until
    // its budget of 100 000 steps ends it near t = 1e-6. (While the first
    // step guess overflowed to h = 0, it stopped at t = 0 having tried
    // nothing, with "step size underflow".)
    let model = CoupledOscillator { omega: 2.0 };
    let (q0, qdot0) = (Vector2::new(1.0, 0.0), Vector2::zeros());
    let failure = Dopri5::new()
        .rtol(1e-14)
        .atol(1e-300)
        .integrate(&model, 0.0, q0, qdot0, &[1.0])
        .unwrap_err();
    let IntegrationError::TooManySteps { t, .. } = failure.error else {
        panic!("expected too many steps, got {}", failure.error);
    };
    assert!(t > 0.0 && t < 1e-3, "t = {t}");
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
fn invalid_inputs_are_refused_before_any_work() {
    let model = CoupledOscillator { omega: 2.0 };
    let (q0, qdot0) = (Vector2::new(1.0, 0.0), Vector2::zeros());
    let refused = |result: lagrange_runtime::IntegrationResult<f64, 2>| {
        let failure = result.unwrap_err();
        assert!(failure.trajectory.is_empty());
        assert_eq!(failure.trajectory.stats().rhs_evals, 0);
        match failure.error {
            IntegrationError::InvalidInput(invalid) => invalid,
            other => panic!("expected invalid input, got {other}"),
        }
    };
    let dopri5 = Dopri5::new();

    let nan_y = Vector2::new(0.0, f64::NAN);
    assert!(matches!(
        refused(dopri5.integrate(&model, 0.0, nan_y, qdot0, &[1.0])),
        InvalidInput::NonFiniteInitialPosition { coordinate: "y", value } if value.is_nan()
    ));
    assert!(matches!(
        refused(dopri5.integrate(&model, 0.0, q0, Vector2::new(f64::INFINITY, 0.0), &[1.0])),
        InvalidInput::NonFiniteInitialVelocity {
            coordinate: "x",
            ..
        }
    ));
    let broken = CoupledOscillator { omega: f64::NAN };
    assert_eq!(
        refused(dopri5.integrate(&broken, 0.0, q0, qdot0, &[1.0])),
        InvalidInput::NonFiniteParameters
    );
    assert_eq!(
        refused(dopri5.integrate(&model, 0.0, q0, qdot0, &[1.0, 0.5])),
        InvalidInput::UnsortedSampleTimes {
            index: 1,
            previous: 1.0,
            time: 0.5
        }
    );
    assert_eq!(
        refused(dopri5.integrate(&model, 1.0, q0, qdot0, &[0.5, 2.0])),
        InvalidInput::SampleBeforeStart {
            index: 0,
            time: 0.5,
            t0: 1.0
        }
    );
    assert!(matches!(
        refused(dopri5.integrate(&model, 0.0, q0, qdot0, &[f64::NAN])),
        InvalidInput::NonFiniteSampleTime { index: 0, .. }
    ));
    assert!(matches!(
        refused(dopri5.integrate(&model, f64::NEG_INFINITY, q0, qdot0, &[1.0])),
        InvalidInput::NonFiniteStartTime { .. }
    ));
    assert_eq!(
        refused(
            Dopri5::new()
                .atol(0.0)
                .integrate(&model, 0.0, q0, qdot0, &[1.0])
        ),
        InvalidInput::InvalidAbsoluteTolerance { atol: 0.0 }
    );
    for h in [0.0, -0.1, f64::INFINITY] {
        assert_eq!(
            refused(Rk4::new(h).integrate(&model, 0.0, q0, qdot0, &[1.0])),
            InvalidInput::InvalidStepSize { h }
        );
    }
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

/// What the Euler methods share with RK4 through the fixed-step driver: bad
/// step sizes refused, the failing evaluation reported with the samples
/// before it, the step budget enforced.
fn fails_like_rk4<I: Integrator<f64>>(new: impl Fn(f64) -> I, budget: impl Fn(I, usize) -> I) {
    let model = InertiaVanishes { t_s: 1.0 };
    let (q0, qdot0) = (Vector2::new(1.0, 1.0), Vector2::zeros());
    for h in [0.0, -0.1, f64::NAN] {
        let failure = new(h)
            .integrate(&model, 0.0, q0, qdot0, &[1.0])
            .unwrap_err();
        assert!(
            matches!(
                failure.error,
                IntegrationError::InvalidInput(InvalidInput::InvalidStepSize { .. })
            ),
            "{}",
            failure.error
        );
        assert_eq!(failure.trajectory.stats().rhs_evals, 0);
    }

    let times = [0.25, 0.5, 0.75, 1.5];
    let failure = new(0.1)
        .integrate(&model, 0.0, q0, qdot0, &times)
        .unwrap_err();
    let IntegrationError::SingularMassMatrix { t, .. } = failure.error else {
        panic!("expected a singular mass matrix, got {}", failure.error);
    };
    // 0.75 → 1.5 in 8 steps of 0.09375; both methods evaluate at step starts
    // only, and 0.75 + 3 · 0.09375 = 1.03125 is the first one past t_s.
    assert_eq!(t, 1.03125);
    assert_eq!(failure.trajectory.times(), &times[..3]);

    let times = [0.1, 0.2, 0.3, 100.0];
    let failure = budget(new(0.01), 25)
        .integrate(&model, 0.0, q0, qdot0, &times)
        .unwrap_err();
    let IntegrationError::TooManySteps { t, max_steps, .. } = failure.error else {
        panic!("expected too many steps, got {}", failure.error);
    };
    assert_eq!(max_steps, 25);
    // 25 steps of 0.01 (to rounding of the sample spacing).
    assert!((t - 0.25).abs() < 1e-15, "t = {t}");
    assert_eq!(failure.trajectory.times(), &times[..2]);
    assert_eq!(failure.trajectory.stats().steps_accepted, 25);
}

#[test]
fn explicit_euler_fails_like_rk4() {
    fails_like_rk4(ExplicitEuler::new, ExplicitEuler::max_steps);
}

#[test]
fn symplectic_euler_fails_like_rk4() {
    fails_like_rk4(SymplecticEuler::new, SymplecticEuler::max_steps);
}

/// Runs DOP853 and DOPRI5 with the same tolerances on the same failing
/// problem and checks that they fail alike: same error, same samples kept,
/// at the same time to within 1e-9. (Both close in on a breakdown until
/// h ≤ 10 ε t, see `CLOSE_IN`; a blow-up's numerical pole moves with each
/// method's global error in time, ~1e-10 at tolerance 1e-10.) Returns
/// DOP853's failure.
fn fails_like_dopri5<L: Lagrangian<N, Scalar = f64>, const N: usize>(
    (rtol, atol): (f64, f64),
    model: &L,
    (q0, qdot0): (SVector<f64, N>, SVector<f64, N>),
    times: &[f64],
) -> Box<Failure<f64, N>> {
    let ours = Dop853::new()
        .rtol(rtol)
        .atol(atol)
        .integrate(model, 0.0, q0, qdot0, times)
        .unwrap_err();
    let theirs = Dopri5::new()
        .rtol(rtol)
        .atol(atol)
        .integrate(model, 0.0, q0, qdot0, times)
        .unwrap_err();
    let (a, b) = (&ours.error, &theirs.error);
    assert_eq!(discriminant(a), discriminant(b), "DOP853: {a}; DOPRI5: {b}");
    assert_eq!(ours.trajectory.times(), theirs.trajectory.times());
    let when = |error: &IntegrationError<f64, N>| match *error {
        IntegrationError::SingularMassMatrix { t, .. }
        | IntegrationError::NonFiniteState { t, .. }
        | IntegrationError::StepSizeUnderflow { t, .. } => Some(t),
        _ => None,
    };
    if let (Some(ta), Some(tb)) = (when(a), when(b)) {
        assert!(
            (ta - tb).abs() < 1e-9,
            "DOP853 at t = {ta}, DOPRI5 at t = {tb}"
        );
    }
    ours
}

#[test]
fn dop853_fails_where_and_how_dopri5_does() {
    let tol = (1e-10, 1e-10);
    let start = (Vector2::new(1.0, 1.0), Vector2::zeros());
    let times = [0.25, 0.5, 0.75, 1.5];
    let failure = fails_like_dopri5(tol, &InertiaVanishes { t_s: 1.0 }, start, &times);
    let IntegrationError::SingularMassMatrix { t, .. } = failure.error else {
        panic!("expected a singular mass matrix, got {}", failure.error);
    };
    assert!(t >= 1.0 && t - 1.0 < CLOSE_IN, "t = {t}");
    assert_eq!(failure.trajectory.times(), &times[..3]);

    let start = (Vector1::new(1.0), Vector1::zeros());
    let failure = fails_like_dopri5(tol, &ForcingBreaksDown { t_star: 2.0 }, start, &[1.0, 3.0]);
    let IntegrationError::NonFiniteState { t, value, .. } = failure.error else {
        panic!("expected a non-finite state, got {}", failure.error);
    };
    assert_eq!(value, NonFiniteValue::Forcing);
    assert!(t > 2.0 && t - 2.0 < 2.0 * CLOSE_IN, "t = {t}");

    let start = (Vector1::new(1.0), Vector1::new(1.0));
    let failure = fails_like_dopri5(tol, &BlowUp, start, &[0.5, 2.0]);
    let IntegrationError::StepSizeUnderflow { t, .. } = failure.error else {
        panic!("expected step size underflow, got {}", failure.error);
    };
    // q = 1 / (1 - t); the numerical pole is the exact one shifted by the
    // global error in time, ~1e-10 at tol 1e-10, to either side (DOP853's
    // lies 9e-12 after it, DOPRI5's before).
    assert!((t - 1.0).abs() < 1e-9, "t = {t}");

    let oscillator = CoupledOscillator { omega: 2.0 };
    let start = (Vector2::new(1.0, 0.0), Vector2::zeros());
    let failure = fails_like_dopri5((1e-14, 1e-300), &oscillator, start, &[1.0]);
    assert!(matches!(
        failure.error,
        IntegrationError::TooManySteps { .. }
    ));
    let failure = fails_like_dopri5((1e-20, 1e-10), &oscillator, start, &[1.0]);
    assert!(matches!(
        failure.error,
        IntegrationError::InvalidInput(InvalidInput::InvalidRelativeTolerance { .. })
    ));
    let failure = fails_like_dopri5((1e-10, 0.0), &oscillator, start, &[1.0]);
    assert!(matches!(
        failure.error,
        IntegrationError::InvalidInput(InvalidInput::InvalidAbsoluteTolerance { .. })
    ));
}

#[test]
fn dop853_exhausted_step_budget_keeps_the_samples_so_far() {
    assert_exhausted_budget_keeps_the_samples(5, |b| Dop853::new().max_steps(b));
}

/// `t0 = 1e20` with `h = 1`: `t + h == t`, so no step of `h` can be taken.
/// The fixed-step methods must say so (`StepSizeUnderflow` with `t = 1e20`,
/// before any step) rather than merge the 98 304 steps to the next sample
/// (1e20 + 98 304, the nearest double to 1e20 + 1e5) into one: forgiving 8
/// ulps of `t` (1.8e5) for the rounding of sample times used to leave a
/// single step of 98 304, from which RK4 returned `Ok` with x ≈ 4e18.
/// Where `h` does advance `t` but only by a few ulps (`h = 1e5`, ulp 16 384),
/// the sample is still reached in 10 steps, not 9 of 1.1 h.
#[test]
fn a_step_that_does_not_advance_time_is_step_size_underflow() {
    let model = Oscillator::new(1.0, 1.0, 0.0);
    let (q0, qdot0) = (Vector1::new(1.0), Vector1::zeros());
    let (t0, end) = (1e20, 1e20 + 1e5);
    let fixed: [(&str, IntegrationResult<f64, 1>); 3] = [
        (
            "RK4",
            Rk4::new(1.0).integrate(&model, t0, q0, qdot0, &[end]),
        ),
        (
            "ImplicitMidpoint",
            ImplicitMidpoint::new(1.0).integrate(&model, t0, q0, qdot0, &[end]),
        ),
        (
            "Variational",
            Variational::new(1.0).integrate(&model, t0, q0, qdot0, &[end]),
        ),
    ];
    for (name, run) in fixed {
        let failure = run.expect_err(name);
        let IntegrationError::StepSizeUnderflow { t, h, q, .. } = failure.error else {
            panic!(
                "{name}: expected step size underflow, got {}",
                failure.error
            );
        };
        assert_eq!((t, h, q), (t0, 1.0, q0), "{name}");
        assert_eq!(failure.trajectory.stats().steps_accepted, 0, "{name}");
    }

    let free = Oscillator::new(1.0, 0.0, 0.0);
    let run = Rk4::new(1e5)
        .integrate(&free, t0, q0, qdot0, &[1e20 + 1e6])
        .unwrap();
    assert_eq!(run.stats().steps_accepted, 10);
}

/// A perfectly integrable motion at a tiny scale, `x = 1e-100 cos t`, with
/// an absolute tolerance tinier still (1e-300): `q̈ / atol` at the start is
/// 1e200, and the sums of squares in Hairer's first-step guess overflow. They
/// used to give h = 0, so Dopri5 and DOP853 stopped at t = 0 with "step size
/// underflow, h = 0" before trying a step, where Radau5 (which falls back to
/// RADAU5's default first step) integrated it. Now they fall back alike and
/// meet the tolerance: relative error ~rtol after 1.6 periods, 10 rtol
/// allowed.
#[test]
fn a_tiny_motion_with_a_tinier_absolute_tolerance_is_integrated() {
    let model = Oscillator::new(1.0, 1.0, 0.0);
    let (x0, v0) = (Vector1::new(1e-100), Vector1::zeros());
    let rtol = 1e-8;
    let runs: [(&str, IntegrationResult<f64, 1>); 3] = [
        (
            "Dopri5",
            Dopri5::new()
                .rtol(rtol)
                .atol(1e-300)
                .integrate(&model, 0.0, x0, v0, &[10.0]),
        ),
        (
            "Dop853",
            Dop853::new()
                .rtol(rtol)
                .atol(1e-300)
                .integrate(&model, 0.0, x0, v0, &[10.0]),
        ),
        (
            "Radau5",
            Radau5::new()
                .rtol(rtol)
                .atol(1e-300)
                .integrate(&model, 0.0, x0, v0, &[10.0]),
        ),
    ];
    for (name, run) in runs {
        let run = run.unwrap_or_else(|f| panic!("{name}: {f}"));
        let x = run.last().unwrap().q[0];
        let exact = 1e-100 * 10f64.cos();
        assert!(
            ((x - exact) / exact).abs() < 10.0 * rtol,
            "{name}: x = {x:e}"
        );
    }
}
