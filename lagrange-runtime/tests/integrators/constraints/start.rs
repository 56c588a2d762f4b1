//! Initial conditions off the constraints: projected by default, refused
//! on request, naming the constraint.

use super::{pendulum, start};
use lagrange_runtime::constraints::InitialConditions;
use lagrange_runtime::nalgebra::Vector2;
use lagrange_runtime::prelude::*;
use lagrange_runtime::{ConstraintLevel, Holonomic, InvalidInput};

/// A bob 1 % too far out, moving partly along the rod.
fn off() -> (Vector2<f64>, Vector2<f64>) {
    let (q0, _) = start();
    (q0 * 1.01, Vector2::new(0.3, 0.4))
}

/// Projected: the sample at `t0` is on both constraints (to rounding, as
/// after a step) and the corrections reported are what moved: the bob
/// back by 1 % of the rod, `|Δq|∞ = 0.01 l sin 1 ≈ 8.4e-3`, and the radial part
/// of the velocity.
#[test]
fn inconsistent_start_is_projected_and_the_correction_reported() {
    let model = pendulum();
    let (q0, qdot0) = off();
    let run = Rk4::new(0.01)
        .integrate(&model, 0.0, q0, qdot0, &[0.0, 0.5])
        .unwrap();
    let first = run.get(0).unwrap();
    assert!(model.constraints(0.0, &first.q)[0].abs() < 1e-14);
    assert!(model.constraint_velocities(0.0, &first.q, &first.qdot)[0].abs() < 1e-14);
    // The projection along the rod (M = m I, so orthogonal) moves the bob
    // straight back: q0 / 1.01.
    assert!((first.q - q0 / 1.01).amax() < 1e-15);
    let stats = run.stats();
    // q0 − q0/1.01 = 0.01 (sin 1, −cos 1): its largest component 0.01 sin 1.
    assert!((stats.initial_position_correction - 0.01 * 1f64.sin()).abs() < 1e-15);
    let radial = first.q.normalize().dot(&qdot0);
    assert!(stats.initial_velocity_correction > 0.0);
    assert!(stats.initial_velocity_correction <= radial.abs() + 1e-15);
}

/// A consistent start is integrated as given, bit for bit.
#[test]
fn consistent_start_is_kept_as_given() {
    let (q0, qdot0) = start();
    let run = Rk4::new(0.01)
        .integrate(&pendulum(), 0.0, q0, qdot0, &[0.0])
        .unwrap();
    assert_eq!((run.positions()[0], run.velocities()[0]), (q0, qdot0));
    assert_eq!(run.stats().initial_position_correction, 0.0);
}

/// Refused on request, naming the constraint, the level and the residual:
/// first the position (`φ = 1.01² − 1`), then, with the position right,
/// the velocity (`φ̇ = 2 q · q̇`).
#[test]
fn inconsistent_start_is_refused_on_request() {
    let model = pendulum();
    let strict = (&model).with_initial_conditions(InitialConditions::Reject);
    let (q0, qdot0) = off();
    let failure = Dopri5::new()
        .integrate(&strict, 0.0, q0, qdot0, &[1.0])
        .unwrap_err();
    let IntegrationError::InvalidInput(InvalidInput::InconsistentInitialConditions {
        constraint,
        level,
        residual,
        ..
    }) = failure.error
    else {
        panic!("{}", failure.error);
    };
    assert_eq!((constraint, level), ("rod", ConstraintLevel::Position));
    assert!((residual - (1.01f64 * 1.01 - 1.0)).abs() < 1e-15);
    assert!(failure.trajectory.is_empty());

    let (q0, _) = start();
    let strict = model.with_initial_conditions(InitialConditions::Reject);
    let failure = Dopri5::new()
        .integrate(&strict, 0.0, q0, qdot0, &[1.0])
        .unwrap_err();
    let IntegrationError::InvalidInput(InvalidInput::InconsistentInitialConditions {
        level,
        residual,
        ..
    }) = failure.error
    else {
        panic!("{}", failure.error);
    };
    assert_eq!(level, ConstraintLevel::Velocity);
    assert!((residual - 2.0 * q0.dot(&qdot0)).abs() < 1e-15);
}
