use lagrange::prelude::*;

lagrangian! {
    pub struct Puck {
        coordinates: x, y, z;
        parameters: m, g, mu;
        kinetic: m/2*(dot(x)^2 + dot(y)^2 + dot(z)^2);
        potential: m*g*z;
        contacts: table: z >= 0 { friction: mu, slip: vector(dot(x), dot(y), dot(z)) };
    }
}

fn main() {
    let _ = Puck::<f64>::CONTACTS;
}
