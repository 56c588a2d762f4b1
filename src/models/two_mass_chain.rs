//! The damped two-mass chain of the textbook, the model of the 25-digit
//! reference in `tests/data/damped_two_mass_spring.json`, with its dampers
//! written as forces and as a Rayleigh dissipation function.

use crate::lagrangian;

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

lagrangian! {
    /// The same chain with its dampers written as a Rayleigh dissipation
    /// function, `R = c1/2 ẋ1² + c2/2 (ẋ2 − ẋ1)² + c3/2 ẋ2²`, instead of
    /// forces: the same equations of motion.
    pub struct RayleighTwoMassChain {
        coordinates: x1, x2;
        parameters: m1, m2, k1, k2, k3, c1, c2, c3;
        kinetic: m1/2*dot(x1)^2 + m2/2*dot(x2)^2;
        potential: k1/2*x1^2 + k2/2*(x2 - x1)^2 + k3/2*x2^2;
        dissipation: c1/2*dot(x1)^2 + c2/2*(dot(x2) - dot(x1))^2 + c3/2*dot(x2)^2;
    }
}
