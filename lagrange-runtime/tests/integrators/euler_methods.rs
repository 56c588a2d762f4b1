//! The two first-order methods: both converge at order one, on a linear and
//! on a nonlinear model, and on an oscillator symplectic Euler keeps the
//! energy where explicit Euler pumps it up.

use crate::models::{CoupledOscillator, max_difference, max_error, observed_order};
use lagrange::models::DoublePendulum;
use lagrange_runtime::Trajectory;
use lagrange_runtime::nalgebra::Vector2;
use lagrange_runtime::prelude::*;

const OMEGA: f64 = 2.0;

fn oscillator_start() -> (Vector2<f64>, Vector2<f64>) {
    (Vector2::new(1.0, -0.5), Vector2::new(0.3, 0.8))
}

/// Every 0.2 up to t = 2.
fn samples() -> Vec<f64> {
    (1..=10).map(|i| 0.2 * i as f64).collect()
}

/// Four halvings from 1e-3: up to 32 000 steps, all in the asymptotic range
/// (see the tolerance argument below).
const STEP_SIZES: [f64; 5] = [1e-3, 5e-4, 2.5e-4, 1.25e-4, 6.25e-5];

/// Runs `method(h)` for every step size and returns the observed order and
/// the errors measured by `error`.
fn order_of<M, const N: usize>(
    method: impl Fn(f64) -> M,
    run: impl Fn(&M) -> Trajectory<f64, N>,
    error: impl Fn(&Trajectory<f64, N>) -> f64,
) -> (f64, Vec<f64>) {
    let errors: Vec<f64> = STEP_SIZES
        .iter()
        .map(|&h| error(&run(&method(h))))
        .collect();
    (observed_order(&STEP_SIZES, &errors), errors)
}

// Tolerance of the order tests: a first-order method's global error is
// C h + D h² + rounding, so the fitted slope is 1 + O(D h / C): the ratio of
// successive errors is 2^(1.00…1.015) here (largest on the pendulum at
// h = 1e-3). Rounding, ~1e-16 per step over ≤ 32 000 steps (≲ 1e-11), is far
// below the smallest error (~6e-5), and the pendulum reference (DOPRI5 at
// 1e-13, error ~1e-11) is too. So the slope is within 0.02 of 1; ±0.2 still
// rejects a method of order 0.8 or 1.2, let alone 2.

#[test]
fn explicit_euler_converges_at_order_one_on_the_oscillator() {
    let model = CoupledOscillator { omega: OMEGA };
    let (q0, qdot0) = oscillator_start();
    let (order, errors) = order_of(
        ExplicitEuler::new,
        |m| m.integrate(&model, 0.0, q0, qdot0, &samples()).unwrap(),
        |t| max_error(&model, t, q0, qdot0),
    );
    assert!(
        (order - 1.0).abs() < 0.2,
        "order {order}, errors {errors:?}"
    );
}

#[test]
fn symplectic_euler_converges_at_order_one_on_the_oscillator() {
    let model = CoupledOscillator { omega: OMEGA };
    let (q0, qdot0) = oscillator_start();
    let (order, errors) = order_of(
        SymplecticEuler::new,
        |m| m.integrate(&model, 0.0, q0, qdot0, &samples()).unwrap(),
        |t| max_error(&model, t, q0, qdot0),
    );
    assert!(
        (order - 1.0).abs() < 0.2,
        "order {order}, errors {errors:?}"
    );
}

/// A double pendulum in regular (not chaotic) motion, and its DOPRI5
/// reference at tolerance 1e-13.
fn pendulum_and_reference() -> (
    DoublePendulum,
    Vector2<f64>,
    Vector2<f64>,
    Trajectory<f64, 2>,
) {
    let model = DoublePendulum::unit();
    let (q0, qdot0) = (Vector2::new(0.5, -0.3), Vector2::new(0.0, 0.4));
    let reference = Dopri5::new()
        .rtol(1e-13)
        .atol(1e-13)
        .integrate(&model, 0.0, q0, qdot0, &samples())
        .unwrap();
    (model, q0, qdot0, reference)
}

#[test]
fn explicit_euler_converges_at_order_one_on_the_double_pendulum() {
    let (model, q0, qdot0, reference) = pendulum_and_reference();
    let (order, errors) = order_of(
        ExplicitEuler::new,
        |m| m.integrate(&model, 0.0, q0, qdot0, &samples()).unwrap(),
        |t| max_difference(t, &reference),
    );
    assert!(
        (order - 1.0).abs() < 0.2,
        "order {order}, errors {errors:?}"
    );
}

#[test]
fn symplectic_euler_is_still_order_one_with_a_configuration_dependent_mass_matrix() {
    let (model, q0, qdot0, reference) = pendulum_and_reference();
    let (order, errors) = order_of(
        SymplecticEuler::new,
        |m| m.integrate(&model, 0.0, q0, qdot0, &samples()).unwrap(),
        |t| max_difference(t, &reference),
    );
    assert!(
        (order - 1.0).abs() < 0.2,
        "order {order}, errors {errors:?}"
    );
}

#[test]
fn symplectic_euler_energy_stays_within_h_omega_while_explicit_euler_energy_grows() {
    let model = CoupledOscillator { omega: OMEGA };
    let (q0, qdot0) = oscillator_start();
    let e0 = model.energy(0.0, &q0, &qdot0);
    let h = 1e-3;
    let steps = 100_000;
    // A sample after every step: t = 100, about 32 periods.
    let times: Vec<f64> = (1..=steps).map(|i| h * i as f64).collect();
    let relative_energy_error = |trajectory: &Trajectory<f64, 2>| -> Vec<f64> {
        let stats = trajectory.stats();
        // One step per sample, one evaluation per step: the samples i·h,
        // rounded late in the run, must not cost a sliver step each.
        assert_eq!((stats.steps_accepted, stats.rhs_evals), (steps, steps));
        trajectory
            .iter()
            .map(|s| (model.energy(s.t, &s.q, &s.qdot) - e0) / e0)
            .collect()
    };

    // Kick-drift Euler on q̈ = -ω² q conserves exactly the modified energy
    // H̃ = E - ½ h ω² qᵀ M q̇, and |qᵀ M q̇| ≤ E / ω, so |E - H̃| ≤ ½ h ω E and
    // |E_n / E_0 - 1| ≤ h ω / (1 - h ω / 2) for every n: O(h), no drift
    // (2.002e-3 here; about 8e-4 is reached, in the first period).
    let symplectic = SymplecticEuler::new(h)
        .integrate(&model, 0.0, q0, qdot0, &times)
        .unwrap();
    let bound = h * OMEGA / (1.0 - h * OMEGA / 2.0);
    let worst = relative_energy_error(&symplectic)
        .into_iter()
        .fold(0.0, |worst: f64, e| worst.max(e.abs()));
    assert!(worst <= bound, "energy error {worst:e} > bound {bound:e}");

    // Explicit Euler multiplies ω² |q|²_M + |q̇|²_M by exactly 1 + h² ω² per
    // step: after 1e5 steps E grows by 49 %. Rounding, ~1e-16 per step, adds
    // at most ~1e-11 relative, so 1e-9 checks the growth law itself.
    let explicit = ExplicitEuler::new(h)
        .integrate(&model, 0.0, q0, qdot0, &times)
        .unwrap();
    let growth = relative_energy_error(&explicit);
    let expected = (1.0 + h * h * OMEGA * OMEGA).powi(steps as i32) - 1.0;
    let last = growth[steps - 1];
    assert!(
        (last - expected).abs() < 1e-9,
        "energy grew by {last}, expected {expected}"
    );
    assert!(growth.windows(2).all(|w| w[1] > w[0]), "growth is monotone");
}

#[test]
fn both_euler_methods_take_one_evaluation_per_step() {
    let model = CoupledOscillator { omega: OMEGA };
    let (q0, qdot0) = oscillator_start();
    // 2 / 0.01 = 200 steps of exactly h.
    for stats in [
        ExplicitEuler::new(0.01)
            .integrate(&model, 0.0, q0, qdot0, &samples())
            .unwrap()
            .stats(),
        SymplecticEuler::new(0.01)
            .integrate(&model, 0.0, q0, qdot0, &samples())
            .unwrap()
            .stats(),
    ] {
        assert_eq!((stats.steps_accepted, stats.rhs_evals), (200, 200));
    }
}

#[test]
fn one_step_of_each_method_is_its_textbook_formula() {
    let model = CoupledOscillator { omega: OMEGA };
    let (q0, qdot0) = oscillator_start();
    let h = 0.1;
    let qddot0 = -q0 * (OMEGA * OMEGA);
    let step = |trajectory: Trajectory<f64, 2>| {
        let s = trajectory.last().unwrap();
        (s.q, s.qdot)
    };
    // q̈ comes from solving M q̈ = f with cond(M) = 3 (backward stable), so
    // it and the updates are exact to a few ε · |y| ≲ 1e-15.
    let close = |(q, qdot): (Vector2<f64>, Vector2<f64>),
                 (eq, eqdot): (Vector2<f64>, Vector2<f64>)| {
        (q - eq).amax().max((qdot - eqdot).amax()) < 1e-14
    };

    let explicit = ExplicitEuler::new(h).integrate(&model, 0.0, q0, qdot0, &[h]);
    let expected = (q0 + qdot0 * h, qdot0 + qddot0 * h);
    assert!(close(step(explicit.unwrap()), expected));

    // The kick first, then the drift with the new velocity.
    let symplectic = SymplecticEuler::new(h).integrate(&model, 0.0, q0, qdot0, &[h]);
    let kicked = qdot0 + qddot0 * h;
    assert!(close(step(symplectic.unwrap()), (q0 + kicked * h, kicked)));
}
