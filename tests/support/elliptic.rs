//! Jacobi elliptic functions and the complete elliptic integral `K`, for the
//! exact pendulum: the arithmetic–geometric mean and the descending Landen
//! transformation (Abramowitz & Stegun 16.4, 17.6), about 20 lines, good to
//! ~1e-14 even a millionth from the separatrix (checked against 30-digit
//! mpmath values in `tests/extremes/separatrix.rs`).
//!
//! Written here rather than taken from a crate: the maintained Rust crates
//! for elliptic integrals do not provide the amplitude `am(u | m)` that a
//! rotating pendulum needs, and all of them take the parameter `m = k²`,
//! whose complement `1 − m` loses the digits that matter near `m = 1`. Here
//! the complementary modulus `k' = √(1 − m)` is an input, computed by the
//! caller without cancellation.

use std::f64::consts::PI;

/// `am`, `sn`, `cn`, `dn` at one argument, and `K` of the modulus.
#[derive(Debug, Clone, Copy)]
pub struct Jacobi {
    pub am: f64,
    pub sn: f64,
    pub cn: f64,
    pub dn: f64,
    /// The complete elliptic integral of the first kind, `K(k)`.
    pub k_complete: f64,
}

/// The Jacobi functions of `u` for modulus `k` (`0 ≤ k < 1`) given with its
/// complement `kp = √(1 − k²)` (pass it accurately: near `k = 1` it carries
/// all the information).
///
/// AGM: `a₀ = 1, b₀ = k', c₀ = k`, `a_{n+1} = (a_n + b_n)/2`,
/// `b_{n+1} = √(a_n b_n)`, `c_{n+1} = c_n² / (4 a_{n+1})` (the form without
/// cancellation), until `c_N < ε a_N`; then `K = π / (2 a_N)`,
/// `φ_N = 2^N a_N u` and `φ_{n−1} = (φ_n + asin(c_n/a_n sin φ_n)) / 2`,
/// `am = φ₀`, which is continuous in `u` (no branch to unwrap for a
/// rotation). `dn = √(k'² + k² cn²)` keeps its absolute accuracy where it is
/// small (a pendulum near the top).
pub fn jacobi(u: f64, k: f64, kp: f64) -> Jacobi {
    let (mut a, mut b, mut c) = (1.0f64, kp, k);
    let mut ratios = [0.0f64; 40];
    let mut n = 0;
    while c > f64::EPSILON * a {
        let a_next = 0.5 * (a + b);
        b = (a * b).sqrt();
        c = c * c / (4.0 * a_next);
        a = a_next;
        n += 1;
        ratios[n] = c / a;
    }
    let mut phi = 2f64.powi(n as i32) * a * u;
    for ratio in ratios[1..=n].iter().rev() {
        phi = 0.5 * (phi + (ratio * phi.sin()).asin());
    }
    let (sn, cn) = phi.sin_cos();
    Jacobi {
        am: phi,
        sn,
        cn,
        dn: (kp * kp + k * k * cn * cn).sqrt(),
        k_complete: PI / (2.0 * a),
    }
}

/// `K(k)`, the quarter period of `sn`.
pub fn complete_k(k: f64, kp: f64) -> f64 {
    jacobi(0.0, k, kp).k_complete
}

/// A pendulum `θ̈ = −ω₀² sin θ` started at `θ = 0` with `θ̇ = 2 ω₀ κ`: a
/// libration for `κ < 1`, a rotation for `κ > 1`. `κ` is the modulus of the
/// libration (`sin(θ_max/2) = κ`); the energy above the bottom is
/// `2 κ²` in units of `m g l`, the separatrix at `κ = 1`.
#[derive(Debug, Clone, Copy)]
pub struct Swing {
    pub omega0: f64,
    pub kappa: f64,
}

impl Swing {
    /// The modulus of the elliptic functions and its complement, computed
    /// from `κ` without cancellation: `1 − κ` and `κ − 1` are exact in
    /// floating point near 1.
    fn moduli(&self) -> (f64, f64) {
        let kappa = self.kappa;
        if kappa < 1.0 {
            (kappa, ((1.0 - kappa) * (1.0 + kappa)).sqrt())
        } else {
            (1.0 / kappa, ((kappa - 1.0) * (kappa + 1.0)).sqrt() / kappa)
        }
    }

    /// `(θ, θ̇)` at `t`: `θ = 2 atan2(κ sn, dn)` and `θ̇ = 2 ω₀ κ cn` at
    /// `u = ω₀ t` for a libration (the `atan2` form is accurate near the top,
    /// where `asin(κ sn)` is not); `θ = 2 am`, `θ̇ = 2 ω₀ κ dn` at `u = κ ω₀ t`
    /// with modulus `1/κ` for a rotation.
    pub fn state(&self, t: f64) -> (f64, f64) {
        let (k, kp) = self.moduli();
        if self.kappa < 1.0 {
            let j = jacobi(self.omega0 * t, k, kp);
            (
                2.0 * (self.kappa * j.sn).atan2(j.dn),
                2.0 * self.omega0 * self.kappa * j.cn,
            )
        } else {
            let j = jacobi(self.kappa * self.omega0 * t, k, kp);
            (2.0 * j.am, 2.0 * self.omega0 * self.kappa * j.dn)
        }
    }

    /// The time from the bottom to the top (rotation) or to the turning
    /// point (libration): `K/ω₀`, or `K/(κ ω₀)` with modulus `1/κ`.
    pub fn quarter(&self) -> f64 {
        let (k, kp) = self.moduli();
        let big_k = complete_k(k, kp);
        if self.kappa < 1.0 {
            big_k / self.omega0
        } else {
            big_k / (self.kappa * self.omega0)
        }
    }
}

/// The planar pendulum released from rest at `θ0 ∈ (0, π)`: the swing
/// through the bottom with `κ = sin(θ0/2)`, run backwards from its turning
/// point, `θ(t) = θ_swing(K/ω₀ − t)`, `θ̇(t) = −θ̇_swing(K/ω₀ − t)`. Returns
/// `(θ, θ̇)` as a function of `t` and the time of the first pass through
/// the bottom, `K/ω₀`.
pub fn released_from_rest(omega0: f64, theta0: f64) -> (impl Fn(f64) -> (f64, f64), f64) {
    let swing = Swing {
        omega0,
        kappa: (0.5 * theta0).sin(),
    };
    let quarter = swing.quarter();
    let state = move |t: f64| {
        let (theta, rate) = swing.state(quarter - t);
        (theta, -rate)
    };
    (state, quarter)
}
