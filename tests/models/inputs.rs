//! Control inputs end to end on the cart-pole (`lagrange::models::CartPole`,
//! a motor force on the cart): unset inputs refused by every method, a
//! constant input against the hand-computed acceleration, a feedback
//! controller run and counted, a controller's NaN reported where it happened.

use lagrange::Method;
use lagrange::analysis::{AnalysisError, equilibrium, linearize, modes};
use lagrange::models::CartPole;
use lagrange::nalgebra::{Matrix2, Vector1, Vector2};
use lagrange::prelude::*;
use lagrange::{InvalidInput, NonFiniteValue};

fn cart() -> CartPole {
    CartPole::new(1.2, 0.3, 0.8, 9.81)
}

/// `M q̈ = f` solved by hand for the cart-pole:
/// `M = [[mc + mp, mp l cos θ], [mp l cos θ, mp l²]]`,
/// `f = (u + mp l sin θ θ̇², mp g l sin θ)`.
fn hand_acceleration(c: &CartPole, u: f64, q: Vector2<f64>, v: Vector2<f64>) -> Vector2<f64> {
    let (s, co) = (q[1].sin(), q[1].cos());
    let m = Matrix2::new(
        c.mc + c.mp,
        c.mp * c.l * co,
        c.mp * c.l * co,
        c.mp * c.l * c.l,
    );
    let f = Vector2::new(u + c.mp * c.l * s * v[1] * v[1], c.mp * c.g * c.l * s);
    m.try_inverse().unwrap() * f
}

#[test]
fn unset_inputs_are_refused_by_every_method() {
    let model = cart();
    assert!(model.force.is_nan(), "inputs start unset");
    assert_eq!(CartPole::<f64>::INPUTS, ["force"]);
    for method in Method::ALL {
        let failure = method
            .integrator(1e-3, 1e-8)
            .integrate(
                &model,
                0.0,
                Vector2::new(0.0, 0.1),
                Vector2::zeros(),
                &[0.1],
            )
            .unwrap_err();
        assert_eq!(
            failure.error,
            IntegrationError::InvalidInput(InvalidInput::InputsNotSet { inputs: &["force"] }),
            "{method:?}"
        );
        assert!(failure.trajectory.is_empty());
        let message = failure.error.to_string();
        assert!(
            message.contains("control inputs (force) that were never set"),
            "{message}"
        );
    }
}

#[test]
fn a_constant_input_gives_the_hand_computed_acceleration() {
    let model = cart().with_inputs(&Vector1::new(3.0));
    assert_eq!(model.inputs(), Vector1::new(3.0));
    let (q, v) = (Vector2::new(0.4, 0.7), Vector2::new(-0.2, 1.3));
    let qdd = lagrange::dynamics::acceleration(&model, 0.0, &q, &v).unwrap();
    let expected = hand_acceleration(&model, 3.0, q, v);
    // A 2 × 2 solve of entries of order 10: rounding ~1e-15, 1e-12 is ample.
    assert!((qdd - expected).norm() < 1e-12, "{qdd} vs {expected}");
    assert_eq!(
        Actuated::input_jacobian(&model, 0.0, &q, &v),
        lagrange::nalgebra::Matrix2x1::new(1.0, 0.0)
    );
    // And a short run with every method reaches the same state as Rk4.
    let times = [0.2];
    let reference = Rk4::new(1e-4).integrate(&model, 0.0, q, v, &times).unwrap();
    for method in Method::ALL {
        let run = method
            .integrator(1e-4, 1e-10)
            .integrate(&model, 0.0, q, v, &times)
            .unwrap();
        // First-order Euler methods err by ~h·t·|q̈| ≈ 1e-4 · 0.2 · 10;
        // the others agree far closer.
        let d = (run.last().unwrap().q - reference.last().unwrap().q).norm();
        assert!(d < 1e-3, "{method:?}: {d}");
    }
}

#[test]
fn a_pd_controller_balances_the_pole_and_its_calls_are_counted() {
    let model = cart();
    let controlled = model.with_controller(|_, q: &Vector2<f64>, v: &Vector2<f64>| {
        Vector1::new(60.0 * q[1] + 12.0 * v[1] + 1.0 * q[0] + 2.5 * v[0])
    });
    let times: Vec<f64> = (1..=50).map(|k| 0.1 * k as f64).collect();
    let h = 1e-3;
    let run = Rk4::new(h)
        .integrate(
            &controlled,
            0.0,
            Vector2::new(0.0, 0.2),
            Vector2::zeros(),
            &times,
        )
        .unwrap();
    // Rk4 evaluates four right-hand sides per step, each one call.
    assert_eq!(controlled.controller_calls(), run.stats().rhs_evals);
    assert!(run.stats().rhs_evals >= 4 * 5000);
    let last = run.last().unwrap();
    assert!(last.q[1].abs() < 1e-2, "the pole falls: θ = {}", last.q[1]);
    // Without the controller the same start falls past horizontal.
    let free = Rk4::new(h)
        .integrate(
            &model.with_inputs(&Vector1::new(0.0)),
            0.0,
            Vector2::new(0.0, 0.2),
            Vector2::zeros(),
            &[2.0],
        )
        .unwrap();
    assert!(free.last().unwrap().q[1].abs() > 1.0);
}

#[test]
fn a_non_finite_controller_output_is_a_typed_error_with_its_time() {
    let model = cart();
    let controlled =
        model.with_controller(|t: f64, _, _| Vector1::new(if t < 0.5 { 1.0 } else { f64::NAN }));
    for method in Method::ALL {
        let failure = method
            .integrator(1e-2, 1e-8)
            .integrate(
                &controlled,
                0.0,
                Vector2::new(0.0, 0.1),
                Vector2::zeros(),
                &[0.3, 1.0],
            )
            .unwrap_err();
        match failure.error {
            IntegrationError::NonFiniteState { t, value, .. } => {
                assert_eq!(value, NonFiniteValue::Inputs, "{method:?}");
                assert!((0.5..1.0).contains(&t), "{method:?}: t = {t}");
            }
            other => panic!("{method:?}: {other}"),
        }
        assert_eq!(
            failure.trajectory.len(),
            1,
            "{method:?}: the sample at 0.3 is kept"
        );
    }
}

lagrange::lagrangian! {
    /// A bob on a rod in Cartesian coordinates, pushed sideways by `fx`.
    struct PushedBob {
        coordinates: x, y;
        parameters: m, l, g;
        inputs: fx;
        kinetic: m/2*(dot(x)^2 + dot(y)^2);
        potential: m*g*y;
        forces: x = fx;
        constraints: rod: x^2 + y^2 = l^2;
    }
}

lagrange::lagrangian! {
    /// The same bob in its angle from the downward vertical.
    struct PushedArm {
        coordinates: theta;
        parameters: m, l, g;
        inputs: fx;
        let xb = l*sin(theta);
        kinetic: m/2*l^2*dot(theta)^2;
        potential: -m*g*l*cos(theta);
        forces: xb = fx;
    }
}

/// A constrained model under a feedback controller: the controller reads
/// the redundant state, its force goes through the saddle-point solve, the
/// constraints stay closed (drift control of the controlled model, set per
/// run with `with_drift`, each of the three), and the motion equals the minimal-coordinate
/// model's under the same physical law `fx = −c ẋ + a sin(ω t)`.
#[test]
fn a_constrained_model_under_a_controller_moves_as_its_minimal_twin() {
    let (m, l, g, c, a, w) = (0.8, 0.6, 9.81, 0.5, 1.3, 2.0);
    let law = move |t: f64, xdot: f64| -c * xdot + a * (w * t).sin();
    let bob = PushedBob::new(m, l, g);
    let arm = PushedArm::new(m, l, g);
    let bob_driven = bob
        .with_controller(move |t, _: &Vector2<f64>, v: &Vector2<f64>| Vector1::new(law(t, v[0])));
    let arm_driven = arm.with_controller(move |t, q: &Vector1<f64>, v: &Vector1<f64>| {
        Vector1::new(law(t, l * q[0].cos() * v[0]))
    });
    let theta0: f64 = 0.7;
    let times: Vec<f64> = (1..=40).map(|k| 0.25 * k as f64).collect();
    let tol = 1e-11;
    let method = Dop853::new().rtol(tol).atol(tol);
    let twin = method
        .integrate(
            &arm_driven,
            0.0,
            Vector1::new(theta0),
            Vector1::zeros(),
            &times,
        )
        .unwrap();
    let q0 = Vector2::new(l * theta0.sin(), -l * theta0.cos());
    for drift in [
        Drift::Projection,
        Drift::Baumgarte {
            alpha: 20.0,
            beta: 20.0,
        },
        Drift::None,
    ] {
        let run = method
            .integrate(
                &(&bob_driven).with_drift(drift),
                0.0,
                q0,
                Vector2::zeros(),
                &times,
            )
            .unwrap();
        let mut worst: f64 = 0.0;
        for (s, r) in run.iter().zip(twin.iter()) {
            worst = worst.max((s.q[0].atan2(-s.q[1]) - r.q[0]).abs());
        }
        let closure = run.stats().max_position_residual;
        println!("{drift:?}: angle error {worst:.1e} rad, largest |φ| {closure:.1e} m²");
        // Both runs' global errors at tolerance 1e-11 over 10 s (≈ 7
        // forced, damped swings) are each a few times the tolerance; the
        // largest seen is 3e-11 rad. 1e-9 (100× the tolerance) fails on a
        // wrong force, a controller reading the wrong state or a lost
        // drift setting. Without drift control |φ| grows by the
        // integration error alone (6e-11 m² here); 1e-9 m² bounds all three.
        assert!(worst < 1e-9, "{drift:?}: {worst}");
        assert!(closure < 1e-9, "{drift:?}: {closure}");
    }
}

/// The three drift controls, for the layered runs below.
fn drifts() -> [Drift<f64>; 3] {
    [
        Drift::Projection,
        Drift::Baumgarte {
            alpha: 20.0,
            beta: 20.0,
        },
        Drift::None,
    ]
}

/// Issue 23, defect 1: a constrained model with inputs never set, given
/// another drift control, was integrated into "the forcing is NaN at
/// t = 0" (the drift wrapper did not pass the input check on). It is
/// refused before the first step, like the model itself.
#[test]
fn unset_inputs_are_refused_under_another_drift_control() {
    let bob = PushedBob::new(0.8, 0.6, 9.81);
    let (q0, v0) = (Vector2::new(0.0, -0.6), Vector2::zeros());
    for method in Method::ALL {
        for drift in drifts() {
            let failure = method
                .integrator(1e-3, 1e-8)
                .integrate(&bob.with_drift(drift), 0.0, q0, v0, &[0.1])
                .unwrap_err();
            assert_eq!(
                failure.error,
                IntegrationError::InvalidInput(InvalidInput::InputsNotSet { inputs: &["fx"] }),
                "{method:?}, {drift:?}"
            );
            assert!(failure.trajectory.is_empty());
        }
    }
}

/// Issue 23, defect 2: a controlled constrained model whose controller
/// returns NaN was reported as "the forcing is NaN" (the saddle-point
/// solve did not ask whom to blame). The inputs are blamed, at a time
/// after the controller turned, with or without another drift control.
#[test]
fn a_constrained_models_nan_controller_is_blamed_with_or_without_a_drift_control() {
    let bob = PushedBob::new(0.8, 0.6, 9.81);
    let (q0, v0) = (Vector2::new(0.0, -0.6), Vector2::new(0.5, 0.0));
    let controller = |t: f64, _: &Vector2<f64>, _: &Vector2<f64>| {
        Vector1::new(if t < 0.5 { 1.0 } else { f64::NAN })
    };
    for method in Method::ALL {
        let integrator = method.integrator(1e-2, 1e-8);
        let plain =
            integrator.integrate(&bob.with_controller(controller), 0.0, q0, v0, &[0.3, 1.0]);
        let mut runs = vec![("no drift layer".to_string(), plain)];
        for drift in drifts() {
            let run = integrator.integrate(
                &bob.with_controller(controller).with_drift(drift),
                0.0,
                q0,
                v0,
                &[0.3, 1.0],
            );
            runs.push((format!("{drift:?}"), run));
        }
        for (layer, run) in runs {
            let failure = run.unwrap_err();
            match failure.error {
                IntegrationError::NonFiniteState { t, value, .. } => {
                    assert_eq!(value, NonFiniteValue::Inputs, "{method:?}, {layer}");
                    assert!((0.5..1.0).contains(&t), "{method:?}, {layer}: t = {t}");
                }
                other => panic!("{method:?}, {layer}: {other}"),
            }
        }
    }
}

/// Issue 23, defect 5: linearizing, searching an equilibrium of, or
/// taking the modes of a model whose inputs were never set said "the
/// forcing is NaN"; it is the inputs' error, before any evaluation.
#[test]
fn analysis_of_a_model_with_inputs_never_set_says_so() {
    let never_set = |error: AnalysisError<f64, 2>| {
        assert_eq!(
            error,
            AnalysisError::Model(IntegrationError::InvalidInput(InvalidInput::InputsNotSet {
                inputs: &["force"]
            })),
        );
    };
    let (q, v) = (Vector2::new(0.0, 0.1), Vector2::zeros());
    never_set(linearize(&cart(), 0.0, &q, &v).unwrap_err());
    never_set(modes(&cart(), 0.0, &Vector2::zeros()).unwrap_err());
    never_set(equilibrium(&cart(), 0.0, &q).unwrap_err());
}

/// Two surprises a new user met (issue 27), as they are used now: layers
/// bind to a name (`with_drift` takes the controlled model by value, so no
/// temporary is borrowed past its statement), and generic code over
/// `Actuated` sets constant inputs through the trait's `with_inputs`,
/// without copying the model to call `set_inputs`. A controller that
/// returns the constant input runs the very steps the constant input
/// does: the same trajectory to the bit.
#[test]
fn layers_bind_to_names_and_generic_code_sets_constant_inputs() {
    fn held<L: Actuated<N, 1, Scalar = f64>, const N: usize>(model: L, u: f64) -> L {
        model.with_inputs(&Vector1::new(u))
    }
    let bob = PushedBob::new(0.8, 0.6, 9.81);
    let (q0, v0) = (Vector2::new(0.0, -0.6), Vector2::new(0.5, 0.0));
    let controlled = bob
        .with_controller(|_: f64, _: &Vector2<f64>, _: &Vector2<f64>| Vector1::new(0.4))
        .with_drift(Drift::None);
    let constant = held(bob, 0.4).with_drift(Drift::None);
    let rk4 = Rk4::new(1e-2);
    let by_controller = rk4
        .integrate(&controlled, 0.0, q0, v0, &[0.5, 1.0])
        .unwrap();
    let by_constant = rk4.integrate(&constant, 0.0, q0, v0, &[0.5, 1.0]).unwrap();
    assert_eq!(by_controller.positions(), by_constant.positions());
    assert_eq!(by_controller.velocities(), by_constant.velocities());
}
