use lagrange::prelude::*;

lagrangian! {
    // A mass on a spring swinging as a pendulum: its length is a
    // coordinate, so its velocity is not a sum of increments along links.
    #[lagrange(articulated)]
    pub struct SpringPendulum {
        coordinates: r, theta;
        parameters: m, k, l, g;
        kinetic: m/2*(dot(r)^2 + r^2*dot(theta)^2);
        potential: k/2*(r - l)^2 - m*g*r*cos(theta);
    }
}

fn main() {
    let model = SpringPendulum::new(1.0, 10.0, 1.0, 9.81);
    let _ = model.mass_matrix(0.0, &lagrange::nalgebra::Vector2::new(1.0, 0.0));
}
