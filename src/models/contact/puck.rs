//! A puck pushed across a rough table: friction in the table's plane, a
//! disc of forces, that holds it until the push leaves the disc.

use crate::lagrangian;

lagrangian! {
    /// A puck of mass `m` on a rough table (`mu`), its slip the vector of
    /// its velocity along the table, pushed along the direction at angle
    /// `a` from the x axis by `P = p0 + rate t`.
    pub struct PushedPuck {
        coordinates: x, y, z;
        parameters: m, g, mu, a, p0, rate;
        kinetic: m/2*(dot(x)^2 + dot(y)^2 + dot(z)^2);
        potential: m*g*z;
        forces: x = (p0 + rate*t)*cos(a), y = (p0 + rate*t)*sin(a);
        contacts: table: z >= 0 { friction: mu, slip: vector(dot(x), dot(y)) };
    }
}

impl PushedPuck<f64> {
    /// When it breaks away, pushed from rest: where the push reaches the
    /// disc of friction, `t_b = (μ m g − p0)/rate`, in any direction.
    pub fn breakaway(&self) -> f64 {
        (self.mu * self.m * self.g - self.p0) / self.rate
    }

    /// How far it has slid along the push by `t`: `rate (t − t_b)³ /
    /// (6 m)` after the breakaway (the push's excess over sliding friction
    /// `μ m g` grows at `rate`), nothing before.
    pub fn slid(&self, t: f64) -> f64 {
        let s = (t - self.breakaway()).max(0.0);
        self.rate * s.powi(3) / (6.0 * self.m)
    }
}
