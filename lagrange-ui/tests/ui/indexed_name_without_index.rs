use lagrange::prelude::*;

lagrangian! {
    pub struct Chain {
        const N = 3;
        coordinates: theta[N];
        parameters: m, l;
        kinetic: sum(i in 0..N, m/2*l^2*dot(theta)^2);
        potential: 0;
    }
}

fn main() {
    let _ = Chain::<f64>::DOF;
}
