use lagrange::prelude::*;

lagrangian! {
    pub struct Chain {
        coordinates: theta;
        parameters: m, l;
        constants: g = 9.81*m;
        kinetic: m/2*l^2*dot(theta)^2;
        potential: -m*g*l*cos(theta);
    }
}

fn main() {
    let _ = Chain::<f64>::DOF;
}
