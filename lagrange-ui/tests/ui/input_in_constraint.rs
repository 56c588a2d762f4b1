use lagrange::prelude::*;
use lagrange::nalgebra::{Vector1, Vector2};

lagrangian! {
    pub struct Cart {
        coordinates: x, theta;
        parameters: m, l;
        inputs: force;
        kinetic: m/2*(dot(x)^2 + l^2*dot(theta)^2);
        potential: 0;
        constraints: slide: x = force*theta;
    }
}

fn main() {
    // The stub keeps the API of a model with inputs: no second error.
    let model = Cart::new(1.0, 0.5).with_inputs(&Vector1::new(1.0));
    let _ = model.input_jacobian(0.0, &Vector2::zeros(), &Vector2::zeros());
    let _ = Cart::<f64>::INPUTS;
}
