use lagrange::prelude::*;

// A body in unit quaternions without inertia about its third axis (a thin
// rod): the constraint `|q| = 1` fixes one of the four rates, and the
// kinetic energy sees only two of the three left.
lagrangian! {
    pub struct Rod {
        coordinates: w, x, y, z;
        parameters: i1, i2;
        let omega1 = 2*(w*dot(x) - x*dot(w) - y*dot(z) + z*dot(y));
        let omega2 = 2*(w*dot(y) - y*dot(w) - z*dot(x) + x*dot(z));
        kinetic: (i1*omega1^2 + i2*omega2^2)/2;
        potential: 0;
        constraints: unit: w^2 + x^2 + y^2 + z^2 = 1;
    }
}

fn main() {
    let _ = Rod::new(1.0, 1.0);
}
