use lagrange::prelude::*;

lagrangian! {
    pub struct Chain {
        // -2^63 / -1 is 2^63, one more than the largest 64-bit integer.
        const N = -2097152*2097152*2097152/-1;
        coordinates: theta[3];
        parameters: m, l, g;
        kinetic: sum(i in 0..3, m/2*l^2*dot(theta[i])^2);
        potential: 0;
    }
}

fn main() {
    let _ = Chain::new(1.0, 1.0, 9.81);
}
