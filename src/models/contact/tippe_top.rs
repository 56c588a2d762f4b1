//! The tippe top: a sphere whose centre of mass lies off its centre,
//! spun on a rough table, turns over onto its stem. Sliding friction at
//! the contact drives it, and no force at the contact changes Jellett's
//! integral `L_G · (P − G)` (the angular momentum about the centre of mass
//! along the arm from it to the contact point): that torque `(P − G) × F`
//! is across the arm, and the arm turns with the axis, across `L_G`'s
//! share that changes. The inversion condition on the moments, `1 − α <
//! C/A < 1 + α` with `α = a/r` (Cohen, "The tippe top revisited", Am. J.
//! Phys. 45, 12 (1977); Ueda, Sasaki and Watanabe, SIAM J. Appl. Dyn.
//! Syst. 4, 1159 (2005)).

use nalgebra::{SVector, UnitQuaternion, Vector3, Vector4};

use crate::lagrangian;
use crate::models::quaternion;

lagrangian! {
    /// A tippe top: a ball of mass `m` and radius `r` whose centre of mass
    /// `G = (x, y, z)` lies `a` below its geometric centre `O` along its
    /// symmetry axis `k = R(q) e₃` (the stem's side, up when it stands
    /// upright), its moments `i1` across the axis and `i3` along it, both
    /// about `G`, its orientation the unit quaternion `q` (body to space),
    /// under gravity `g`. It touches the table `z = 0` at `P = O − r e_z`,
    /// where `O = G + a k`: the gap is `z + a k_z − r`, and its slip is
    /// `P`'s velocity along the table, `v_G + ω × (a k − r e_z)`, with
    /// friction `mu` in the table's plane.
    ///
    /// The top of Leine and Glocker (European Journal of Mechanics A/Solids
    /// 22, 193 (2003), the tippe top of its §6: 6 g, 15 mm, `a` = 3 mm,
    /// moments 8e-7 and 7e-7 kg m²), spun about the vertical at 180 rad/s,
    /// tilted 0.1 rad, on a table with `μ = 0.1`: its contact slips from the
    /// start and its axis rises through the horizontal (2.22 s) to 2.71
    /// rad, where the slip stops (3.466 s) and it rolls, Jellett's integral
    /// unchanged (`tests/trajectories/contact/tippe_top.rs`). The slip comes
    /// to rest turning with the precession, where Coulomb's law is stiff:
    /// that test runs it with a
    /// [`direction_speed`](crate::contact::ContactSettings::direction_speed)
    /// of 1e-4 m/s.
    ///
    /// ```
    /// use lagrange::contact::{self, ContactSettings, Mode};
    /// use lagrange::models::TippeTop;
    /// use lagrange::nalgebra::SVector;
    /// use lagrange::prelude::*;
    ///
    /// let top = TippeTop::leine_glocker(0.1);
    /// let (q0, v0) = top.spun(0.1, 180.0);
    /// let run = contact::integrate(
    ///     &Dop853::new().rtol(1e-12).atol(1e-12),
    ///     &top,
    ///     0.0,
    ///     SVector::from(q0),
    ///     SVector::from(v0),
    ///     &[0.05],
    ///     ContactSettings::default(),
    /// )?;
    /// let end = run.trajectory().last().unwrap();
    /// let j0 = top.jellett(&q0.into(), &v0.into());
    /// assert!((top.jellett(&end.q, &end.qdot) - j0).abs() < 1e-10 * j0.abs());
    /// assert_eq!(run.modes().last().unwrap()[0], Mode::Slipping);
    /// assert!(top.tilt(&end.q) > 0.1);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub struct TippeTop {
        coordinates: x, y, z, q[4];
        parameters: m, r, a, i1, i3, g, mu;
        let omega = body_rates(q);
        let spin = space_rates(q);
        let axis = rotate(q, vector(0, 0, 1));
        let low = vector(dot(x), dot(y), dot(z)) + cross(spin, a*axis - vector(0, 0, r));
        kinetic: m/2*(dot(x)^2 + dot(y)^2 + dot(z)^2)
            + (i1*(omega[0]^2 + omega[1]^2) + i3*omega[2]^2)/2;
        potential: m*g*z;
        constraints: unit: inner(q, q) = 1;
        contacts: table: z + a*axis[2] >= r { friction: mu, slip: vector(low[0], low[1]) };
    }
}

impl TippeTop<f64> {
    /// Leine and Glocker's tippe top (2003, §6): 6 g, radius 15 mm, its
    /// centre of mass 3 mm below the centre (`α = 0.2`), moments 8e-7 kg m²
    /// across the axis and 7e-7 kg m² along it (`C/A = 0.875`, inside `(1 −
    /// α, 1 + α)`), under 9.81 m/s², on a table with friction `mu`.
    pub fn leine_glocker(mu: f64) -> Self {
        Self::new(6e-3, 0.015, 0.003, 8e-7, 7e-7, 9.81, mu)
    }

    /// Leine and Glocker's tippe top with its two moments exchanged: 7e-7
    /// kg m² across the axis and 8e-7 kg m² along it (`C/A = 8/7`, still
    /// inside `(1 − α, 1 + α)` = (0.8, 1.2)), otherwise the same. Spun at
    /// 180 rad/s and tilted 0.1 rad on a table with `μ = 0.1`, it turns
    /// over fully: its slip stops at 3.0971 rad (177.5°, at 4.22 s) and it
    /// rolls on its stem's side, where
    /// [`leine_glocker`](Self::leine_glocker)'s stops at 2.71 rad
    /// (`tests/trajectories/contact/tippe_top.rs`). With `C/A` = 0.825,
    /// 0.875, 0.975, 1, 1.05, 1.1 and 8/7 at that spin, the slip stopped at
    /// 2.34, 2.71, 3.03, 3.05, 3.08, 3.10 and 3.10 rad (the moment across
    /// the axis 8e-7 kg m² but for 8/7).
    pub fn oblate(mu: f64) -> Self {
        Self::new(6e-3, 0.015, 0.003, 7e-7, 8e-7, 9.81, mu)
    }

    /// The symmetry axis in space, `k = R(q) e₃` (up when the top stands
    /// on its ball, down when it has turned over onto its stem).
    pub fn axis(q: &SVector<f64, 7>) -> Vector3<f64> {
        quaternion::rotation(&q.fixed_rows::<4>(3).into_owned()) * Vector3::z()
    }

    /// The tilt of the symmetry axis from the vertical: 0 upright, `π`
    /// turned over.
    pub fn tilt(&self, q: &SVector<f64, 7>) -> f64 {
        Self::axis(q)[2].clamp(-1.0, 1.0).acos()
    }

    /// Jellett's integral `L_G · (P − G)`: the angular momentum about the
    /// centre of mass, `R (i1 ω₁, i1 ω₂, i3 ω₃)`, along the arm `a k − r e_z`
    /// to the contact point. Forces at the contact and gravity leave it
    /// unchanged, sliding or not.
    pub fn jellett(&self, q: &SVector<f64, 7>, qdot: &SVector<f64, 7>) -> f64 {
        let (quat, rates): (Vector4<f64>, Vector4<f64>) = (
            q.fixed_rows::<4>(3).into_owned(),
            qdot.fixed_rows::<4>(3).into_owned(),
        );
        let omega = quaternion::body_rates(&quat, &rates);
        let turn = quaternion::rotation(&quat);
        let momentum =
            turn * Vector3::new(self.i1 * omega[0], self.i1 * omega[1], self.i3 * omega[2]);
        let arm = turn * Vector3::z() * self.a - Vector3::z() * self.r;
        momentum.dot(&arm)
    }

    /// The velocity of the contact point `P` (the material point of the
    /// ball at the bottom), `v_G + ω × (a k − r e_z)`: along the table, the
    /// slip.
    pub fn contact_velocity(&self, q: &SVector<f64, 7>, qdot: &SVector<f64, 7>) -> Vector3<f64> {
        let quat: Vector4<f64> = q.fixed_rows::<4>(3).into_owned();
        let turn = quaternion::rotation(&quat);
        let omega = turn * quaternion::body_rates(&quat, &qdot.fixed_rows::<4>(3).into_owned());
        let arm = turn * Vector3::z() * self.a - Vector3::z() * self.r;
        qdot.fixed_rows::<3>(0).into_owned() + omega.cross(&arm)
    }

    /// The top touching the table, its axis tilted by `tilt` about the x
    /// axis, turning at `rate` about the vertical through its centre of
    /// mass, which is at rest: its contact slips at `rate a sin(tilt)`
    /// across the plane of the tilt, and it touches without approaching
    /// (`ω × k` is horizontal).
    pub fn spun(&self, tilt: f64, rate: f64) -> ([f64; 7], [f64; 7]) {
        let turned = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), tilt);
        let (q, qdot) =
            quaternion::state(&turned, &(turned.inverse() * Vector3::new(0.0, 0.0, rate)));
        let z = self.r - self.a * tilt.cos();
        (
            [0.0, 0.0, z, q[0], q[1], q[2], q[3]],
            [0.0, 0.0, 0.0, qdot[0], qdot[1], qdot[2], qdot[3]],
        )
    }
}
