use lagrange::prelude::*;

lagrangian! {
    pub struct Puck {
        coordinates: x, y;
        parameters: m, g;
        kinetic: m/2*(dot(x)^2 + dot(y)^2);
        potential: m*g*y;
        contacts: floor: y + dot(y) >= 0;
    }
}

fn main() {
    let _ = Puck::<f64>::CONTACTS;
}
