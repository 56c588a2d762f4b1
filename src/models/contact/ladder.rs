//! A ladder sliding down a frictionless wall and floor.

use crate::lagrangian;

lagrangian! {
    /// A uniform ladder of mass `m` and length `l` (its moment of inertia
    /// `m l²/12` about its centre) between a frictionless wall (`x = 0`)
    /// and floor (`y = 0`), in the coordinates of its centre `(x, y)` and
    /// its angle `theta` from the floor: its top `(x − l/2 cos θ, y + l/2
    /// sin θ)` against the wall, its foot `(x + l/2 cos θ, y − l/2 sin θ)`
    /// on the floor.
    pub struct Ladder {
        coordinates: x, y, theta;
        parameters: m, l, g;
        let top_x = x - l/2*cos(theta);
        let foot_y = y - l/2*sin(theta);
        kinetic: m/2*(dot(x)^2 + dot(y)^2) + m*l^2/24*dot(theta)^2;
        potential: m*g*y;
        contacts: wall: top_x >= 0, floor: foot_y >= 0;
    }
}

impl Ladder<f64> {
    /// At rest at angle `theta0` from the floor, touching both.
    pub fn at_rest(&self, theta0: f64) -> ([f64; 3], [f64; 3]) {
        let h = self.l / 2.0;
        ([h * theta0.cos(), h * theta0.sin(), theta0], [0.0; 3])
    }

    /// The angle at which a ladder released from rest at `theta0` leaves
    /// the wall: its top at 2/3 of its initial height, `sin θ = (2/3) sin
    /// θ₀` (the centre moves on a circle of radius `l/2` about the corner
    /// until the wall's force vanishes).
    pub fn release_angle(theta0: f64) -> f64 {
        (2.0 / 3.0 * theta0.sin()).asin()
    }
}
