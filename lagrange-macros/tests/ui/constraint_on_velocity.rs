use lagrange::prelude::*;

lagrangian! {
    pub struct RollingDisk {
        coordinates: x, theta;
        parameters: m, r;
        kinetic: m/2*dot(x)^2 + m*r^2/4*dot(theta)^2;
        potential: 0;
        constraints: rolling: dot(x) = r*dot(theta);
    }
}

fn main() {
    let _ = RollingDisk::<f64>::CONSTRAINTS;
}
