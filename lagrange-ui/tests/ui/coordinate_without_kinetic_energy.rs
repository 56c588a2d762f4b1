use lagrange::prelude::*;

lagrangian! {
    pub struct Springs {
        coordinates: x, y;
        parameters: m, k;
        kinetic: m/2*dot(x)^2;
        potential: k/2*x^2 + k/2*(y - x)^2;
    }
}

fn main() {
    let model = Springs::new(1.0, 2.0);
    let _ = model.mass_matrix(0.0, &lagrange::nalgebra::Vector2::new(0.0, 0.0));
}
