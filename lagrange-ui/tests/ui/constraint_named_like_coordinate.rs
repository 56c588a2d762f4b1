use lagrange::prelude::*;

lagrangian! {
    pub struct Pendulum {
        coordinates: x, y;
        parameters: m, l, g;
        kinetic: m/2*(dot(x)^2 + dot(y)^2);
        potential: m*g*y;
        constraints: y: x^2 + y^2 = l^2;
    }
}

fn main() {
    let _ = Pendulum::<f64>::CONSTRAINTS;
}
