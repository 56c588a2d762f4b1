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

use lagrange::models::{DoublePendulum, TwoMassChain};
use lagrange::nalgebra::Vector2;
use lagrange::prelude::*;
use serde_json::Value;

struct Sample {
    t: f64,
    q: Vector2<f64>,
    qdot: Vector2<f64>,
    energy: f64,
    growth: f64,
}

struct Reference {
    params: Value,
    q0: Vector2<f64>,
    qdot0: Vector2<f64>,
    samples: Vec<Sample>,
}

fn num(v: &Value) -> f64 {
    match v {
        Value::String(s) => s.parse().unwrap(),
        v => v.as_f64().unwrap(),
    }
}

fn vec2(v: &Value) -> Vector2<f64> {
    Vector2::new(num(&v[0]), num(&v[1]))
}

fn reference(name: &str) -> Reference {
    let path = format!("{}/tests/data/{name}.json", env!("CARGO_MANIFEST_DIR"));
    let json: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let growth = json["float64_check"]["perturbation_growth"].clone();
    let samples = json["samples"]
        .as_array()
        .unwrap()
        .iter()
        .enumerate()
        .map(|(k, s)| Sample {
            t: num(&s["t"]),
            q: vec2(&s["q"]),
            qdot: vec2(&s["dq"]),
            energy: num(&s["energy"]),
            // The chain's flow contracts (damped, linear): growth ≤ 1.
            growth: growth.get(k).map(num).unwrap_or(1.0),
        })
        .collect();
    Reference {
        params: json["parameters_exact"].clone(),
        q0: vec2(&json["q0"]),
        qdot0: vec2(&json["dq0"]),
        samples,
    }
}

fn chain(r: &Reference) -> TwoMassChain {
    let p = |k: &str| num(&r.params[k]);
    TwoMassChain::new(
        p("m1"),
        p("m2"),
        p("k1"),
        p("k2"),
        p("k3"),
        p("c1"),
        p("c2"),
        p("c3"),
    )
}

fn pendulum(r: &Reference) -> DoublePendulum {
    let p = |k: &str| num(&r.params[k]);
    DoublePendulum::new(p("m1"), p("m2"), p("l1"), p("l2"), p("g"))
}

/// Largest |q − q_ref|, |q̇ − q̇_ref| component over the state.
fn state_error(traj: &Trajectory<f64, 2>, k: usize, s: &Sample) -> f64 {
    let got = traj.get(k).unwrap();
    assert_eq!(got.t, s.t);
    (got.q - s.q).amax().max((got.qdot - s.qdot).amax())
}

fn report<const N: usize>(name: &str, traj: &Trajectory<f64, N>, errors: &[f64]) {
    let e: Vec<String> = errors.iter().map(|e| format!("{e:.2e}")).collect();
    println!(
        "{name}: errors [{}], stats {:?}",
        e.join(", "),
        traj.stats()
    );
}

#[test]
fn damped_chain_matches_reference_with_dormand_prince() {
    let r = reference("damped_two_mass_spring");
    let model = chain(&r);
    let times: Vec<f64> = r.samples.iter().map(|s| s.t).collect();
    let tol = 1e-12;
    let traj = Dopri5::new()
        .rtol(tol)
        .atol(tol)
        .integrate(&model, 0.0, r.q0, r.qdot0, &times)
        .unwrap();
    let errors: Vec<f64> = r
        .samples
        .iter()
        .enumerate()
        .map(|(k, s)| state_error(&traj, k, s))
        .collect();
    report("chain dopri5", &traj, &errors);
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
    let r = reference("damped_two_mass_spring");
    let model = chain(&r);
    let times: Vec<f64> = r.samples.iter().map(|s| s.t).collect();
    let h = 1e-3;
    let traj = Rk4::new(h)
        .integrate(&model, 0.0, r.q0, r.qdot0, &times)
        .unwrap();
    let errors: Vec<f64> = r
        .samples
        .iter()
        .enumerate()
        .map(|(k, s)| state_error(&traj, k, s))
        .collect();
    report("chain rk4", &traj, &errors);
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
    let r = reference("double_pendulum");
    let model = pendulum(&r);
    let times: Vec<f64> = r.samples.iter().map(|s| s.t).collect();
    let tol = 1e-13;
    let traj = Dopri5::new()
        .rtol(tol)
        .atol(tol)
        .max_steps(1_000_000)
        .integrate(&model, 0.0, r.q0, r.qdot0, &times)
        .unwrap();
    let errors: Vec<f64> = r
        .samples
        .iter()
        .enumerate()
        .map(|(k, s)| state_error(&traj, k, s))
        .collect();
    report("double pendulum dopri5", &traj, &errors);
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
    let r = reference("damped_two_mass_spring");
    let p = |k: &str| num(&r.params[k]) as f32;
    let model: TwoMassChain<f32> = TwoMassChain::new(
        p("m1"),
        p("m2"),
        p("k1"),
        p("k2"),
        p("k3"),
        p("c1"),
        p("c2"),
        p("c3"),
    );
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
