use lagrange::prelude::*;

lagrangian! {
    pub struct Pendulum {
        coordinates: theta;
        parameters: m, l, g;
        let l = 2*g;
        kinetic: m/2*l^2*dot(theta)^2;
        potential: -m*g*l*cos(theta);
    }
}

fn main() {}
