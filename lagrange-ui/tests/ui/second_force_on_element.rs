use lagrange::prelude::*;

lagrangian! {
    pub struct Chain {
        const N = 2;
        coordinates: theta[N];
        parameters: m, l, F;
        let x[i in 0..N] = sum(j in 0..=i, l*sin(theta[j]));
        kinetic: sum(i in 0..N, m/2*l^2*dot(theta[i])^2);
        potential: 0;
        forces: x[1] = F, x[N-1] = -F;
    }
}

fn main() {
    let _ = Chain::<f64>::DOF;
}
