use lagrange::prelude::*;

lagrangian! {
    pub struct Driven {
        coordinates: x;
        parameters: m, k, c, f;
        kinetic: m/2*dot(x)^2;
        potential: k/2*x^2;
        forces: x = -c*dot(x);
        forces: x = f*cos(t);
    }
}

fn main() {}
