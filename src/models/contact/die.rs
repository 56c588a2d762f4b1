//! A die thrown onto a table: a cube in a unit quaternion, its eight
//! corners contacts with friction in the table's plane.

use crate::lagrangian;

lagrangian! {
    /// A die: a uniform cube of mass `m` and side `s` (moment `m s²/6`
    /// about any axis through its centre), its centre `(x, y, z)` and its
    /// orientation the unit quaternion `q`, each of its eight corners a
    /// contact with the table `z = 0` (restitution `e`, friction `mu` in
    /// the table's plane). At rest on a face its four corners' forces are
    /// not determined; the run's are the smallest that hold it.
    pub struct Die {
        coordinates: x, y, z, q[4];
        parameters: m, s, g, e, mu;
        let omega = body_rates(q);
        let centre = vector(x, y, z);
        let c0 = centre + rotate(q, vector(s/2, s/2, s/2));
        let c1 = centre + rotate(q, vector(-s/2, s/2, s/2));
        let c2 = centre + rotate(q, vector(-s/2, -s/2, s/2));
        let c3 = centre + rotate(q, vector(s/2, -s/2, s/2));
        let c4 = centre + rotate(q, vector(s/2, s/2, -s/2));
        let c5 = centre + rotate(q, vector(-s/2, s/2, -s/2));
        let c6 = centre + rotate(q, vector(-s/2, -s/2, -s/2));
        let c7 = centre + rotate(q, vector(s/2, -s/2, -s/2));
        kinetic: m/2*(dot(x)^2 + dot(y)^2 + dot(z)^2) + m*s^2/12*inner(omega, omega);
        potential: m*g*z;
        constraints: unit: inner(q, q) = 1;
        contacts:
            k0: c0[2] >= 0 { restitution: e, friction: mu, slip: vector(dot(c0[0]), dot(c0[1])) },
            k1: c1[2] >= 0 { restitution: e, friction: mu, slip: vector(dot(c1[0]), dot(c1[1])) },
            k2: c2[2] >= 0 { restitution: e, friction: mu, slip: vector(dot(c2[0]), dot(c2[1])) },
            k3: c3[2] >= 0 { restitution: e, friction: mu, slip: vector(dot(c3[0]), dot(c3[1])) },
            k4: c4[2] >= 0 { restitution: e, friction: mu, slip: vector(dot(c4[0]), dot(c4[1])) },
            k5: c5[2] >= 0 { restitution: e, friction: mu, slip: vector(dot(c5[0]), dot(c5[1])) },
            k6: c6[2] >= 0 { restitution: e, friction: mu, slip: vector(dot(c6[0]), dot(c6[1])) },
            k7: c7[2] >= 0 { restitution: e, friction: mu, slip: vector(dot(c7[0]), dot(c7[1])) };
    }
}

impl Die<f64> {
    /// Its eight corners in space at `q`: the centre plus the rotated
    /// `(±s/2, ±s/2, ±s/2)`, the points its contacts watch (in another
    /// order).
    pub fn corners(&self, q: &nalgebra::SVector<f64, 7>) -> [nalgebra::Vector3<f64>; 8] {
        let turn = crate::models::quaternion::rotation(&q.fixed_rows::<4>(3).into_owned());
        let h = self.s / 2.0;
        core::array::from_fn(|k| {
            let sign = |bit: usize| if k >> bit & 1 == 0 { h } else { -h };
            q.fixed_rows::<3>(0).into_owned()
                + turn * nalgebra::Vector3::new(sign(0), sign(1), sign(2))
        })
    }
}
