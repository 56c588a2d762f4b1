use lagrange::prelude::*;

lagrangian! {
    pub struct Oscillator {
        coordinates: x;
        parameters: m, k;
        let t = x^2;
        kinetic: m/2*dot(x)^2;
        potential: k/2*t;
    }
}

fn main() {}
