use lagrange::prelude::*;

lagrangian! {
    pub struct Odd {
        coordinates: x;
        parameters: m, k;
        kinetic: m*cos(dot(x));
        potential: k/2*x^2;
    }
}

fn main() {}
