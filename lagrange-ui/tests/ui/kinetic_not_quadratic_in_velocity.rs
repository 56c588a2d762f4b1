use lagrange::prelude::*;

lagrangian! {
    pub struct Quartic {
        coordinates: x, y;
        parameters: m, k;
        kinetic: m/2*dot(y)^2 + m/4*dot(x)^4;
        potential: k/2*(x^2 + y^2);
    }
}

fn main() {
    let model = Quartic::new(1.0, 2.0);
    let _ = model.mass_matrix(0.0, &lagrange::nalgebra::Vector2::new(0.0, 0.0));
}
