//! Every capability of a model survives every layer, and every pair of
//! layers in either order: the constraints and their settings, the inputs
//! and their checks, the exact derivatives, the named `let`s, and the blame
//! for a non-finite value. The layers: another drift control
//! (`with_drift`), a controller (`with_controller`), no exact Jacobians
//! (`without_jacobians`) and a borrow (`&model`). It would have caught
//! issue 23's defect 1: the hand-written drift wrapper lost the input
//! check.

use lagrange::constraints::{ConstraintSettings, Visitor as ConstraintVisitor};
use lagrange::dynamics::acceleration;
use lagrange::inputs::{Inputs, Visitor as InputVisitor};
use lagrange::lets::{Lets, Visitor as LetVisitor};
use lagrange::nalgebra::{Vector1, Vector2};
use lagrange::prelude::*;
use lagrange::{InvalidInput, NonFiniteValue};

lagrange::lagrangian! {
    /// A bob on a rod in Cartesian coordinates, pushed sideways: one model
    /// with every capability (constraints, an input, named `let`s, exact
    /// Jacobians).
    #[lagrange(jacobians)]
    struct Bob {
        coordinates: x, y;
        parameters: m, l, g;
        inputs: fx;
        let r2 = x^2 + y^2;
        let speed2 = dot(x)^2 + dot(y)^2;
        kinetic: m/2*speed2;
        potential: m*g*y;
        forces: x = fx;
        constraints: rod: r2 = l^2;
    }
}

/// A controller that pushes until `t = 1`, then returns NaN.
fn push(t: f64, _: &Vector2<f64>, _: &Vector2<f64>) -> Vector1<f64> {
    Vector1::new(if t < 1.0 { 0.5 } else { f64::NAN })
}

/// What a layered model must still show.
#[derive(Debug, Clone, Copy)]
struct Expect {
    /// Under a controller: inputs none held, set at every evaluation.
    controlled: bool,
    /// Under `with_drift(Drift::None)`.
    drift_none: bool,
    /// Exact Jacobians (no controller, no `without_jacobians`).
    exact: bool,
}

struct Constraints;
impl ConstraintVisitor<f64, 2> for Constraints {
    type Output = (usize, &'static str, Drift<f64>);
    fn visit<H, const C: usize>(self, _: &H, settings: ConstraintSettings<f64>) -> Self::Output
    where
        H: Holonomic<2, C, Scalar = f64> + ?Sized,
    {
        (C, H::CONSTRAINTS[0], settings.drift)
    }
}

struct InputNames;
impl InputVisitor<f64, 2> for InputNames {
    type Output = (Vec<&'static str>, bool);
    fn visit<A, const K: usize>(self, model: &A) -> Self::Output
    where
        A: Inputs<2, K, Scalar = f64> + ?Sized,
    {
        (A::NAMES.to_vec(), model.held_inputs().is_some())
    }
}

struct LetValues(Vector2<f64>, Vector2<f64>);
impl LetVisitor<f64, 2> for LetValues {
    type Output = (Vec<&'static str>, Vec<f64>);
    fn visit<L, const K: usize>(self, model: &L) -> Self::Output
    where
        L: Lets<2, K, Scalar = f64> + ?Sized,
    {
        (L::LETS.to_vec(), model.lets(0.0, &self.0, &self.1).to_vec())
    }
}

fn check<L: Lagrangian<2, Scalar = f64>>(name: &str, model: &L, expect: Expect) {
    let base = Bob::new(0.8, 0.6, 9.81);
    let (q, v) = (
        Vector2::new(0.6 * 0.3f64.sin(), -0.6 * 0.3f64.cos()),
        Vector2::new(0.4, 0.2),
    );

    // Constraints, with the settings of the run.
    let drift = if expect.drift_none {
        Drift::None
    } else {
        Drift::Projection
    };
    assert_eq!(
        model.visit_constraints(Constraints),
        Some((1, "rod", drift)),
        "{name}: constraints"
    );

    // Inputs: named; held unless a controller sets them.
    assert_eq!(
        model.visit_inputs(InputNames),
        Some((vec!["fx"], !expect.controlled)),
        "{name}: inputs"
    );

    // Their check: never set is refused before the first step, unless a
    // controller sets them.
    let run = Rk4::new(1e-3).integrate(model, 0.0, q, Vector2::zeros(), &[0.01]);
    if expect.controlled {
        assert!(run.is_ok(), "{name}: {:?}", run.err().map(|f| f.error));
    } else {
        assert_eq!(
            run.unwrap_err().error,
            IntegrationError::InvalidInput(InvalidInput::InputsNotSet { inputs: &["fx"] }),
            "{name}: the input check"
        );
    }

    // Exact derivatives.
    let a = Vector2::new(0.1, -0.2);
    assert_eq!(
        model.residual_jacobians(0.0, &q, &v, &a).is_some(),
        expect.exact,
        "{name}: exact Jacobians"
    );

    // Named lets, the model's own values.
    assert_eq!(
        model.visit_lets(LetValues(q, v)),
        Some((vec!["r2", "speed2"], base.lets(0.0, &q, &v).to_vec())),
        "{name}: lets"
    );

    // Blame: a NaN input (never set, or the controller's after t = 1) is
    // the inputs' fault, through the saddle-point solve.
    match acceleration(model, 2.0, &q, &v) {
        Err(IntegrationError::NonFiniteState { value, .. }) => {
            assert_eq!(value, NonFiniteValue::Inputs, "{name}: blame")
        }
        other => panic!("{name}: blame: {other:?}"),
    }
}

const PLAIN: Expect = Expect {
    controlled: false,
    drift_none: false,
    exact: true,
};

#[test]
fn every_capability_survives_every_layer() {
    let bob = Bob::new(0.8, 0.6, 9.81);
    let drift = Expect {
        drift_none: true,
        ..PLAIN
    };
    let controlled = Expect {
        controlled: true,
        exact: false,
        ..PLAIN
    };
    let finite_differences = Expect {
        exact: false,
        ..PLAIN
    };
    check("the model", &bob, PLAIN);
    check("with_drift", &bob.with_drift(Drift::None), drift);
    check("with_controller", &bob.with_controller(push), controlled);
    check(
        "without_jacobians",
        &bob.without_jacobians(),
        finite_differences,
    );
    check("a borrow", &&bob, PLAIN);
}

#[test]
fn every_capability_survives_every_pair_of_layers_in_either_order() {
    let bob = Bob::new(0.8, 0.6, 9.81);
    let both = |a: Expect, b: Expect| Expect {
        controlled: a.controlled || b.controlled,
        drift_none: a.drift_none || b.drift_none,
        exact: a.exact && b.exact,
    };
    let (drift, control, fd) = (
        Expect {
            drift_none: true,
            ..PLAIN
        },
        Expect {
            controlled: true,
            exact: false,
            ..PLAIN
        },
        Expect {
            exact: false,
            ..PLAIN
        },
    );
    let none = Drift::None;
    // Drift and controller.
    check(
        "drift, control",
        &bob.with_drift(none).with_controller(push),
        both(drift, control),
    );
    check(
        "control, drift",
        &bob.with_controller(push).with_drift(none),
        both(control, drift),
    );
    // Drift and finite differences.
    check(
        "drift, fd",
        &bob.with_drift(none).without_jacobians(),
        both(drift, fd),
    );
    check(
        "fd, drift",
        &bob.without_jacobians().with_drift(none),
        both(fd, drift),
    );
    // Controller and finite differences.
    check(
        "control, fd",
        &bob.with_controller(push).without_jacobians(),
        both(control, fd),
    );
    check(
        "fd, control",
        &bob.without_jacobians().with_controller(push),
        both(fd, control),
    );
    // A borrow under and over each.
    check("borrow, drift", &(&bob).with_drift(none), drift);
    check("drift, borrow", &&bob.with_drift(none), drift);
    // (No controller over a borrow: it sets inputs in copies of the model,
    // so it takes the model itself.)
    let controlled = bob.with_controller(push);
    check("control, borrow", &&controlled, control);
    check("borrow, fd", &(&bob).without_jacobians(), fd);
    check("fd, borrow", &&bob.without_jacobians(), fd);
}

/// Whether the model reached through `visit_constraints` says its `M` is
/// regular only on its constraints.
struct SingularMass;
impl<const N: usize> ConstraintVisitor<f64, N> for SingularMass {
    type Output = bool;
    fn visit<H, const C: usize>(self, model: &H, _: ConstraintSettings<f64>) -> bool
    where
        H: Holonomic<N, C, Scalar = f64> + ?Sized,
    {
        model.mass_regular_on_constraints_only()
    }
}

fn singular_mass<L: Lagrangian<N, Scalar = f64>, const N: usize>(model: &L) -> Option<bool> {
    model.visit_constraints(SingularMass)
}

/// A mass matrix regular only on the constraints (a body in quaternions)
/// is known as such through every layer and pair of layers the model takes
/// (it has no inputs, so no controller: that layer passes `Holonomic` on
/// through the same implementation as the others), and a regular one is
/// not: the runtime would otherwise factor a singular `M`, or regularize
/// one that needs none and move its results.
#[test]
fn a_mass_matrix_regular_only_on_the_constraints_survives_every_layer() {
    let body = lagrange::models::FreeBody::new(1.0, 2.0, 3.0);
    assert_eq!(singular_mass(&body), Some(true), "the model");
    assert_eq!(singular_mass(&&body), Some(true), "a borrow");
    let drift = body.with_drift(Drift::None);
    let fd = body.without_jacobians();
    assert_eq!(singular_mass(&drift), Some(true), "with_drift");
    assert_eq!(singular_mass(&fd), Some(true), "without_jacobians");
    assert_eq!(
        singular_mass(&drift.without_jacobians()),
        Some(true),
        "with_drift, then without_jacobians"
    );
    assert_eq!(
        singular_mass(&fd.with_drift(Drift::None)),
        Some(true),
        "without_jacobians, then with_drift"
    );
    assert_eq!(
        singular_mass(&(&body).with_drift(Drift::None)),
        Some(true),
        "a borrow with_drift"
    );
    let bob = Bob::new(0.8, 0.6, 9.81);
    assert_eq!(singular_mass(&bob), Some(false), "a regular M");
    assert_eq!(
        singular_mass(&bob.with_controller(push).with_drift(Drift::None)),
        Some(false)
    );
}

/// Whether the model reached through `visit_constraints` has constraints
/// on its velocities.
struct OnVelocities;
impl<const N: usize> ConstraintVisitor<f64, N> for OnVelocities {
    type Output = bool;
    fn visit<H, const C: usize>(self, model: &H, _: ConstraintSettings<f64>) -> bool
    where
        H: Holonomic<N, C, Scalar = f64> + ?Sized,
    {
        model.has_velocity_constraints()
    }
}

/// Which constraints are on the velocities survives every layer and pair
/// of layers too: a layer that lost it would let the variational
/// integrator run a knife edge as if it were a holonomic constraint.
#[test]
fn velocity_constraints_survive_every_layer() {
    let sleigh = lagrange::models::ChaplyginSleigh::new(2.0, 0.3, 0.4);
    assert_eq!(
        sleigh.visit_constraints(OnVelocities),
        Some(true),
        "the model"
    );
    assert_eq!(
        Lagrangian::visit_constraints(&&sleigh, OnVelocities),
        Some(true),
        "a borrow"
    );
    let drift = sleigh.with_drift(Drift::None);
    let fd = sleigh.without_jacobians();
    assert_eq!(
        drift.visit_constraints(OnVelocities),
        Some(true),
        "with_drift"
    );
    assert_eq!(
        fd.visit_constraints(OnVelocities),
        Some(true),
        "without_jacobians"
    );
    assert_eq!(
        drift.without_jacobians().visit_constraints(OnVelocities),
        Some(true)
    );
    assert_eq!(
        fd.with_drift(Drift::None).visit_constraints(OnVelocities),
        Some(true)
    );
    let bob = Bob::new(0.8, 0.6, 9.81);
    assert_eq!(
        bob.with_controller(push)
            .with_drift(Drift::None)
            .visit_constraints(OnVelocities),
        Some(false)
    );
}
