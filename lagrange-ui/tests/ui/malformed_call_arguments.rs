use lagrange::prelude::*;

lagrangian! {
    pub struct Pendulum {
        coordinates: theta;
        parameters: m, l, g;
        kinetic: m/2*l^2*dot(theta)^2;
        potential: -m*g*l*cos(theta theta);
    }
}

fn main() {
    let model = Pendulum::new(1.0, 1.0, 9.81);
    let _ = model.mass_matrix(0.0, &lagrange::nalgebra::Vector1::new(0.0));
}
