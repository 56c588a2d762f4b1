//! A block on a moving belt held by a spring: stick–slip.

use crate::lagrangian;

lagrangian! {
    /// A block of mass `m` on a belt moving at `v`, held back by a spring
    /// of stiffness `k` (rest at `x = 0`), under gravity `g`; static
    /// friction `mus` above kinetic `muk`. It rides with the belt until
    /// the spring outpulls static friction, slips back, and sticks again.
    pub struct BlockOnBelt {
        coordinates: x, y;
        parameters: m, g, k, v, mus, muk;
        kinetic: m/2*(dot(x)^2 + dot(y)^2);
        potential: k/2*x^2 + m*g*y;
        contacts: belt: y >= 0 { static_friction: mus, kinetic_friction: muk, slip: dot(x) - v };
    }
}

/// The stick–slip cycle of [`BlockOnBelt`] in closed form.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StickSlip {
    /// Where it slips: `x₁ = μ_s m g / k`.
    pub slips_at: f64,
    /// Where it sticks again: `x₂ = (2 μ_k − μ_s) m g / k`, as far below
    /// the kinetic balance point `μ_k m g / k` as `x₁` is above it.
    pub sticks_at: f64,
    /// How long it slips: `(2π − 2δ)/ω`, `ω = √(k/m)`, `tan δ = A ω / v`,
    /// `A = x₁ − μ_k m g / k`.
    pub slip_duration: f64,
    /// How long it rides with the belt from `x₂` to `x₁`: `(x₁ − x₂)/v`.
    pub stick_duration: f64,
}

impl BlockOnBelt<f64> {
    /// The cycle (see [`StickSlip`]): harmonic about `μ_k m g / k` while it
    /// slips (the friction `μ_k m g` pulls it along the belt), from the
    /// belt's speed back to it.
    pub fn cycle(&self) -> StickSlip {
        let (weight, omega) = (self.m * self.g, (self.k / self.m).sqrt());
        let slips_at = self.mus * weight / self.k;
        let balance = self.muk * weight / self.k;
        let a = slips_at - balance;
        let delta = (a * omega).atan2(self.v);
        StickSlip {
            slips_at,
            sticks_at: balance - a,
            slip_duration: (2.0 * core::f64::consts::PI - 2.0 * delta) / omega,
            stick_duration: 2.0 * a / self.v,
        }
    }
}
