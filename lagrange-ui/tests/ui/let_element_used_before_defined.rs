use lagrange::prelude::*;

lagrangian! {
    pub struct Chain {
        const N = 3;
        coordinates: theta[N];
        parameters: m, l, g;
        let y[i in 0..N] = y[i+1] - l*cos(theta[i]);
        kinetic: sum(i in 0..N, m/2*l^2*dot(theta[i])^2);
        potential: m*g*y[0];
    }
}

fn main() {
    let _ = Chain::<f64>::DOF;
}
