use lagrange::prelude::*;

lagrangian! {
    pub struct Infinite {
        coordinates: x;
        parameters: m, k;
        kinetic: m/2*dot(x)^2/0;
        potential: k/2*x^2;
    }
}

fn main() {
    let s = Infinite::new(1.0, 2.0);
    let _ = s.mass_matrix(0.0, &lagrange::nalgebra::Vector1::new(0.0));
}
