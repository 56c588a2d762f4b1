use lagrange::nalgebra::Vector1;
use lagrange::prelude::*;
use lagrange::sensitivity::{Direction, Sensitivity};
use lagrange::ParameterDerivatives;

lagrangian! {
    #[lagrange(parameter_derivatives)]
    pub struct Pendulum {
        coordinates: theta;
        parameters: m, l;
        kinetic: m/2*l^2*dot(theta)^2;
        potential: -m*g*l*cos(theta);
    }
}

fn main() {
    // The stub keeps the `ParameterDerivatives` impl: no second error.
    let model = Pendulum::new(1.0, 0.5);
    let _ = model.parameter_values();
    let direction = Direction::parameter::<Pendulum, 1, 2>("l").unwrap();
    let sensitivity = Sensitivity::<_, 1, 2, 1, 2>::new(model, [direction]).unwrap();
    let _ = sensitivity.initial_state(&Vector1::new(0.1), &Vector1::new(0.0));
}
