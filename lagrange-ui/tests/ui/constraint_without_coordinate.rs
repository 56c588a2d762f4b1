use lagrange::prelude::*;

lagrangian! {
    pub struct Pendulum {
        coordinates: x, y;
        parameters: m, l, g;
        kinetic: m/2*(dot(x)^2 + dot(y)^2);
        potential: m*g*y;
        constraints: rod: l - 1;
    }
}

fn main() {
    let _ = Pendulum::<f64>::CONSTRAINTS;
}
