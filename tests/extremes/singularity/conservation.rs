//! Swings kept off the pole by their azimuthal momentum: energy and `p_φ`
//! conserved to what each method's errors allow.

use super::methods::ALL;
use super::methods::Method::Variational;
use super::{G, H, azimuthal_momentum, closest_approach, model, planar, sample_times, start};
use lagrange::nalgebra::Vector2;
use lagrange::prelude::*;

/// `Σ |∂Q/∂y_i| (1 + |y_i|)` for `Q` = energy and `p_φ`: what a local
/// error of `tol` in each component of `y = (θ, φ, θ̇, φ̇)` (absolute plus
/// relative, as the error control measures it) can change `Q` by, per step.
fn conservation_sensitivity(q: &Vector2<f64>, qdot: &Vector2<f64>) -> (f64, f64) {
    let (s, c) = q[0].sin_cos();
    let weight = |x: f64| 1.0 + x.abs();
    // E = ½ θ̇² + ½ sin²θ φ̇² − g cos θ
    let energy = (s * c * qdot[1].powi(2) + G * s).abs() * weight(q[0])
        + qdot[0].abs() * weight(qdot[0])
        + (s * s * qdot[1]).abs() * weight(qdot[1]);
    // p_φ = sin²θ φ̇
    let momentum = (2.0 * s * c * qdot[1]).abs() * weight(q[0]) + s * s * weight(qdot[1]);
    (energy, momentum)
}

/// The largest conservation sensitivity along a run: at its samples and at
/// the closest approach (`θ_min`, `θ̇ = 0`, `φ̇ = p_φ/sin²θ_min`), where
/// the centrifugal barrier is steepest and the samples rarely fall.
fn worst_sensitivity(run: &Trajectory<f64, 2>, p: f64) -> (f64, f64) {
    let theta_min = closest_approach(p);
    let closest = (
        Vector2::new(theta_min, 0.0),
        Vector2::new(0.0, p / theta_min.sin().powi(2)),
    );
    run.iter()
        .map(|s| (s.q, s.qdot))
        .chain(std::iter::once(closest))
        .map(|(q, qdot)| conservation_sensitivity(&q, &qdot))
        .fold((0.0, 0.0), |(e, m), (e1, m1)| {
            (f64::max(e, e1), f64::max(m, m1))
        })
}

/// Energy and `p_φ` at each sample.
fn invariants(run: &Trajectory<f64, 2>) -> Vec<(f64, f64)> {
    let model = model();
    run.iter()
        .map(|s| {
            (
                model.energy(s.t, &s.q, &s.qdot),
                azimuthal_momentum(&s.q, &s.qdot),
            )
        })
        .collect()
}

/// The largest difference of energy and of `p_φ` between two series.
fn largest_gap(a: &[(f64, f64)], b: &[(f64, f64)]) -> (f64, f64) {
    a.iter()
        .zip(b)
        .map(|(x, y)| ((x.0 - y.0).abs(), (x.1 - y.1).abs()))
        .fold((0.0, 0.0), |(e, m), (e1, m1)| {
            (f64::max(e, e1), f64::max(m, m1))
        })
}

/// Largest drift of energy and `p_φ` from their initial values over a run.
fn drifts(run: &Trajectory<f64, 2>, e0: f64, p0: f64) -> (f64, f64) {
    let start = vec![(e0, p0); run.len()];
    largest_gap(&invariants(run), &start)
}

/// A small azimuthal momentum (`φ̇0 = 1e-3`: `θ_min ≈ 2.4e-4`, `κ(M)` up to
/// 1.8e7, `φ̇` up to 1.3e4 rad/s, `φ` turning by π within ~1e-4 s) is a
/// regular but violent passage. Adaptive methods resolve it: they succeed,
/// `φ` has turned by π (to 1 %: the precession per pass is `O(θ_min)`),
/// and energy and `p_φ` drift by no more than the steps' local errors can
/// move them, `steps · tol · Σ|∂Q/∂y|(1 + |y|)` with the sensitivity's
/// maximum at the closest approach. Fixed steps of 1e-3 cannot (the turn
/// takes a tenth of one): they stop with a typed error within a few steps
/// of `T/4`, keeping the samples before.
#[test]
fn a_near_planar_swing_is_resolved_by_adaptive_steps_and_stops_fixed_ones() {
    let (_, quarter) = planar();
    let (q0, v0) = start(1e-3);
    let model = model();
    let (e0, p0) = (model.energy(0.0, &q0, &v0), azimuthal_momentum(&q0, &v0));
    let theta_min = closest_approach(p0);
    let times = sample_times();
    println!(
        "near-planar swing: p_φ = {p0:.2e}, θ_min = {theta_min:.2e}, κ(M) up to {:.1e}, \
         φ̇ up to {:.1e}",
        1.0 / theta_min.sin().powi(2),
        p0 / theta_min.sin().powi(2)
    );
    for method in ALL {
        match method.run(q0, v0, &times) {
            Ok(run) => {
                assert!(method.adaptive(), "{method:?} integrated the passage");
                let (energy_drift, momentum_drift) = drifts(&run, e0, p0);
                let (energy_sens, momentum_sens) = worst_sensitivity(&run, p0);
                let steps = (run.stats().steps_accepted + run.stats().steps_rejected) as f64;
                let tol = method.allowance() / 100.0;
                let turned = run.get(12).unwrap().q[1]; // t = 0.65, past the pole
                println!(
                    "near-planar swing, {method:?}: φ turned by {turned:.4}, energy drift \
                     {energy_drift:.1e} (bound {:.1e}), p_φ drift {momentum_drift:.1e} (bound \
                     {:.1e}), {} steps",
                    steps * tol * energy_sens,
                    steps * tol * momentum_sens,
                    run.stats().steps_accepted
                );
                assert!((turned - std::f64::consts::PI).abs() < 0.01 * std::f64::consts::PI);
                assert!(energy_drift <= steps * tol * energy_sens);
                assert!(momentum_drift <= steps * tol * momentum_sens);
            }
            Err(failure) => {
                println!("near-planar swing, {method:?}: {failure}");
                assert!(!method.adaptive(), "{method:?}: {failure}");
                let (IntegrationError::NewtonDivergence { t, .. }
                | IntegrationError::Unstable { t, .. }) = failure.error
                else {
                    panic!("{method:?}: unexpected {}", failure.error);
                };
                assert!((t - quarter).abs() < 3.0 * H, "{method:?}: t = {t}");
                let before = times.iter().filter(|&&s| s < t).count();
                assert_eq!(failure.trajectory.len(), before, "{method:?}");
            }
        }
    }
}

/// A clearly spherical swing (`φ̇0 = 1`: `θ_min ≈ 0.23`, `κ(M) ≤ 19`) never
/// comes near the pole: every method succeeds. Energy and `p_φ` are
/// conserved by the exact flow; the adaptive methods' drift is bounded by
/// their local errors as above, the fixed-step methods' by twice their
/// Richardson estimate (from `h` and `h/2`) plus round-off. The variational
/// integrator conserves `p_φ` exactly (discrete Noether: `φ` is cyclic), so
/// its `p_φ` differs from the start only by the rounding of converting the
/// momenta to `q̇` at each sample, a few ε of `p_φ`.
#[test]
fn azimuthal_momentum_keeps_the_swing_off_the_pole_and_is_conserved() {
    let (q0, v0) = start(1.0);
    let model = model();
    let (e0, p0) = (model.energy(0.0, &q0, &v0), azimuthal_momentum(&q0, &v0));
    let theta_min = closest_approach(p0);
    let times = sample_times();
    println!(
        "spherical swing: p_φ = {p0:.3}, θ_min = {theta_min:.3}, κ(M) ≤ {:.1}",
        1.0 / theta_min.sin().powi(2)
    );
    for method in ALL {
        let run = method
            .run(q0, v0, &times)
            .unwrap_or_else(|f| panic!("{method:?}: {f}"));
        assert!(run.positions().iter().all(|q| q[0] >= 0.99 * theta_min));
        let (energy_drift, momentum_drift) = drifts(&run, e0, p0);
        let steps = run.stats().steps_accepted as f64;
        let (energy_bound, momentum_bound) = match method.refined() {
            None => {
                let (energy_sens, momentum_sens) = worst_sensitivity(&run, p0);
                let attempts = steps + run.stats().steps_rejected as f64;
                let tol = method.allowance() / 100.0;
                (attempts * tol * energy_sens, attempts * tol * momentum_sens)
            }
            Some((order, half)) => {
                // The drift at h is ≈ 2^p/(2^p − 1) times its change from h
                // to h/2, sample by sample; round-off adds ~10 ε per step of
                // quantities of size ≤ 10.
                let fine = half.run(q0, v0, &times).unwrap();
                let (energy_gap, momentum_gap) = largest_gap(&invariants(&run), &invariants(&fine));
                let richardson = 2f64.powi(order) / (2f64.powi(order) - 1.0);
                let roundoff = steps * 10.0 * f64::EPSILON * 10.0;
                (
                    2.0 * richardson * energy_gap + roundoff,
                    2.0 * richardson * momentum_gap + roundoff,
                )
            }
        };
        let momentum_bound = match method {
            Variational(_) => 8.0 * f64::EPSILON * p0,
            _ => momentum_bound,
        };
        println!(
            "spherical swing, {method:?}: energy drift {energy_drift:.1e} (bound \
             {energy_bound:.1e}), p_φ drift {momentum_drift:.1e} (bound {momentum_bound:.1e}), \
             {} steps",
            run.stats().steps_accepted
        );
        assert!(energy_drift <= energy_bound, "{method:?}: energy");
        assert!(momentum_drift <= momentum_bound, "{method:?}: p_φ");
    }
}
