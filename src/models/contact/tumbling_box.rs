//! A box tumbling onto the floor, its four corners contacts.

use crate::lagrangian;

lagrangian! {
    /// A uniform box of mass `m`, width `w` and height `h` (moment of
    /// inertia `m (w² + h²)/12`) in the vertical plane: its centre `(x,
    /// y)` and its angle `theta`, under gravity `g`. Each corner is a
    /// contact with the floor `y = 0`, with restitution `e` and friction
    /// `mu` along the floor.
    pub struct TumblingBox {
        coordinates: x, y, theta;
        parameters: m, w, h, g, e, mu;
        let a = vector(x, y, 0) + rotate_z(theta, vector(w/2, h/2, 0));
        let b = vector(x, y, 0) + rotate_z(theta, vector(-w/2, h/2, 0));
        let c = vector(x, y, 0) + rotate_z(theta, vector(-w/2, -h/2, 0));
        let d = vector(x, y, 0) + rotate_z(theta, vector(w/2, -h/2, 0));
        kinetic: m/2*(dot(x)^2 + dot(y)^2) + m*(w^2 + h^2)/24*dot(theta)^2;
        potential: m*g*y;
        contacts:
            corner_a: a[1] >= 0 { restitution: e, friction: mu, slip: dot(a[0]) },
            corner_b: b[1] >= 0 { restitution: e, friction: mu, slip: dot(b[0]) },
            corner_c: c[1] >= 0 { restitution: e, friction: mu, slip: dot(c[0]) },
            corner_d: d[1] >= 0 { restitution: e, friction: mu, slip: dot(d[0]) };
    }
}
