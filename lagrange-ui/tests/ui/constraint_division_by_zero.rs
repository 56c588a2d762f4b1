use lagrange::prelude::*;

lagrangian! {
    pub struct Pendulum {
        coordinates: x, y;
        parameters: m, l, g;
        constants: a = 0;
        kinetic: m/2*(dot(x)^2 + dot(y)^2);
        potential: m*g*y;
        constraints: rod: x^2 + y^2 = l^2/a;
    }
}

fn main() {
    let _ = Pendulum::<f64>::CONSTRAINTS;
}
