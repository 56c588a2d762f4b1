use lagrange::prelude::*;

lagrangian! {
    /// A double pendulum whose generated code is over the limit it gives
    /// itself: the guard that stops a model rustc could not build within
    /// the machine's memory (4 MB of code by default), without writing it.
    #[lagrange(articulated = false, max_code = 2000)]
    pub struct DoublePendulum {
        coordinates: theta1, theta2;
        parameters: m1, m2, l1, l2, g;
        let x1 = l1*sin(theta1);
        let y1 = -l1*cos(theta1);
        let x2 = x1 + l2*sin(theta2);
        let y2 = y1 - l2*cos(theta2);
        kinetic: m1/2*(dot(x1)^2 + dot(y1)^2) + m2/2*(dot(x2)^2 + dot(y2)^2);
        potential: m1*g*y1 + m2*g*y2;
    }
}

fn main() {
    let model = DoublePendulum::new(1.0, 1.0, 1.0, 1.0, 9.81);
    let _ = model.mass_matrix(0.0, &lagrange::nalgebra::Vector2::new(0.1, 0.2));
}
