//! Trajectories against `tests/data/` (25-digit references computed by two
//! independent methods; copied from the project's shared references).
//!
//! Bounds come from the tolerance and the problem's error growth, not from
//! what happens to pass. Dormand–Prince with per-step error control keeps
//! the global error of a non-chaotic problem within a small factor of
//! `tol · scale` (the runtime's own oscillator test measures ≈ 9×); a flow
//! amplifies it by at most its `perturbation_growth` (given by the reference;
//! ≤ 1 for the damped chain, whose flow contracts). So the bound is
//! `C · tol · growth · scale` with `C = 100`: ten times the measured factor,
//! for a nonlinear problem. A wrong term in M or f gives O(1) errors.

use crate::support::reference::{Reference, Sample};
use lagrange::models::TwoMassChain;
use lagrange::prelude::*;

/// Largest |q − q_ref|, |q̇ − q̇_ref| component over the state.
fn state_error(traj: &Trajectory<f64, 2>, k: usize, s: &Sample) -> f64 {
    let got = traj.get(k).unwrap();
    assert_eq!(got.t, s.t);
    (got.q - s.q).amax().max((got.qdot - s.qdot).amax())
}

/// The state error at each reference sample, printed with the run's work.
fn errors(name: &str, r: &Reference, traj: &Trajectory<f64, 2>) -> Vec<f64> {
    let errors: Vec<f64> = r
        .samples
        .iter()
        .enumerate()
        .map(|(k, s)| state_error(traj, k, s))
        .collect();
    let e: Vec<String> = errors.iter().map(|e| format!("{e:.2e}")).collect();
    println!(
        "{name}: errors [{}], stats {:?}",
        e.join(", "),
        traj.stats()
    );
    errors
}

#[test]
fn damped_chain_matches_reference_with_dormand_prince() {
    let r = Reference::damped_chain();
    let model = r.two_mass_chain_model();
    let times = r.times();
    let tol = 1e-12;
    let traj = Dopri5::new()
        .rtol(tol)
        .atol(tol)
        .integrate(&model, 0.0, r.q0, r.qdot0, &times)
        .unwrap();
    let errors = errors("chain dopri5", &r, &traj);
    for (k, s) in r.samples.iter().enumerate() {
        // |y| ≤ 1 here: scale 1.
        let bound = 100.0 * tol * s.growth;
        assert!(
            errors[k] <= bound,
            "t = {}: error {:.2e} > bound {bound:.2e}",
            s.t,
            errors[k]
        );
        // Energy to the same bound times the stiffness scale (k ≤ 20 · |x| ≤ 0.1).
        let e = model.energy(s.t, &traj.get(k).unwrap().q, &traj.get(k).unwrap().qdot);
        assert!(
            (e - s.energy).abs() <= 20.0 * bound,
            "t = {}: energy {e} vs {}",
            s.t,
            s.energy
        );
    }
}

#[test]
fn damped_chain_matches_reference_with_rk4() {
    let r = Reference::damped_chain();
    let model = r.two_mass_chain_model();
    let times = r.times();
    let h = 1e-3;
    let traj = Rk4::new(h)
        .integrate(&model, 0.0, r.q0, r.qdot0, &times)
        .unwrap();
    let errors = errors("chain rk4", &r, &traj);
    // RK4's local error is ≈ (h ω)⁵ / 120 · |y| per step (ω = 6.26 rad/s the
    // fast mode, |y| ≤ 0.1·ω): summed over t/h steps in a contracting flow,
    // the global error is ≤ t/h · (hω)⁵/120 · 0.1ω.
    let omega = 6.26f64;
    for (k, s) in r.samples.iter().enumerate() {
        let bound = s.t / h * (h * omega).powi(5) / 120.0 * 0.1 * omega;
        assert!(
            errors[k] <= bound,
            "t = {}: error {:.2e} > bound {bound:.2e}",
            s.t,
            errors[k]
        );
    }
}

#[test]
fn chaotic_double_pendulum_matches_reference_within_its_perturbation_growth() {
    let r = Reference::double_pendulum();
    let model = r.double_pendulum_model();
    let times = r.times();
    let tol = 1e-13;
    let traj = Dopri5::new()
        .rtol(tol)
        .atol(tol)
        .max_steps(1_000_000)
        .integrate(&model, 0.0, r.q0, r.qdot0, &times)
        .unwrap();
    let errors = errors("double pendulum dopri5", &r, &traj);
    let steps = traj.stats().steps_accepted as f64;
    for (k, s) in r.samples.iter().enumerate() {
        // Scale: the state's size, max(1, |y|) (up to ≈ 9 here). At t = 10
        // (growth 1.1e9) the bound is ~0.1: no float64 run can do better
        // than ~1e-7 there, and ours reaches ~5e-5.
        let scale = 1f64.max(s.q.amax()).max(s.qdot.amax());
        let bound = 100.0 * tol * s.growth * scale;
        assert!(
            errors[k] <= bound,
            "t = {}: error {:.2e} > bound {bound:.2e}",
            s.t,
            errors[k]
        );
        // Energy is a conserved quantity: its error is the local errors' sum,
        // not chaotically amplified: ≤ steps · tol · scale (10) · |∇E| (≲ 100).
        let end = traj.get(k).unwrap();
        let e = model.energy(s.t, &end.q, &end.qdot);
        let e_bound = steps * tol * 10.0 * 100.0;
        assert!(
            (e - s.energy).abs() <= e_bound,
            "t = {}: energy error {:.2e}",
            s.t,
            (e - s.energy).abs()
        );
    }
}

#[test]
fn damped_chain_in_f32_stays_within_single_precision_round_off() {
    let r = Reference::damped_chain();
    let model: TwoMassChain<f32> = r.two_mass_chain_model();
    let h = 1e-3f32;
    let q0 = r.q0.map(|x| x as f32);
    let qdot0 = r.qdot0.map(|x| x as f32);
    let s = &r.samples[0]; // t = 1
    let traj = Rk4::new(h)
        .integrate(&model, 0.0, q0, qdot0, &[s.t as f32])
        .unwrap();
    let end = traj.last().unwrap();
    let err = (end.q.map(f64::from) - s.q)
        .amax()
        .max((end.qdot.map(f64::from) - s.qdot).amax());
    // Truncation is ~1e-11 (see the f64 RK4 test); round-off of f32 grows at
    // most linearly: steps · eps_f32 · scale = 1000 · 1.2e-7 · 1 = 1.2e-4.
    // f64 would be ~1e-11: f32 costs seven digits here.
    println!("chain f32 rk4 error at t = 1: {err:.2e}");
    assert!(err <= 1000.0 * f32::EPSILON as f64, "f32 error {err:.2e}");
    assert!(
        err > 1e-10,
        "suspiciously accurate for f32: is it really computed in f32?"
    );
}
