//! The double pendulum with a damper in each joint, written for parameters
//! from data: every parameter (masses, lengths, gravity, damping) enters
//! `M` or `f`, and the model carries its exact Jacobians, its parameter
//! derivatives and its regressor in the masses and dampers. The model of
//! the sensitivity and identification tests and of the `identify` example.

use crate::lagrangian;

lagrangian! {
    /// A double pendulum with a damper in each joint: point masses `m1`,
    /// `m2` on massless rods `l1`, `l2`, angles from the downward vertical,
    /// gravity `g`, a damper `c1` at the pivot and `c2` between the rods;
    /// masses and lengths positive, dampers not negative.
    /// With its exact Jacobians (`#[lagrange(jacobians)]`), its parameter
    /// derivatives and its regressor in the masses and dampers (the lengths
    /// and `g` known).
    #[lagrange(jacobians, parameter_derivatives, regressor(m1, m2, c1, c2))]
    pub struct DampedDoublePendulum {
        coordinates: theta1, theta2;
        parameters: m1 > 0, m2 > 0, l1 > 0, l2 > 0, g, c1 >= 0, c2 >= 0;
        let x1 = l1*sin(theta1);
        let y1 = -l1*cos(theta1);
        let x2 = x1 + l2*sin(theta2);
        let y2 = y1 - l2*cos(theta2);
        kinetic: m1/2*(dot(x1)^2 + dot(y1)^2) + m2/2*(dot(x2)^2 + dot(y2)^2);
        potential: m1*g*y1 + m2*g*y2;
        dissipation: c1/2*dot(theta1)^2 + c2/2*(dot(theta2) - dot(theta1))^2;
    }
}
