//! Constrained models: closed loops and redundant coordinates, against
//! what is known of them exactly (the θ pendulum, the slider-crank's
//! kinematics) and over long runs (the four-bar linkage).

mod cartesian_pendulum;
mod four_bar;
mod slider_crank;

use lagrange::Trajectory;

/// The worst difference between a constrained run's first coordinate (a
/// crank angle) and its minimal twin's, relative: the angle's to the
/// angle (at least 1), the rate's to `rate`, the speed it turns at.
fn worst_against_minimal<const N: usize>(
    run: &Trajectory<f64, N>,
    minimal: &Trajectory<f64, 1>,
    rate: f64,
) -> f64 {
    let mut worst = 0.0f64;
    for (a, b) in run.iter().zip(minimal) {
        worst = worst.max((a.q[0] - b.q[0]).abs() / b.q[0].abs().max(1.0));
        worst = worst.max((a.qdot[0] - b.qdot[0]).abs() / rate);
    }
    worst
}
