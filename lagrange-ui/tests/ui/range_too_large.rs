use lagrange::prelude::*;

lagrangian! {
    pub struct Chain {
        coordinates: x;
        parameters: m;
        kinetic: m/2*dot(x)^2 + sum(i in 0..1000000, 0*x);
        potential: 0;
    }
}

fn main() {
    let _ = Chain::<f64>::DOF;
}
