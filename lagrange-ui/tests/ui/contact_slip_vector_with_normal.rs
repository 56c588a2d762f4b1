use lagrange::prelude::*;

lagrangian! {
    pub struct Braked {
        coordinates: x, y;
        parameters: m, f, mu;
        kinetic: m/2*(dot(x)^2 + dot(y)^2);
        potential: 0;
        contacts: brake: { normal: f, friction: mu, slip: vector(dot(x), dot(y)) };
    }
}

fn main() {
    let _ = Braked::<f64>::CONTACTS;
}
