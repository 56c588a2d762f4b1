use lagrange::prelude::*;

lagrangian! {
    pub struct Particle {
        coordinates: x, y, z;
        parameters: m, l;
        kinetic: m/2*(dot(x)^2 + dot(y)^2 + dot(z)^2);
        potential: 0;
        constraints: sphere: x^2 + y^2 + z^2 = l^2;
        constraints: sphere: z = 0;
    }
}

fn main() {
    let _ = Particle::<f64>::CONSTRAINTS;
}
