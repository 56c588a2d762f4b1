//! A fixed step beyond the method's stability limit stops with a typed
//! `Unstable` error, before the state overflows, with the samples before it.

use crate::models::{BlowUp, StiffChain};
use lagrange::models::Oscillator;
use lagrange_runtime::IntegrationResult;
use lagrange_runtime::nalgebra::{Vector1, Vector2};
use lagrange_runtime::prelude::*;

/// RK4's stability interval on the imaginary axis is |hω| ≤ 2.83; the stiff
/// chain's fast mode has ω = √(2·10⁶) ≈ 1414, so h = 0.01 (hω ≈ 14) is far
/// beyond it and h = 0.001 (hω ≈ 1.4) within it.
#[test]
fn rk4_beyond_its_stability_limit_reports_instability_not_infinity() {
    let chain = StiffChain::new();
    let (q0, v0) = (Vector2::new(0.1, 0.1001), Vector2::zeros());
    let times: Vec<f64> = (1..=10).map(|k| 0.1 * k as f64).collect();
    let failure = Rk4::new(0.01)
        .integrate(&chain, 0.0, q0, v0, &times)
        .unwrap_err();
    match failure.error {
        IntegrationError::Unstable {
            t,
            h,
            steps,
            q,
            qdot,
        } => {
            assert_eq!(h, 0.01);
            assert!(steps >= 1);
            // RK4 amplifies the fast mode by |R(14i)| ≈ 1570 per step; the
            // run is stopped on the first step past the floor (1000× the
            // starting scale of 1) once it has grown 256× in all, so the
            // state is at most 1000 · 1570, not the 1e22 of eight steps.
            let size = q.amax().max(qdot.amax());
            assert!(size < 1.6e6, "caught late, at |y| = {size:e}");
            assert!(t < 0.2, "caught late, at t = {t}");
            // Caught within ten steps: at |R(14i)| ≈ 1500 per step the state
            // is ~1e21 by then (1e40 leaves room), some 70 steps short of
            // overflowing an f64.
            let size = q
                .iter()
                .chain(qdot.iter())
                .fold(0.0f64, |m, x| m.max(x.abs()));
            assert!(size < 1e40, "state grew to {size:e}");
        }
        other => panic!("expected Unstable, got {other}"),
    }
    // The stable step runs to the end.
    assert!(
        Rk4::new(0.001)
            .integrate(&chain, 0.0, q0, v0, &times)
            .is_ok()
    );
}

/// Explicit Euler is unstable for any undamped oscillation, but slowly when
/// hω is small: no false alarm on an ordinary run, where the energy grows by
/// (1 + h²ω²)ⁿ — 1% here — not 2× per step.
#[test]
fn slow_growth_of_explicit_euler_is_no_false_alarm() {
    let chain = StiffChain::new();
    let (q0, v0) = (Vector2::new(0.1, 0.1), Vector2::zeros());
    assert!(
        ExplicitEuler::new(1e-5)
            .integrate(&chain, 0.0, q0, v0, &[0.05])
            .is_ok()
    );
}

/// The undamped chain and its fast angular frequency, `√` of the largest
/// eigenvalue of `K` (≈ 1414).
fn undamped_chain() -> (StiffChain, f64) {
    let chain = StiffChain {
        c_soft: 0.0,
        c_hard: 0.0,
        ..StiffChain::new()
    };
    let omega = chain.stiffness().symmetric_eigenvalues().max().sqrt();
    (chain, omega)
}

/// Every explicit method 1 % beyond its stability limit on the imaginary
/// axis (`hω = 2√2` for RK4, 2 for symplectic Euler; explicit Euler has no
/// such interval, so `hω = 1`, where it gains 41 % per step). The fast mode
/// then grows by only 7 % (RK4) or 33 % (symplectic Euler) per step, never
/// the 2× that marks fast growth, but it turns by 106° or flips sign from
/// one step to the next. Before the guard knew that signature, RK4 returned
/// `Ok` with a state of 1e115 at t = 10 and the Euler methods ran into an
/// overflow reported as a NaN forcing.
#[test]
fn explicit_methods_just_beyond_their_limit_stop_before_garbage() {
    let (chain, omega) = undamped_chain();
    let (q0, v0) = (Vector2::new(0.1, 0.1001), Vector2::zeros());
    let times: Vec<f64> = (1..=20).map(|k| 0.5 * k as f64).collect();
    let runs: [(&str, IntegrationResult<f64, 2>); 3] = [
        (
            "RK4",
            Rk4::new(1.01 * 8f64.sqrt() / omega).integrate(&chain, 0.0, q0, v0, &times),
        ),
        (
            "symplectic Euler",
            SymplecticEuler::new(1.01 * 2.0 / omega).integrate(&chain, 0.0, q0, v0, &times),
        ),
        (
            "explicit Euler",
            ExplicitEuler::new(1.0 / omega).integrate(&chain, 0.0, q0, v0, &times),
        ),
    ];
    for (name, run) in runs {
        let failure = run.expect_err(name);
        let IntegrationError::Unstable { t, q, qdot, .. } = failure.error else {
            panic!("{name}: expected Unstable, got {}", failure.error);
        };
        assert!(t < 1.0, "{name}: caught late, at t = {t}");
        // Caught within a few doublings of the 1000× floor, far from overflow.
        let size = q
            .iter()
            .chain(qdot.iter())
            .fold(0.0f64, |m, x| m.max(x.abs()));
        assert!(size < 1e12, "{name}: state grew to {size:e}");
        let kept = failure.trajectory.len();
        assert_eq!(failure.trajectory.times(), &times[..kept]);
    }
}

/// The other side of the line: a coarse but stable oscillation (symplectic
/// Euler at hω = 1.9, 3.3 steps per period: every step changes the state by
/// its own size, but it does not grow), and a resolved physical blow-up
/// (q = 1/(1 − t) to 2·10⁴, far above the 1000× floor, growing smoothly) run
/// to the end.
#[test]
fn rough_but_bounded_and_smooth_but_growing_are_no_false_alarms() {
    let (chain, omega) = undamped_chain();
    let (q0, v0) = (Vector2::new(0.1, 0.1001), Vector2::zeros());
    assert!(
        SymplecticEuler::new(1.9 / omega)
            .integrate(&chain, 0.0, q0, v0, &[10.0])
            .is_ok()
    );

    let blow_up = Rk4::new(1e-6)
        .integrate(
            &BlowUp,
            0.0,
            Vector1::new(1.0),
            Vector1::new(1.0),
            &[0.99995],
        )
        .unwrap();
    let q = blow_up.last().unwrap().q[0];
    assert!((q * (1.0 - 0.99995) - 1.0).abs() < 1e-6, "q = {q}");
}

/// A stiff damper instead of a stiff spring: `ẍ = −x − 1000 ẋ` decays at
/// rate λ ≈ −1000, and RK4 is stable for `hλ ≥ −2.785` on the negative real
/// axis. 1 % beyond, `R(hλ) = 1.02`: the mode grows by 2 % per step without
/// turning, smooth in `x` alone, but it moves against its own velocity
/// (`Δx ≈ +0.02 x` where `h ẋ ≈ −2.8 x`). Before the guard compared the two,
/// RK4 returned `Ok` with `x ≈ 1e49` at t = 10.
#[test]
fn rk4_just_beyond_its_limit_on_a_stiff_damper_stops_too() {
    let honey = Oscillator::new(1.0, 1.0, 1000.0);
    let lambda = (1000.0 + (1000.0f64.powi(2) - 4.0).sqrt()) / 2.0;
    let times: Vec<f64> = (1..=10).map(|k| k as f64).collect();
    let failure = Rk4::new(1.01 * 2.785 / lambda)
        .integrate(&honey, 0.0, Vector1::new(1.0), Vector1::new(0.0), &times)
        .unwrap_err();
    let IntegrationError::Unstable { t, q, qdot, .. } = failure.error else {
        panic!("expected Unstable, got {}", failure.error);
    };
    assert!(t < 10.0);
    assert!(q[0].abs().max(qdot[0].abs()) < 1e12, "q = {q}, q̇ = {qdot}");
    let kept = failure.trajectory.len();
    assert_eq!(failure.trajectory.times(), &times[..kept]);
}
