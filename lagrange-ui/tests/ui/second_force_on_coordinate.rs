use lagrange::prelude::*;

lagrangian! {
    pub struct Driven {
        coordinates: x;
        parameters: m, k, c, f;
        kinetic: m/2*dot(x)^2;
        potential: k/2*x^2;
        forces: x = -c*dot(x), x = f*cos(t);
    }
}

fn main() {
    let model = Driven::new(1.0, 2.0, 0.1, 0.5);
    let _ = model.mass_matrix(0.0, &lagrange::nalgebra::Vector1::new(0.0));
}
