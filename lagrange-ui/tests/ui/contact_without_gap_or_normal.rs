use lagrange::prelude::*;

lagrangian! {
    pub struct Wheel {
        coordinates: theta;
        parameters: j, r, mu;
        kinetic: j/2*dot(theta)^2;
        potential: 0;
        contacts: brake: { friction: mu, slip: r*dot(theta) };
    }
}

fn main() {
    let _ = Wheel::<f64>::CONTACTS;
}
