use lagrange::prelude::*;

lagrangian! {
    #[lagrange(max_code = 0)]
    pub struct Pendulum {
        coordinates: theta;
        parameters: m, l, g;
        kinetic: m/2*l^2*dot(theta)^2;
        potential: -m*g*l*cos(theta);
    }
}

fn main() {
    let _ = Pendulum::new(1.0, 1.0, 9.81);
}
