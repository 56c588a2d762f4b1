use lagrange::prelude::*;

lagrangian! {
    pub struct Deep {
        coordinates: x;
        parameters: m, k;
        kinetic: m/2*dot(x)^2;
        // 129 parentheses: one level more than the engine takes.
        potential: k/2*(((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((x)))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))));
    }
}

fn main() {
    let _ = Deep::new(1.0, 1.0).energy(0.0, &lagrange::nalgebra::Vector1::new(0.0), &lagrange::nalgebra::Vector1::new(0.0));
}
