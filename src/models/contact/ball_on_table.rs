//! A ball in 3D on a rough table: thrown with spin, it slides until its
//! lowest point comes to rest, then rolls.

use nalgebra::{UnitQuaternion, Vector3};

use crate::lagrangian;
use crate::models::quaternion;

lagrangian! {
    /// A uniform ball of mass `m` and radius `r` (moment `2 m r²/5`) on a
    /// rough table `z = 0` (`mu`, restitution `e`), its centre `(x, y, z)`
    /// and its orientation the unit quaternion `q`: its slip is the
    /// velocity of its lowest point along the table, `v + ω × (0, 0, −r)`,
    /// a vector whose friction turns with it.
    pub struct BallOnTable {
        coordinates: x, y, z, q[4];
        parameters: m, r, g, mu, e;
        let omega = space_rates(q);
        let low = vector(dot(x), dot(y), dot(z)) + cross(omega, vector(0, 0, -r));
        kinetic: m/2*(dot(x)^2 + dot(y)^2 + dot(z)^2) + m*r^2/5*inner(omega, omega);
        potential: m*g*z;
        constraints: unit: inner(q, q) = 1;
        contacts: table: z >= r { restitution: e, friction: mu, slip: vector(low[0], low[1]) };
    }
}

impl BallOnTable<f64> {
    /// On the table, its centre moving at `v0` along it and spinning at
    /// `omega` (in space).
    pub fn thrown(&self, v0: &Vector3<f64>, omega: &Vector3<f64>) -> ([f64; 7], [f64; 7]) {
        let (q, qdot) = quaternion::state(&UnitQuaternion::identity(), omega);
        (
            [0.0, 0.0, self.r, q[0], q[1], q[2], q[3]],
            [v0[0], v0[1], 0.0, qdot[0], qdot[1], qdot[2], qdot[3]],
        )
    }

    /// How its lowest point slips when thrown at `v0` spinning at
    /// `omega`: `s₀ = v₀ + ω₀ × (0, 0, −r)`.
    pub fn slip(&self, v0: &Vector3<f64>, omega: &Vector3<f64>) -> Vector3<f64> {
        v0 + omega.cross(&Vector3::new(0.0, 0.0, -self.r))
    }

    /// When it starts to roll: friction `μ m g` against the slip slows the
    /// slip at `(7/2) μ g` along its own direction (which therefore never
    /// turns), so at `t* = 2 |s₀| / (7 μ g)`.
    pub fn rolling_time(&self, v0: &Vector3<f64>, omega: &Vector3<f64>) -> f64 {
        2.0 * self.slip(v0, omega).norm() / (7.0 * self.mu * self.g)
    }

    /// Its centre's velocity from then on: `v₀ − μ g t* ŝ₀`. Along the
    /// throw with backspin `ω₀` about the axis across it, `(5 v₀ −
    /// 2 r ω₀)/7`: it comes back when `2 r ω₀ > 5 v₀`.
    pub fn rolling_velocity(&self, v0: &Vector3<f64>, omega: &Vector3<f64>) -> Vector3<f64> {
        let s0 = self.slip(v0, omega);
        if s0.norm() == 0.0 {
            return *v0;
        }
        v0 - s0.normalize() * (self.mu * self.g * self.rolling_time(v0, omega))
    }
}
