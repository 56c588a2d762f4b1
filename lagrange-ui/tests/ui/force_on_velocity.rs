use lagrange::prelude::*;

lagrangian! {
    pub struct Chain {
        coordinates: theta;
        parameters: m, l, g, c;
        let v = l*dot(theta);
        kinetic: m/2*v^2;
        potential: -m*g*l*cos(theta);
        forces: v = -c*v;
    }
}

fn main() {
    let _ = Chain::<f64>::DOF;
}
