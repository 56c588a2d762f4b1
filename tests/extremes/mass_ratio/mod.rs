//! Numerical stability at the extremes: a double pendulum whose bobs differ
//! in mass by a factor of 10⁶, either way.
//!
//! `M = [[(m1 + m2) l1², m2 l1 l2 c], [m2 l1 l2 c, m2 l2²]]` with
//! `c = cos(θ1 − θ2)` has a condition number of ~10⁶ at both extremes, for
//! different reasons:
//!
//! - **light outer bob** (`m2/m1 = 10⁻⁶`): the second row is 10⁻⁶ of the
//!   first. Nothing is stiff: the outer bob barely pulls on the inner one,
//!   which swings as a simple pendulum of length `l1` (to relative
//!   `O(m2/m1)`), while the outer one is a pendulum hanging from that moving
//!   support.
//! - **heavy outer bob** (`m2/m1 = 10⁶`): the two rows are nearly equal
//!   when the rods are aligned (`det M = m2 l1² l2² (m1 + m2 sin²(θ1 − θ2))`).
//!   The light joint has almost no inertia, so it cannot bend the chain: a
//!   kink `θ1 − θ2` is pulled straight by the tension `≈ m2 g` acting on the
//!   mass `m1`, a vibration of frequency
//!   `ω_k ≈ √(m2/m1 · g cos Θ (l1 + l2)/(l1 l2)) ≈ 4.1·10³ rad/s`, while the
//!   straight chain swings as a simple pendulum of length `l1 + l2`. The
//!   physically right limit is that pendulum (the massless chain of two rods
//!   stays straight while in tension, which it is at these amplitudes), and
//!   the model is **stiff**: explicit methods must resolve `ω_k`.
//!
//! Every test prints the figures quoted in STABILITY.md; run with
//! `cargo test --release --test suite -- extremes::mass_ratio:: --nocapture`.
//!
//! The solve at this conditioning is checked in `conditioning.rs`, the two
//! physical limits in `limits.rs`, the integrators against them in
//! `methods.rs`.

use lagrange::models::DoublePendulum;
use lagrange::nalgebra::Vector2;
use lagrange::prelude::*;

mod conditioning;
mod limits;
mod methods;

const G: f64 = 9.81;
const END: f64 = 5.0;

/// Unit rods, the given masses.
fn chain(m1: f64, m2: f64) -> DoublePendulum {
    DoublePendulum::new(m1, m2, 1.0, 1.0, G)
}

/// Light outer bob: both rods swinging, at moderate amplitude (not chaotic
/// over 5 s).
fn light_start() -> (Vector2<f64>, Vector2<f64>) {
    (Vector2::new(0.5, 0.3), Vector2::zeros())
}

/// Heavy outer bob: released from rest with the chain straight at 0.5 rad.
fn heavy_start() -> (Vector2<f64>, Vector2<f64>) {
    (Vector2::new(0.5, 0.5), Vector2::zeros())
}

/// Samples every 0.01 s: dense enough to see the kink vibration's amplitude
/// (period 1.5 ms, sampled at unrelated phases) and every swing.
fn sample_times() -> Vec<f64> {
    (1..=500).map(|k| 0.01 * k as f64).collect()
}

/// Dop853 at 1e-13, our reference for each extreme: its error is ≈ 10 ×
/// tol × growth (docs/guides/methods.md, "Accuracy"), below 1e-8 even with the heavy chain's
/// growth of ~2300 (measured below), far below every error it judges.
fn reference(model: &DoublePendulum, start: (Vector2<f64>, Vector2<f64>)) -> Trajectory<f64, 2> {
    Dop853::new()
        .rtol(1e-13)
        .atol(1e-13)
        .max_steps(2_000_000)
        .integrate(model, 0.0, start.0, start.1, &sample_times())
        .expect("the reference run")
}

/// Largest state difference `max |Δq|, |Δq̇|` over all samples.
fn max_distance(a: &Trajectory<f64, 2>, b: &Trajectory<f64, 2>) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b.iter())
        .map(|(x, y)| (x.q - y.q).amax().max((x.qdot - y.qdot).amax()))
        .fold(0.0, f64::max)
}
