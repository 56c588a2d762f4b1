use lagrange::prelude::*;

lagrangian! {
    pub struct Damped {
        coordinates: x;
        parameters: m, k, c;
        kinetic: m/2*dot(x)^2;
        potential: k/2*x^2 + c*x*dot(x);
    }
}

fn main() {
    let model = Damped::new(1.0, 2.0, 0.1);
    let _ = model.mass_matrix(0.0, &lagrange::nalgebra::Vector1::new(0.0));
}
