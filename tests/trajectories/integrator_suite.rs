//! Every integrator on models derived by the macro: the observed order of
//! each fixed-step method, the tolerance behaviour of each adaptive one, and
//! the long-run energy behaviour that separates symplectic methods from the
//! rest.

use crate::support::fit::{log_slope, sci};
use lagrange::models::{DoublePendulum, Kepler, PolarKepler};
use lagrange::nalgebra::Vector2;
use lagrange::prelude::*;

/// The double pendulum at moderate amplitude: smooth and not chaotic over
/// one second, so errors follow each method's asymptotic law.
fn smooth_problem() -> (DoublePendulum, Vector2<f64>, Vector2<f64>) {
    DoublePendulum::regular()
}

fn final_state<I: Integrator<f64>>(method: &I, end: f64) -> (Vector2<f64>, Vector2<f64>) {
    let (model, q0, v0) = smooth_problem();
    let t = method.integrate(&model, 0.0, q0, v0, &[end]).unwrap();
    let s = t.last().unwrap();
    (s.q, s.qdot)
}

fn distance(a: &(Vector2<f64>, Vector2<f64>), b: &(Vector2<f64>, Vector2<f64>)) -> f64 {
    (a.0 - b.0).amax().max((a.1 - b.1).amax())
}

/// Dopri5 at 1e-13: its global error (≈ 10·tol, see the reference tests)
/// is far below the smallest error measured in the order fits (≳ 1e-10).
fn reference(end: f64) -> (Vector2<f64>, Vector2<f64>) {
    final_state(&Dopri5::new().rtol(1e-13).atol(1e-13), end)
}

/// The order check: four halvings of `h` in the asymptotic range, where the
/// error is far above round-off (checked) and the leading term dominates.
/// "Within 0.2 of theory" is the acceptance bound.
fn assert_order(
    name: &str,
    order: f64,
    hs: &[f64],
    run: impl Fn(f64) -> (Vector2<f64>, Vector2<f64>),
) {
    let end = 1.0;
    let exact = reference(end);
    let errors: Vec<f64> = hs.iter().map(|&h| distance(&run(h), &exact)).collect();
    assert!(
        errors.iter().all(|&e| e > 1e-11),
        "{name}: errors {} reach round-off",
        sci(&errors)
    );
    let p = log_slope(hs, &errors);
    println!(
        "{name}: observed order {p:.3} (theory {order}), errors {}",
        sci(&errors)
    );
    assert!(
        (p - order).abs() <= 0.2,
        "{name}: observed order {p:.3}, theory {order}"
    );
}

#[test]
fn rk4_shows_fourth_order_on_a_derived_model() {
    let hs = [0.01, 0.005, 0.0025, 0.00125];
    assert_order("rk4", 4.0, &hs, |h| final_state(&Rk4::new(h), 1.0));
}

/// Adaptive methods: the error falls as the tolerance tightens, and stays
/// within a small factor of it on a smooth problem. The factor (100) is the
/// same as in the reference tests: error-per-step control keeps the global
/// error of a non-chaotic problem within ≈ 10× of tol, with 10× margin.
fn assert_tracks_tolerance<I: Integrator<f64>>(name: &str, make: impl Fn(f64) -> I) {
    let exact = reference(1.0);
    let tolerances = [1e-4, 1e-6, 1e-8, 1e-10];
    let errors: Vec<f64> = tolerances
        .iter()
        .map(|&tol| distance(&final_state(&make(tol), 1.0), &exact))
        .collect();
    println!(
        "{name}: errors {} at tolerances {}",
        sci(&errors),
        sci(&tolerances)
    );
    for (tol, e) in tolerances.iter().zip(&errors) {
        assert!(*e <= 100.0 * tol, "{name}: error {e:.2e} at tol {tol:.0e}");
    }
    // Each 100× tighter tolerance buys at least 3× less error: enough to
    // catch a stall, loose enough for a high-order method at loose
    // tolerances, whose error is not yet proportional to tol (DOP853 gains
    // 7× from 1e-4 to 1e-6, 700× from 1e-6 to 1e-8); the bound above keeps
    // the error tied to tol overall.
    for w in errors.windows(2) {
        assert!(
            w[1] <= w[0] / 3.0,
            "{name}: errors {} do not fall with the tolerance",
            sci(&errors)
        );
    }
}

#[test]
fn dopri5_error_tracks_its_tolerance() {
    assert_tracks_tolerance("dopri5", |tol| Dopri5::new().rtol(tol).atol(tol));
}

/// Relative energy error of a Kepler orbit (e = 0.6) sampled 40 times per
/// orbit (the error of a symplectic method oscillates along the orbit; one
/// sample per orbit at a slowly sliding phase would mistake that oscillation
/// for growth), in polar coordinates (M(q) = diag(1, r²), non-separable) or Cartesian
/// ones (constant M, and no exact Jacobians: the implicit methods difference
/// the acceleration); returns (worst over the first tenth of the run, worst
/// over the last tenth).
fn energy_error_early_and_late<I: Integrator<f64>>(method: &I, orbits: usize) -> (f64, f64) {
    kepler_energy_errors(method, orbits, true)
}

fn kepler_energy_errors<I: Integrator<f64>>(method: &I, orbits: usize, polar: bool) -> (f64, f64) {
    let e: f64 = 0.6;
    let period = 2.0 * std::f64::consts::PI;
    let per_orbit = 40;
    let times: Vec<f64> = (1..=orbits * per_orbit)
        .map(|k| period * k as f64 / per_orbit as f64)
        .collect();
    let errors: Vec<f64> = if polar {
        let model = PolarKepler::new(1.0);
        let (q0, v0) = model.pericentre(e);
        let e0 = model.energy(0.0, &q0, &v0);
        let t = method.integrate(&model, 0.0, q0, v0, &times).unwrap();
        t.iter()
            .map(|s| ((model.energy(s.t, &s.q, &s.qdot) - e0) / e0).abs())
            .collect()
    } else {
        let model = Kepler::new(1.0).without_jacobians();
        let (q0, v0) = model.model().pericentre(e);
        let e0 = model.energy(0.0, &q0, &v0);
        let t = method.integrate(&model, 0.0, q0, v0, &times).unwrap();
        t.iter()
            .map(|s| ((model.energy(s.t, &s.q, &s.qdot) - e0) / e0).abs())
            .collect()
    };
    let tenth = errors.len() / 10;
    let worst = |xs: &[f64]| xs.iter().copied().fold(0.0, f64::max);
    (
        worst(&errors[..tenth]),
        worst(&errors[errors.len() - tenth..]),
    )
}

/// A method with secular drift has an energy error that grows in
/// proportion to time: over a run ten times longer than its first tenth,
/// the late error is ≈ 10× the early one (a ratio above 4 is drift, allowing
/// for the oscillation within an orbit).
#[test]
fn rk4_and_dopri5_drift_in_energy_over_a_long_kepler_run() {
    let period = 2.0 * std::f64::consts::PI;
    let (early, late) = energy_error_early_and_late(&Rk4::new(period / 200.0), 500);
    println!("rk4 energy error: first tenth {early:.2e}, last tenth {late:.2e}");
    assert!(late > 4.0 * early, "rk4: {early:.2e} → {late:.2e}");
    let (early, late) = energy_error_early_and_late(&Dopri5::new().rtol(1e-7).atol(1e-7), 500);
    println!("dopri5 energy error: first tenth {early:.2e}, last tenth {late:.2e}");
    assert!(late > 4.0 * early, "dopri5: {early:.2e} → {late:.2e}");
}

#[test]
fn variational_shows_second_order_on_a_derived_model() {
    let hs = [0.02, 0.01, 0.005, 0.0025];
    assert_order("variational", 2.0, &hs, |h| {
        final_state(&Variational::new(h), 1.0)
    });
}

/// A method without drift keeps the worst energy error of the last tenth of
/// the run at the level of the first tenth: bounded oscillation (a ratio
/// below 2; drift would give ≈ 10).
fn assert_no_drift<I: Integrator<f64>>(name: &str, method: &I) {
    let (early, late) = energy_error_early_and_late(method, 500);
    println!("{name} energy error: first tenth {early:.2e}, last tenth {late:.2e}");
    assert!(late < 2.0 * early, "{name}: {early:.2e} → {late:.2e}");
}

#[test]
fn variational_energy_error_stays_bounded_over_a_long_kepler_run() {
    assert_no_drift(
        "variational",
        &Variational::new(2.0 * std::f64::consts::PI / 200.0),
    );
}

#[test]
fn implicit_midpoint_shows_second_order_on_a_derived_model() {
    let hs = [0.02, 0.01, 0.005, 0.0025];
    assert_order("implicit midpoint", 2.0, &hs, |h| {
        final_state(&ImplicitMidpoint::new(h), 1.0)
    });
}

#[test]
fn gauss_legendre_two_stage_shows_fourth_order_on_a_derived_model() {
    let hs = [0.04, 0.02, 0.01, 0.005];
    assert_order("gauss-legendre 2", 4.0, &hs, |h| {
        final_state(&GaussLegendre::two_stage(h), 1.0)
    });
}

#[test]
fn gauss_legendre_three_stage_shows_sixth_order_on_a_derived_model() {
    let hs = [0.16, 0.08, 0.04, 0.02];
    assert_order("gauss-legendre 3", 6.0, &hs, |h| {
        final_state(&GaussLegendre::three_stage(h), 1.0)
    });
}

/// With constant M (Cartesian Kepler) the implicit Runge–Kutta methods are
/// symplectic, and with the variational integrator none drifts.
#[test]
fn symplectic_methods_show_no_energy_drift_on_a_cartesian_kepler_run() {
    let h = 2.0 * std::f64::consts::PI / 200.0;
    let check = |name: &str, (early, late): (f64, f64)| {
        println!("cartesian {name} energy error: first tenth {early:.2e}, last tenth {late:.2e}");
        assert!(late < 2.0 * early, "{name}: {early:.2e} → {late:.2e}");
    };
    check(
        "implicit midpoint",
        kepler_energy_errors(&ImplicitMidpoint::new(h), 500, false),
    );
    check(
        "gauss-legendre 2",
        kepler_energy_errors(&GaussLegendre::two_stage(h), 500, false),
    );
    check(
        "gauss-legendre 3",
        kepler_energy_errors(&GaussLegendre::three_stage(h), 500, false),
    );
    check(
        "variational",
        kepler_energy_errors(&Variational::new(h), 500, false),
    );
}

/// With M(q) (polar Kepler) the variational integrator is still symplectic
/// (it works in (q, p)); the implicit Runge–Kutta methods, applied in
/// (q, q̇), are not symplectic there but are symmetric, and on this
/// reversible, integrable problem they show no drift either.
#[test]
fn symmetric_methods_show_no_energy_drift_with_a_position_dependent_mass_matrix() {
    let h = 2.0 * std::f64::consts::PI / 200.0;
    assert_no_drift("implicit midpoint", &ImplicitMidpoint::new(h));
    assert_no_drift("gauss-legendre 2", &GaussLegendre::two_stage(h));
    assert_no_drift("gauss-legendre 3", &GaussLegendre::three_stage(h));
    assert_no_drift("variational", &Variational::new(h));
}

#[test]
fn euler_methods_show_first_order_on_a_derived_model() {
    let hs = [0.002, 0.001, 0.0005, 0.00025];
    assert_order("explicit euler", 1.0, &hs, |h| {
        final_state(&ExplicitEuler::new(h), 1.0)
    });
    assert_order("symplectic euler", 1.0, &hs, |h| {
        final_state(&SymplecticEuler::new(h), 1.0)
    });
}

#[test]
fn dop853_error_tracks_its_tolerance() {
    assert_tracks_tolerance("dop853", |tol| Dop853::new().rtol(tol).atol(tol));
}

#[test]
fn radau5_error_tracks_its_tolerance() {
    assert_tracks_tolerance("radau5", |tol| Radau5::new().rtol(tol).atol(tol));
}
