use lagrange::prelude::*;

lagrangian! {
    pub struct Ball {
        coordinates: z;
        parameters: m, g, e;
        kinetic: m/2*dot(z)^2;
        potential: m*g*z;
        contacts: floor: z >= 0 { restitution: e*dot(z) };
    }
}

fn main() {
    let _ = Ball::<f64>::CONTACTS;
}
