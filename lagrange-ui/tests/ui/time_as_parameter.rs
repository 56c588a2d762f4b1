use lagrange::prelude::*;

lagrangian! {
    pub struct Oscillator {
        coordinates: x;
        parameters: m, k, t;
        kinetic: m/2*dot(x)^2;
        potential: k/2*x^2;
    }
}

fn main() {
    let model = Oscillator::new(1.0, 2.0);
    let _ = model.mass_matrix(0.0, &lagrange::nalgebra::Vector1::new(0.0));
}
