use lagrange::prelude::*;

lagrangian! {
    pub struct Rigid {
        coordinates: x, y;
        parameters: m, k;
        kinetic: m/2*(dot(x) + dot(y))^2;
        potential: k/2*(x^2 + y^2);
    }
}

fn main() {
    let model = Rigid::new(1.0, 2.0);
    let _ = model.mass_matrix(0.0, &lagrange::nalgebra::Vector2::new(0.0, 0.0));
}
