//! The pendulum in Cartesian coordinates against the θ pendulum: the same
//! motion, and a multiplier that is the rod tension.

use crate::support::elliptic;
use crate::support::fit::{log_slope, sci};
use lagrange::Method;
use lagrange::models::CartesianPendulum;
use lagrange::nalgebra::Vector2;
use lagrange::prelude::*;

/// Released from rest at 1 rad: far from the small-angle limit, so the
/// period and the tension are those of the full nonlinear pendulum.
const THETA0: f64 = 1.0;

fn model() -> CartesianPendulum {
    CartesianPendulum::new(0.7, 1.3, 9.81)
}

/// The exact state at `t`: the θ pendulum's elliptic-function solution,
/// good to ~1e-14 (`tests/support/elliptic.rs`), mapped to `(x, y)`.
fn exact(model: &CartesianPendulum, t: f64) -> (Vector2<f64>, Vector2<f64>) {
    let (theta, _) = elliptic::released_from_rest((model.g / model.l).sqrt(), THETA0);
    let (angle, rate) = theta(t);
    model.state(angle, rate)
}

fn start(model: &CartesianPendulum) -> (Vector2<f64>, Vector2<f64>) {
    model.state(THETA0, 0.0)
}

fn distance(a: &(Vector2<f64>, Vector2<f64>), b: &(Vector2<f64>, Vector2<f64>)) -> f64 {
    (a.0 - b.0).amax().max((a.1 - b.1).amax())
}

/// The bound: the same trajectory as the θ pendulum to 1e-9 over
/// 10 s, and the multiplier equal to the tension to 1e-9. Dop853 at
/// rtol = atol = 1e-13 makes a global error of ~1e-12 over these seven
/// periods (the reference tests show ~10 tol on non-chaotic problems), so
/// 1e-9 is met with three orders to spare; the tension is a function of
/// the state (λ from the saddle-point solve), so it errs by the state's
/// error times `m (g + 2 l |θ̇|) / l` ≈ 10, still far below 1e-9 · m g.
#[test]
fn cartesian_pendulum_follows_the_theta_pendulum_and_its_multiplier_is_the_tension() {
    let model = model();
    let (q0, v0) = start(&model);
    let times: Vec<f64> = (1..=200).map(|k| 0.05 * k as f64).collect();
    let run = Dop853::new()
        .rtol(1e-13)
        .atol(1e-13)
        .integrate(&model, 0.0, q0, v0, &times)
        .unwrap();
    let (mut worst_state, mut worst_tension) = (0.0f64, 0.0f64);
    for s in &run {
        let want = exact(&model, s.t);
        worst_state = worst_state.max(distance(&(s.q, s.qdot), &want));
        // φ = x² + y² − l²: the force on the bob is −Gᵀλ = −2λ (x, y), a
        // pull of 2 l λ towards the pivot.
        let lambda = model.multipliers(s.t, &s.q, &s.qdot).unwrap()[0];
        let tension = model.tension(&want.0, &want.1);
        worst_tension = worst_tension.max((2.0 * model.l * lambda - tension).abs());
    }
    println!("state error {worst_state:.2e}, tension error {worst_tension:.2e} N");
    assert!(worst_state < 1e-9, "state error {worst_state:.2e}");
    assert!(
        worst_tension < 1e-9 * model.m * model.g,
        "tension error {worst_tension:.2e}"
    );
}

/// Every method on the constrained model, with projection: each fixed-step
/// method keeps its order (projection onto the manifold after a step of
/// order p is a method of order p, Hairer–Lubich–Wanner IV.4), measured
/// over four halvings of h with errors far above round-off; the bound 0.2
/// on the observed order is the integrator suite's (the projection adds an
/// O(h^{p+1}) term, below the leading one). Adaptive methods at tolerance
/// 1e-9 stay within 100 tol, as in the reference tests.
#[test]
fn every_method_keeps_its_order_on_the_cartesian_pendulum() {
    let model = model();
    let (q0, v0) = start(&model);
    let end = 1.0;
    let want = exact(&model, end);
    for method in Method::ALL {
        if method.is_adaptive() {
            let tol = 1e-9;
            let run = method
                .with_tolerance(tol)
                .integrate(&model, 0.0, q0, v0, &[end])
                .unwrap();
            let s = run.last().unwrap();
            let error = distance(&(s.q, s.qdot), &want);
            println!("{}: error {error:.2e} at tol {tol:e}", method.id());
            assert!(error < 100.0 * tol, "{method:?}: {error:.2e}");
            continue;
        }
        let hs: Vec<f64> = match method.order() {
            1 => vec![2e-3, 1e-3, 5e-4, 2.5e-4],
            2 => vec![1e-2, 5e-3, 2.5e-3, 1.25e-3],
            4 => vec![4e-2, 2e-2, 1e-2, 5e-3],
            _ => vec![2e-1, 1e-1, 5e-2, 2.5e-2],
        };
        let errors: Vec<f64> = hs
            .iter()
            .map(|&h| {
                let run = method
                    .with_step(h)
                    .integrate(&model, 0.0, q0, v0, &[end])
                    .unwrap();
                let s = run.last().unwrap();
                distance(&(s.q, s.qdot), &want)
            })
            .collect();
        let p = log_slope(&hs, &errors);
        println!(
            "{}: order {p:.3} (theory {}), errors {}",
            method.id(),
            method.order(),
            sci(&errors)
        );
        assert!(
            errors.iter().all(|&e| e > 1e-11),
            "{method:?}: {}",
            sci(&errors)
        );
        assert!(
            (p - method.order() as f64).abs() <= 0.2,
            "{method:?}: order {p:.3}"
        );
    }
}
