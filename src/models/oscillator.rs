//! The damped harmonic oscillator: the problem with an exact solution for
//! orders, step-size limits and the variational integrator's forces.

use crate::lagrangian;

lagrangian! {
    /// A mass `m` on a spring `k` beside a dashpot `c`: `m ẍ = −k x − c ẋ`,
    /// the harmonic oscillator for `c = 0`. With exact Jacobians.
    #[lagrange(jacobians)]
    pub struct Oscillator {
        coordinates: x;
        parameters: m, k, c;
        kinetic: m/2*dot(x)^2;
        potential: k/2*x^2;
        dissipation: c/2*dot(x)^2;
    }
}

impl Oscillator<f64> {
    /// The exact `(x, ẋ)` at `t` from `(x0, v0)` at 0, for an underdamped
    /// oscillator (`c² < 4 m k`): `x = e^{−γt} (a cos ωt + b sin ωt)` with
    /// `γ = c/2m`, `ω = √(k/m − γ²)`.
    pub fn exact(&self, t: f64, x0: f64, v0: f64) -> (f64, f64) {
        let gamma = self.c / (2.0 * self.m);
        let omega = (self.k / self.m - gamma * gamma).sqrt();
        let (a, b) = (x0, (v0 + gamma * x0) / omega);
        let (s, c) = (omega * t).sin_cos();
        let decay = (-gamma * t).exp();
        let x = decay * (a * c + b * s);
        let v = decay * ((b * omega - gamma * a) * c - (a * omega + gamma * b) * s);
        (x, v)
    }
}
