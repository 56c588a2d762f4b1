//! Numerical stability at the extremes: Kepler orbits of eccentricity 0.6
//! and 0.9 over up to 10⁴ periods with a fixed step. Over runs this long the
//! methods part ways not by order but by kind: the energy error of the
//! symplectic and symmetric methods stays bounded, RK4's drifts linearly,
//! explicit Euler's runs away; and the angular momentum `x ẏ − y ẋ`, a
//! quadratic invariant in Cartesian coordinates, is kept to round-off by the
//! Gauss methods and lost at the truncation error by RK4.
//!
//! **How growth is measured.** The energy error of a symplectic method
//! oscillates along the orbit with a sharp peak at pericentre (at e = 0.9 a
//! pericentre passage takes about 1/300 of the period). Every step is
//! sampled and each orbit keeps its worst error; windows of doubling length
//! (orbit 1, 2, 3–4, 5–8, …, the last cut at the run's end) keep the worst of
//! their orbits, and the least-squares slope of log(worst) against log(end of
//! window) is the *growth exponent*: 0 for a bounded error, 1 for linear
//! drift, ½ for a random walk. Sampling once per orbit at a slowly sliding
//! phase would read the oscillation as growth.
//!
//! Each orbit is one `integrate` call sampling every step, started from the
//! previous orbit's last sample, so memory holds one orbit. Restarting is
//! exact for the one-step methods, whose state is `(q, q̇)`; `Variational`
//! converts `q̇ ↔ p` at each restart, exact for `M = I` and one rounding per
//! orbit in polar coordinates, far below its `O(h²)` energy error.
//!
//! The figures (for STABILITY.md):
//! `cargo test --release --test suite -- extremes::kepler:: --nocapture` (a few
//! seconds). The full 10⁴-period runs are ignored in CI (about two minutes
//! on two cores):
//! `cargo test --release --test suite -- extremes::kepler:: --ignored --nocapture`.
//!
//! The measurement is in `flight.rs`, what each kind of method must show
//! in `bounds.rs`; the orbits in `e06.rs` and `e09.rs`.

use std::f64::consts::PI;

use lagrange::models::{Kepler, PolarKepler};
use lagrange::nalgebra::Vector2;

mod bounds;
mod e06;
mod e09;
mod flight;

/// The period of every orbit here: semi-major axis 1, μ = 1.
const PERIOD: f64 = 2.0 * PI;
const EPS: f64 = f64::EPSILON;

type V2 = Vector2<f64>;

/// Start at pericentre of the orbit of eccentricity `e`.
fn cartesian_start(e: f64) -> (V2, V2) {
    Kepler::new(1.0).pericentre(e)
}

fn polar_start(e: f64) -> (V2, V2) {
    PolarKepler::new(1.0).pericentre(e)
}

fn cartesian_angular_momentum(q: &V2, v: &V2) -> f64 {
    Kepler::angular_momentum(q, v)
}

fn polar_angular_momentum(q: &V2, v: &V2) -> f64 {
    PolarKepler::angular_momentum(q, v)
}
