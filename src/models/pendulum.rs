//! The simple pendulum: the separatrix, the limits of the double pendulum at
//! extreme mass ratios, and the variational integrator's first test.

use crate::lagrangian;

lagrangian! {
    /// The simple pendulum, `θ` from the downward vertical.
    #[lagrange(jacobians)]
    pub struct Pendulum {
        coordinates: theta;
        parameters: m, l, g;
        kinetic: m*l^2/2*dot(theta)^2;
        potential: -m*g*l*cos(theta);
    }
}
