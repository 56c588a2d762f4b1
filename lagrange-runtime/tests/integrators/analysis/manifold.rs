//! Constrained models on their manifold: the Cartesian pendulum against
//! the θ pendulum, the four-bar's hanging mode against a simulation, and
//! a change point refused.

use lagrange::models::{CartesianPendulum, FourBar, Pendulum};
use lagrange_runtime::analysis::{
    AnalysisError, Derivatives, ModeKind, equilibrium, is_equilibrium, linearize,
    linearize_on_manifold, modes,
};
use lagrange_runtime::nalgebra::{DVector, Vector2, Vector3};
use lagrange_runtime::{ConstraintLevel, Dopri5, IntegrationError, Integrator};

const G: f64 = 9.81;
const L: f64 = 2.0;
const M: f64 = 1.5;

fn pendulum() -> CartesianPendulum {
    CartesianPendulum::new(M, L, G)
}

fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Central differences of the saddle-point `q̈`: relative error
/// `≈ ε^(2/3) ≈ 4e-11` times the ratio of the model's third to first
/// derivatives (order one here: `l = 2`, angles of order one); `1e-8`
/// leaves a factor of 200 for that ratio and the rounding of the `M_z`,
/// `K_z` products.
const DIFFERENCES: f64 = 1e-8;

/// Hanging, the rod's tension `m g` is the only restoring force: along
/// the circle `K_z = m g / l`, `M_z = m`, so `ω² = g / l`. The saddle
/// solve's `q̈` carries the tension's dependence on `x`; without it the
/// tangent stiffness would be zero (gravity is vertical).
#[test]
fn hanging_cartesian_pendulum_swings_at_root_g_over_l() {
    let model = pendulum();
    let (q, _) = model.state(0.0, 0.0);
    let found = modes(&model, 0.0, &q).unwrap();
    assert_eq!(found.derivatives, Derivatives::CentralDifferences);
    assert_eq!(found.modes.len(), 1, "one degree of freedom");
    let mode = &found.modes[0];
    println!(
        "hanging ω² relative error {:e}",
        relative(mode.omega_squared, G / L)
    );
    assert!(
        relative(mode.omega_squared, G / L) < DIFFERENCES,
        "{mode:?}"
    );
    assert!(matches!(mode.kind, ModeKind::Oscillating { .. }));
    // Sideways along the circle, mass-normalized: (1/√m, 0).
    assert!((mode.shape - Vector2::new(1.0 / M.sqrt(), 0.0)).amax() < DIFFERENCES);
}

/// Upright, the rod pushes with `m g` and the bob falls off either side:
/// `ω² = −g / l`, growth rate `√(g / l)`.
#[test]
fn upright_cartesian_pendulum_falls_at_root_g_over_l() {
    let model = pendulum();
    let (q, _) = model.state(std::f64::consts::PI, 0.0);
    let found = modes(&model, 0.0, &q).unwrap();
    let mode = &found.modes[0];
    println!(
        "upright ω² relative error {:e}",
        relative(mode.omega_squared, -G / L)
    );
    assert!(
        relative(mode.omega_squared, -G / L) < DIFFERENCES,
        "{mode:?}"
    );
    let ModeKind::Unstable { growth_rate } = mode.kind else {
        panic!("{mode:?}");
    };
    assert!(relative(growth_rate, (G / L).sqrt()) < DIFFERENCES);
    assert!(!found.is_stable());
}

/// A guess off the circle is projected onto it and Newton on the tangent
/// force takes it to the bottom (or the top): `|x|` at rounding, `y = ∓l`
/// to the rounding of the projection (`100 ε` of `l²` in `φ`).
#[test]
fn equilibrium_of_the_cartesian_pendulum_is_found_from_off_the_circle() {
    let model = pendulum();
    for (guess, target) in [
        (Vector2::new(0.5, -1.7), Vector2::new(0.0, -L)),
        (Vector2::new(-0.3, 2.4), Vector2::new(0.0, L)),
    ] {
        let q = equilibrium(&model, 0.0, &guess).unwrap().q;
        println!("equilibrium from {guess:?}: {q:?}");
        assert!((q - target).amax() < 1e-14, "{q} vs {target}");
        assert!(model.constraints(0.0, &q)[0].abs() < 1e-13);
        assert!(is_equilibrium(&model, 0.0, &q, 1e-12).unwrap());
    }
    // Off the circle, or swung out, is no equilibrium.
    assert!(!is_equilibrium(&model, 0.0, &Vector2::new(0.0, -1.9), 1e-8).unwrap());
    let (out, _) = model.state(0.3, 0.0);
    assert!(!is_equilibrium(&model, 0.0, &out, 1e-8).unwrap());
}

/// Swinging through `θ = 0.7` at `θ̇ = 1.3`: the reduced `A` against the
/// θ pendulum's, `∂θ̈/∂θ = −(g/l) cos θ`. In `z = Tᵀ (q − q₀)` (arc length
/// to first order, `δz = ±l δθ`: `A` is unchanged by the scaling) the chart
/// is fixed while the bob turns at `θ̇`, which adds the chart's own rate:
/// `ż = l θ̇ cos(θ − θ₀)` gives `∂ż/∂θ = −l θ̇ sin(θ − θ₀)`, whose rate
/// along the motion is `−l θ̇²`; so `∂z̈/∂z = −(g/l) cos θ − θ̇²`, and
/// `∂z̈/∂ż = 0` (no damping, and `sin(θ − θ₀)` vanishes at the point).
#[test]
fn swinging_cartesian_pendulum_linearizes_as_the_angle_pendulum() {
    let model = pendulum();
    let (theta, theta_dot) = (0.7, 1.3);
    let (q, qdot) = model.state(theta, theta_dot);
    let lin = linearize_on_manifold(&model, 0.0, &q, &qdot).unwrap();
    let angle = linearize(
        &Pendulum::new(M, L, G),
        0.0,
        &[theta].into(),
        &[theta_dot].into(),
    )
    .unwrap();
    let a = &lin.state_matrix;
    assert_eq!((a.nrows(), a.ncols()), (2, 2));
    let expected = angle.dqddot_dq[(0, 0)] - theta_dot * theta_dot;
    println!(
        "moving ∂z̈/∂z = {} vs {expected} (error {:e}), ∂z̈/∂ż = {:e}",
        a[(1, 0)],
        relative(a[(1, 0)], expected),
        a[(1, 1)]
    );
    assert!(relative(a[(1, 0)], expected) < DIFFERENCES);
    // ∂z̈/∂ż is zero exactly; its error is the differences' relative to
    // the size of q̈'s velocity derivative, 2 θ̇ ≈ 3.
    assert!(a[(1, 1)].abs() < DIFFERENCES * 3.0);
    assert_eq!((a[(0, 0)], a[(0, 1)]), (0.0, 1.0));

    // The map back keeps a deviation on the manifold to first order:
    // φ and φ̇ at the deviated state are O(s²) for a deviation of size s.
    let s = 1e-6;
    let (dq, dqdot) =
        lin.to_coordinates(&DVector::from_element(1, s), &DVector::from_element(1, s));
    let (q1, v1) = (q + dq, qdot + dqdot);
    // O(s²) with coefficients of order l and θ̇ (≤ 4): 1e-11 is 10 s².
    assert!(model.constraints(0.0, &q1)[0].abs() < 10.0 * s * s);
    assert!(model.constraint_velocities(0.0, &q1, &v1)[0].abs() < 10.0 * s * s);
    // Without the velocity lift W the rate constraint would be broken at
    // first order: W is not zero away from rest.
    assert!(lin.velocity_lift.amax() > 0.1);
}

/// Inconsistent states are refused, naming the level.
#[test]
fn linearization_off_the_circle_is_refused() {
    let model = pendulum();
    let (q, qdot) = model.state(0.4, 1.0);
    let err = linearize_on_manifold(&model, 0.0, &(q * 1.001), &qdot).unwrap_err();
    let AnalysisError::OffConstraints {
        level, constraint, ..
    } = err
    else {
        panic!("{err}");
    };
    assert_eq!((level, constraint), (ConstraintLevel::Position, "rod"));
    let err = linearize_on_manifold(&model, 0.0, &q, &(qdot + Vector2::new(0.0, 0.1))).unwrap_err();
    assert!(
        matches!(
            err,
            AnalysisError::OffConstraints {
                level: ConstraintLevel::Velocity,
                ..
            }
        ),
        "{err}"
    );
}

/// The crank-rocker hanging under gravity: found from a guess a third of a
/// radian of crank off (and off the loop), one degree of freedom, one
/// stable mode. Its period is checked against a small-amplitude run: the
/// crank released `10⁻⁴` rad off equilibrium (nonlinear period shift
/// `∝ amplitude² ≈ 10⁻⁸`), integrated by Dopri5 at `10⁻¹²` and projected
/// onto the loop after each step; the time between two upward zero
/// crossings, each located by linear interpolation between samples `T/2000`
/// apart (error `≈ (T/2000)² × curvature`, `< 10⁻⁶` relative), matches
/// `2π/ω` to `10⁻⁶` (measured: `2·10⁻⁹`).
#[test]
fn hanging_four_bar_has_one_mode_with_the_simulated_period() {
    let linkage = FourBar::crank_rocker();
    // The potential along the loop is lowest near a crank angle of −1.83
    // (a scan of `FourBar::state`); start 0.33 rad away, off the loop.
    let (start, _) = linkage.state(-1.5, 0.0).unwrap();
    let guess = start + Vector3::new(0.0, 0.01, -0.02);
    let rest = equilibrium(&linkage, 0.0, &guess).unwrap().q;
    let phi = linkage.constraints(0.0, &rest);
    assert!(phi.amax() < 1e-14, "{phi}");
    assert!(is_equilibrium(&linkage, 0.0, &rest, 1e-10).unwrap());
    let found = modes(&linkage, 0.0, &rest).unwrap();
    assert_eq!(found.modes.len(), 1);
    let mode = found.modes[0];
    let ModeKind::Oscillating { frequency } = mode.kind else {
        panic!("{mode:?}");
    };
    // The shape is tangent to the loop: G v = 0 to the differences' error.
    let g = linkage.constraint_jacobian(0.0, &rest);
    assert!((g * mode.shape).amax() < DIFFERENCES * mode.shape.amax());
    let period = 2.0 * std::f64::consts::PI / frequency;
    println!("four-bar rest {rest:?}, ω = {frequency}, T = {period}");

    let (q0, v0) = linkage.state(rest[0] + 1e-4, 0.0).unwrap();
    let samples = 6000;
    let times: Vec<f64> = (1..=samples)
        .map(|i| i as f64 * 3.0 * period / samples as f64)
        .collect();
    let run = Dopri5::new()
        .rtol(1e-12)
        .atol(1e-14)
        .integrate(&linkage, 0.0, q0, v0, &times)
        .unwrap();
    let crank: Vec<f64> = run.positions().iter().map(|q| q[0] - rest[0]).collect();
    let crossings: Vec<f64> = (1..crank.len())
        .filter(|&i| crank[i - 1] < 0.0 && crank[i] >= 0.0)
        .map(|i| {
            let (t0, t1) = (run.times()[i - 1], run.times()[i]);
            t0 + (t1 - t0) * crank[i - 1] / (crank[i - 1] - crank[i])
        })
        .collect();
    assert!(crossings.len() >= 2, "{crossings:?}");
    let simulated = crossings[1] - crossings[0];
    println!(
        "simulated period {simulated}, relative error {:e}",
        relative(simulated, period)
    );
    assert!(relative(simulated, period) < 1e-6);
}

/// The parallelogram at `θ = 0` has all four pins on one line: `G` has rank
/// one, there is no tangent plane of dimension one, and every analysis
/// says so with the state (the saddle solve's own singular-constraint
/// error), never NaN.
#[test]
fn parallelogram_dead_centre_is_refused_as_singular_constraints() {
    let linkage = FourBar::parallelogram();
    let q = Vector3::zeros();
    let singular = |err: AnalysisError<f64, 3>| matches!(err, AnalysisError::Model(IntegrationError::SingularConstraints { q, .. }) if q == Vector3::zeros());
    let err = modes(&linkage, 0.0, &q).unwrap_err();
    assert!(singular(err.clone()), "{err}");
    let err = linearize_on_manifold(&linkage, 0.0, &q, &q).unwrap_err();
    assert!(singular(err.clone()), "{err}");
    let err = is_equilibrium(&linkage, 0.0, &q, 1e-8).unwrap_err();
    assert!(singular(err.clone()), "{err}");
}
