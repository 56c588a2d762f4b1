use lagrange::prelude::*;

lagrangian! {
    pub struct Particle {
        coordinates: x, y, z;
        parameters: m;
        let r = vector(x, y, z);
        kinetic: m/2*dot(r)*dot(r);
        potential: 0;
    }
}

fn main() {
    let _ = Particle::<f64>::DOF;
}
