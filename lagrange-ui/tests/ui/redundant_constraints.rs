use lagrange::prelude::*;

lagrangian! {
    pub struct Particle {
        coordinates: x, y, z;
        parameters: m;
        kinetic: m/2*(dot(x)^2 + dot(y)^2 + dot(z)^2);
        potential: 0;
        constraints: a: x - y, b: 2*x - 2*y;
    }
}

fn main() {
    let _ = Particle::<f64>::CONSTRAINTS;
}
