//! The slider-crank in redundant coordinates against its closed-form
//! kinematics and against the same mechanism in its minimal coordinate.

use lagrange::models::{SliderCrank, slider_crank_kinematics};
use lagrange::nalgebra::Vector1;
use lagrange::prelude::*;

/// A run of 10 s from the crank at 30° turning at 20 rad/s: about 30
/// revolutions, through both dead centres of the piston.
fn run() -> (SliderCrank, Trajectory<f64, 3>) {
    let model = SliderCrank::engine();
    let (q0, v0) = model.state(30f64.to_radians(), 20.0);
    let times: Vec<f64> = (1..=1000).map(|k| 0.01 * k as f64).collect();
    let run = Dop853::new()
        .rtol(1e-12)
        .atol(1e-12)
        .integrate(&model, 0.0, q0, v0, &times)
        .unwrap();
    (model, run)
}

/// Along the whole run, the rod angle and the piston position are the
/// closed-form functions of the crank angle, and their rates those of the
/// crank rate. With projection after every step the loop closes to a few
/// ulps (the Newton projection stops at rounding), so the redundant
/// coordinates agree with the closed form evaluated at the computed crank
/// angle to rounding of the closed form itself (`asin`, `sqrt`: ~1e-15);
/// 1e-10 is the bound on the closure residual.
#[test]
fn slider_crank_follows_its_closed_form_kinematics() {
    let (model, run) = run();
    let mut worst = [0.0f64; 4];
    for s in &run {
        let want = slider_crank_kinematics(model.r, model.l, s.q[0], s.qdot[0]);
        let got = [s.q[1], s.q[2], s.qdot[1], s.qdot[2]];
        for k in 0..4 {
            worst[k] = worst[k].max((got[k] - want[k]).abs());
        }
    }
    println!(
        "closed-form kinematics: |Δφ| {:.1e}, |Δs| {:.1e}, |Δφ̇| {:.1e}, |Δṡ| {:.1e}",
        worst[0], worst[1], worst[2], worst[3]
    );
    assert!(worst[0] < 1e-10 && worst[1] < 1e-10, "positions {worst:?}");
    // Rates scale with θ̇ ≈ 20 rad/s: 1e-10 of it.
    assert!(worst[2] < 2e-9 && worst[3] < 2e-9, "rates {worst:?}");
}

/// The constrained mechanism moves as the same mechanism in its minimal
/// coordinate: both by Dop853 at 1e-12, whose global errors over 30
/// revolutions of a regular (non-chaotic) motion are ~1e-10 each; the crank
/// angle grows to ~200 rad, so the bound is relative to it.
#[test]
fn slider_crank_moves_as_its_minimal_coordinate_form() {
    let (model, run) = run();
    let minimal = model.minimal();
    let (q0, v0) = model.state(30f64.to_radians(), 20.0);
    let times = run.times().to_vec();
    let reference = Dop853::new()
        .rtol(1e-12)
        .atol(1e-12)
        .integrate(
            &minimal,
            0.0,
            Vector1::new(q0[0]),
            Vector1::new(v0[0]),
            &times,
        )
        .unwrap();
    let worst = super::worst_against_minimal(&run, &reference, 20.0);
    println!("constrained vs minimal: {worst:.2e} (relative)");
    assert!(worst < 1e-8, "{worst:.2e}");
}
