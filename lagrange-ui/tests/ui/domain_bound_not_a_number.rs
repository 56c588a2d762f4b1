use lagrange::prelude::*;

lagrangian! {
    pub struct Pendulum {
        coordinates: theta;
        parameters: m > 0, l > m;
        constants: g = 9.81;
        kinetic: m/2*l^2*dot(theta)^2;
        potential: -m*g*l*cos(theta);
    }
}

fn main() {
    let _ = Pendulum::new(1.0, 0.5);
}
