use lagrange::prelude::*;

lagrangian! {
    pub struct Spring {
        coordinates: x > 0;
        parameters: m, k;
        kinetic: m/2*dot(x)^2;
        potential: k/2*x^2;
    }
}

fn main() {}
