//! A block on an incline: it stays put below the friction angle and slides
//! above it.

use crate::lagrangian;

lagrangian! {
    /// A block of mass `m` on a plane inclined at `alpha`, in the plane's
    /// axes: `x` down the slope, `y` off the plane, under gravity `g`;
    /// static friction `mus`, kinetic friction `muk`.
    pub struct BlockOnIncline {
        coordinates: x, y;
        parameters: m, g, alpha, mus, muk;
        kinetic: m/2*(dot(x)^2 + dot(y)^2);
        potential: m*g*(y*cos(alpha) - x*sin(alpha));
        contacts: plane: y >= 0 { static_friction: mus, kinetic_friction: muk, slip: dot(x) };
    }
}

impl BlockOnIncline<f64> {
    /// Whether a block at rest stays put: `tan α ≤ μ_s`.
    pub fn holds(&self) -> bool {
        self.alpha.tan() <= self.mus
    }

    /// The acceleration down the slope while it slides down: `g (sin α −
    /// μ_k cos α)`.
    pub fn sliding_acceleration(&self) -> f64 {
        self.g * (self.alpha.sin() - self.muk * self.alpha.cos())
    }
}
