//! Linearization at arbitrary states against central differences of the
//! accelerations.

use lagrange::models::DoublePendulum;
use lagrange_runtime::analysis::{AnalysisError, Derivatives, linearize};
use lagrange_runtime::linalg::mass::solve_mass_matrix;
use lagrange_runtime::nalgebra::{Matrix2, Vector2};
use lagrange_runtime::{Lagrangian, WithLayers};

use super::{Rng, differences};

/// The differences' own error at a state, `ε^(2/3)` (≈ 4e-11) times the
/// size of what is differenced and its third derivatives: here
/// `(1 + |q̇|)² g`-sized accelerations (gravity and centripetal terms),
/// magnified by `|M⁻¹| ≲ 4`
/// (`det M = m2 l1² l2² (m1 + m2 sin²(θ1 − θ2)) ≥ 0.45` here): ≲ 3e-8.
/// Measured: at most 3.9e-9 in absolute terms over the 20 random states;
/// `1e-7 (1 + |q̇|)²` leaves a margin of 25 or more.
fn tolerance(qdot: &Vector2<f64>) -> f64 {
    1e-7 * (1.0 + qdot.amax()).powi(2)
}

/// 20 random states, far from equilibrium and moving: angles anywhere,
/// velocities up to 3 rad/s. The exact blocks agree with differences of
/// `acceleration` to the differences' error.
#[test]
fn double_pendulum_linearization_matches_differences_at_random_states() {
    let (pendulum, _, _) = DoublePendulum::<f64>::regular();
    let mut rng = Rng(12);
    let mut worst: f64 = 0.0;
    for _ in 0..20 {
        let pi = std::f64::consts::PI;
        let q = Vector2::new(rng.uniform(-pi, pi), rng.uniform(-pi, pi));
        let qdot = Vector2::new(rng.uniform(-3.0, 3.0), rng.uniform(-3.0, 3.0));
        let lin = linearize(&pendulum, 0.0, &q, &qdot).unwrap();
        assert_eq!(lin.derivatives, Derivatives::Exact);
        let (dq, dv) = differences(&pendulum, &q, &qdot);
        let gap = (lin.dqddot_dq - dq)
            .amax()
            .max((lin.dqddot_dqdot - dv).amax());
        assert!(gap < tolerance(&qdot), "gap {gap:e} at q = {q}, q̇ = {qdot}");
        worst = worst.max(gap);
        // The upper blocks of A are [0, I].
        let a = lin.state_matrix();
        assert_eq!(a[(0, 2)], 1.0);
        assert_eq!(a[(1, 2)], 0.0);
        assert_eq!(a[(3, 1)], lin.dqddot_dq[(1, 1)]);
    }
    println!("worst gap exact vs differences over 20 states: {worst:e}");
}

/// Away from rest `∂q̈/∂q = −M⁻¹ (∂(M q̈)/∂q − ∂f/∂q)`: dropping the first
/// term (`M⁻¹ ∂f/∂q` alone, what holds at an equilibrium) is wrong by
/// `M⁻¹ ∂M/∂q q̈`, of the size of `q̈`, far beyond the differences' error,
/// while the linearization agrees with them.
#[test]
fn linearization_away_from_rest_includes_the_mass_matrix_variation() {
    let (pendulum, _, _) = DoublePendulum::<f64>::regular();
    let (q, qdot) = (Vector2::new(1.1, -0.4), Vector2::new(0.0, 0.0));
    let lin = linearize(&pendulum, 0.0, &q, &qdot).unwrap();
    assert!(
        lin.qddot.amax() > 1.0,
        "not an equilibrium: q̈ = {}",
        lin.qddot
    );
    // ∂f/∂q alone: the residual Jacobian at q̈ = 0 is −∂f/∂q.
    let (dr_dq_at_rest, _) =
        Lagrangian::residual_jacobians(&pendulum, 0.0, &q, &qdot, &Vector2::zeros()).unwrap();
    let m = pendulum.mass_matrix(0.0, &q);
    let naive = Matrix2::from_columns(
        &[0, 1].map(|k| solve_mass_matrix(&m, &(-dr_dq_at_rest.column(k).into_owned())).unwrap()),
    );
    let (dq, _) = differences(&pendulum, &q, &qdot);
    assert!((lin.dqddot_dq - dq).amax() < tolerance(&qdot));
    assert!(
        (naive - dq).amax() > 1e4 * tolerance(&qdot),
        "{naive} vs {dq}"
    );
}

/// The double pendulum's velocity terms are the centripetal `θ̇²`: their
/// derivative vanishes at rest and is `∝ θ̇` in motion, where it must agree
/// with the differences.
#[test]
fn linearization_in_motion_includes_the_velocity_terms() {
    let (pendulum, _, _) = DoublePendulum::<f64>::regular();
    let q = Vector2::new(0.6, -0.4);
    let at_rest = linearize(&pendulum, 0.0, &q, &Vector2::zeros()).unwrap();
    assert!(at_rest.dqddot_dqdot.amax() < 1e-15);
    let qdot = Vector2::new(2.0, -1.5);
    let moving = linearize(&pendulum, 0.0, &q, &qdot).unwrap();
    assert!(moving.dqddot_dqdot.amax() > 1.0);
    let (dq, dv) = differences(&pendulum, &q, &qdot);
    assert!((moving.dqddot_dqdot - dv).amax() < tolerance(&qdot));
    assert!((moving.dqddot_dq - dq).amax() < tolerance(&qdot));
}

/// Without exact Jacobians the library differences `q̈` itself, with the
/// same step rule as the test's: the two agree with the exact blocks to
/// the differences' error.
#[test]
fn linearization_without_jacobians_is_by_central_differences() {
    let (pendulum, _, _) = DoublePendulum::<f64>::regular();
    let (q, qdot) = (Vector2::new(-2.0, 0.7), Vector2::new(1.0, 2.5));
    let exact = linearize(&pendulum, 0.0, &q, &qdot).unwrap();
    let numeric = linearize(&pendulum.without_jacobians(), 0.0, &q, &qdot).unwrap();
    assert_eq!(numeric.derivatives, Derivatives::CentralDifferences);
    assert_eq!(numeric.qddot, exact.qddot);
    assert!((numeric.dqddot_dq - exact.dqddot_dq).amax() < tolerance(&qdot));
    assert!((numeric.dqddot_dqdot - exact.dqddot_dqdot).amax() < tolerance(&qdot));
}

/// `linearize` works in the model's own coordinates, which a constrained
/// model's are not free to vary: refused, pointing to
/// `linearize_on_manifold` (tested in `manifold.rs`).
#[test]
fn constrained_model_is_refused_in_redundant_coordinates() {
    let pendulum = crate::models::CartesianPendulum::unit();
    let (q, qdot) = pendulum.state(0.3, 0.0);
    let err = linearize(&pendulum, 0.0, &q, &qdot).unwrap_err();
    assert!(matches!(err, AnalysisError::Constrained { .. }), "{err}");
}

/// A singular mass matrix comes back as the model's error, with the state.
#[test]
fn zero_rod_is_reported_with_its_state() {
    let pendulum = DoublePendulum::new(1.0, 1.0, 0.0, 1.0, 9.81);
    let q = Vector2::new(0.1, 0.2);
    let err = linearize(&pendulum, 0.0, &q, &Vector2::zeros()).unwrap_err();
    assert!(
        matches!(err, AnalysisError::Model(ref e) if e.to_string().contains("singular")),
        "{err}"
    );
}
