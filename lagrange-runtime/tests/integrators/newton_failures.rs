//! How the implicit methods fail: a step too large for Newton is
//! `NewtonDivergence` with the samples before it, never a NaN; a model that
//! breaks is still the model's error, not Newton's.

use crate::models::{BlowUp, CartPole, ForcingBreaksDown};
use lagrange::Method;
use lagrange_runtime::nalgebra::{Vector1, Vector2};
use lagrange_runtime::prelude::*;
use lagrange_runtime::{InvalidInput, NonFiniteValue};

#[test]
fn blow_up_ends_in_newton_divergence_with_the_samples_before_it() {
    // q = 1 / (1 − t): as q grows, q̈ = 2 q³ stiffens until the stage
    // equations have no solution near the start. For the midpoint rule the
    // stage u = q + Z_q solves (h²/2) u³ − u + q + h q̇ / 2 = 0, which has a
    // positive root only while q + h q̇ / 2 ≤ (2/3)^{3/2} / h ≈ 5.4 at
    // h = 0.1, i.e. up to t ≈ 0.75; the Gauss methods fail a step later.
    let times: Vec<f64> = (1..=10).map(|i| 0.2 * i as f64).collect();
    for method in Method::GAUSS {
        let failure = method
            .with_step(0.1)
            .integrate(&BlowUp, 0.0, Vector1::new(1.0), Vector1::new(1.0), &times)
            .unwrap_err();
        let IntegrationError::NewtonDivergence {
            t,
            h,
            iterations,
            q,
            qdot,
        } = failure.error
        else {
            panic!(
                "{method:?}: expected Newton divergence, got {}",
                failure.error
            );
        };
        // Before the pole, at the start of a step of the requested size,
        // in a finite state.
        assert!(t < 1.0, "{method:?}: t = {t}");
        assert!((h - 0.1).abs() < 1e-15, "{method:?}: h = {h}");
        assert!((1..=20).contains(&iterations), "{method:?}: {iterations}");
        assert!(q[0].is_finite() && qdot[0].is_finite() && q[0] > 1.0);
        // The samples it passed, all finite.
        let kept = &failure.trajectory;
        assert!(!kept.is_empty(), "{method:?}: no samples kept");
        assert_eq!(kept.times(), &times[..kept.len()]);
        assert!(kept.times().iter().all(|&s| s <= t));
        for s in kept {
            assert!(s.q[0].is_finite() && s.qdot[0].is_finite());
        }
        let stats = kept.stats();
        assert_eq!(stats.linear_solves, stats.newton_iterations);
        // One Jacobian per accepted step, then the failing step's own and
        // the fresh one it tried at its stages before giving up.
        assert_eq!(stats.jacobian_evals, stats.steps_accepted + 2, "{stats:?}");
    }
}

#[test]
fn iteration_limit_is_newton_divergence_with_that_many_iterations() {
    // Two iterations cannot take the first step's Euler guess, O(h²) off,
    // down to 10 ε on a nonlinear model.
    let (q0, qdot0) = (Vector2::new(0.0, 1.2), Vector2::new(0.3, 0.0));
    let failure = GaussLegendre::three_stage(0.05)
        .max_iterations(2)
        .integrate(&CartPole::new(true), 0.0, q0, qdot0, &[1.0])
        .unwrap_err();
    assert_eq!(
        failure.error,
        IntegrationError::NewtonDivergence {
            t: 0.0,
            h: 0.05,
            iterations: 2,
            q: q0,
            qdot: qdot0
        }
    );
    assert!(failure.trajectory.is_empty());
    assert_eq!(failure.trajectory.stats().newton_iterations, 2);
    let message = failure.to_string();
    assert!(
        message.starts_with(
            "Newton iteration did not converge in 2 iterations at t = 0.0 with step h = 0.05"
        ),
        "{message}"
    );
}

#[test]
fn a_model_that_breaks_inside_a_step_is_the_models_error() {
    // The forcing turns NaN after t* = 0.53, inside the step 0.5 → 0.6:
    // the first evaluation of a stage past t* finds it, at the starting
    // guess, which is close to the trajectory, so it is reported as the
    // model's error at that stage, not as a Newton failure.
    let t_star = 0.53;
    let model = ForcingBreaksDown { t_star };
    for method in Method::GAUSS {
        let failure = method
            .with_step(0.1)
            .integrate(
                &model,
                0.0,
                Vector1::new(1.0),
                Vector1::new(0.0),
                &[0.5, 1.0],
            )
            .unwrap_err();
        let IntegrationError::NonFiniteState { t, value, .. } = failure.error else {
            panic!("{method:?}: expected a NaN forcing, got {}", failure.error);
        };
        assert_eq!(value, NonFiniteValue::Forcing);
        assert!(t > t_star && t < 0.6, "{method:?}: t = {t}");
        assert_eq!(failure.trajectory.times(), &[0.5]);
    }
}

#[test]
fn invalid_step_sizes_are_refused_before_any_work() {
    let (q0, qdot0) = (Vector2::new(0.0, 1.2), Vector2::new(0.3, 0.0));
    for h in [0.0, -0.1, f64::INFINITY] {
        for method in Method::GAUSS {
            let failure = method
                .with_step(h)
                .integrate(&CartPole::new(true), 0.0, q0, qdot0, &[1.0])
                .unwrap_err();
            assert_eq!(
                failure.error,
                IntegrationError::InvalidInput(InvalidInput::InvalidStepSize { h })
            );
            assert_eq!(failure.trajectory.stats().rhs_evals, 0);
        }
    }
}

/// An ill-conditioned mass matrix is no reason for Newton to fail: with a
/// bob 10⁶ times lighter than its neighbour (pivot ratio 10⁶) the
/// accelerations carry a relative rounding error of ~κ ε ≈ 10⁻¹⁰, so the
/// corrections stall there, far above the 10 ε the iteration aims for. At a
/// step that resolves even the fast kink mode (`h ω ≈ 0.014`, nothing for
/// Newton to struggle with) every implicit method must take the step, and
/// track the linear solution (exact through its two normal modes) to its
/// order: `(h ω)^p`-sized errors on the fast mode, far below 1e-6.
#[test]
fn an_ill_conditioned_mass_matrix_does_not_fail_a_converged_newton_iteration() {
    use crate::models::LightJoint;
    use lagrange_runtime::linalg::mass::pivot_ratio;
    use lagrange_runtime::nalgebra::Matrix2;

    let model = LightJoint { mu: 1e-6 };
    let m = model.mass_matrix(0.0, &Vector2::zeros());
    let kappa = pivot_ratio(&m).unwrap();
    assert!(kappa > 9e5, "pivot ratio {kappa:e}");
    let (q0, v0) = (Vector2::new(0.1, 0.1), Vector2::zeros());
    let (h, end) = (1e-5, 2e-3);
    // The exact solution: q(t) = Σ modes, from the generalized eigenproblem
    // K x = ω² M x, solved as the symmetric one L⁻¹ K L⁻ᵀ.
    let chol = m.cholesky().unwrap();
    let l_inv = chol.l().try_inverse().unwrap();
    let k = Matrix2::new(1.0 + model.mu, 0.0, 0.0, 1.0);
    let eig = (l_inv * k * l_inv.transpose()).symmetric_eigen();
    let exact = |t: f64| {
        let y0 = chol.l().transpose() * q0;
        let modal = eig.eigenvectors.transpose() * y0;
        let at_t = Vector2::new(
            modal[0] * (eig.eigenvalues[0].sqrt() * t).cos(),
            modal[1] * (eig.eigenvalues[1].sqrt() * t).cos(),
        );
        l_inv.transpose() * eig.eigenvectors * at_t
    };
    let omega_fast = eig.eigenvalues.max().sqrt();
    assert!(h * omega_fast < 0.02, "h ω = {}", h * omega_fast);
    for method in Method::GAUSS {
        let trajectory = method
            .with_step(h)
            .integrate(&model, 0.0, q0, v0, &[end])
            .unwrap_or_else(|f| panic!("{method:?}: {f}"));
        let error = (trajectory.last().unwrap().q - exact(end)).amax();
        assert!(error < 1e-6, "{method:?}: error {error:e}");
    }
    let trajectory = Variational::new(h)
        .integrate(&model, 0.0, q0, v0, &[end])
        .unwrap_or_else(|f| panic!("variational: {f}"));
    let error = (trajectory.last().unwrap().q - exact(end)).amax();
    assert!(error < 1e-6, "variational: error {error:e}");
}
