//! Methods that share a driver or a step control fail alike: the Euler
//! methods as RK4, DOP853 as DOPRI5.

use super::CLOSE_IN;
use crate::models::{
    BlowUp, CoupledOscillator, ForcingBreaksDown, InertiaVanishes,
    assert_exhausted_budget_keeps_the_samples,
};
use lagrange_runtime::nalgebra::{SVector, Vector1, Vector2};
use lagrange_runtime::prelude::*;
use lagrange_runtime::{InvalidInput, NonFiniteValue};
use std::mem::discriminant;

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
    // y = 1e-10 asked to be right to ~1e-24, below the rounding x's terms
    // leave in its acceleration. From exactly 0 it would stay exactly 0 (the
    // solve of M q̈ = f is exact there) and any atol would be met.
    let start = (Vector2::new(1.0, 1e-10), Vector2::zeros());
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
