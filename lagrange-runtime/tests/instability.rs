//! A fixed step beyond the method's stability limit stops with a typed
//! `Unstable` error, before the state overflows, with the samples before it.

mod models;

use lagrange_runtime::nalgebra::Vector2;
use lagrange_runtime::prelude::*;
use models::StiffChain;

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
            assert!(q.iter().chain(qdot.iter()).all(|x| x.is_finite()));
        }
        other => panic!("expected Unstable, got {other}"),
    }
    // The stable step runs to the end.
    assert!(Rk4::new(0.001)
        .integrate(&chain, 0.0, q0, v0, &times)
        .is_ok());
}

/// Explicit Euler is unstable for any undamped oscillation, but slowly when
/// hω is small: no false alarm on an ordinary run, where the energy grows by
/// (1 + h²ω²)ⁿ — 1% here — not 2× per step.
#[test]
fn slow_growth_of_explicit_euler_is_no_false_alarm() {
    let chain = StiffChain::new();
    let (q0, v0) = (Vector2::new(0.1, 0.1), Vector2::zeros());
    assert!(ExplicitEuler::new(1e-5)
        .integrate(&chain, 0.0, q0, v0, &[0.05])
        .is_ok());
}
