//! A ball thrown sliding onto a table: friction slows it and spins it up
//! until it rolls.

use crate::lagrangian;

lagrangian! {
    /// A uniform solid ball of mass `m` and radius `r` (moment of inertia
    /// `2/5 m r²`) on a table with friction `mu`, in the plane of its
    /// motion: its centre `(x, y)` and its angle `phi` (counterclockwise).
    /// Its contact point slips at `ẋ + r φ̇`.
    pub struct SlidingBall {
        coordinates: x, y, phi;
        parameters: m, r, g, mu;
        kinetic: m/2*(dot(x)^2 + dot(y)^2) + m*r^2/5*dot(phi)^2;
        potential: m*g*y;
        contacts: table: y >= r { friction: mu, slip: dot(x) + r*dot(phi) };
    }
}

impl SlidingBall<f64> {
    /// On the table, sliding at `v0` without spin.
    pub fn thrown(&self, v0: f64) -> ([f64; 3], [f64; 3]) {
        ([0.0, self.r, 0.0], [v0, 0.0, 0.0])
    }

    /// When a ball thrown sliding at `v0` without spin starts to roll:
    /// `t = 2 v₀ / (7 μ g)` (friction `μ m g` decelerates it by `μ g` and
    /// spins it up by `5 μ g / (2 r)`, so its slip falls at `7 μ g / 2`).
    pub fn rolling_time(&self, v0: f64) -> f64 {
        2.0 * v0 / (7.0 * self.mu * self.g)
    }

    /// Its speed from then on: `5 v₀ / 7`.
    pub fn rolling_speed(v0: f64) -> f64 {
        5.0 * v0 / 7.0
    }
}
