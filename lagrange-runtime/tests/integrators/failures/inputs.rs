//! Inputs that are wrong, or at the edge of what the arithmetic can do:
//! refused before any work, or ended by a clean typed error rather than a
//! hang; and one that only looks impossible, integrated.

use crate::models::{CoupledOscillator, assert_exhausted_budget_keeps_the_samples};
use lagrange::models::Oscillator;
use lagrange_runtime::nalgebra::{Vector1, Vector2};
use lagrange_runtime::prelude::*;
use lagrange_runtime::{IntegrationResult, InvalidInput};

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
    // y = 1e-10 is asked to be right to rtol |y| + atol ≈ 1e-24, far below
    // the rounding (~1e-16) that x's terms leave in its acceleration: the
    // steps shrink until the budget of 100 000 ends the run short of t = 1.
    // (While the first step guess overflowed to h = 0, it stopped at t = 0
    // having tried nothing, with "step size underflow".) From exactly
    // y = 0 it would stay exactly 0, the solve of M q̈ = f being exact there,
    // and any atol would be met.
    let model = CoupledOscillator { omega: 2.0 };
    let (q0, qdot0) = (Vector2::new(1.0, 1e-10), Vector2::zeros());
    let failure = Dopri5::new()
        .rtol(1e-14)
        .atol(1e-300)
        .integrate(&model, 0.0, q0, qdot0, &[1.0])
        .unwrap_err();
    let IntegrationError::TooManySteps { t, .. } = failure.error else {
        panic!("expected too many steps, got {}", failure.error);
    };
    assert!(t > 0.0 && t < 1.0, "t = {t}");
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

/// `ẍ = −x` solved by hand in `accelerations`; its `M` and `f` say
/// `ẍ = 0`, so a run that ignored the method would leave `x` at 1.
struct SolvedSpring<const FLAGGED: bool>;

impl<const FLAGGED: bool> Lagrangian<1> for SolvedSpring<FLAGGED> {
    type Scalar = f64;
    const COORDINATES: [&'static str; 1] = ["x"];
    const SOLVES_ACCELERATIONS: bool = FLAGGED;
    fn mass_matrix(&self, _: f64, _: &Vector1<f64>) -> lagrange_runtime::nalgebra::Matrix1<f64> {
        lagrange_runtime::nalgebra::Matrix1::new(1.0)
    }
    fn forcing(&self, _: f64, _: &Vector1<f64>, _: &Vector1<f64>) -> Vector1<f64> {
        Vector1::new(0.0)
    }
    fn kinetic_energy(&self, _: f64, _: &Vector1<f64>, v: &Vector1<f64>) -> f64 {
        0.5 * v[0] * v[0]
    }
    fn potential_energy(&self, _: f64, q: &Vector1<f64>) -> f64 {
        0.5 * q[0] * q[0]
    }
    fn accelerations(
        &self,
        _: f64,
        q: &Vector1<f64>,
        _: &Vector1<f64>,
    ) -> Option<Result<Vector1<f64>, IntegrationError<f64, 1>>> {
        Some(Ok(-q))
    }
}

#[test]
fn accelerations_without_their_flag_are_refused_instead_of_ignored() {
    let (q0, qdot0) = (Vector1::new(1.0), Vector1::new(0.0));
    let failure = Dop853::new()
        .integrate(&SolvedSpring::<false>, 0.0, q0, qdot0, &[1.0])
        .unwrap_err();
    assert!(
        matches!(
            failure.error,
            IntegrationError::InvalidInput(InvalidInput::AccelerationsNotFlagged)
        ),
        "{}",
        failure.error
    );
    assert!(failure.trajectory.is_empty());
    // Flagged, the method is what the run integrates: x = cos t (Dop853 at
    // its default tolerances, 1e-6, is within 1e-6 of it at t = 1).
    let run = Dop853::new()
        .integrate(&SolvedSpring::<true>, 0.0, q0, qdot0, &[1.0])
        .unwrap();
    let x = run.iter().last().unwrap().q[0];
    assert!((x - 1f64.cos()).abs() < 1e-6, "{x}");
}
