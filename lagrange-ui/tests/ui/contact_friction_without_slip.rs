use lagrange::prelude::*;

lagrangian! {
    pub struct Block {
        coordinates: x, y;
        parameters: m, g, mu;
        kinetic: m/2*(dot(x)^2 + dot(y)^2);
        potential: m*g*y;
        contacts: floor: y >= 0 { friction: mu };
    }
}

fn main() {
    let _ = Block::<f64>::CONTACTS;
}
