use lagrange::prelude::*;

lagrangian! {
    pub struct Raw {
        coordinates: r#type;
        parameters: m;
        kinetic: m/2*dot(x)^2;
        potential: 0;
    }
}

fn main() {}
