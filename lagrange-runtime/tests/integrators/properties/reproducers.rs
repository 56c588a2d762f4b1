//! Reproducers: each failed before its fix.

use lagrange::Method;
use lagrange_runtime::nalgebra::{Matrix2, Vector1, Vector2};
use lagrange_runtime::prelude::*;
use lagrange_runtime::{InvalidInput, NonFiniteValue};

use super::models::{DoublePendulum, Pendulum};
use super::{Settings, run};

fn pendulum() -> Pendulum {
    Pendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    }
}

/// `h = 0.01` up to `t = 1e300` needs 1e302 steps: more than any budget.
/// The step count used to saturate and the step was stretched to ~5e280,
/// running into a non-finite state; now the interval is refused before its
/// first step, with the samples before it, never covered by longer steps.
#[test]
fn a_fixed_step_too_small_for_the_span_is_too_many_steps_before_any_step() {
    let fixed = Settings {
        h: 0.01,
        rtol: 1e-8,
        atol: 1e-8,
        max_steps: 10_000_000,
    };
    for method in Method::FIXED_STEP {
        let start = (0.0, [0.5], [0.0]);
        let failure = run(method, fixed, &pendulum(), start, &[1e300]).unwrap_err();
        let IntegrationError::TooManySteps { t, max_steps, .. } = failure.error else {
            panic!("{method:?}: {}", failure.error);
        };
        assert_eq!((t, max_steps), (0.0, 10_000_000), "{method:?}");
        assert_eq!(failure.trajectory.stats().steps_accepted, 0, "{method:?}");
        assert!(failure.trajectory.is_empty(), "{method:?}");

        // With a reachable sample first: 100 steps of 0.01 to it, then the
        // same refusal there, the sample kept.
        let failure = run(method, fixed, &pendulum(), start, &[1.0, 1e300]).unwrap_err();
        let IntegrationError::TooManySteps { t, .. } = failure.error else {
            panic!("{method:?}: {}", failure.error);
        };
        assert_eq!(t, 1.0, "{method:?}");
        assert_eq!(failure.trajectory.times(), &[1.0], "{method:?}");
        assert_eq!(failure.trajectory.stats().steps_accepted, 100, "{method:?}");
    }
}

/// Masses of opposite sign: `M = diag(1, −1)` is regular, and LU used to
/// solve it into a run-away motion. A kinetic energy negative for some
/// velocities is a modelling error, reported as such at the first state by
/// every method.
#[test]
fn opposite_masses_are_an_indefinite_mass_matrix_at_the_first_state() {
    /// `T = ½ (ẋ² − ẏ²)`, `V = ½ (x² + y²)`.
    #[derive(Debug)]
    struct OppositeMasses;
    impl Lagrangian<2> for OppositeMasses {
        type Scalar = f64;
        const COORDINATES: [&'static str; 2] = ["x", "y"];
        fn mass_matrix(&self, _t: f64, _q: &Vector2<f64>) -> Matrix2<f64> {
            Matrix2::new(1.0, 0.0, 0.0, -1.0)
        }
        fn forcing(&self, _t: f64, q: &Vector2<f64>, _qd: &Vector2<f64>) -> Vector2<f64> {
            -q
        }
        fn kinetic_energy(&self, _t: f64, _q: &Vector2<f64>, qd: &Vector2<f64>) -> f64 {
            0.5 * (qd[0] * qd[0] - qd[1] * qd[1])
        }
        fn potential_energy(&self, _t: f64, q: &Vector2<f64>) -> f64 {
            0.5 * q.norm_squared()
        }
        fn momentum(&self, _t: f64, _q: &Vector2<f64>, qd: &Vector2<f64>) -> Option<Vector2<f64>> {
            Some(Vector2::new(qd[0], -qd[1]))
        }
        fn lagrangian_gradient(
            &self,
            _t: f64,
            q: &Vector2<f64>,
            _qd: &Vector2<f64>,
        ) -> Option<Vector2<f64>> {
            Some(-q)
        }
        fn nonconservative_forces(
            &self,
            _t: f64,
            _q: &Vector2<f64>,
            _qd: &Vector2<f64>,
        ) -> Option<Vector2<f64>> {
            Some(Vector2::zeros())
        }
    }
    let s = Settings {
        h: 0.01,
        rtol: 1e-8,
        atol: 1e-8,
        max_steps: 100_000,
    };
    let start = (0.5, [1.0, 1.0], [0.0, 0.3]);
    for method in Method::ALL {
        let failure = run(method, s, &OppositeMasses, start, &[1.0, 10.0]).unwrap_err();
        let IntegrationError::IndefiniteMassMatrix { t, q, qdot } = failure.error else {
            panic!("{method:?}: {}", failure.error);
        };
        assert_eq!(
            (t, q, qdot),
            (0.5, start.1.into(), start.2.into()),
            "{method:?}"
        );
        assert!(failure.trajectory.is_empty(), "{method:?}");
    }
}

/// `rtol = atol = 10` on the README's double pendulum: accepted as asked by
/// every adaptive method. It allows each step an error larger than the
/// state, so nothing holds the explicit methods within their stability
/// regions; Dopri5 used to end in a step-size underflow and Dop853 in an
/// infinite forcing, both far from the cause. Both now stop with
/// `Unstable`, as a fixed step beyond its limit does; Radau5, L-stable,
/// integrates to the end.
#[test]
fn loose_tolerances_are_honoured_and_an_unstable_explicit_run_is_unstable() {
    let model = DoublePendulum { g: 9.81 };
    let start = (0.0, [2.0, 2.5], [0.0, 0.0]);
    let times = [0.5, 1.0, 2.0];
    let loose = Settings {
        h: f64::NAN,
        rtol: 10.0,
        atol: 10.0,
        max_steps: 100_000,
    };
    for method in [Method::Dopri5, Method::Dop853] {
        let failure = run(method, loose, &model, start, &times).unwrap_err();
        assert!(
            matches!(failure.error, IntegrationError::Unstable { .. }),
            "{method:?}: {}",
            failure.error
        );
    }
    let radau = run(Method::Radau5, loose, &model, start, &times).unwrap();
    assert_eq!(radau.times(), &times);
}

/// `max_iterations = 0` allows no Newton iteration: refused before any
/// step by every implicit method, where Variational used to raise it to 1
/// silently and the Gauss methods failed each step as a divergence.
#[test]
fn zero_newton_iterations_are_invalid_input() {
    let (q0, v0) = (Vector1::new(0.5), Vector1::new(0.0));
    let runs = [
        ImplicitMidpoint::new(0.01)
            .max_iterations(0)
            .integrate(&pendulum(), 0.0, q0, v0, &[1.0]),
        GaussLegendre::three_stage(0.01)
            .max_iterations(0)
            .integrate(&pendulum(), 0.0, q0, v0, &[1.0]),
        Variational::new(0.01)
            .max_iterations(0)
            .integrate(&pendulum(), 0.0, q0, v0, &[1.0]),
    ];
    for (run, method) in runs
        .into_iter()
        .zip(["ImplicitMidpoint", "GaussLegendre", "Variational"])
    {
        let failure = run.unwrap_err();
        let expected = InvalidInput::NoNewtonIterations { method };
        assert_eq!(failure.error, IntegrationError::InvalidInput(expected));
        assert!(failure.trajectory.is_empty());
    }
}

/// A damped spring released at the largest finite `q`, at tolerance 1:
/// Dop853's steps stay finite, but its dense output between two of them
/// overflowed, and the run returned `Ok` with a NaN sample at t = 7.33.
/// A sample the interpolant cannot represent is now a typed error there,
/// with the samples before it.
#[test]
fn a_dense_output_that_overflows_is_an_error_not_a_nan_sample() {
    use super::models::DampedSpring;
    let model = DampedSpring {
        m: 1.0,
        k: 0.01,
        c: 0.5,
    };
    let loose = Settings {
        h: 1.0,
        rtol: 1.0,
        atol: 1.0,
        max_steps: 101,
    };
    let times = [7.330937750935154, 8.782849975120511];
    let failure = run(
        Method::Dop853,
        loose,
        &model,
        (0.0, [f64::MAX], [0.0]),
        &times,
    )
    .expect_err("the sample at t = 7.33 overflows");
    let IntegrationError::NonFiniteState { t, value, .. } = failure.error else {
        panic!("{}", failure.error);
    };
    assert_eq!((t, value), (times[0], NonFiniteValue::DenseOutput));
    assert!(failure.trajectory.is_empty());
    assert!(failure.trajectory.stats().steps_accepted > 0);
}
