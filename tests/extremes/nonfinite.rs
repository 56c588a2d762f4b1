//! Numerical stability at the extremes: NaN and infinity going in, and a
//! model that starts returning NaN part-way.
//!
//! A NaN or an infinity in the initial state or in a parameter is refused
//! before the model is evaluated even once; a force that turns NaN at `t*`
//! stops the run with an error that says when (as close to `t*` as the
//! method can resolve) and in which state, and keeps every sample before.
//! For every integrator.
//!
//! Every test prints its figures; `cargo test --release --test suite --
//! extremes::nonfinite:: --nocapture --test-threads=1` shows them in order.

use lagrange::Method;
use lagrange::nalgebra::Vector1;
use lagrange::prelude::*;
use lagrange::{IntegrationResult, InvalidInput, NonFiniteValue, Stats};

lagrangian! {
    /// A spring `ω²` pushed by `a √(t* − t)`: the square root of a quantity
    /// that turns negative, as a model with a clearance, a remaining fuel
    /// mass or a table lookup past its end would have. With `a = 0` the
    /// motion is `x = cos ω t` up to `t*`, and the force is `0 · NaN = NaN`
    /// after it.
    pub struct RunsOut {
        coordinates: x;
        parameters: omega, a, t_star;
        kinetic: dot(x)^2/2;
        potential: omega^2*x^2/2;
        forces: x = a*sqrt(t_star - t);
    }
}

/// The fixed step, and the adaptive tolerances (the defaults).
const H: f64 = 0.01;

fn run(
    method: Method,
    model: &RunsOut,
    x0: f64,
    v0: f64,
    times: &[f64],
) -> IntegrationResult<f64, 1> {
    let (q0, qdot0) = (Vector1::new(x0), Vector1::new(v0));
    method.with_step(H).integrate(model, 0.0, q0, qdot0, times)
}

/// Every 1/2 up to 5.
fn samples() -> Vec<f64> {
    (1..=10).map(|k| 0.5 * k as f64).collect()
}

/// NaN and ±inf in `x0`, in `ẋ0`, and in each kind of parameter: every
/// method refuses each with the `InvalidInput` that names it, before any
/// work (all of `Stats` zero, no sample), so that a NaN never enters a
/// trajectory or an error estimate.
#[test]
fn non_finite_initial_state_or_parameters_are_refused_before_any_work() {
    let good = RunsOut::new(1.0, 0.0, 10.0);
    let bad_parameters = [
        RunsOut::new(f64::NAN, 0.0, 10.0),
        RunsOut::new(1.0, f64::INFINITY, 10.0),
        RunsOut::new(1.0, 0.0, f64::NEG_INFINITY),
    ];
    for method in Method::ALL {
        let name = &format!("{method:?}");
        let mut refused = 0;
        let mut check = |run: IntegrationResult<f64, 1>,
                         expected: &dyn Fn(&InvalidInput<f64>) -> bool| {
            let failure = run.expect_err(name);
            let IntegrationError::InvalidInput(invalid) = &failure.error else {
                panic!("{name}: expected InvalidInput, got {}", failure.error);
            };
            assert!(expected(invalid), "{name}: {invalid}");
            assert_eq!(
                failure.trajectory.stats(),
                Stats::default(),
                "{name}: {invalid}"
            );
            assert!(failure.trajectory.is_empty());
            refused += 1;
        };
        for x0 in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            check(
                run(method, &good, x0, 0.0, &samples()),
                &|e| matches!(e, InvalidInput::NonFiniteInitialPosition { coordinate: "x", value } if value.to_bits() == x0.to_bits()),
            );
            check(
                run(method, &good, 1.0, x0, &samples()),
                &|e| matches!(e, InvalidInput::NonFiniteInitialVelocity { coordinate: "x", value } if value.to_bits() == x0.to_bits()),
            );
        }
        for model in &bad_parameters {
            check(run(method, model, 1.0, 0.0, &samples()), &|e| {
                matches!(e, InvalidInput::NonFiniteParameters)
            });
        }
        check(run(method, &good, 1.0, 0.0, &[1.0, f64::NAN]), &|e| {
            matches!(e, InvalidInput::NonFiniteSampleTime { index: 1, .. })
        });
        println!(
            "nonfinite | {name} | {refused} non-finite inputs refused as InvalidInput, 0 evaluations"
        );
        assert_eq!(refused, 10);
    }
}

/// Where in a step of length 1 each fixed-step method evaluates the model:
/// the step start (explicit Euler and symplectic Euler only there; the
/// Gauss methods also take their Jacobian there), the stage nodes, or the
/// midpoint alone (the variational integrator).
fn evaluation_nodes(method: Method) -> Vec<f64> {
    let (r3, r15) = (3f64.sqrt() / 6.0, 15f64.sqrt() / 10.0);
    match method {
        Method::ExplicitEuler | Method::SymplecticEuler => vec![0.0],
        Method::Rk4 => vec![0.0, 0.5, 1.0],
        Method::ImplicitMidpoint => vec![0.0, 0.5],
        Method::GaussLegendre2 => vec![0.0, 0.5 - r3, 0.5 + r3],
        Method::GaussLegendre3 => vec![0.0, 0.5 - r15, 0.5, 0.5 + r15],
        Method::Variational => vec![0.5],
        m if m.is_adaptive() => unreachable!("{m:?} is adaptive"),
        m => panic!("{m:?}: where does a step evaluate the model?"),
    }
}

/// The first evaluation time past `t_star` on the grid of steps `H` from
/// the sample before it.
fn first_evaluation_past(nodes: Vec<f64>, t_star: f64) -> f64 {
    let start = (t_star / 0.5).floor() * 0.5;
    (0..)
        .flat_map(|k| nodes.iter().map(move |c| start + (k as f64 + c) * H))
        .find(|&t| t > t_star)
        .unwrap()
}

/// `a √(t* − t)` with `a = 0` is 0 up to `t* = 2.3456` and NaN after. Every
/// method must stop with `NonFiniteState` at the first evaluation past `t*`
/// (the forcing is `Forcing`; the variational integrator, which evaluates
/// the forces on their own, reports `NonconservativeForces`):
///
/// - fixed steps (h = 0.01) evaluate on a grid, so the first time past `t*`
///   is within one step, `t* < t ≤ t* + h`, and it is exactly the first of
///   the method's evaluation times past `t*` (step starts, stage nodes, or
///   midpoints for the variational integrator; see `evaluation_nodes`);
/// - adaptive ones retry a failed step shorter (Dopri5 and DOP853 by 5×,
///   Radau5 by 2×) until the step no longer moves `t`, `h ≤ 10 ε t`, so the
///   failing evaluation is within a few `10 ε t*` of `t*`: 1e-12 relative
///   leaves a factor of ~100.
///
/// The state reported is where the model was evaluated, `x ≈ cos t` up to
/// the method's error there: first-order methods ≈ h t / 2 ≈ 1.2e-2, so
/// 0.05; the others err by less than a Runge–Kutta stage's `h²/2 = 5e-5`,
/// so 1e-3 (adaptive ones at tolerance 1e-8, far less). Every sample before
/// `t*` is kept, finite and as accurate; none after.
#[test]
fn a_force_that_turns_nan_at_t_star_stops_the_run_there() {
    let t_star = 2.3456;
    let model = RunsOut::new(1.0, 0.0, t_star);
    let times = samples();
    let before = times.iter().filter(|&&t| t < t_star).count();
    for method in Method::ALL {
        let name = &format!("{method:?}");
        let failure = run(method, &model, 1.0, 0.0, &times).expect_err(name);
        let IntegrationError::NonFiniteState { t, q, qdot, value } = failure.error else {
            panic!("{name}: expected NonFiniteState, got {}", failure.error);
        };
        let stats = failure.trajectory.stats();
        let error = (q[0] - t.cos()).abs().max((qdot[0] + t.sin()).abs());
        println!(
            "nonfinite | force NaN after t* = {t_star} | {name} | NonFiniteState ({value:?}) at t* + {:.1e}, state error {error:.1e}, {} samples kept, {} rhs",
            t - t_star,
            failure.trajectory.len(),
            stats.rhs_evals
        );
        let expected = if method == Method::Variational {
            NonFiniteValue::NonconservativeForces
        } else {
            NonFiniteValue::Forcing
        };
        assert_eq!(value, expected, "{name}");
        assert!(t > t_star, "{name}: t = {t}");
        if method.is_adaptive() {
            assert!(t - t_star <= 1e-12 * t_star, "{name}: t = {t}");
        } else {
            assert!(t - t_star <= H, "{name}: t = {t}");
            let first = first_evaluation_past(evaluation_nodes(method), t_star);
            assert!(
                (t - first).abs() < 1e-12,
                "{name}: t = {t}, expected {first}"
            );
        }
        let first_order = method.order() == 1;
        let allowed = if first_order { 0.05 } else { 1e-3 };
        assert!(error <= allowed, "{name}: state error {error:e}");
        assert_eq!(failure.trajectory.times(), &times[..before], "{name}");
        for s in &failure.trajectory {
            let e = (s.q[0] - s.t.cos())
                .abs()
                .max((s.qdot[0] + s.t.sin()).abs());
            assert!(e <= allowed, "{name}: sample at {} off by {e:e}", s.t);
        }
    }
}
