//! The double pendulum: the textbook's chaotic system, and the model of the
//! README, the benchmarks and the 25-digit reference in
//! `tests/data/double_pendulum.json`.

use crate::lagrangian;
use nalgebra::{RealField, Vector2};

lagrangian! {
    /// The double pendulum: point masses `m1`, `m2` on massless rods `l1`,
    /// `l2`, angles `theta1`, `theta2` from the downward vertical, gravity `g`.
    /// With exact Jacobians, for the implicit integrators.
    #[lagrange(jacobians)]
    pub struct DoublePendulum {
        coordinates: theta1, theta2;
        parameters: m1, m2, l1, l2, g;
        let x1 = l1*sin(theta1);
        let y1 = -l1*cos(theta1);
        let x2 = x1 + l2*sin(theta2);
        let y2 = y1 - l2*cos(theta2);
        kinetic: m1/2*(dot(x1)^2 + dot(y1)^2) + m2/2*(dot(x2)^2 + dot(y2)^2);
        potential: m1*g*y1 + m2*g*y2;
    }
}

impl DoublePendulum<f64> {
    /// Unit masses and rods, `g = 9.81`: the pendulum of the references and
    /// the benchmarks, chaotic when released at large angles.
    pub fn unit() -> Self {
        Self::new(1.0, 1.0, 1.0, 1.0, 9.81)
    }
}

impl<S: RealField + Copy> DoublePendulum<S> {
    /// The regular motion the integrator tests measure orders on: masses 1
    /// and 0.7, rods 1 and 0.8, released from `θ = (0.6, −0.4)` with
    /// `θ̇ = (0, 0.5)`, about a tenth of the energy it takes to swing the
    /// upper rod over the top: smooth, and not chaotic over ten seconds.
    pub fn regular() -> (Self, Vector2<S>, Vector2<S>) {
        let c = nalgebra::convert::<f64, S>;
        (
            Self::new(c(1.0), c(0.7), c(1.0), c(0.8), c(9.81)),
            Vector2::new(c(0.6), c(-0.4)),
            Vector2::new(c(0.0), c(0.5)),
        )
    }
}
