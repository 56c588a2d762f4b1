use lagrange::prelude::*;

lagrangian! {
    pub struct Spring {
        coordinates: x;
        parameters: m, e in [1, 0];
        kinetic: m/2*dot(x)^2;
        potential: e*x^2;
    }
}

fn main() {
    let _ = Spring::new(1.0, 0.5);
}
