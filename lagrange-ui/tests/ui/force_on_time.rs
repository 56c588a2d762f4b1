use lagrange::prelude::*;

lagrangian! {
    pub struct Chain {
        coordinates: x;
        parameters: m, F;
        kinetic: m/2*dot(x)^2;
        potential: 0;
        forces: t = F;
    }
}

fn main() {
    let _ = Chain::<f64>::DOF;
}
