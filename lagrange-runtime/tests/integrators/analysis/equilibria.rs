//! Equilibria found by Newton's method, and the guesses and models where
//! there is none to find.

use lagrange::models::{CartPole, CartesianPendulum, DoublePendulum};
use lagrange_runtime::WithLayers;
use lagrange_runtime::analysis::{
    AnalysisError, EquilibriumSearch, equilibrium, is_equilibrium, linearize,
};
use lagrange_runtime::nalgebra::{Vector1, Vector2};

use super::models::{Falling, SaturatingSpring};

/// From 0.3 rad off, Newton lands on the hanging pendulum to rounding:
/// `sin θ ≈ θ` there, so the iteration converges quadratically to `|θ| ≲ ε`.
#[test]
fn newton_finds_the_hanging_double_pendulum_from_a_nearby_guess() {
    let pendulum = DoublePendulum::unit();
    for guess in [Vector2::new(0.3, -0.2), Vector2::new(-0.1, 0.4)] {
        let q = equilibrium(&pendulum, 0.0, &guess).unwrap().q;
        assert!(q.amax() < 1e-15, "{q}");
        let q = equilibrium(&pendulum.without_jacobians(), 0.0, &guess)
            .unwrap()
            .q;
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
        let q = equilibrium(&pendulum, 0.0, &guess).unwrap().q;
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
    let q = equilibrium(&SaturatingSpring, 0.0, &Vector1::new(1.0))
        .unwrap()
        .q;
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

/// Issue 23, defect 6: the upright cart-pole is a family of equilibria
/// (the cart may stand anywhere), where `∂f/∂q` is singular. The search
/// returned `SingularStiffness`; it now takes minimum-norm Newton steps,
/// which leave the cart where the guess put it, and names the neutral
/// direction, the cart's position, checked against the stiffness: `K v = 0`
/// to rounding, and the model still at rest a metre along it.
#[test]
fn a_family_of_equilibria_gives_the_member_nearest_the_guess_and_its_neutral_direction() {
    let pi = std::f64::consts::PI;
    let cart = CartPole::new(1.2, 0.3, 0.8, 9.81).with_inputs(&Vector1::new(0.0));
    for guess in [Vector2::new(0.7, 3.0), Vector2::new(-0.4, 3.3)] {
        let exact = equilibrium(&cart, 0.0, &guess).unwrap();
        let differenced = equilibrium(&cart.without_jacobians(), 0.0, &guess).unwrap();
        for found in [exact, differenced] {
            // The cart's column of ∂f/∂q is zero: no step moves it. The
            // pole converges quadratically to π, to its rounding.
            assert!(
                (found.q - Vector2::new(guess[0], pi)).amax() < 1e-14,
                "{}",
                found.q
            );
            assert_eq!(found.neutral.len(), 1);
            let v = found.neutral[0];
            assert!(
                (v[0].abs() - 1.0).abs() < 1e-14 && v[1].abs() < 1e-14,
                "{v}"
            );
            // K v = −M ∂q̈/∂q v at rest: zero to rounding (the exact
            // Jacobian of a column that does not depend on x).
            let rest = Vector2::zeros();
            let k_v = linearize(&cart, 0.0, &found.q, &rest).unwrap().dqddot_dq * v;
            assert!(k_v.amax() < 1e-14, "{k_v}");
            assert!(is_equilibrium(&cart, 0.0, &(found.q + v), 1e-12).unwrap());
        }
    }
    // An isolated equilibrium has no neutral direction.
    let hanging = equilibrium(&DoublePendulum::unit(), 0.0, &Vector2::new(0.2, 0.1)).unwrap();
    assert!(hanging.neutral.is_empty());
}

/// A constrained family: a bob on a rod without gravity rests anywhere on
/// its circle. The guess is projected onto the circle, no tangent force
/// moves it, and the neutral direction is the circle's tangent there.
#[test]
fn a_constrained_family_rests_where_the_guess_lands_on_its_constraint() {
    let l: f64 = 2.0;
    let weightless = CartesianPendulum::new(1.0, l, 0.0);
    let found = equilibrium(&weightless, 0.0, &Vector2::new(0.3, -1.8)).unwrap();
    let q: Vector2<f64> = found.q;
    // On the circle to the projection's rounding-level tolerance.
    assert!((q.norm() - l).abs() < 1e-14, "{q}");
    assert_eq!(found.neutral.len(), 1);
    // The tangent (−y, x)/l, up to sign: orthogonal to q, unit length.
    let v: Vector2<f64> = found.neutral[0];
    assert!(
        (v.norm() - 1.0).abs() < 1e-14 && v.dot(&q).abs() < 1e-13,
        "{v} at {q}"
    );
}
