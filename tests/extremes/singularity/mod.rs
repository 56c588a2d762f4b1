//! Numerical stability at the extremes: a coordinate singularity. The
//! spherical pendulum in its usual chart, `θ` the polar angle from the
//! downward vertical and `φ` the azimuth, has
//! `M = diag(m l², m l² sin²θ)`, which loses rank at the pole `θ = 0`, the
//! bottom of the sphere. Released from `θ0 = 1` rad it passes there, or
//! near, after a quarter period `T/4 = K(sin(θ0/2))/ω₀ ≈ 0.535 s`.
//!
//! What happens depends on the azimuthal momentum `p_φ = m l² sin²θ φ̇`,
//! conserved because `φ` is cyclic:
//!
//! - `p_φ ≠ 0`: the centrifugal barrier `p_φ² / (2 m l² sin²θ)` keeps the
//!   bob off the pole, at `θ_min ≈ p_φ / (m l² θ̇_bottom)`, where `φ` turns
//!   by about π at `φ̇ = p_φ / (m l² sin²θ_min)`. The chart is regular along
//!   the way, only badly conditioned (`κ(M) = 1/sin²θ_min`) and fast.
//! - `p_φ = 0` exactly: a planar swing. The equation for `φ` reads
//!   `m l² sin²θ φ̈ = −2 m l² sin θ cos θ θ̇ φ̇ = 0`, so its singularity is
//!   removable: `φ̈ = 0` except *at* `θ = 0`, where `φ` is undefined. The
//!   motion in the chart is `θ` passing through zero to negative values,
//!   which is the same physical swing (`(−θ, φ)` is the point `(θ, φ + π)`).
//!
//! The solve `M q̈ = f` refuses a pivot ratio `sin²θ ≤ 2 ε`, i.e.
//! `|θ| ≤ √(2ε) ≈ 2.1e-8` rad: closer to the pole than that, `φ̈` would be
//! rounding noise amplified by `1/sin²θ`, and the typed
//! `SingularMassMatrix` error is the answer.
//!
//! Every test prints the figures quoted in STABILITY.md; run with
//! `cargo test --release --test suite -- extremes::singularity:: --nocapture`.
//!
//! The methods are in `methods.rs`; the swings at or through the pole in
//! `pole.rs`, those its momentum keeps off it in `conservation.rs`.

use crate::support::elliptic;
use lagrange::nalgebra::Vector2;
use lagrange::prelude::*;

mod conservation;
mod methods;
mod pole;

lagrangian! {
    /// The spherical pendulum: bob `m` on a massless rod `l`, `θ` from the
    /// downward vertical, `φ` the azimuth.
    #[lagrange(jacobians)]
    pub struct SphericalPendulum {
        coordinates: theta, phi;
        parameters: m, l, g;
        kinetic: m*l^2/2*(dot(theta)^2 + sin(theta)^2*dot(phi)^2);
        potential: -m*g*l*cos(theta);
    }
}

const G: f64 = 9.81;
const THETA0: f64 = 1.0;
/// Adaptive methods' tolerance.
const TOL: f64 = 1e-10;
/// Fixed-step methods' step.
const H: f64 = 1e-3;

fn model() -> SphericalPendulum {
    SphericalPendulum::new(1.0, 1.0, G)
}

/// Every 0.05 s for 2 s: through the pole region at 0.535 s and 1.60 s.
fn sample_times() -> Vec<f64> {
    (1..=40).map(|k| 0.05 * k as f64).collect()
}

/// Released at rest from `θ0 = 1` with azimuthal rate `φ̇0`.
fn start(phi_rate: f64) -> (Vector2<f64>, Vector2<f64>) {
    (Vector2::new(THETA0, 0.0), Vector2::new(0.0, phi_rate))
}

/// `p_φ = m l² sin²θ φ̇` (m = l = 1).
fn azimuthal_momentum(q: &Vector2<f64>, qdot: &Vector2<f64>) -> f64 {
    q[0].sin().powi(2) * qdot[1]
}

/// Where the solve stops: `sin²θ ≤ N ε` with `N = 2`.
fn pole_radius() -> f64 {
    (2.0 * f64::EPSILON).sqrt()
}

/// The planar pendulum released from `θ0`, exact, and `T/4`.
fn planar() -> (impl Fn(f64) -> (f64, f64), f64) {
    elliptic::released_from_rest(G.sqrt(), THETA0)
}

/// The inner turning point: `p²/(2 sin²θ) − g cos θ = E` below `θ0`, by
/// bisection (the left side falls monotonically on `(0, θ0]` down to `E`).
fn closest_approach(p: f64) -> f64 {
    let energy = p * p / (2.0 * THETA0.sin().powi(2)) - G * THETA0.cos();
    let excess = |theta: f64| p * p / (2.0 * theta.sin().powi(2)) - G * theta.cos() - energy;
    let (mut lo, mut hi) = (1e-300f64, THETA0 * (1.0 - 1e-9));
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if excess(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}
