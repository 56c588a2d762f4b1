use lagrange::prelude::*;

// A velocity constraint must be linear in the velocities (A(t, q) q̇ + b = 0):
// a speed fixed in magnitude is not.
lagrangian! {
    pub struct FixedSpeed {
        coordinates: x, y;
        parameters: m, v;
        kinetic: m/2*(dot(x)^2 + dot(y)^2);
        potential: 0;
        constraints: speed: dot(x)^2 + dot(y)^2 = v^2;
    }
}

fn main() {
    let _ = FixedSpeed::<f64>::CONSTRAINTS;
}
