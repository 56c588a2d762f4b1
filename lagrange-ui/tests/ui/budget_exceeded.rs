use lagrange::prelude::*;

lagrangian! {
    /// A pendulum given a budget far too small for it.
    #[lagrange(budget = 1000)]
    pub struct Pendulum {
        coordinates: theta;
        parameters: m, l, g;
        kinetic: m/2*l^2*dot(theta)^2;
        potential: -m*g*l*cos(theta);
    }
}

fn main() {
    let p = Pendulum::new(1.0, 1.0, 9.81);
    let _ = p.mass_matrix(0.0, &lagrange::nalgebra::Vector1::new(0.1));
}
