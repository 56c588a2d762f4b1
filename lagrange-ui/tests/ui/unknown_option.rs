use lagrange::prelude::*;

lagrangian! {
    #[lagrange(jacobian)]
    pub struct Oscillator {
        coordinates: x;
        parameters: m, k;
        kinetic: m/2*dot(x)^2;
        potential: k/2*x^2;
    }
}

fn main() {
    let _ = Oscillator::new(1.0, 1.0).mass_matrix(0.0, &lagrange::nalgebra::Vector1::new(0.0));
}
