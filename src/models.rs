//! The textbook's two worked examples, ready to use: shared by the tests,
//! the benchmarks and anyone who wants a known model to try an integrator on.
//! Each is nothing but a `lagrangian!` invocation; read the source.

use crate::lagrangian;

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

lagrangian! {
    /// The damped two-mass chain: wall – k1 – m1 – k2 – m2 – k3 – wall, with
    /// dampers c1, c2, c3 beside the springs, their forces written as
    /// generalized forces (the textbook's `Q`). With exact Jacobians.
    #[lagrange(jacobians)]
    pub struct TwoMassChain {
        coordinates: x1, x2;
        parameters: m1, m2, k1, k2, k3, c1, c2, c3;
        kinetic: m1/2*dot(x1)^2 + m2/2*dot(x2)^2;
        potential: k1/2*x1^2 + k2/2*(x2 - x1)^2 + k3/2*x2^2;
        forces: x1 = -(c1 + c2)*dot(x1) + c2*dot(x2),
                x2 = c2*dot(x1) - (c2 + c3)*dot(x2);
    }
}
