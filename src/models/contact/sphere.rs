//! A particle sliding off a frictionless sphere.

use crate::lagrangian;

lagrangian! {
    /// A particle of mass `m` on the outside of a frictionless sphere of
    /// radius `r` centred at the origin (its great circle in the vertical
    /// plane), in Cartesian coordinates `(x, y)`, `y` up, under gravity
    /// `g`. The gap is the distance from the surface, so the normal force
    /// is in newtons.
    pub struct ParticleOnSphere {
        coordinates: x, y;
        parameters: m, g, r;
        kinetic: m/2*(dot(x)^2 + dot(y)^2);
        potential: m*g*y;
        contacts: sphere: sqrt(x^2 + y^2) >= r;
    }
}

impl ParticleOnSphere<f64> {
    /// The angle from the top where a particle released from rest at
    /// `theta0` leaves the sphere: `cos θ = (2/3) cos θ₀` (the normal force
    /// `m (g cos θ − v²/r)` vanishes, with `v² = 2 g r (cos θ₀ − cos θ)`).
    pub fn release_angle(theta0: f64) -> f64 {
        (2.0 / 3.0 * theta0.cos()).acos()
    }

    /// The state at rest on the sphere at angle `theta` from the top.
    pub fn at_rest(&self, theta: f64) -> ([f64; 2], [f64; 2]) {
        ([self.r * theta.sin(), self.r * theta.cos()], [0.0, 0.0])
    }
}
