use lagrange::prelude::*;

lagrangian! {
    pub struct Free {
        coordinates: x;
        parameters: m;
        kinetic: m/2*dot(x)^2;
    }
}

fn main() {
    let model = Free::new(1.0);
    let _ = model.mass_matrix(0.0, &lagrange::nalgebra::Vector1::new(0.0));
}
