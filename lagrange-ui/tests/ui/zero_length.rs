use lagrange::prelude::*;

lagrangian! {
    pub struct Chain {
        const N = 0;
        coordinates: x, theta[N];
        parameters: m;
        kinetic: m/2*dot(x)^2;
        potential: 0;
    }
}

fn main() {
    let _ = Chain::<f64>::DOF;
}
