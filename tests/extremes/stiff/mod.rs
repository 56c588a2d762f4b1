//! Numerical stability at the extremes: a stiff spring chain, stiffness
//! ratio 10⁶ and 10⁸.
//!
//! Two unit masses between walls on soft springs (`k1 = 2`, `k2 = 1`), joined
//! by a spring `kc = ratio · k2`. The slow mode (ω ≈ 1.22, the masses moving
//! together) is the motion of interest; the fast one (ω ≈ √(2 kc): 1414 and
//! 14 142) is the stiff spring ringing. No damping, so that what each
//! method does to the fast mode (keep, damp or alias it) shows against an
//! exact solution that keeps it. Every method here is a (partitioned)
//! Runge–Kutta method, the variational one included (on this model it is
//! the implicit midpoint rule), and those commute with linear changes of
//! variables: each advances each mode separately by its stability function,
//! `z ↦ R(i ω h) z` for the modal amplitude `z = η̇ + i ω η`. So a two-mode
//! chain shows all there is, and the exact solution is the modal one, in
//! closed form.
//!
//! Every test prints its figures; `cargo test --release --test suite --
//! extremes::stiff:: --nocapture --test-threads=1` shows them in order.
//!
//! The exact solution is in `modes.rs`; the scenarios by kind of method:
//! `explicit.rs`, `radau5.rs`, `symmetric.rs`.

use lagrange::nalgebra::Complex;
use lagrange::prelude::*;

mod explicit;
mod modes;
mod radau5;
mod symmetric;

lagrangian! {
    /// Two unit masses between walls, on soft springs `k1` and `k2`, joined
    /// by a stiff spring `kc`.
    #[lagrange(jacobians)]
    pub struct StiffPair {
        coordinates: x1, x2;
        parameters: k1, k2, kc;
        kinetic: (dot(x1)^2 + dot(x2)^2)/2;
        potential: k1/2*x1^2 + kc/2*(x2 - x1)^2 + k2/2*x2^2;
    }
}

/// The stiffness ratios of the scenario.
const RATIOS: [f64; 2] = [1e6, 1e8];
/// Time span: two slow periods.
const T: f64 = 10.0;
const EPS: f64 = f64::EPSILON;

fn chain(ratio: f64) -> StiffPair {
    StiffPair::new(2.0, 1.0, ratio)
}

/// Every 0.5 up to `T`.
fn samples() -> Vec<f64> {
    (1..=20).map(|k| 0.5 * k as f64).collect()
}

type C = Complex<f64>;

fn ratio_name(ratio: f64) -> &'static str {
    if ratio == 1e6 { "1e6" } else { "1e8" }
}
