use lagrange::prelude::*;

lagrangian! {
    pub struct Plane {
        coordinates: x, y, x;
        parameters: m;
        kinetic: m/2*(dot(x)^2 + dot(y)^2);
        potential: 0;
    }
}

fn main() {
    let model = Plane::new(1.0);
    let _ = model.mass_matrix(0.0, &lagrange::nalgebra::Vector2::new(0.0, 0.0));
}
