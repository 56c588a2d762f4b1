//! Equilibria found by Newton's method, and the guesses and models where
//! there is none to find.

use lagrange::models::DoublePendulum;
use lagrange_runtime::analysis::{equilibrium, is_equilibrium, AnalysisError, EquilibriumSearch};
use lagrange_runtime::nalgebra::{Vector1, Vector2};
use lagrange_runtime::Lagrangian;

use super::models::{Falling, SaturatingSpring};

/// From 0.3 rad off, Newton lands on the hanging pendulum to rounding:
/// `sin θ ≈ θ` there, so the iteration converges quadratically to `|θ| ≲ ε`.
#[test]
fn newton_finds_the_hanging_double_pendulum_from_a_nearby_guess() {
    let pendulum = DoublePendulum::unit();
    for guess in [Vector2::new(0.3, -0.2), Vector2::new(-0.1, 0.4)] {
        let q = equilibrium(&pendulum, 0.0, &guess).unwrap();
        assert!(q.amax() < 1e-15, "{q}");
        let q = equilibrium(&pendulum.without_jacobians(), 0.0, &guess).unwrap();
        // Differenced Jacobian: linear convergence at rate ~ε^(2/3), same limit.
        assert!(q.amax() < 1e-15, "{q}");
    }
}

/// Each of the four equilibria from a guess near it: `(π, π)` is found to
/// the rounding of `π` itself, a few ε of 3.14.
#[test]
fn newton_finds_each_of_the_four_equilibria() {
    let pi = std::f64::consts::PI;
    let pendulum = DoublePendulum::new(1.0, 0.7, 1.0, 0.8, 9.81);
    for target in [[0.0, 0.0], [pi, 0.0], [0.0, pi], [pi, pi]] {
        let target = Vector2::from(target);
        let guess = target + Vector2::new(0.2, -0.15);
        let q = equilibrium(&pendulum, 0.0, &guess).unwrap();
        assert!((q - target).amax() < 1e-14, "{q} vs {target}");
        assert!(is_equilibrium(&pendulum, 0.0, &q, 1e-12).unwrap());
    }
}

/// The test is relative to the stiffness: the same pendulum a million
/// times heavier is in equilibrium at the same points, and not elsewhere.
#[test]
fn equilibrium_test_is_free_of_the_force_units() {
    let light = DoublePendulum::new(1.0, 1.0, 1.0, 1.0, 9.81);
    let heavy = DoublePendulum::new(1e6, 1e6, 1.0, 1.0, 9.81);
    for q in [Vector2::new(1e-10, 0.0), Vector2::new(1e-6, 0.0)] {
        let tol = 1e-8;
        let expected = q.amax() < tol;
        assert_eq!(is_equilibrium(&light, 0.0, &q, tol).unwrap(), expected);
        assert_eq!(is_equilibrium(&heavy, 0.0, &q, tol).unwrap(), expected);
    }
}

/// Newton on `atan` from `x = 10` overshoots further each time and leaves
/// the finite numbers: refused with the last finite iterate, not NaN.
#[test]
fn saturating_spring_from_far_away_does_not_converge() {
    let err = equilibrium(&SaturatingSpring, 0.0, &Vector1::new(10.0)).unwrap_err();
    let AnalysisError::NotConverged {
        q,
        residual,
        iterations,
        ..
    } = err
    else {
        panic!("{err}");
    };
    assert!(
        q[0].is_finite() && q[0].abs() > 10.0 && iterations < 50,
        "{q} after {iterations}"
    );
    assert!((residual[0] + q[0].atan()).abs() < 1e-15);
    // From inside the basin it converges.
    let q = equilibrium(&SaturatingSpring, 0.0, &Vector1::new(1.0)).unwrap();
    assert!(q[0].abs() < 1e-15);
}

/// Few iterations: reported as not converged after exactly that many.
#[test]
fn iteration_limit_is_reported() {
    let search = EquilibriumSearch::new().max_iterations(2);
    let err = search
        .solve(&DoublePendulum::unit(), 0.0, &Vector2::new(1.0, 1.0))
        .unwrap_err();
    assert!(
        matches!(err, AnalysisError::NotConverged { iterations: 2, .. }),
        "{err}"
    );
}

/// A falling body has no equilibrium: `∂f/∂q = 0`, said so.
#[test]
fn falling_body_has_no_equilibrium() {
    let falling = Falling { m: 2.0, g: 9.81 };
    let err = equilibrium(&falling, 0.0, &Vector1::new(0.0)).unwrap_err();
    let AnalysisError::SingularStiffness { residual, .. } = err else {
        panic!("{err}");
    };
    assert_eq!(residual[0], -2.0 * 9.81);
    assert!(!is_equilibrium(&falling, 0.0, &Vector1::new(0.0), 1e-8).unwrap());
}
