//! The heavy symmetric top in unit quaternions: a body spinning about its
//! symmetry axis on a fixed pivot under gravity. No chart, so no pole: the
//! axis may pass through the vertical, where Euler angles lock (the test
//! `tests/trajectories/heavy_top.rs` runs both). Its invariants are the
//! energy, the angular momentum about the vertical and about the symmetry
//! axis (Goldstein, Classical Mechanics, §5.7).

use nalgebra::{Vector3, Vector4};

use super::quaternion;
use crate::lagrangian;

lagrangian! {
    /// A top with moments `a` across its symmetry axis (about the pivot)
    /// and `c` along it, its mass centre at `l` along the axis from the
    /// pivot, `z` up; the orientation the unit quaternion
    /// `w + x i + y j + z k` (body to space), the body rates three `let`s.
    /// `M` alone is singular (rank 3 of 4); `|q| = 1` makes it regular on
    /// the rates it allows.
    ///
    /// ```
    /// use lagrange::models::{quaternion, HeavyTop};
    /// use lagrange::nalgebra::{UnitQuaternion, Vector3};
    /// use lagrange::prelude::*;
    ///
    /// let top = HeavyTop::new(1.0, 0.5, 1.0, 9.81, 0.2);
    /// // Tilted by 1 rad about x, spinning at 20 rad/s about its axis.
    /// let tilt = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 1.0);
    /// let (q0, v0) = quaternion::state(&tilt, &Vector3::new(0.0, 0.0, 20.0));
    /// let run = Dop853::new().rtol(1e-12).atol(1e-12).integrate(&top, 0.0, q0, v0, &[5.0])?;
    /// let end = run.last().unwrap();
    /// let [e0, lz0, l30] = top.invariants(&q0, &v0);
    /// let [e, lz, l3] = top.invariants(&end.q, &end.qdot);
    /// assert!((e - e0).abs() < 1e-9 * e0.abs() && (lz - lz0).abs() < 1e-9 && (l3 - l30).abs() < 1e-9);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub struct HeavyTop {
        coordinates: w, x, y, z;
        parameters: a, c, m, g, l;
        let omega1 = 2*(w*dot(x) - x*dot(w) - y*dot(z) + z*dot(y));
        let omega2 = 2*(w*dot(y) - y*dot(w) - z*dot(x) + x*dot(z));
        let omega3 = 2*(w*dot(z) - z*dot(w) - x*dot(y) + y*dot(x));
        // The height of the mass centre: l times R₃₃ = w² − x² − y² + z².
        let height = l*(w^2 - x^2 - y^2 + z^2);
        kinetic: (a*(omega1^2 + omega2^2) + c*omega3^2)/2;
        potential: m*g*height;
        constraints: unit: w^2 + x^2 + y^2 + z^2 = 1;
    }
}

lagrangian! {
    /// The same top in z–x–z Euler angles (precession `phi`, nutation
    /// `theta`, spin `psi`): a chart that locks at the pole `θ = 0`, where
    /// `φ` and `ψ` turn about the same axis and `M` is singular. Kept beside
    /// [`HeavyTop`] to compare the two (`tests/trajectories/heavy_top.rs`).
    pub struct EulerTop {
        coordinates: phi, theta, psi;
        parameters: a, c, m, g, l;
        kinetic: a/2*(dot(theta)^2 + dot(phi)^2*sin(theta)^2) + c/2*(dot(psi) + dot(phi)*cos(theta))^2;
        potential: m*g*l*cos(theta);
    }
}

impl HeavyTop {
    /// The symmetry axis in space, `R(q) e₃`.
    pub fn axis(q: &Vector4<f64>) -> Vector3<f64> {
        quaternion::rotation(q) * Vector3::z()
    }

    /// The invariants of a state: the energy, the angular momentum about
    /// the vertical `L_z`, and about the symmetry axis `L₃ = c ω₃`.
    pub fn invariants(&self, q: &Vector4<f64>, qdot: &Vector4<f64>) -> [f64; 3] {
        let omega = quaternion::body_rates(q, qdot);
        let r = quaternion::rotation(q);
        let momentum = r * Vector3::new(self.a * omega[0], self.a * omega[1], self.c * omega[2]);
        let kinetic =
            (self.a * (omega[0].powi(2) + omega[1].powi(2)) + self.c * omega[2].powi(2)) / 2.0;
        let energy = kinetic + self.m * self.g * self.l * (r * Vector3::z())[2];
        [energy, momentum[2], self.c * omega[2]]
    }
}
