//! The four-bar linkage over 100 s with every method, against its minimal
//! form, and at its change point.

use lagrange::Method;
use lagrange::models::FourBar;
use lagrange::nalgebra::{Vector1, Vector3};
use lagrange::prelude::*;

/// The crank-rocker, crank at 45° turning at 12 rad/s: about 190 crank
/// revolutions in 100 s, the flywheel carrying it over the top.
fn start(model: &FourBar) -> (Vector3<f64>, Vector3<f64>) {
    model
        .state(45f64.to_radians(), 12.0)
        .expect("the crank-rocker assembles")
}

/// The worst closure residual `max |φ|` over the samples.
fn worst_closure(model: &FourBar, run: &Trajectory<f64, 3>) -> f64 {
    run.iter()
        .map(|s| model.constraints(s.t, &s.q).amax())
        .fold(0.0, f64::max)
}

/// The worst energy error over the samples, relative to the initial
/// energy.
fn worst_energy(model: &FourBar, run: &Trajectory<f64, 3>, e0: f64) -> f64 {
    run.iter()
        .map(|s| ((model.energy(s.t, &s.q, &s.qdot) - e0) / e0).abs())
        .fold(0.0, f64::max)
}

/// With projection (the default) the loop stays closed to rounding with
/// every method, whatever its accuracy: the bound 1e-10 is the issue's. The
/// projection takes at least one Newton iteration, landing at rounding
/// (~1e-14 m here); the variational method's RATTLE iteration stops at the
/// rounding bound `100 ε ‖G_i‖₁ ‖q‖∞`, which grows with the crank angle
/// (≈ 1200 rad after 100 s: 3e-11 m), still below 1e-10.
/// Fixed steps of 1e-3, except 1e-4 for the two first-order methods:
/// explicit Euler's energy grows by `exp(h ω² t / 2)` on an oscillation of
/// frequency ω ≈ 12 /s, a factor 1e3 over 100 s at 1e-3, and the linkage
/// then spins up until no step stays near the loop (a typed
/// `ProjectionFailed`, not a wrong answer). The energy error is each
/// method's own (printed; the issue asks for it).
fn stays_closed_for_100_s(methods: impl IntoIterator<Item = Method>) {
    let model = FourBar::crank_rocker();
    let (q0, v0) = start(&model);
    let e0 = model.energy(0.0, &q0, &v0);
    let times: Vec<f64> = (1..=1000).map(|k| 0.1 * k as f64).collect();
    for method in methods {
        let h = if method.order() == 1 { 1e-4 } else { 1e-3 };
        let run = method
            .integrator(h, 1e-8)
            .max_steps(10_000_000)
            .integrate(&model, 0.0, q0, v0, &times)
            .unwrap_or_else(|f| panic!("{method:?}: {}", f.error));
        let closure = worst_closure(&model, &run);
        let energy = worst_energy(&model, &run, e0);
        println!(
            "{:<18} closure {closure:.1e} m, energy error {energy:.1e}, {} steps, {} rhs",
            method.id(),
            run.stats().steps_accepted,
            run.stats().rhs_evals
        );
        assert!(closure < 1e-10, "{method:?}: closure {closure:.2e}");
        assert!(energy.is_finite(), "{method:?}");
    }
}

// Three tests, not one, so that the test threads share them: the two
// first-order methods take a million steps each, as long as all the others
// together. Between them they run every method of `Method::ALL`.
#[test]
fn four_bar_stays_closed_for_100_s_with_explicit_euler() {
    stays_closed_for_100_s([Method::ExplicitEuler]);
}

#[test]
fn four_bar_stays_closed_for_100_s_with_symplectic_euler() {
    stays_closed_for_100_s([Method::SymplecticEuler]);
}

#[test]
fn four_bar_stays_closed_for_100_s_with_every_other_method() {
    let (first_order, others): (Vec<Method>, Vec<Method>) =
        Method::ALL.iter().copied().partition(|m| m.order() == 1);
    assert_eq!(
        first_order,
        [Method::ExplicitEuler, Method::SymplecticEuler],
        "a first-order method the tests above do not run"
    );
    stays_closed_for_100_s(others);
}

/// Without projection the loop opens as each method's error accumulates:
/// measured, not hidden. Dopri5 at 1e-8 over 100 s: the closure residual
/// grows with time (the drift), well beyond the projected run's rounding,
/// and Baumgarte stabilization (α = β = 20 /s, critically damped and fast
/// beside the motion's ~2 Hz) holds it near the error per step instead.
/// The bounds are loose on purpose: the test states the ordering
/// none > Baumgarte > projection and that the drift grows, the figures are
/// printed (and in the README, from `lagrange-studies/examples/four_bar`).
#[test]
fn four_bar_drifts_open_without_projection_and_baumgarte_holds_it() {
    use lagrange::constraints::Drift;
    let model = FourBar::crank_rocker();
    let (q0, v0) = start(&model);
    let times: Vec<f64> = (1..=1000).map(|k| 0.1 * k as f64).collect();
    let method = Dopri5::new().rtol(1e-8).atol(1e-8).max_steps(10_000_000);
    let closure = |drift| {
        let run = method
            .integrate(&model.with_drift(drift), 0.0, q0, v0, &times)
            .unwrap();
        let early = run
            .iter()
            .take(100)
            .map(|s| model.constraints(s.t, &s.q).amax())
            .fold(0.0, f64::max);
        (early, worst_closure(&model, &run), run.stats())
    };
    let (_, projected, stats) = closure(Drift::Projection);
    let (early, drifted, _) = closure(Drift::None);
    let (_, held, _) = closure(Drift::Baumgarte {
        alpha: 20.0,
        beta: 20.0,
    });
    println!(
        "closure after 100 s: projection {projected:.1e} (largest per step {:.1e}), none {drifted:.1e} (first 10 s {early:.1e}), Baumgarte {held:.1e}",
        stats.max_position_residual
    );
    assert!(projected < 1e-10);
    assert!(
        drifted > early && drifted > 1e3 * projected,
        "drift {drifted:.1e}, first 10 s {early:.1e}"
    );
    assert!(held < drifted, "Baumgarte {held:.1e} vs none {drifted:.1e}");
}

/// The parallelogram at its change point: all pins on one line, the two
/// loop constraints' gradients parallel, `G M⁻¹ Gᵀ` singular. Every method
/// stops there with the typed error, at `t = 0` and in that state, and
/// hands back the (here empty) trajectory: never a NaN.
#[test]
fn four_bar_at_its_change_point_is_a_typed_error_with_every_method() {
    let model = FourBar::parallelogram();
    // θ1 = θ2 = θ3 = 0, crank and rocker turning alike: on the constraints
    // (G q̇ = 0), at the configuration where G has rank one.
    let (q0, v0) = (Vector3::zeros(), Vector3::new(1.0, 0.0, 1.0));
    assert!(model.constraints(0.0, &q0).amax() < 1e-15);
    for method in Method::ALL {
        let failure = method
            .integrator(1e-3, 1e-8)
            .integrate(&model, 0.0, q0, v0, &[1.0])
            .expect_err("the change point has no unique motion");
        match failure.error {
            IntegrationError::SingularConstraints { t, q, qdot } => {
                assert_eq!((t, q, qdot), (0.0, q0, v0), "{method:?}");
            }
            other => panic!("{method:?}: {other}"),
        }
        assert!(failure.trajectory.is_empty(), "{method:?}");
    }
}

/// The constrained linkage moves as the same linkage in its one minimal
/// coordinate (`MinimalFourBar`, the loop eliminated by hand): two
/// derivations of one motion. Both by Dop853 at 1e-12 over 10 s, about 19
/// crank turns of a regular (non-chaotic) motion, whose global errors are
/// ~1e-10 each; the crank angle grows to ~120 rad, so the bound on it is
/// relative, and the rate's is relative to the 12 rad/s it turns at.
#[test]
fn four_bar_moves_as_its_minimal_coordinate_form() {
    let model = FourBar::crank_rocker();
    let (q0, v0) = start(&model);
    let times: Vec<f64> = (1..=100).map(|k| 0.1 * k as f64).collect();
    let tight = Dop853::new().rtol(1e-12).atol(1e-12);
    let run = tight.integrate(&model, 0.0, q0, v0, &times).unwrap();
    let (x0, w0) = (Vector1::new(q0[0]), Vector1::new(v0[0]));
    let reference = tight
        .integrate(&model.minimal(), 0.0, x0, w0, &times)
        .unwrap();
    let worst = super::worst_against_minimal(&run, &reference, 12.0);
    println!("constrained vs minimal: {worst:.2e} (relative)");
    assert!(worst < 1e-8, "{worst:.2e}");
}
