use lagrange::prelude::*;

lagrangian! {
    pub struct Bob {
        coordinates: x, y;
        parameters: m, g, l;
        kinetic: m/2*(dot(x)^2 + dot(y)^2);
        potential: m*g*y;
        constraints: rod: x^2 + y^2 = l^2;
        contacts: floor: y + l >= 0;
    }
}

fn main() {
    let _ = Bob::<f64>::CONTACTS;
}
