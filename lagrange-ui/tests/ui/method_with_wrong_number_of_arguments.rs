use lagrange::prelude::*;

lagrangian! {
    pub struct Oscillator {
        coordinates: x;
        parameters: m, k;
        kinetic: m/2*dot(x).powi();
        potential: k/2*x^2;
    }
}

fn main() {}
