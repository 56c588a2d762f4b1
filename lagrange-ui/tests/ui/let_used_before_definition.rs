use lagrange::prelude::*;

lagrangian! {
    pub struct Pendulum {
        coordinates: theta;
        parameters: m, l, g;
        let y = -l*c;
        let c = cos(theta);
        kinetic: m/2*l^2*dot(theta)^2;
        potential: m*g*y;
    }
}

fn main() {}
