use lagrange::prelude::*;

lagrangian! {
    pub struct Chain {
        coordinates: theta;
        parameters: m, l, g, F;
        let h = 2*l;
        kinetic: m/2*l^2*dot(theta)^2;
        potential: -m*g*l*cos(theta);
        forces: h = F;
    }
}

fn main() {
    let _ = Chain::<f64>::DOF;
}
