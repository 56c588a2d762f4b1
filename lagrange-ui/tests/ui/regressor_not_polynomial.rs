use lagrange::nalgebra::Vector1;
use lagrange::prelude::*;

lagrangian! {
    // The incline's angle enters through a sine: the equations are not
    // linear in any product of it.
    #[lagrange(regressor(m, alpha))]
    pub struct Incline {
        coordinates: x;
        parameters: m, alpha;
        constants: g = 9.81;
        kinetic: m/2*dot(x)^2;
        potential: -m*g*x*sin(alpha);
    }
}

fn main() {
    // The stub keeps the regressor's API: no second error.
    let model = Incline::new(1.0, 0.3);
    let q = Vector1::new(0.0);
    let _ = model.regressor(0.0, &q, &q, &q);
    let _ = model.regressor_parameters();
    let _ = Incline::<f64>::REGRESSOR_PARAMETERS;
}
