use lagrange::prelude::*;

lagrangian! {
    pub struct Clock {
        coordinates: x, t;
        parameters: m;
        kinetic: m/2*dot(x)^2;
        potential: 0;
    }
}

fn main() {
    let model = Clock::new(1.0);
    let _ = model.mass_matrix(0.0, &lagrange::nalgebra::Vector1::new(0.0));
}
